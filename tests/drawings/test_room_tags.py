"""Room tags (castor.drawings.rooms): a space the plan cuts gets its tag inside
it, where it fits nearest its middle; a space too small for its tag at the
scale, or empty, is reported by name and FILE:LINE."""

from __future__ import annotations

import numpy as np

from castor.drawings.paper import text_width
from tests.support.symbols import SVG, svg_of

WALLS = """\
R0 = 0;  // [storey "Rez"]
murs = $D(@h(8, 6, 2.8) !cu(1, 1, 1), @t(0.2, 0.2, -0.1) @h(7.6, 5.6, 3) !cu(1, 1, 1));  // [wall]
"""
# an L: its centroid is inside, but its tag there would cross the inner corner
L_ROOM = WALLS + """\
a = @t(0.2, 0.2, 0) @h(7.6, 1.4, 2.8) !cu(1, 1, 1);
b = @t(0.2, 0.2, 0) @h(1.4, 5.6, 2.8) !cu(1, 1, 1);
piece = $U(a, b);  // [space "Salle de séjour"]
placard = @t(6.8, 5, 0) @h(0.5, 0.4, 2.8) !cu(1, 1, 1);  // [space "Placard"]
vide = $D(@h(1, 1, 1) !cu(1, 1, 1), @t(-1, -1, -1) @h(3, 3, 3) !cu(1, 1, 1));  // [space "Vide"]
> $U(murs, piece, placard, vide);
"""


def _tags(root) -> dict:
    """name -> (x, y) of each room tag's first line (paper mm)."""
    symbols = root.find(f"{SVG}g[@id='symbols']")
    texts = list(symbols.iter(f"{SVG}text"))
    return {t.text: (float(t.get("x")), float(t.get("y"))) for t in texts
            if t.get("font-size") == "3"}


def test_a_tag_goes_where_it_fits_and_a_space_too_small_is_reported(tmp_path):
    root, back, said = svg_of(tmp_path, L_ROOM, "--section", "z=1.2", "--scale", "1:50")
    warnings = [line for line in said.splitlines() if ": warning: " in line]
    assert warnings == [
        "s.cas:8:1: warning: space 'vide' (s.cas:7) is empty: it has no room tag",
        "s.cas:8:1: warning: space 'placard' (s.cas:6) is too small at 1:50 for its room tag: "
        "the tag is drawn over its outline"]
    tags = _tags(root)
    assert set(tags) == {"Salle de séjour", "Placard"}
    # the L's tag lies wholly inside the L: both its lines, in metres
    x, y = tags["Salle de séjour"]
    half = text_width("Salle de séjour", 3.0) / 2
    for px, py in ((x - half, y - 1.5), (x + half, y - 1.5), (x - half, y + 3.9 + 1.25),
                   (x + half, y + 3.9 + 1.25)):
        mx, my = back(px, py)
        in_a = 0.2 < mx < 7.8 and 0.2 < my < 1.6
        in_b = 0.2 < mx < 1.6 and 0.2 < my < 5.8
        assert in_a or in_b, (mx, my)
    # the area is the L's, to 0.01
    areas = [t.text for t in root.iter(f"{SVG}text") if t.text and t.text.endswith("m²")]
    assert f"{7.6 * 1.4 + 1.4 * 4.2:.2f} m²" in areas


def test_at_a_smaller_scale_the_cupboard_tag_fits_nowhere_and_still_reported(tmp_path):
    _, _, said = svg_of(tmp_path, L_ROOM, "--section", "z=1.2", "--scale", "1:200")
    assert any("space 'placard' (s.cas:6) is too small at 1:200 for its room tag" in line
               for line in said.splitlines())


def test_at_1_100_the_l_tag_leaves_the_middle_where_it_would_cross_the_corner(tmp_path):
    root, back, _ = svg_of(tmp_path, L_ROOM, "--section", "z=1.2", "--scale", "1:100")
    x, y = _tags(root)["Salle de séjour"]
    mx, my = back(x, y)
    assert (round(mx, 2), round(my, 2)) != (0.9, 1.9)  # the middle, where it does not fit
    half = text_width("Salle de séjour", 3.0) / 2
    for px, py in ((x - half, y - 1.5), (x + half, y - 1.5), (x - half, y + 3.9 + 1.25),
                   (x + half, y + 3.9 + 1.25)):
        mx, my = back(px, py)
        assert (0.2 < mx < 7.8 and 0.2 < my < 1.6) or (0.2 < mx < 1.6 and 0.2 < my < 5.8)
