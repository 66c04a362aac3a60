"""The seed benchmark: the union of two spheres, from 16 to 100,000+ facets each.

castor (a whole process, writing binary STL) against a script calling
manifold3d directly and writing the same binary STL with numpy, in the same
run; time per output triangle, and the 1986 figures beside.
"""

import math
import os
import sys
import tempfile

from _common import castor_command, runs_from_env, table, timed

RUNS = runs_from_env(3)
# 1986, the best CSG evaluator of its day (the figures the brief quotes):
# facets per sphere -> seconds. Only these two are known here.
PAPER = {16: 1.6, 4096: 145.7}

DIRECT = r'''
import sys, numpy as np, manifold3d as m
segments = int(sys.argv[1]); out = sys.argv[2]
a = m.Manifold.sphere(1.0, segments)
b = a.translate([0.5, 0.3, 0.2])
u = a + b
mesh = u.to_mesh64()
v = np.asarray(mesh.vert_properties)[:, :3]
t = np.asarray(mesh.tri_verts, dtype=np.int64)
c = v[t]
n = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
rec = np.zeros(len(t), dtype=[("n", "<f4", 3), ("c", "<f4", (3, 3)), ("a", "<u2")])
rec["n"] = n; rec["c"] = c
with open(out, "wb") as f:
    f.write(b"direct".ljust(80, b" ")); f.write(np.uint32(len(t)).tobytes()); f.write(rec.tobytes())
'''


def sphere_tolerance(facets: int) -> float:
    """The tolerance that gives castor's unit sphere about this many facets.

    castor's sphere has 2*a*r triangles with a = 2r; its step is 2*pi/a and
    step = sqrt(2) * acos(1 - t).
    """
    around = max(8, round(math.sqrt(facets)))
    step = 2 * math.pi / around
    return 1 - math.cos(step / math.sqrt(2)) * (1 - 1e-9)


def triangles_in(path: str) -> int:
    with open(path, "rb") as handle:
        handle.seek(80)
        return int.from_bytes(handle.read(4), "little")


def main() -> None:
    rows = []
    work = tempfile.mkdtemp()
    script = os.path.join(work, "direct.py")
    with open(script, "w") as handle:
        handle.write(DIRECT)
    for facets in [16, 64, 256, 1024, 4096, 16384, 65536, 131072, 524288]:
        tolerance = sphere_tolerance(facets)
        scene = b"> $U(!sp(1, 1, 1), @t(0.5, 0.3, 0.2) !sp(1, 0, 0));\n"
        out = os.path.join(work, "castor.stl")
        castor = timed(castor_command() + ["--no-cpp", "-t", repr(tolerance), "-o", out],
                       stdin=scene, runs=RUNS)
        castor_tris = triangles_in(out)
        # manifold3d's sphere of n circular segments has about n*n/2 triangles:
        # match castor's facets per sphere
        around = max(8, round(math.sqrt(facets)))
        per_sphere = 2 * around * max(4, around // 2)
        segments = max(8, round(math.sqrt(2 * per_sphere)))
        direct_out = os.path.join(work, "direct.stl")
        direct = timed([sys.executable, script, str(segments), direct_out], runs=RUNS)
        direct_tris = triangles_in(direct_out)
        per_castor = castor / castor_tris * 1e6
        per_direct = direct / direct_tris * 1e6
        paper = PAPER.get(facets)
        rows.append([facets, castor_tris, f"{castor:.3f}", f"{per_castor:.2f}",
                     direct_tris, f"{direct:.3f}", f"{per_direct:.2f}",
                     f"{per_castor / per_direct:.2f}", f"{paper:.1f}" if paper else "-"])
    print(table(rows, ["facets/sphere", "castor tris", "castor s", "us/tri",
                       "direct tris", "direct s", "us/tri", "ratio", "1986 s"]))
    print("\nratio: castor's time per output triangle over manifold3d called directly "
          "(target <= 1.5); whole processes, including start-up.")


if __name__ == "__main__":
    main()
