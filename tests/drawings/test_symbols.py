"""What the classes add to a drawing (OUTPUT.md, "What a contractor builds
from"): doors, windows, stairs, overhead lines, room tags and hatches by
class, read back from the SVG, the DXF and the PDF of a small house whose
numbers are known by hand."""

from __future__ import annotations

import shutil
import subprocess
import xml.etree.ElementTree as ET

import pytest

from tests.support.symbols import HOUSE, SVG, castor, dxf_of, numbers, svg_of


def test_a_door_swings_from_its_hinge_with_an_arc_of_its_width(tmp_path):
    doc = dxf_of(tmp_path, HOUSE, "--section", "z=1.2")
    arcs = doc.modelspace().query("ARC")
    assert len(arcs) == 1
    arc = arcs[0]
    # hinge left seen from inside (where it opens): the east jamb, on the inner face
    assert (arc.dxf.center.x, arc.dxf.center.y) == pytest.approx((1.9, 0.2), abs=1e-9)
    assert arc.dxf.radius == pytest.approx(0.9, abs=1e-9)
    # a quarter from the open leaf (north) round to the closed one (west)
    assert (arc.dxf.start_angle, arc.dxf.end_angle) == pytest.approx((90, 180), abs=1e-6)
    leaf = [line for line in doc.modelspace().query("LINE")
            if abs(line.dxf.start.x - 1.9) < 1e-9 and abs(line.dxf.end.x - 1.9) < 1e-9]
    assert any(sorted((l.dxf.start.y, l.dxf.end.y)) == pytest.approx([0.2, 1.1]) for l in leaf)
    root, metres, _ = svg_of(tmp_path, HOUSE, "--section", "z=1.2")
    arcs = [p for p in root.iter(SVG + "path") if "A" in p.get("d") and p.get("class") == "symbol"]
    assert len(arcs) == 1 and float(arcs[0].get("stroke-width")) == 0.18
    x, y = numbers(arcs[0].get("data-centre"))
    assert metres(x, y) == pytest.approx((1.9, 0.2), abs=1e-3)


def test_a_door_hinged_right_opening_out_mirrors(tmp_path):
    scene = HOUSE.replace("hinge=left swing=in", "hinge=right swing=out")
    arc = dxf_of(tmp_path, scene, "--section", "z=1.2").modelspace().query("ARC")[0]
    # opening out (south), hinge on the right of one standing south: the east jamb
    assert (arc.dxf.center.x, arc.dxf.center.y) == pytest.approx((1.9, 0.0), abs=1e-9)
    assert (arc.dxf.start_angle, arc.dxf.end_angle) == pytest.approx((180, 270), abs=1e-6)


def test_the_eaves_above_the_cut_are_dashed(tmp_path):
    doc = dxf_of(tmp_path, HOUSE, "--section", "z=1.2")
    dashed = [l for l in doc.modelspace().query("LINE") if l.dxf.linetype == "CASTOR_DASHED"]
    eaves = {(round(l.dxf.start.x, 6), round(l.dxf.start.y, 6), round(l.dxf.end.x, 6),
              round(l.dxf.end.y, 6)) for l in dashed}
    south = [e for e in eaves if e[1] == e[3] == -0.5]
    assert len(south) == 1 and sorted((south[0][0], south[0][2])) == [-0.5, 6.5]
    assert "CASTOR_DASHED" in doc.linetypes
    root, metres, _ = svg_of(tmp_path, HOUSE, "--section", "z=1.2")
    overhead = [p for p in root.iter(SVG + "path") if p.get("class") == "overhead"]
    assert overhead and all(p.get("stroke-dasharray") for p in overhead)
    ends = [metres(*numbers(p.get("d"))[k:k + 2]) for p in overhead
            for k in range(0, len(numbers(p.get("d"))), 2)]
    assert any(pt == pytest.approx((-0.5, -0.5), abs=1e-3) for pt in ends)
    assert any(pt == pytest.approx((6.5, 4.5), abs=1e-3) for pt in ends)


def test_a_room_tag_gives_its_name_and_area(tmp_path):
    root, metres, _ = svg_of(tmp_path, HOUSE, "--section", "z=1.2")
    texts = ["".join(t.itertext()) for t in root.iter(SVG + "text")]
    assert "Sejour" in texts and "20.16 m²" in texts  # 5.6 x 3.6
    # the plan's storey and its floor level
    assert "±0.00" in texts
    assert any("Rez ±0.00" in t for t in texts)


def test_a_space_partly_crossing_the_plan_is_measured_at_the_plan(tmp_path):
    # an L of two parts, only one of which reaches the plan's height
    scene = HOUSE.replace(
        'piece = @t(0.2, 0.2, 0) @h(5.6, 3.6, 2.8) !cu(1, 1, 1);',
        'piece = $U(@t(0.2, 0.2, 0) @h(3, 3.6, 2.8) !cu(1, 1, 1), '
        '@t(3.2, 0.2, 0) @h(2.6, 3.6, 1) !cu(1, 1, 1));')
    root, _, _ = svg_of(tmp_path, scene, "--section", "z=1.2")
    texts = ["".join(t.itertext()) for t in root.iter(SVG + "text")]
    assert "10.80 m²" in texts  # 3 x 3.6: the part the plan cuts
    root, _, _ = svg_of(tmp_path, scene, "--section", "z=3.5")
    texts = ["".join(t.itertext()) for t in root.iter(SVG + "text")]
    assert "Sejour" not in texts  # a plan above the room: no tag


