"""Smooth solids: castor's subdivision (castor/mesh/subdivide.py) against the engine's.

For the unit cube smoothed everywhere (``@s(120) !cu``), level by level:

- castor: triangles written per second of ``subdivide.smooth`` (Catmull–Clark,
  creases, limit positions, the distance estimate, the look-ahead level);
- manifold3d: the cube made smooth (``smooth_out(180)``) then ``refine(n)``,
  the engine's own interpolating subdivision, triangles per second of
  ``refine`` alone; and its volume, which shows it bulging out of the cube
  (a smooth solid lies inside its control mesh: the Catmull–Clark limit has
  volume 0.3275).

And the issue's target: the whole command ``castor --tolerance 0.001`` on
``> @s(120) @h(5) !cu(1, 0, 0);`` (start-up, parsing, smoothing, the engine,
merging, writing), at most 2 s; its wall time and the CPU time it used (on
a machine shared with other work the wall time is the larger).

Each figure is the best of three runs.

    python benchmarks/smooth.py
"""

from __future__ import annotations

import time

import numpy as np


def cube():
    v = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    f = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
    return v, np.arange(0, 25, 4), np.array(f).ravel()


def best(run, times=3):
    seconds = []
    for _ in range(times):
        started = time.perf_counter()
        out = run()
        seconds.append(time.perf_counter() - started)
    return min(seconds), out


def volume(vertices, triangles):
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6)


def whole_command(text: str = "> @s(120) @h(5) !cu(1, 0, 0);", tolerance: float = 0.001):
    """Best of three: (wall seconds, CPU seconds) of castor run on ``text``."""
    import os
    import resource
    import subprocess
    import sys

    runs = []
    for _ in range(3):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        started = time.perf_counter()
        subprocess.run([sys.executable, "-m", "castor", "--no-cpp", "-q", "--tolerance",
                        str(tolerance)], input=text, text=True, capture_output=True, check=True,
                       env=dict(os.environ))
        wall = time.perf_counter() - started
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        runs.append((wall, after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime))
    return min(runs)


def main() -> None:
    import manifold3d

    from castor.mesh import subdivide

    print("castor: subdivide.smooth(unit cube, @s(120), tolerance)")
    print(f"{'tolerance':>10} {'levels':>6} {'triangles':>10} {'seconds':>8} {'tri/s':>12} "
          f"{'volume':>8} {'distance':>9}")
    for tolerance in (0.01, 0.001, 0.0002, 0.00005):
        seconds, out = best(lambda: subdivide.smooth(*cube(), 120, tolerance, 10 ** 8))
        print(f"{tolerance:>10g} {out.levels:>6} {len(out.triangles):>10,} {seconds:>8.3f} "
              f"{len(out.triangles) / seconds:>12,.0f} {volume(out.vertices, out.triangles):>8.4f} "
              f"{out.distance:>9.2e}")
    print("\nmanifold3d: Manifold.cube().smooth_out(180).refine(n)")
    print(f"{'n':>10} {'triangles':>10} {'seconds':>8} {'tri/s':>12} {'volume':>8}")
    smooth = manifold3d.Manifold.cube((1, 1, 1)).smooth_out(180, 0)
    for n in (8, 32, 64, 128):
        seconds, out = best(lambda: smooth.refine(n))
        triangles = out.num_tri()
        print(f"{n:>10} {triangles:>10,} {seconds:>8.3f} {triangles / seconds:>12,.0f} "
              f"{out.volume():>8.4f}")
    wall, cpu = whole_command()
    print(f"\nthe whole command, @s(120) @h(5) !cu at --tolerance 0.001: {wall:.2f} s "
          f"({cpu:.2f} s of CPU); the target is 2 s")


if __name__ == "__main__":
    main()
