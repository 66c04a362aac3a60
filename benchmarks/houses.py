"""A block of 64 houses (walls, 13 openings cut, a roof, 4 columns each):
castor against OpenSCAD (Debian's openscad 2021.01, CGAL), the same scene
written in each language, in the same run. Both write binary STL; the volumes
are compared so that the two really did the same work.

Target: castor at least 30x faster.
"""

import os
import shutil
import subprocess
import tempfile
import time

from _common import castor_command, runs_from_env

RUNS = runs_from_env(3)

CASTOR = """
L = 10; P = 8; H = 3; E = 0.3;
murs = $D(@h(L, P, H) !cu(0.9, 0.9, 0.8), @t(E, E, -1) @h(L - 2 * E, P - 2 * E, H + 2) !cu(0.9, 0.9, 0.8));
fen_s = @t(1 + K * 1.8, -1, 1) @h(1, 3, 1.2) !cu(0.2, 0.4, 0.9);
fen_n = @t(1 + K * 1.8, P - 2, 1) @h(1, 3, 1.2) !cu(0.2, 0.4, 0.9);
ouvertures = $U($U[K = 0, 4](fen_s), $U[K = 0, 4](fen_n),
                @t(-1, 3, 1) @h(3, 1, 1.2) !cu(0.2, 0.4, 0.9), @t(L - 2, 3, 1) @h(3, 1, 1.2) !cu(0.2, 0.4, 0.9),
                @t(4.5, -1, -0.5) @h(1, 3, 2.6) !cu(0.2, 0.4, 0.9));
toit = @t(L / 2, P / 2, H) @rz(45) @h(7.5, 7.5, 2.5) !py(0.7, 0.2, 0.1, 4);
colonne = @t(1 + C * 2.6, -1.5, 0) @h(0.2, 0.2, H) !pr(0.8, 0.8, 0.8, 16);
maison = $U($D(murs, ouvertures), toit, $U[C = 0, 3](colonne));
> $U[I = 0, 7]($U[J = 0, 7](@t(15 * I, 15 * J, 0) maison));
"""

OPENSCAD = """
L = 10; P = 8; H = 3; E = 0.3;
module murs() { difference() { cube([L, P, H]); translate([E, E, -1]) cube([L - 2 * E, P - 2 * E, H + 2]); } }
module ouvertures() {
  union() {
    for (k = [0:4]) translate([1 + k * 1.8, -1, 1]) cube([1, 3, 1.2]);
    for (k = [0:4]) translate([1 + k * 1.8, P - 2, 1]) cube([1, 3, 1.2]);
    translate([-1, 3, 1]) cube([3, 1, 1.2]);
    translate([L - 2, 3, 1]) cube([3, 1, 1.2]);
    translate([4.5, -1, -0.5]) cube([1, 3, 2.6]);
  }
}
module toit() { translate([L / 2, P / 2, H]) rotate([0, 0, 45]) scale([7.5, 7.5, 2.5]) cylinder(r1 = 1, r2 = 0, h = 1, $fn = 4); }
module colonne(c) { translate([1 + c * 2.6, -1.5, 0]) scale([0.2, 0.2, H]) cylinder(r = 1, h = 1, $fn = 16); }
module maison() { union() { difference() { murs(); ouvertures(); } toit(); for (c = [0:3]) colonne(c); } }
union() { for (i = [0:7]) for (j = [0:7]) translate([15 * i, 15 * j, 0]) maison(); }
"""


def stl_volume(path: str) -> float:
    import numpy as np

    with open(path, "rb") as handle:
        head = handle.read(5)
    if head == b"solid":  # ASCII STL (OpenSCAD 2021 writes ASCII)
        points = []
        for line in open(path):
            line = line.strip()
            if line.startswith("vertex"):
                points.append([float(x) for x in line.split()[1:4]])
        tri = np.array(points).reshape(-1, 3, 3)
    else:
        data = open(path, "rb").read()
        count = int.from_bytes(data[80:84], "little")
        record = np.dtype([("n", "<f4", 3), ("c", "<f4", (3, 3)), ("a", "<u2")])
        tri = np.frombuffer(data[84:84 + 50 * count], dtype=record)["c"].astype(float)
    return float(np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum() / 6)


def run_timed(command, cwd, runs):
    times = []
    for _ in range(runs):
        started = time.perf_counter()
        result = subprocess.run(command, cwd=cwd, capture_output=True)
        times.append(time.perf_counter() - started)
        if result.returncode != 0:
            raise SystemExit(f"{command[0]} failed: {result.stderr.decode()[-600:]}")
    return sorted(times)[len(times) // 2]


def main() -> None:
    work = tempfile.mkdtemp()
    with open(os.path.join(work, "houses.cas"), "w") as handle:
        handle.write(CASTOR)
    with open(os.path.join(work, "houses.scad"), "w") as handle:
        handle.write(OPENSCAD)
    castor = run_timed(castor_command() + ["-o", "castor.stl", "houses.cas"], work, RUNS)
    castor_volume = stl_volume(os.path.join(work, "castor.stl"))
    print(f"castor      {castor:8.3f} s   volume {castor_volume:.6f}")
    openscad = shutil.which("openscad")
    if openscad is None:
        print("openscad not installed (apt-get install openscad): no comparison")
        return
    version = subprocess.run([openscad, "--version"], capture_output=True, text=True)
    scad = run_timed([openscad, "-o", "openscad.stl", "houses.scad"], work, 1)
    scad_volume = stl_volume(os.path.join(work, "openscad.stl"))
    print(f"openscad    {scad:8.3f} s   volume {scad_volume:.6f}   "
          f"({(version.stderr or version.stdout).strip()}, one run)")
    print(f"castor is {scad / castor:.1f}x faster (target >= 30x); "
          f"volumes differ by {abs(castor_volume - scad_volume) / scad_volume:.2e} (relative)")


if __name__ == "__main__":
    main()
