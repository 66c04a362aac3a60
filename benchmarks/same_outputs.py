"""Do two checkouts of castor write the same bytes? The redesign's check.

For every example and a few small scenes, castor writes the polygon stream,
STL, GLB, OFF, PLY, OBJ, a picture, an elevation and a plan in SVG and DXF;
this prints the SHA-256 of each output, or compares two checkouts:

    python benchmarks/same_outputs.py --record before.json            # this checkout
    python benchmarks/same_outputs.py --record after.json --repo ../other
    python benchmarks/same_outputs.py --compare before.json after.json

Each run uses ``python -m castor`` with the checkout first on PYTHONPATH, so
one installed environment serves both. A DXF's dates and GUIDs, which ezdxf
writes anew at every run, are left out of its sum.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import re
import subprocess
import sys
import tempfile

EXAMPLES = ["house.cas", "car.cas", "door.cas", "staircase.cas", "bus_shelter.cas"]

# Small scenes that reach what the examples do not: every primitive, mirrors,
# coincident faces, repetition, a cavity.
SCENES = {
    "primitives": """
> $U(!cu(1, 0, 0), @t(2, 0, 0) !sp(0, 1, 0), @t(4, 0, 0) !cy(0, 0, 1),
     @t(6, 0, 0) !co(1, 1, 0), @t(8, 0, 0) !to(0, 1, 1, 0.3), @t(10, 0, 0) !pr(1, 0, 1, 6),
     @t(12, 0, 0) !py(0.5, 0.5, 0.5, 5), @t(14, 0, 0) !ex(1, 0.5, 0, 0, 0, 1, 0, 1, 1, 0.5, 0.4, 0, 1),
     @t(16, 0, 0) !rv(0.2, 0.3, 0.4, 0, 0, 1, 0, 0.5, 0.5, 0.3, 1, 0, 1));
""",
    "booleans": """
b = @h(2) !cu(0.9, 0.9, 0.9);
> $D(b, $U(@t(0.5, 0.5, -1) @h(1, 1, 4) !cu(1, 0, 0), @t(1, 1, 1) @h(0.6) !sp(0, 0, 1)));
> $I(b, @t(1, 1, 1) @h(1.3) !sp(0, 1, 0)), @t(3, 0, 0) @h(-1, 1, 1) $D(b, @t(1, 1, 0.5) @h(0.4, 0.4, 3) !cy(1, 1, 0));
> $U[I = 0, 4](@t(I, 0, 0) @rz(I * 17) !cu(0.2 * I, 0.5, 0.5));
> $D(@h(3) !cu(1, 1, 1), @t(1, 1, 1) !cu(1, 0, 0));
""",
    "column": """
> @h(1, 1, 3) !pr(0.8, 0.8, 0.8, 10), @t(3, 0, 0) @h(0.25, 0.25, 3) !cy(0.8, 0.8, 0.8);
""",
}

# (suffix, extra options)
OUTPUTS = [
    ("cps", []),
    ("stl", []),
    ("glb", []),
    ("off", []),
    ("ply", []),
    ("obj", []),
    ("png", ["--size", "160x120", "--samples", "2"]),
    ("svg", ["--view", "front"]),
    ("dxf", ["--section", "z=1"]),
]


# What ezdxf writes differently at every run: dates, GUIDs, its own time stamp.
_STAMP = re.compile(rb"^(\d{7}\.\d+|\{[0-9A-F-]{36}\}|\d+\.\d+\.\d+ @ [0-9T:.+-]+)\r?$", re.M)


def _without_stamps(data: bytes) -> bytes:
    return _STAMP.sub(b"STAMP", data)


def run_all(repo: str) -> dict[str, str]:
    # ezdxf orders some objects by hash: a fixed seed makes its files repeatable.
    env = dict(os.environ, PYTHONPATH=os.path.abspath(repo), PYTHONHASHSEED="0")
    sums: dict[str, str] = {}
    with tempfile.TemporaryDirectory() as tmp:
        sources = [(name, os.path.join(os.path.abspath(repo), "examples", name))
                   for name in EXAMPLES]
        for name, text in SCENES.items():
            path = os.path.join(tmp, name + ".cas")
            with open(path, "w") as f:
                f.write(text)
            sources.append((name, path))
        for name, path in sources:
            for suffix, extra in OUTPUTS:
                single = suffix not in ("cps",)
                out = os.path.join(tmp, f"{name}-%03d.{suffix}" if single else f"{name}.{suffix}")
                if name == "bus_shelter.cas" and suffix in ("png", "svg", "dxf"):
                    extra = extra + ["-D", "ONE_FRAME"]
                command = [sys.executable, "-m", "castor", "-q", "-o", out, *extra, path]
                result = subprocess.run(command, env=env, capture_output=True,
                                        cwd=os.path.dirname(path))
                key = f"{name} {suffix}"
                if result.returncode != 0:
                    sums[key] = f"exit {result.returncode}: {result.stderr.decode()[-200:]}"
                    continue
                written = sorted(f for f in os.listdir(tmp)
                                 if f.startswith(name + "-") or f == f"{name}.{suffix}")
                digest = hashlib.sha256()
                for f in written:
                    if f.endswith("." + suffix) or f.endswith(".mtl"):
                        with open(os.path.join(tmp, f), "rb") as handle:
                            data = handle.read()
                        if f.endswith(".dxf"):
                            data = _without_stamps(data)
                        digest.update(f.encode() + b"\0" + data)
                        os.remove(os.path.join(tmp, f))
                sums[key] = digest.hexdigest()
                print(f"{key:28s} {sums[key][:16]}", file=sys.stderr)
    return sums


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repo", default=os.path.join(os.path.dirname(__file__), ".."))
    parser.add_argument("--record", metavar="JSON")
    parser.add_argument("--compare", nargs=2, metavar=("BEFORE", "AFTER"))
    args = parser.parse_args()
    if args.compare:
        before, after = (json.load(open(p)) for p in args.compare)
        differ = [k for k in sorted(set(before) | set(after)) if before.get(k) != after.get(k)]
        for key in differ:
            print(f"differs: {key}")
        print(f"{len(before) - len(differ)} of {len(before)} outputs the same byte for byte")
        return 1 if differ else 0
    sums = run_all(args.repo)
    if args.record:
        with open(args.record, "w") as f:
            json.dump(sums, f, indent=1, sort_keys=True)
    else:
        json.dump(sums, sys.stdout, indent=1, sort_keys=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
