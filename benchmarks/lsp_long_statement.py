"""castor --lsp and one statement of 40,000 cubes (1.1 MB): five quick edits,
then the time until the diagnostics of the last text are published, and the
time one analysis of that text takes alone (what the last edit cannot wait
less than). Before stale analyses were stopped inside a statement, each edit's
analysis ran to the end of the statement: the final diagnostics came after
the sum of several analyses (13 s on the user's machine for 5 to 6.6 s each).
Target: the last text answered within a couple of seconds of its own analysis.
"""

from __future__ import annotations

import shutil
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests" / "preview"))
from test_lsp import Client  # noqa: E402

CUBES = 40_000


def scene(colour: int) -> str:
    cubes = ", ".join(f"@t({k % 200}, {k // 200}, 0) !cu({colour / 10:g}, 0, 0)"
                      for k in range(CUBES))
    return f"big = $U({cubes});\n> big;\n"


def main() -> None:
    work = Path(tempfile.mkdtemp(prefix="castor-long-"))
    try:
        path = work / "big.cas"
        path.write_text(scene(0))
        client = Client(work)
        client.start(work)
        started = time.perf_counter()
        uri = client.open(path)
        client.diagnostics(uri, 1, timeout=300)
        alone = time.perf_counter() - started
        for version in range(2, 7):  # five quick edits
            client.change(uri, scene(version) + f"// edit {version}\n", version)
            time.sleep(0.3)
        last = time.perf_counter()
        published = client.diagnostics(uri, 6, timeout=300)
        final = time.perf_counter() - last
        client.stop()
        print(f"one analysis of the 1.1 MB statement: {alone:.2f} s")
        print(f"five edits 0.3 s apart, the last one's diagnostics {final:.2f} s after it "
              f"({len(published)} diagnostics)")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
