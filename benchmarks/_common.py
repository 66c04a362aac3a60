"""Helpers for the benchmarks: whole-process timing, median of several runs."""

from __future__ import annotations

import os
import shutil
import statistics
import subprocess
import sys
import time


def castor_command() -> list[str]:
    found = shutil.which("castor")
    return [found] if found else [sys.executable, "-m", "castor"]


def timed(command: list[str], stdin: bytes | None = None, runs: int = 5,
          cwd: str | None = None) -> float:
    """Median wall-clock seconds of running a whole process."""
    times = []
    for _ in range(runs):
        started = time.perf_counter()
        result = subprocess.run(command, input=stdin, stdout=subprocess.DEVNULL,
                                stderr=subprocess.PIPE, cwd=cwd)
        times.append(time.perf_counter() - started)
        if result.returncode not in (0,):
            raise SystemExit(f"{' '.join(command)} failed: {result.stderr.decode()[:400]}")
    return statistics.median(times)


def table(rows: list[list[str]], header: list[str]) -> str:
    widths = [max(len(str(r[i])) for r in [header, *rows]) for i in range(len(header))]
    line = lambda r: "  ".join(str(c).rjust(w) for c, w in zip(r, widths))
    return "\n".join([line(header), line(["-" * w for w in widths]), *map(line, rows)])


def runs_from_env(default: int) -> int:
    return int(os.environ.get("BENCH_RUNS", default))
