"""Pictures, 800x600, 4 samples per pixel, shadows: castor's ray tracer of the
exact solids (castor -o x.png) beside the polygon pipe (castor | castor-view),
whole processes, with each process's peak memory (GNU time's maximum RSS).

Targets: house <= 2 s, bus shelter (one frame) <= 10 s, 64 houses <= 15 s;
castor-view <= 1 s and <= 100 MB beyond the frame for the bus shelter.
"""

from __future__ import annotations

import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

from _common import castor_command, runs_from_env, table
from houses import CASTOR as HOUSES

RUNS = runs_from_env(3)
HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.join(HERE, "..", "examples")


def _peak(command, stdin=None) -> tuple[float, float]:
    """Seconds and peak megabytes of one whole process."""
    gnu_time = shutil.which("time") or "/usr/bin/time"
    started = time.perf_counter()
    done = subprocess.run([gnu_time, "-f", "%M", *command], input=stdin,
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    seconds = time.perf_counter() - started
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(command)} failed: {done.stderr.decode()[-400:]}")
    return seconds, int(done.stderr.decode().split()[-1]) / 1024


def median_run(command, stdin=None) -> tuple[float, float]:
    runs = [_peak(command, stdin) for _ in range(RUNS)]
    return statistics.median(r[0] for r in runs), max(r[1] for r in runs)


def main() -> None:
    work = tempfile.mkdtemp()
    houses = os.path.join(work, "houses.cas")
    with open(houses, "w") as handle:
        handle.write(HOUSES)
    castor = castor_command()
    view = [shutil.which("castor-view") or sys.executable, *([] if shutil.which("castor-view")
                                                             else ["-m", "castor.view.cli"])]
    out = os.path.join(work, "x.png")
    rows = []
    for name, args, target in (
            ("house", [os.path.join(EXAMPLES, "house.cas")], 2),
            ("bus shelter", ["-D", "ONE_FRAME", os.path.join(EXAMPLES, "bus_shelter.cas")], 10),
            ("64 houses", [houses], 15)):
        seconds, megabytes = median_run(castor + ["-o", out, *args])
        stream = subprocess.run(castor + args, capture_output=True, check=True).stdout
        pipe_seconds, _ = median_run(castor + args)
        view_seconds, view_megabytes = median_run(view + ["-o", out], stream)
        rows.append([name, f"{seconds:.2f} s", f"<= {target} s", f"{megabytes:.0f} MB",
                     f"{pipe_seconds:.2f} + {view_seconds:.2f} s", f"{view_megabytes:.0f} MB",
                     f"{stream.count(b'poly ')}"])
    print(f"800x600, 4 samples per pixel, sun 135,50 with shadows; median of {RUNS} runs")
    print(table(rows, ["scene", "castor -o x.png", "target", "peak", "castor | castor-view",
                       "castor-view peak", "polygons"]))


if __name__ == "__main__":
    main()
