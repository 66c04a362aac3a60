"""Plan annotations are not drawn across each other (issue 29): a door
swinging out of the south wall pushes that side's dimension chains out past
its leaf and swing, as a draughtsman moves them; and a dimension value never
sits under a section's cut line across the plan: it moves along its
dimension. Read back from the SVG and the DXF, in the page's mm."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from castor.drawings.paper import CHAIN_LINE, OVERALL_LINE, text_width
from tests.support.symbols import HOUSE, SVG, castor, register, svg_of

# the house's door 1 m wide at x = 2 .. 3, hinged on the right, opening out:
# its leaf and swing reach 1 m (20 mm at 1:50) below the south wall
OUT = HOUSE.replace("porte = @t(1, -0.1, 0) @h(0.9, 0.4, 2.1) !cu(0, 0, 1);  "
                    "// [door hinge=left swing=in]",
                    "porte = @t(2, -0.1, 0) @h(1, 0.4, 2.1) !cu(0, 0, 1);  "
                    "// [door hinge=right swing=out]")
# a section through the door's middle: its cut line runs through the "1.00"'s middle
CROSSED = register(("A-1", "plan z=1.2"), ("A-3", "section x=2.5"))


def _segments(path) -> list:
    return [((float(a), float(b)), (float(c), float(d))) for a, b, c, d in re.findall(
        r"M([-\d.]+) ([-\d.]+)L([-\d.]+) ([-\d.]+)", path.get("d"))]


def _svg_texts(root) -> list:
    """The dimension values and their paper boxes ((x0, y0), (x1, y1)): upright,
    or turned to read from the right, centred on their anchor; a quarter mm
    round their capitals."""
    boxes = []
    for text in root.find(f"{SVG}g[@id='dimensions']").iter(f"{SVG}text"):
        x, y, size = (float(text.get(k)) for k in ("x", "y", "font-size"))
        assert text.get("text-anchor") == "middle"
        w, h = text_width(text.text, size) / 2 + 0.25, 0.72 * size + 0.25
        if text.get("transform"):  # rotate(-90 x y): it reads up the page, its top to the left
            boxes.append((text.text, ((x - h, y - w), (x + 0.25, y + w))))
        else:
            boxes.append((text.text, ((x - w, y - h), (x + w, y + 0.25))))
    return boxes


def _meets(points: np.ndarray, box) -> bool:
    (x0, y0), (x1, y1) = box
    return bool(np.any((points[:, 0] > x0) & (points[:, 0] < x1)
                       & (points[:, 1] > y0) & (points[:, 1] < y1)))


def _along(p, q, step: float = 0.05) -> np.ndarray:
    p, q = np.asarray(p, float), np.asarray(q, float)
    n = max(2, int(np.linalg.norm(q - p) / step) + 2)
    return p + np.linspace(0, 1, n)[:, None] * (q - p)


def _arc(centre, radius: float, start: float, end: float) -> np.ndarray:
    """An arc's points, counter-clockwise from start to end degrees (y up)."""
    t = np.radians(start + np.linspace(0, (end - start) % 360, 400))
    return np.column_stack([centre[0] + radius * np.cos(t), centre[1] + radius * np.sin(t)])


def _plan_svg(tmp_path, scene: str = OUT, sheets: str = CROSSED) -> ET.Element:
    (tmp_path / "r.toml").write_text(sheets)
    castor(tmp_path, scene, "--sheets", "r.toml", "-o", "s-%d.svg")
    return ET.fromstring((tmp_path / "s-1.svg").read_bytes())


