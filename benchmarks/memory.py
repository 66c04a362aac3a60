"""Peak memory per output polygon, for large frames.

Each scene runs in a fresh process; the figure is that process's peak
resident memory (ru_maxrss) over the polygons of its frame. Four ways:

- "facetize": castor's own pipeline (evaluation, booleans, the engine's
  triangles, polygon merging, the frame's arrays), the writer replaced by a
  counter, so the figure is the geometry's alone;
- "stl": the whole command, `castor --no-cpp -f stl -o scene.stl` (its
  count is of triangles, read from the file);
- "cps file": the whole command writing the polygon stream (the default
  format) to a file, `castor --no-cpp -o scene.cps`;
- "cps pipe": the same to standard output, `castor --no-cpp | tail -n 1`
  (tail reads all of it, as wc would, and keeps the count of 'endframe').

No --stats: its figures (volume, area, shells of each object) take memory
of their own, as much again as the writers for large frames.

    python memory.py            # the default set (about a minute, 3 GB at most)
    python memory.py --large    # also 5 M polygons of spheres (needs ~3 GB)
"""

from __future__ import annotations

import argparse
import json
import os
import shlex
import subprocess
import sys
import tempfile

from _common import castor_command, table

FACETIZE = r'''
import json, resource, sys, time
import castor.formats.output as output
counts = []
def encode(frame, name, target=None):
    counts.append(frame.polygon_count)
    return b"", {}
output.encode = encode  # what castor.jobs calls when it encodes a frame (before)
output.encode_pieces = lambda frame, name, target=None, **info: (iter([encode(frame, name)[0]]), {})
output.Output.start = lambda self: None
output.Output.put = lambda self, *args: None
output.Output.finish = lambda self, had_errors: True
from castor import cli
started = time.perf_counter()
status = cli.main(["--no-cpp", "-q", *sys.argv[1:]])
seconds = time.perf_counter() - started
print(json.dumps({"status": status, "polygons": sum(counts), "seconds": seconds,
                  "peak": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024}))
'''

WHOLE = r'''
import json, resource, subprocess, sys, time
started = time.perf_counter()
result = subprocess.run(sys.argv[1], shell=True, stderr=subprocess.PIPE, text=True)
seconds = time.perf_counter() - started
print(json.dumps({"status": result.returncode, "stderr": result.stderr[-400:], "seconds": seconds,
                  "peak": resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024}))
'''


HOWS = ("facetize", "stl", "cps file", "cps pipe")


def spheres(count: int, tolerance: float) -> str:
    return (f"TOLERANCE = {tolerance};\n"
            f"> $U[I = 0, {count - 1}](@t(3 * I, 0, 0) !sp(1, 1, 1));\n")


def cubes(count: int) -> str:
    side = 500
    return (f"> $U[I = 0, {count - 1}](@t(2 * (I % {side}), 2 * floor(I / {side}), 0) "
            f"!cu(1, 1, 1));\n")


def measure(scene: str, how: str) -> dict:
    with tempfile.NamedTemporaryFile("w", suffix=".cas", delete=False) as handle:
        handle.write(scene)
    # no --stats: its figures (volume, area, shells) cost memory of their own
    castor = [*castor_command(), "--no-cpp", "-q", handle.name]
    written = handle.name[:-4] + (".stl" if how == "stl" else ".cps")
    if how == "facetize":
        command = [sys.executable, "-c", FACETIZE, handle.name]
    else:
        # WHOLE's peak is its children's largest: castor's (tail's is tiny)
        shell = {"stl": shlex.join([*castor, "-f", "stl", "-o", written]),
                 "cps file": shlex.join([*castor, "-o", written]),
                 "cps pipe": shlex.join(castor) + " | tail -n 1"}[how]
        command = [sys.executable, "-c", WHOLE, shell]
    polygons = None
    try:
        result = subprocess.run(command, capture_output=True, text=True)
        if how == "stl" and os.path.exists(written):  # the triangle count in its header
            with open(written, "rb") as stl:
                polygons = int.from_bytes(stl.read(84)[80:], "little")
        elif how == "cps file" and os.path.exists(written):
            with open(written, "rb") as stream:
                stream.seek(-100, os.SEEK_END)
                polygons = int(stream.read().splitlines()[-1].split()[-1])
    finally:
        for name in (handle.name, written):
            if os.path.exists(name):
                os.unlink(name)
    if result.returncode != 0:
        raise SystemExit(result.stderr[-2000:])
    lines = result.stdout.strip().splitlines()
    figures = json.loads(lines[-1])
    if figures["status"] != 0:
        raise SystemExit(figures.get("stderr", "")[-2000:])
    if how == "cps pipe":  # tail's line: "endframe 1 COUNT"
        polygons = int(lines[-2].split()[-1])
    if polygons is not None:
        figures["polygons"] = polygons
    return figures


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--large", action="store_true")
    parser.add_argument("--how", action="append", choices=HOWS,
                        help="measure only this way (repeatable); all four by default")
    args = parser.parse_args()
    cases = [
        ("10 spheres, TOLERANCE 0.0001", spheres(10, 0.0001)),
        ("30 spheres, TOLERANCE 0.0001", spheres(30, 0.0001)),
        ("union of 200,000 disjoint cubes", cubes(200_000)),
    ]
    if args.large:
        cases.append(("86 spheres, TOLERANCE 0.0001", spheres(86, 0.0001)))
    rows = []
    for name, scene in cases:
        for how in args.how or HOWS:
            f = measure(scene, how)
            rows.append([name, how, f"{f['polygons']:,}", f"{f['seconds']:.1f}",
                         f"{f['peak'] / 1e9:.2f}", f"{f['peak'] / max(f['polygons'], 1):.0f}"])
            print(rows[-1], file=sys.stderr)
    print(table(rows, ["scene", "measured", "polygons", "seconds", "peak GB", "B/polygon"]))


if __name__ == "__main__":
    main()
