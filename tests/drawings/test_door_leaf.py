"""A door's closed leaf modelled in its opening (an unclassed solid wholly
inside the door's block, as examples/house.cas's 'battant') is the door's own:
a plan that cuts the door draws its symbol (the leaf open, the swing) and not
the closed leaf as a grey cut bar with its edges; a section still cuts it, and
an unclassed solid that only reaches into the opening stays as it is."""

from __future__ import annotations

import numpy as np

from tests.support.drawings import Drawn
from tests.support.symbols import HOUSE, ROOT, castor

# the door at x = 1 .. 1.9 in the south wall (y = 0 .. 0.2); its leaf closed,
# 4 cm thick, in the middle of the wall, unclassed
LEAF = "battant = @t(1, 0.08, 0) @h(0.9, 0.04, 2.1) !cu(0.6, 0.4, 0.2);\n"
WITH_LEAF = HOUSE.replace("maison = $U(murs,", LEAF + "maison = $U(murs, battant,")
# a bench from inside the room into the opening: not within it
BENCH = "banc = @t(1.2, 0.1, 0) @h(0.5, 1, 0.45) !cu(0.6, 0.4, 0.2);\n"
WITH_BENCH = HOUSE.replace("maison = $U(murs,", BENCH + "maison = $U(murs, banc,")


def plan(tmp_path, scene, *options) -> Drawn:
    castor(tmp_path, scene, *options, "-o", "d.svg")
    return Drawn((tmp_path / "d.svg").read_bytes(), 100)


def inside(points, x0, y0, x1, y1) -> bool:
    """Inside a door's block: between its jambs or on them, strictly inside
    across the wall."""
    p = np.asarray(points)
    return bool(np.all((p[:, 0] > x0 - 1e-6) & (p[:, 0] < x1 + 1e-6)
                       & (p[:, 1] > y0 + 1e-6) & (p[:, 1] < y1 - 1e-6)))


def within_opening(points) -> bool:
    return inside(points, 1, 0, 1.9, 0.2)


def test_a_plan_draws_the_doors_symbol_not_its_closed_leaf(tmp_path):
    drawn = plan(tmp_path, WITH_LEAF, "--section", "z=1.2")
    cuts = [loop for loops in drawn.cuts.values() for loop in loops]
    assert cuts  # the walls
    assert not [loop for loop in cuts if within_opening(loop)]
    lines = [p for group in drawn.lines.values() for p in group]
    assert not [p for p in lines if within_opening(p) and abs(p[0][0] - p[1][0]) > 1e-6]
    # as without the leaf: the same walls' cut, the door's arc
    bare = plan(tmp_path, HOUSE, "--section", "z=1.2")
    assert sorted(np.round(np.concatenate(cuts), 6).tolist()) == sorted(
        np.round(np.concatenate([c for cs in bare.cuts.values() for c in cs]), 6).tolist())
    legend = [t.text for t in drawn.root.iter("{http://www.w3.org/2000/svg}text")]
    assert "Unclassed" not in legend


def test_a_section_through_the_door_still_cuts_its_leaf(tmp_path):
    drawn = plan(tmp_path, WITH_LEAF, "--section", "x=1.45")
    # the leaf's cut, 0.04 m thick, 2.1 m high
    sizes = [tuple(np.round(loop.max(axis=0) - loop.min(axis=0), 3))
             for loops in drawn.cuts.values() for loop in loops]
    assert (0.04, 2.1) in sizes


def test_an_unclassed_solid_reaching_into_the_opening_stays(tmp_path):
    drawn = plan(tmp_path, WITH_BENCH, "--section", "z=0.3")
    sizes = [tuple(np.round(loop.max(axis=0) - loop.min(axis=0), 3))
             for loops in drawn.cuts.values() for loop in loops]
    assert (0.5, 1.0) in sizes
    assert "Unclassed" in [t.text for t in drawn.root.iter("{http://www.w3.org/2000/svg}text")]


def test_the_house_plans_front_door_is_drawn_once(tmp_path):
    drawn = plan(tmp_path, (ROOT / "examples" / "house.cas").read_text(), "--section", "z=1.2")
    cuts = [loop for loops in drawn.cuts.values() for loop in loops]
    # the door 'porte_trou' at x = 4 .. 5 in the south wall (y = 0 .. 0.3)
    assert not [loop for loop in cuts if inside(loop, 4, 0, 5, 0.3)]
    lines = [p for group in drawn.lines.values() for p in group]
    assert not [p for p in lines if inside(p, 4, 0, 5, 0.3)
                and abs(p[0][0] - p[1][0]) > 1e-6]
    arcs = [a for a in drawn.root.iter("{http://www.w3.org/2000/svg}path")
            if a.get("class") == "symbol" and "A" in a.get("d")]
    assert len(arcs) == 1