def test_a_window_has_its_frame_and_glass_in_the_wall(tmp_path):
    doc = dxf_of(tmp_path, HOUSE, "--section", "z=1.2")
    glass = [l for l in doc.modelspace().query("LINE")
             if abs(l.dxf.start.y - 0.1) < 1e-9 and abs(l.dxf.end.y - 0.1) < 1e-9]
    assert any(sorted((l.dxf.start.x, l.dxf.end.x)) == pytest.approx([3.5, 4.7]) for l in glass)


def test_a_stair_has_its_break_line_and_an_arrow_with_its_risers(tmp_path):
    root, metres, _ = svg_of(tmp_path, HOUSE, "--section", "z=1.2")
    texts = ["".join(t.itertext()) for t in root.iter(SVG + "text")]
    assert "14 R" in texts
    # the treads beyond the cut (above 1.2 m: from the 7th, y = 1.7) are dashed
    doc = dxf_of(tmp_path, HOUSE, "--section", "z=1.2")
    dashed = [l for l in doc.modelspace().query("LINE") if l.dxf.linetype == "CASTOR_DASHED"
              and abs(l.dxf.start.y - l.dxf.end.y) < 1e-9
              and sorted((l.dxf.start.x, l.dxf.end.x)) == pytest.approx([4, 5])]
    assert sorted(round(l.dxf.start.y, 6) for l in dashed) == pytest.approx(
        [0.5 + 0.2 * k for k in range(6, 14)])


def test_a_stair_against_a_wall_has_its_break_line_stop_at_the_wall(tmp_path):
    # the flight moved against the east wall (x 4.8 to 5.8, the wall's inner
    # face): the break line runs 0.1 m past the flight's free side, as drawn
    # by hand, but not into the wall's hatch
    scene = HOUSE.replace("marche = @t(4,", "marche = @t(4.8,")
    doc = dxf_of(tmp_path, scene, "--section", "z=1.2")
    slanted = [l for l in doc.modelspace().query("LINE")
               if l.dxf.layer == "symbols" and l.dxf.linetype != "CASTOR_DASHED"
               and abs(l.dxf.start.x - l.dxf.end.x) > 1e-6 and abs(l.dxf.start.y - l.dxf.end.y) > 1e-6]
    xs = [x for l in slanted for x in (l.dxf.start.x, l.dxf.end.x)]
    assert (min(xs), max(xs)) == pytest.approx((4.7, 5.8))


def test_a_stair_of_one_riser_is_said_and_drawn_as_cut(tmp_path):
    scene = HOUSE.replace("$U[I = 0, 13](marche)", "$U[I = 0, 0](marche)")
    _, _, said = svg_of(tmp_path, scene, "--section", "z=0.1")
    assert "stair 'escalier'" in said and "1 riser" in said


def test_a_door_that_cuts_nothing_is_said(tmp_path):
    scene = HOUSE.replace("porte = @t(1, -0.1, 0)", "porte = @t(1, -3, 0)")
    root, _, said = svg_of(tmp_path, scene, "--section", "z=1.2")
    assert "door 'porte'" in said and "cuts nothing" in said
    assert not [p for p in root.iter(SVG + "path") if "A" in p.get("d")
                and p.get("class") == "symbol"]


def test_cut_regions_are_hatched_by_class(tmp_path):
    doc = dxf_of(tmp_path, HOUSE, "--section", "x=3")
    patterns = {h.dxf.pattern_name for h in doc.modelspace().query("HATCH")}
    assert {"ANSI31", "ANSI37"} <= patterns  # walls; the roof and the floor slab
    root, _, _ = svg_of(tmp_path, HOUSE, "--section", "x=3")
    hatched = {(p.get("data-class"), p.get("data-pattern")) for p in root.iter(SVG + "path")
               if p.get("class") == "hatch"}
    assert {("IfcWall", "ANSI31"), ("IfcRoof", "ANSI37"), ("IfcSlab", "ANSI37")} <= hatched
    ids = {p.get("id") for p in root.iter(SVG + "pattern")}
    assert {"hatch-ANSI31", "hatch-ANSI37"} <= ids
    legend = ["".join(t.itertext()) for t in root.find(f"{SVG}g[@id='sheet']").iter(SVG + "text")]
    assert "Walls" in legend and "Slabs and roofs" in legend


def test_an_unclassed_object_stays_solid_grey(tmp_path):
    scene = HOUSE.replace("maison = $U(", "maison = $U(@t(2, 2, 0) @h(0.3, 0.3, 2) !cu(1, 0, 0), ")
    root, _, _ = svg_of(tmp_path, scene, "--section", "z=1.2")
    greys = [p for p in root.find(f"{SVG}g[@id='drawing']").iter(SVG + "path")
             if p.get("class") == "cut" and p.get("fill") == "#8c8c8c"]
    assert len(greys) == 1
    legend = ["".join(t.itertext()) for t in root.find(f"{SVG}g[@id='sheet']").iter(SVG + "text")]
    assert "Unclassed" in legend


@pytest.mark.skipif(shutil.which("pdftotext") is None, reason="poppler's pdftotext")
def test_the_pdf_carries_the_symbols_texts(tmp_path):
    castor(tmp_path, HOUSE, "--section", "z=1.2", "-o", "d.pdf")
    text = subprocess.run(["pdftotext", str(tmp_path / "d.pdf"), "-"], capture_output=True,
                          text=True).stdout
    assert "Sejour" in text and "20.16 m²" in text and "14 R" in text and "Walls" in text


def test_a_scene_without_classes_draws_as_before(tmp_path):
    scene = "\n".join(line.split("//")[0] for line in HOUSE.splitlines()) + "\n"
    root, _, _ = svg_of(tmp_path, scene, "--section", "z=1.2")
    assert not list(root.iter(SVG + "pattern"))
    assert root.find(f"{SVG}g[@id='symbols']") is None