def test_no_value_meets_the_door_swinging_out_or_the_cut_line_svg(tmp_path):
    root = _plan_svg(tmp_path)
    symbols = root.find(f"{SVG}g[@id='symbols']")
    arcs = [p for p in symbols.iter(f"{SVG}path") if p.get("data-centre")]
    assert len(arcs) == 1
    cx, cy = (float(v) for v in arcs[0].get("data-centre").split())
    radius = float(re.search(r"A([\d.]+) ", arcs[0].get("d")).group(1))
    assert radius == pytest.approx(20.0)  # 1 m at 1:50
    numbers = [float(v) for v in re.findall(r"[-\d.]+", arcs[0].get("d"))]
    (sx, sy), (ex, ey) = numbers[:2], numbers[-2:]
    start = np.degrees(np.arctan2(cy - sy, sx - cx))
    end = np.degrees(np.arctan2(cy - ey, ex - cx))
    swing = _arc((cx, -cy), radius, start, end) * [1, -1]  # back to paper y down
    assert swing[:, 1].max() == pytest.approx(cy + 20.0)  # it swings out, below the wall
    # the leaf: from the hinge (the arc's centre) 20 mm long
    leaf = [s for p in symbols.iter(f"{SVG}path") if p.get("class") == "symbol"
            for s in _segments(p) if np.allclose(s[0], (cx, cy))]
    assert len(leaf) == 1 and np.linalg.norm(np.subtract(*leaf[0])) == pytest.approx(20.0)
    cut = [s for p in symbols.iter(f"{SVG}path") if p.get("class") == "cutline"
           for s in _segments(p)]
    assert len(cut) == 1
    assert cut[0][0][0] == pytest.approx(cx - 10.0)  # x = 2.5, the door's middle
    drawn = {"the swing": swing, "the leaf": _along(*leaf[0]), "the cut line": _along(*cut[0])}
    texts = _svg_texts(root)
    assert sorted(t for t, _ in texts).count("1.00") == 1 and len(texts) >= 8
    hits = [(text, what) for text, box in texts for what, points in drawn.items()
            if _meets(points, box)]
    assert hits == []
    # the south chain's values and lines stand beyond the swing and the leaf
    south = [box for text, box in texts if box[0][1] > cy]
    assert south and min(b[0][1] for b in south) > swing[:, 1].max()
    lines = [s for p in root.find(f"{SVG}g[@id='dimensions']").iter(f"{SVG}path")
             for s in _segments(p) if s[0][1] == s[1][1] and s[0][1] > cy]
    assert len(lines) == 2  # the chain's and the overall's
    for line in lines:
        for points in (swing, _along(*leaf[0])):
            gaps = np.linalg.norm(_along(*line)[:, None] - points[None, ::4], axis=2)
            assert gaps.min() > 1.0


def test_no_value_meets_the_door_swinging_out_or_the_cut_line_dxf(tmp_path):
    import ezdxf

    (tmp_path / "r.toml").write_text(CROSSED)
    castor(tmp_path, OUT, "--sheets", "r.toml", "-o", "set.dxf")
    doc = ezdxf.readfile(tmp_path / "set.dxf")
    msp = doc.modelspace()
    arcs = msp.query("ARC[layer=='symbols']")
    assert len(arcs) == 1
    arc = arcs[0]
    centre, radius = (arc.dxf.center.x, arc.dxf.center.y), arc.dxf.radius
    swing = _arc(centre, radius, arc.dxf.start_angle, arc.dxf.end_angle)
    assert swing[:, 1].min() == pytest.approx(centre[1] - 1.0)  # it swings out
    leaf = [e for e in msp.query("LINE[layer=='symbols']")
            if np.allclose((e.dxf.start.x, e.dxf.start.y), centre)]
    assert len(leaf) == 1
    cut = msp.query("LINE[linetype=='CASTOR_CHAIN_50']")
    assert len(cut) == 1
    k = 50 / 1000  # metres per paper mm

    def points(line):
        return _along(line.dxf.start.vec2, line.dxf.end.vec2, 0.05 * k)

    drawn = {"the swing": swing, "the leaf": points(leaf[0]), "the cut line": points(cut[0])}
    values, hits = 0, []
    for dimension in msp.query("DIMENSION"):
        for text in doc.blocks.get(dimension.dxf.geometry).query("MTEXT"):
            assert text.dxf.attachment_point == 5  # its middle at its insert point
            x, y = text.dxf.insert.x, text.dxf.insert.y
            h = text.dxf.char_height / 2 + 0.25 * k
            w = text_width(text.text, text.dxf.char_height / 0.72) / 2 + 0.25 * k
            if abs(dimension.dxf.angle - 90) < 1e-9:
                w, h = h, w
            box = ((x - w, y - h), (x + w, y + h))
            values += 1
            hits += [(text.text, what) for what, points in drawn.items() if _meets(points, box)]
    assert values >= 8 and hits == []


