"""The car (examples/car.cas) at fine tolerances, and the engine alone on the
same kind of union (issue 29: at ``-t 1e-8`` the car took 23 s and 456 MB,
at ``1e-9`` more than a minute).

    python benchmarks/fine_tolerance.py            # the car: polygons, s, peak MB
    python benchmarks/fine_tolerance.py --engine   # manifold3d alone
    PYTHONPATH=/other/checkout python benchmarks/fine_tolerance.py   # another castor

Each run is a whole process, one at a time, BENCH_RUNS times (2 by default):
its polygons (``--stats``), wall and CPU seconds, and peak memory (the
child's maximum resident size). ``--engine`` times manifold3d's union of a
box and one cylinder of n segments whose circle crosses a face of the box
(the rear wheel) or touches it (the front wheel), the best of two: that
union alone grows with the square of n, which is why the car's time does,
while what castor does before and after it grows as its polygons
(tests/geometry/test_sheet_pairs.py).
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import time

from _common import castor_command, runs_from_env

RUNS = runs_from_env(2)
TOLERANCES = ("1e-7", "3e-8", "1e-8")
SEGMENTS = (1000, 2000, 4000, 8000)
CAR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples", "car.cas")


def car(tolerance: str) -> tuple[int, float, float, float]:
    """Polygons, wall s, CPU s and peak MB of one ``castor --stats`` of the car."""
    command = [*castor_command(), "--stats", "-t", tolerance, CAR]
    started = time.perf_counter()
    # run in the examples' folder, so that PYTHONPATH says which castor runs
    # (``python -m`` puts the current folder first)
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                               cwd=os.path.dirname(CAR))
    stderr = process.stderr.read().decode()
    _, status, usage = os.wait4(process.pid, 0)  # this process's own CPU time and peak
    wall = time.perf_counter() - started
    if status != 0:
        raise SystemExit(f"{' '.join(command)} failed: {stderr[:400]}")
    polygons = int(re.search(r"(\d+) polygons", stderr).group(1))
    return polygons, wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024


def engine() -> None:
    import manifold3d

    body = manifold3d.Manifold.cube((4, 1.6, 1.0)).translate((0, 0, 0.35))
    print(f"{'segments':>8} {'crossing s':>11} {'touching s':>11} {'apart s':>8}")
    for n in SEGMENTS:
        wheel = manifold3d.Manifold.cylinder(0.25, 0.35, 0.35, n).rotate((90, 0, 0))
        times = []
        for where in ((3.2, 0.1, 0.35), (0.8, 0, 0.35), (3.2, -0.5, 0.35)):
            best = float("inf")
            for _ in range(2):
                started = time.perf_counter()
                (body + wheel.translate(where)).num_tri()
                best = min(best, time.perf_counter() - started)
            times.append(best)
        print(f"{n:>8} {times[0]:>11.3f} {times[1]:>11.3f} {times[2]:>8.3f}")


def main() -> None:
    if "--engine" in sys.argv[1:]:
        engine()
        return
    print(f"{'-t':>6} {'polygons':>9} {'wall s':>7} {'CPU s':>7} {'peak MB':>8}")
    for tolerance in TOLERANCES:
        for _ in range(RUNS):
            polygons, wall, cpu, peak = car(tolerance)
            print(f"{tolerance:>6} {polygons:>9} {wall:>7.2f} {cpu:>7.2f} {peak:>8.0f}", flush=True)


if __name__ == "__main__":
    main()
