"""Chains and levels with classes (OUTPUT.md, "What a contractor builds
from"): a façade's chain along the cut walls' outer face, breaking at every
opening and never at a porch's columns, its overall its extent; vertical
chains on sections and elevations; the storeys' levels first, never an edge
seen through an opening. Read back from the DXF's DIMENSION entities and the
SVG's texts."""

from __future__ import annotations

import re

import pytest

from tests.support.symbols import HOUSE, SVG, dxf_of, levels, svg_of

# the house with a porch in front of its south wall: two columns and a canopy
PORCH = HOUSE.replace("> maison;", "") + """\
poteaux = $U(@t(0.5, -1.5, 0) @h(0.2, 0.2, 2.6) !cu(1, 1, 1), @t(2.5, -1.5, 0) @h(0.2, 0.2, 2.6) !cu(1, 1, 1));  // [column]
auvent = @t(0.3, -1.7, 2.6) @h(2.6, 1.7, 0.15) !cu(0.5, 0.5, 0.5);  // [slab]
maison2 = $U(poteaux, auvent, murs, escalier, toit, sol, piece);
> maison2;
"""


def south_dimensions(doc, axis="x"):
    dims = list(doc.modelspace().query("DIMENSION"))
    south = sorted((d for d in dims if d.dxf.angle == 0 and d.dxf.defpoint.y < -0.5),
                   key=lambda d: (d.dxf.defpoint.y, min(d.dxf.defpoint2.x, d.dxf.defpoint3.x)))
    return [round(d.get_measurement(), 9) for d in south], south


def test_the_south_chain_follows_the_wall_not_the_porch(tmp_path):
    doc = dxf_of(tmp_path, PORCH, "--section", "z=1.2")
    measured, south = south_dimensions(doc)
    overall, chain = measured[0], measured[1:]
    # wall 0..1, door ..1.9, wall ..3.5, window ..4.7, wall ..6: no column
    assert chain == [1.0, 0.9, 1.6, 1.2, 1.3]
    assert overall == pytest.approx(sum(chain)) == 6.0
    # on the walls' outer face
    assert all(abs(d.dxf.defpoint2.y) < 1e-9 for d in south[1:])


def test_the_overall_is_the_extent_of_its_chain(tmp_path):
    doc = dxf_of(tmp_path, HOUSE, "--section", "z=1.2")
    dims = list(doc.modelspace().query("DIMENSION"))
    for side in (lambda d: d.dxf.angle == 0 and d.dxf.defpoint.y < 0,
                 lambda d: d.dxf.angle == 90 and d.dxf.defpoint.x < 0):
        values = sorted((round(d.get_measurement(), 9) for d in dims if side(d)), reverse=True)
        if len(values) > 1:
            assert values[0] == pytest.approx(sum(values[1:]))


def test_a_section_marks_the_floor_levels_first(tmp_path):
    scene = HOUSE.replace("R1 = 3;", "R1 = 2.8;")
    root, _, _ = svg_of(tmp_path, scene, "--section", "x=3", "--scale", "1:50")
    shown = levels(root)
    # the storey at 2.80 is shown; the slab's soffit at 2.80 is the same level
    assert "±0.00" in shown and "+2.80" in shown and "+3.00" in shown


def test_an_edge_seen_through_a_window_is_no_level(tmp_path):
    # the stair's treads (every 0.2 m) are seen through the south window
    root, _, _ = svg_of(tmp_path, HOUSE, "--view", "front", "--scale", "1:20")
    shown = levels(root)
    assert "+0.90" in shown and "+2.10" in shown  # the window's sill and head, the door's head
    for tread in ("+1.00", "+1.20", "+1.40", "+1.60", "+1.80", "+2.00"):
        assert tread not in shown


def test_an_elevation_has_vertical_chains(tmp_path):
    doc = dxf_of(tmp_path, HOUSE, "--view", "front", "--scale", "1:50")
    vertical = [d for d in doc.modelspace().query("DIMENSION") if d.dxf.angle == 90]
    left = sorted(round(d.get_measurement(), 9) for d in vertical if d.dxf.defpoint.x < 3)
    right = sorted(round(d.get_measurement(), 9) for d in vertical if d.dxf.defpoint.x > 3)
    # left: the door (0 .. 2.1), the top of the roof at 3.0; right: the window
    assert left == sorted([2.1, 0.9, 3.0])
    assert right == sorted([0.9, 1.2, 0.9, 3.0])


def test_a_plan_marks_its_floor_level(tmp_path):
    scene = HOUSE.replace("murs = $D(@h(6, 4, 2.8)", "murs = $D(@t(0, 0, 3) @h(6, 4, 2.8)") \
        .replace('piece = @t(0.2, 0.2, 0)', 'piece = @t(0.2, 0.2, 3)')
    root, _, _ = svg_of(tmp_path, scene, "--section", "z=4.2")
    texts = ["".join(t.itertext()) for t in root.iter(SVG + "text")]
    assert "+3.00" in texts
    assert any(re.search(r"Etage \+3\.00", t) for t in texts)


def test_a_section_measures_the_slabs_it_cuts(tmp_path):
    # the pavilion cut across: ground slab 0.20 below ±0.00, storey 2.80 to the
    # first floor's slab (0.20), 3.00 to the roof, roof 0.25 thick: the chain
    # gives the structure's thicknesses, as a contractor builds it
    from pathlib import Path

    scene = (Path(__file__).resolve().parents[2] / "examples" / "pavilion.cas").read_text()
    doc = dxf_of(tmp_path, scene, "--section", "x=3", "--scale", "1:50")
    vertical = [d for d in doc.modelspace().query("DIMENSION") if d.dxf.angle == 90]
    middle = sum(d.dxf.defpoint.x for d in vertical) / len(vertical)  # the page runs -y
    for side in (lambda x: x < middle, lambda x: x > middle):
        chain = sorted(((min(d.dxf.defpoint2.y, d.dxf.defpoint3.y), round(d.get_measurement(), 9))
                        for d in vertical if side(d.dxf.defpoint.x)))
        measured = [m for _, m in chain]
        overall = max(measured)
        measured.remove(overall)
        assert measured == [0.2, 2.8, 0.2, 3.0, 0.25], chain
        assert overall == pytest.approx(6.45)