def test_a_value_under_a_cut_line_moves_along_its_dimension(tmp_path):
    # the house's 6 x 4 m cut at x = 3 and y = 2: both overalls' middles, and a
    # chain's value between two breaks a cut line crosses
    sheets = register(("A-1", "plan z=1.2"), ("A-2", "section x=3"), ("A-3", "section y=2"),
                      ("A-4", "section x=1.45"))
    root = _plan_svg(tmp_path, HOUSE, sheets)
    symbols = root.find(f"{SVG}g[@id='symbols']")
    cuts = [s for p in symbols.iter(f"{SVG}path") if p.get("class") == "cutline"
            for s in _segments(p)]
    assert len(cuts) == 3
    texts = _svg_texts(root)
    assert [t for t, _ in texts].count("6.00") == 2 and [t for t, _ in texts].count("4.00") == 2
    for text, box in texts:
        for cut in cuts:
            assert not _meets(_along(*cut), box), f"'{text}' at {box} meets the cut line {cut}"
    # each still between its dimension's ends: the overall's 6.00 within the
    # house's 120 mm, just beside the cut line at its middle
    drawing = root.find(f"{SVG}g[@id='drawing']")
    ox = float(drawing.get("data-origin").split()[0])
    assert float(drawing.get("data-mm-per-metre")) == 20
    for text, ((x0, _), (x1, _)) in texts:
        if text == "6.00":
            assert ox < x0 and x1 < ox + 120 and min(abs(x0 - (ox + 60)), abs(x1 - (ox + 60))) < 2


def test_a_door_swinging_in_leaves_the_chains_where_they_were(tmp_path):
    """Nothing the symbols draw passes the walls: the south chain's line stays
    CHAIN_LINE mm from the drawing (the roof is over the walls only)."""
    scene = HOUSE.replace("toit = @t(-0.5, -0.5, 2.8) @h(7, 5, 0.2)", "toit = @t(0, 0, 2.8) @h(6, 4, 0.2)")
    root = _plan_svg(tmp_path, scene, register(("A-1", "plan z=1.2")))
    drawing = root.find(f"{SVG}g[@id='drawing']")
    oy = float(drawing.get("data-origin").split()[1])
    lines = [s for p in root.find(f"{SVG}g[@id='dimensions']").iter(f"{SVG}path")
             for s in _segments(p) if s[0][1] == s[1][1] and s[0][1] > oy]
    assert min(s[0][1] for s in lines) == pytest.approx(oy + CHAIN_LINE)


def test_a_single_plan_moves_its_chain_out_past_the_swing_too(tmp_path):
    """Without a register: `--section z=1.2` at 1:50. The door's leaf reaches
    1 m (20 mm) below the wall, farther than the eaves (0.5 m): the south
    chain's line stands CHAIN_LINE mm beyond it, 30 mm from the wall."""
    root, _, _ = svg_of(tmp_path, OUT, "--section", "z=1.2", "--scale", "1:50")
    drawing = root.find(f"{SVG}g[@id='drawing']")
    oy = float(drawing.get("data-origin").split()[1])
    lines = sorted(s[0][1] for p in root.find(f"{SVG}g[@id='dimensions']").iter(f"{SVG}path")
                   for s in _segments(p) if s[0][1] == s[1][1] and s[0][1] > oy)
    assert lines == pytest.approx([oy + 20 + CHAIN_LINE, oy + 20 + OVERALL_LINE])
