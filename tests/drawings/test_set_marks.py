"""The marks a plan of a drawing set carries (castor.drawings.marks): each
section's cut line and sheet number, each elevation's triangle and number,
stand clear of the plan's dimension chains (read back from the SVG)."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import numpy as np

from castor.drawings.paper import text_width
from tests.support.symbols import HOUSE, SVG, castor, register

REGISTER = register(("A-101", "plan z=1.2"), ("A-201", "section x=3"), ("A-202", "section y=2"),
                    ("A-301", "elevation front"), ("A-302", "elevation right"), title="Maison")
NUMBERS = ("A-201", "A-202", "A-301", "A-302")


def _segments(group) -> list:
    """The straight segments of a group's paths (M x y L x y ... pairs)."""
    out = []
    for path in group.iter(f"{SVG}path"):
        for a, b, c, d in re.findall(r"M([-\d.]+) ([-\d.]+)L([-\d.]+) ([-\d.]+)", path.get("d")):
            out.append(((float(a), float(b)), (float(c), float(d))))
    return out


def _crosses(segment, box) -> bool:
    """Whether a segment passes through a box (paper mm), sampled every 0.05 mm."""
    (x0, y0), (x1, y1) = box
    p, q = np.array(segment)
    n = max(2, int(np.linalg.norm(q - p) / 0.05) + 2)
    points = p + np.linspace(0, 1, n)[:, None] * (q - p)
    return bool(np.any((points[:, 0] > x0) & (points[:, 0] < x1)
                       & (points[:, 1] > y0) & (points[:, 1] < y1)))


def _plan(tmp_path) -> ET.Element:
    (tmp_path / "r.toml").write_text(REGISTER)
    castor(tmp_path, HOUSE, "--sheets", "r.toml", "-o", "sheet-%d.svg")
    return ET.fromstring((tmp_path / "sheet-1.svg").read_bytes())


def test_no_mark_or_its_number_touches_a_chain(tmp_path):
    root = _plan(tmp_path)
    chains = _segments(root.find(f"{SVG}g[@id='dimensions']"))
    symbols = root.find(f"{SVG}g[@id='symbols']")
    assert len(chains) > 20
    labels = [t for t in symbols.iter(f"{SVG}text") if t.text in NUMBERS]
    # two ends of each section's cut line, one triangle per elevation
    assert sorted(t.text for t in labels) == ["A-201", "A-201", "A-202", "A-202", "A-301", "A-302"]
    boxes = []
    for text in labels:
        x, y, size = (float(text.get(k)) for k in ("x", "y", "font-size"))
        assert text.get("text-anchor") == "middle" and text.get("transform") is None
        w = text_width(text.text, size) / 2 + 0.5  # half a mm clear all round
        box = ((x - w, y - size - 0.5), (x + w, y + 0.3 * size + 0.5))
        boxes.append(box)
        hits = [s for s in chains if _crosses(s, box)]
        assert not hits, f"{text.text} at ({x:.1f}, {y:.1f}) meets a chain line: {hits[:2]}"
    # and the heavy cut lines cross no chain either
    heavy = [p for p in symbols.iter(f"{SVG}path") if p.get("stroke-width") == "0.5"]
    assert len(heavy) == 1
    cuts = _segments(heavy[0])
    assert len(cuts) == 4
    for (p, q) in cuts:
        thin = ((min(p[0], q[0]) - 0.01, min(p[1], q[1]) - 0.01),
                (max(p[0], q[0]) + 0.01, max(p[1], q[1]) + 0.01))
        assert not any(_crosses(s, thin) for s in chains)
    # nor do two numbers overlap
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:]:
            assert not (a[0][0] < b[1][0] and b[0][0] < a[1][0]
                        and a[0][1] < b[1][1] and b[0][1] < a[1][1])


def test_the_marks_stay_on_the_paper_inside_the_border(tmp_path):
    root = _plan(tmp_path)
    symbols = root.find(f"{SVG}g[@id='symbols']")
    points = np.array([p for s in _segments(symbols) for p in s])
    for text in symbols.iter(f"{SVG}text"):
        points = np.vstack([points, [float(text.get("x")), float(text.get("y"))]])
    # A3 landscape, the border 10 mm in
    assert points[:, 0].min() > 10 and points[:, 0].max() < 410
    assert points[:, 1].min() > 10 and points[:, 1].max() < 287
