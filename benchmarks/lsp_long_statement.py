"""castor --lsp and one statement of 40,000 cubes (1.1 MB): five quick edits,
then the time until the diagnostics of the last text are published, and the
time one analysis of that text takes alone (what the last edit cannot wait
less than). Before stale analyses were stopped inside a statement, each edit's
analysis ran to the end of the statement: the final diagnostics came after
the sum of several analyses (13 s on the user's machine for 5 to 6.6 s each).
Target: the last text answered within a couple of seconds of its own analysis,
and within about 2 s of the last edit on a quiet machine.

The machines are shared: the server's CPU time (from /proc, on Linux) is given
beside each wall time, and what one analysis costs when nothing else runs is
``castor --check`` on the same text (benchmarks/long_statement.py).
"""

from __future__ import annotations

import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
from tests.support.lsp import Client  # noqa: E402

from long_statement import scene  # noqa: E402

CUBES = 40_000


def cpu_seconds(pid: int) -> float:
    """The CPU time (user and system) a process has used so far; NaN off Linux."""
    try:
        with open(f"/proc/{pid}/stat") as handle:
            fields = handle.read().rsplit(")", 1)[1].split()
    except OSError:
        return float("nan")
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def main() -> None:
    work = Path(tempfile.mkdtemp(prefix="castor-long-"))
    try:
        path = work / "big.cas"
        path.write_text(scene(CUBES))
        client = Client(work)
        client.start(work)
        pid = client.process.pid
        started, cpu = time.perf_counter(), cpu_seconds(pid)
        uri = client.open(path)
        client.diagnostics(uri, 1, timeout=300)
        alone, alone_cpu = time.perf_counter() - started, cpu_seconds(pid) - cpu
        for version in range(2, 7):  # five quick edits
            client.change(uri, scene(CUBES, version) + f"// edit {version}\n", version)
            time.sleep(0.3)
        last, cpu = time.perf_counter(), cpu_seconds(pid)
        published = client.diagnostics(uri, 6, timeout=300)
        final, final_cpu = time.perf_counter() - last, cpu_seconds(pid) - cpu
        client.stop()
        print(f"one analysis of the 1.1 MB statement: {alone:.2f} s "
              f"(the server's CPU: {alone_cpu:.2f} s)")
        print(f"five edits 0.3 s apart, the last one's diagnostics {final:.2f} s after it "
              f"(the server's CPU meanwhile: {final_cpu:.2f} s; {len(published)} diagnostics)")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
