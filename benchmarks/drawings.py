"""Drawings: the house's plan (z = 1.2) and front elevation, the bus
shelter's front elevation and plan, as SVG and DXF; whole processes
(start-up, parsing and facetization included).

Targets: the house's plan and elevation each <= 1 s; the bus shelter's
elevation <= 5 s.
"""

import os
import tempfile

from _common import castor_command, runs_from_env, table, timed

RUNS = runs_from_env(5)
EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples")

CASES = [
    ("house plan z=1.2", "house.cas", ["--section", "z=1.2"]),
    ("house front elevation", "house.cas", ["--view", "front"]),
    ("house section x=3", "house.cas", ["--section", "x=3"]),
    ("bus shelter front elevation", "bus_shelter.cas", ["-D", "ONE_FRAME", "--view", "front"]),
    ("bus shelter plan z=1.2", "bus_shelter.cas", ["-D", "ONE_FRAME", "--section", "z=1.2"]),
]


def main() -> None:
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for label, source, options in CASES:
            row = [label]
            for suffix in (".svg", ".dxf"):
                out = os.path.join(tmp, "d" + suffix)
                seconds = timed([*castor_command(), *options, "-o", out, source],
                                runs=RUNS, cwd=EXAMPLES)
                row.append(f"{seconds:.2f} s")
            row.append(f"{os.path.getsize(os.path.join(tmp, 'd.svg')) / 1000:.0f} kB")
            rows.append(row)
    print(table(rows, ["drawing", "SVG, whole process", "DXF, whole process", "SVG size"]))


if __name__ == "__main__":
    main()
