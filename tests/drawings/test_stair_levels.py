"""A section through a stair (docs/drawings.md, "Levels"): the stair's treads,
cut or seen, are no levels; the storeys, the top and the sills and heads of
the openings cut come first, then the cut's other horizontal edges (a slab's
underside) as room allows. Read back from the SVG's ``levels`` group."""

from __future__ import annotations

from tests.support.scenes import TRIAL_HOUSE as HOUSE
from tests.support.symbols import levels, svg_of

# 10 x 6 m, storeys at 0 and 3.2; a stair of 17 risers (3.2 / 17 = 0.188 m)
# at x = 8.7 .. 9.7 going north; in the south wall windows at x = 5 .. 6.5 and
# 8 .. 9.5, sill 1.0, head 2.2; the upper floor 0.25 thick (its underside at
# 2.95) with a well over the stair; a roof 0.3 on top at 6.4

TREADS = {f"+{k * 3.2 / 17:.2f}" for k in range(1, 17)}


def test_a_section_through_a_stair_marks_no_tread(tmp_path):
    root, _, said = svg_of(tmp_path, HOUSE, "--section", "x=9", "--sheet", "A3",
                           "--scale", "1:50")
    shown = levels(root)
    assert not TREADS & set(shown), shown
    # the storeys, the top, the ground slab's underside
    assert {"±0.00", "+3.20", "+6.70", "-0.25"} <= set(shown), shown
    # the window cut: its sill and head; the upper floor's underside
    assert {"+1.00", "+2.20", "+2.95"} <= set(shown), shown
    assert said == ""


def test_a_stair_seen_beyond_the_cut_marks_no_tread(tmp_path):
    # cut at x = 8.5, the stair (x = 8.7 .. 9.7) is seen behind the window
    root, _, _ = svg_of(tmp_path, HOUSE, "--section", "x=8.5", "--sheet", "A3",
                        "--scale", "1:50")
    shown = levels(root)
    assert not TREADS & set(shown), shown
    assert {"±0.00", "+1.00", "+2.20", "+3.20"} <= set(shown), shown


def test_a_sill_comes_before_an_edge_of_the_cut_below_it(tmp_path):
    # a bench 0.8 m high cut at x = 6: at 1:100 its top (0.2 m = 2 mm below the
    # sill) and the window's sill cannot both be shown; the sill is
    scene = HOUSE.replace("house = $U(", "bench = @t(4, 3, 0) @h(3, 0.5, 0.8) !cu(1, 1, 1);\n"
                          "house = $U(bench, ")
    root, _, _ = svg_of(tmp_path, scene, "--section", "x=6", "--sheet", "A3",
                        "--scale", "1:100")
    shown = levels(root)
    assert {"±0.00", "+1.00", "+2.20", "+3.20", "+6.70"} <= set(shown), shown
    assert "+0.80" not in shown
