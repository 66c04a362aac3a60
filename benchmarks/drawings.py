"""Drawings: the house's plan (z = 1.2) with its dimensions and title block,
on an A3 sheet and not, section and front elevation, the bus shelter's
front elevation and plan, and a generated plan of 200 rooms, as SVG, DXF and
PDF; whole processes (start-up, parsing and facetization included).

Targets: the house's plan with its dimensions and sheet <= 1 s; the bus
shelter's elevation <= 5 s; the 200-room plan <= 10 s. With the classes
(issue 31): the house's plan with every symbol its classes give (door,
windows, eaves dashed, hatches by class, legend) <= 1 s, the pavilion's plan
(door, windows, stair, rooms, hatches) likewise; the pavilion's set of five
sheets (two plans, a section, two elevations) as one PDF <= 5 s.
"""

import os
import tempfile

from _common import castor_command, runs_from_env, table, timed

RUNS = runs_from_env(5)
EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples")

# 20 x 10 rooms of 4 x 3.5 m, outer walls 0.3 m, inner 0.15 m, a door from each
# room to the south (the southern ones through the outer wall), a window in each
# northern room: 200 rooms, 220 openings
ROOMS = """
NX = 20; NY = 10; W = 4; D = 3.5; E = 0.3; IW = 0.15; H = 3;
LX = E + NX * W - IW + E;
LY = E + NY * D - IW + E;
plein = @h(LX, LY, H) !cu(0.9, 0.9, 0.85);
pieces = $U[I = 0, NX - 1]($U[J = 0, NY - 1](@t(E + I * W, E + J * D, -1)
         @h(W - IW, D - IW, H + 2) !cu(0.9, 0.9, 0.85)));
portes = $U[I = 0, NX - 1]($U[J = 0, NY - 1](@t(E + I * W + 1, E + J * D - 0.5, -0.1)
         @h(0.9, 0.6, 2.2) !cu(0.3, 0.4, 0.8)));
fenetres = $U[I = 0, NX - 1](@t(E + I * W + 1.5, LY - E - 0.1, 0.9) @h(1.2, E + 0.2, 1.2)
           !cu(0.3, 0.4, 0.8));
batiment = $D(plein, $U(pieces, portes, fenetres));
> batiment;
"""

CASES = [
    ("house plan z=1.2", "house.cas", ["--section", "z=1.2"]),
    ("house plan z=1.2, A3 sheet", "house.cas", ["--section", "z=1.2", "--sheet", "A3"]),
    ("house front elevation", "house.cas", ["--view", "front"]),
    ("house section x=3", "house.cas", ["--section", "x=3"]),
    ("bus shelter front elevation", "bus_shelter.cas", ["-D", "ONE_FRAME", "--view", "front"]),
    ("bus shelter plan z=1.2", "bus_shelter.cas", ["-D", "ONE_FRAME", "--section", "z=1.2"]),
    ("200-room plan z=1.2", "ROOMS", ["--section", "z=1.2", "--scale", "1:200"]),
    ("pavilion plan z=1.2 (every symbol), A3", "pavilion.cas",
     ["--section", "z=1.2", "--sheet", "A3", "--scale", "1:50"]),
]


def sets(tmp: str) -> list:
    """The pavilion's five sheets (its register, examples/pavilion-sheets.toml) as
    one PDF and as one DXF."""
    register = os.path.join(EXAMPLES, "pavilion-sheets.toml")
    row = ["pavilion set of five sheets"]
    for suffix in (".pdf", ".dxf"):
        out = os.path.join(tmp, "set" + suffix)
        before = os.times()
        seconds = timed([*castor_command(), "-q", "--sheets", register, "-o", out,
                         "pavilion.cas"], runs=RUNS, cwd=EXAMPLES)
        after = os.times()
        cpu = (after.children_user + after.children_system
               - before.children_user - before.children_system) / RUNS
        row.append(f"{seconds:.2f} s ({cpu:.2f} s CPU)")
    return row


def main() -> None:
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        rooms = os.path.join(tmp, "rooms.cas")
        with open(rooms, "w") as handle:
            handle.write(ROOMS)
        for label, source, options in CASES:
            source = rooms if source == "ROOMS" else source
            row = [label]
            for suffix in (".svg", ".dxf", ".pdf"):
                out = os.path.join(tmp, "d" + suffix)
                before = os.times()
                seconds = timed([*castor_command(), "-q", *options, "-o", out, source],
                                runs=RUNS, cwd=EXAMPLES)
                after = os.times()
                # the processor time the runs took, which a loaded machine does not inflate
                cpu = (after.children_user + after.children_system
                       - before.children_user - before.children_system) / RUNS
                row.append(f"{seconds:.2f} s ({cpu:.2f} s CPU)")
            row.append(f"{os.path.getsize(os.path.join(tmp, 'd.svg')) / 1000:.0f} kB")
            rows.append(row)
        set_row = sets(tmp)
    print(table(rows, ["drawing", "SVG, whole process", "DXF, whole process",
                       "PDF, whole process", "SVG size"]))
    print()
    print(table([set_row], ["drawing set (--sheets)", "one PDF, whole process",
                            "one DXF, whole process"]))


if __name__ == "__main__":
    main()
