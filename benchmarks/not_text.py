"""Input that is not text (issue 29, item 1): how long castor takes to refuse
random bytes, and its peak memory, by size, as a file and on standard input,
with and without the preprocessor.

    python benchmarks/not_text.py                 1 and 5 MB
    python benchmarks/not_text.py --sizes 1 5 20  megabytes

Target: well under a second per megabyte, in bounded memory, one message.
Before the fix (issue 29): 5 MB took 158 s (453 s and 1 GB without any '#');
500 KB 6.4 s. Each figure is one run (a refusal is quick, so runs of one are
steady enough); the peak memory is the process's, from /usr/bin/time.
"""

from __future__ import annotations

import argparse
import os
import random
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import castor_command, table  # noqa: E402


def run(command: list[str], stdin: bytes | None, cwd: str) -> tuple[float, int, int]:
    """Seconds, the process's peak resident kB (from /usr/bin/time: the children
    rusage of this process would count the copy that fork makes of it) and the
    number of message lines."""
    started = time.perf_counter()
    done = subprocess.run(["/usr/bin/time", "-f", "%M"] + command, input=stdin,
                          capture_output=True, cwd=cwd)
    seconds = time.perf_counter() - started
    *messages, peak = done.stderr.decode(errors="replace").splitlines()
    messages = [m for m in messages if not m.startswith("Command exited with")]
    return seconds, int(peak), len(messages)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=float, nargs="+", default=[1, 5])
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for size in args.sizes:
            data = random.Random(29).randbytes(int(size * 1_000_000))
            for label, content in (("random", data), ("random, no '#'", data.replace(b"#", b"")),
                                   ("7-bit", bytes(b & 0x7f for b in data))):
                path = os.path.join(folder, "garbage.bin")
                with open(path, "wb") as handle:
                    handle.write(content)
                for options in ([], ["--no-cpp"]):
                    for where in ("file", "stdin"):
                        command = castor_command() + ["--check", *options]
                        if where == "file":
                            seconds, peak, lines = run(command + [path], None, folder)
                        else:
                            seconds, peak, lines = run(command, content, folder)
                        rows.append([f"{size:g} MB", label, " ".join(options) or "cpp", where,
                                     f"{seconds:.2f}", f"{peak / 1024:.0f}", lines])
    print(table(rows, ["size", "bytes", "reading", "from", "seconds", "peak MB", "messages"]))


if __name__ == "__main__":
    main()
