"""An elevation's vertical chains and levels take the openings of the façade
it looks at, never those of a wall inside seen nowhere (a blank east wall with
a door in a partition behind it: the pavilion's east elevation marked the
upstairs door's head +5.10)."""

from __future__ import annotations

from tests.support.symbols import SVG, svg_of

SCENE = """\
R0 = 0;  // [storey "Rez"]
murs = $D(@h(8, 6, 2.8) !cu(1, 1, 1), @t(0.2, 0.2, -0.1) @h(7.6, 5.6, 3) !cu(1, 1, 1));  // [wall]
porte = @t(3.9, 2, -0.1) @h(0.3, 0.9, 2.2) !cu(0, 0, 1);  // [door]
cloison = $D(@t(3.95, 0.2, 0) @h(0.1, 5.6, 2.8) !cu(1, 1, 1), porte);  // [wall]
> $U(murs, cloison);
"""


def _texts(root, group: str) -> list[str]:
    return [t.text for t in root.find(f"{SVG}g[@id='{group}']").iter(f"{SVG}text")]


def test_a_blank_facade_has_no_chain_break_or_level_from_a_door_inside(tmp_path):
    root, _, _ = svg_of(tmp_path, SCENE, "--view", "right", "--scale", "1:50")
    assert "+2.10" not in _texts(root, "levels")
    assert "2.10" not in _texts(root, "dimensions")
    assert "+2.80" in _texts(root, "levels")  # the top is still marked
