"""`castor --check` on one long statement: $U of 10,000 to 40,000 cubes, each
moved (`@t(X, Y, 0) !cu(0, 0, 0)`: 1.1 MB at 40,000), as benchmarks/lsp_long_statement.py
sends it to the language server (issue 29, item 11).

Per size: the CPU time (user + system, of the whole process) and the wall
time, medians of BENCH_RUNS runs; the CPU time per thousand cubes says whether
the time grows as the statement (tests/language/test_long_statement.py counts
the parser's work instead of timing it). The machines are shared: the CPU time
is the steadier figure.
"""

from __future__ import annotations

import os
import resource
import statistics
import subprocess
import tempfile
import time

from _common import castor_command, runs_from_env

RUNS = runs_from_env(3)
SIZES = (10_000, 20_000, 40_000)


def scene(cubes: int, colour: int = 0) -> str:
    """One definition of the union of ``cubes`` cubes, then its frame."""
    operands = ", ".join(f"@t({k % 200}, {k // 200}, 0) !cu({colour / 10:g}, 0, 0)"
                         for k in range(cubes))
    return f"big = $U({operands});\n> big;\n"


def run(command: list[str]) -> tuple[float, float]:
    """CPU and wall seconds of one whole process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    started = time.perf_counter()
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    wall = time.perf_counter() - started
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(command)} failed: {done.stderr.decode()[:400]}")
    return (after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime), wall


def main() -> None:
    work = tempfile.mkdtemp(prefix="castor-long-")
    print(f"{'cubes':>7} {'MB':>5} {'CPU s':>7} {'wall s':>7} {'CPU s / 1000 cubes':>19}")
    for cubes in SIZES:
        path = os.path.join(work, f"long{cubes}.cas")
        with open(path, "w") as handle:
            handle.write(scene(cubes))
        runs = [run(castor_command() + ["--check", path]) for _ in range(RUNS)]
        cpu = statistics.median(r[0] for r in runs)
        wall = statistics.median(r[1] for r in runs)
        print(f"{cubes:7d} {os.path.getsize(path) / 1e6:5.2f} {cpu:7.2f} {wall:7.2f} "
              f"{cpu / cubes * 1000:19.3f}")
        os.unlink(path)
    os.rmdir(work)


if __name__ == "__main__":
    main()
