"""A section's cut line on the set's plans (ISO 128): heavy at its ends beyond
the chains, joined across the plan by a thin long-dashed dotted line at the
section's place; read back from the SVG and the DXF."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import pytest

from tests.support.symbols import HOUSE, SVG, castor, register

REGISTER = register(("A-101", "plan z=1.2"), ("A-201", "section x=3"), ("A-202", "section y=2"))


def segments(path) -> list:
    return [((float(a), float(b)), (float(c), float(d))) for a, b, c, d in re.findall(
        r"M([-\d.]+) ([-\d.]+)L([-\d.]+) ([-\d.]+)", path.get("d"))]


def test_a_thin_chain_line_joins_the_heavy_ends_across_the_plan(tmp_path):
    (tmp_path / "r.toml").write_text(REGISTER)
    castor(tmp_path, HOUSE, "--sheets", "r.toml", "-o", "s-%d.svg")
    root = ET.fromstring((tmp_path / "s-1.svg").read_bytes())
    drawing = root.find(f"{SVG}g[@id='drawing']")
    ox, oy = (float(v) for v in drawing.get("data-origin").split())
    mm = float(drawing.get("data-mm-per-metre"))
    symbols = root.find(f"{SVG}g[@id='symbols']")
    chains = [p for p in symbols.iter(f"{SVG}path") if p.get("class") == "cutline"]
    assert len(chains) == 1
    chain = chains[0]
    assert chain.get("stroke-width") == "0.18"
    assert chain.get("stroke-dasharray") == "12 1.5 0.5 1.5"
    lines = segments(chain)
    assert len(lines) == 2
    heavy = [s for p in symbols.iter(f"{SVG}path") if p.get("stroke-width") == "0.5"
             for s in segments(p)]
    inner_ends = {s[0] for s in heavy}  # each heavy end runs outwards from its inner point
    for (a, b) in lines:
        assert {a, b} <= inner_ends
    vertical = next(s for s in lines if s[0][0] == s[1][0])
    horizontal = next(s for s in lines if s[0][1] == s[1][1])
    assert (vertical[0][0] - ox) / mm == pytest.approx(3.0)  # section x = 3
    assert (oy - horizontal[0][1]) / mm == pytest.approx(2.0)  # section y = 2
    # across the whole plan: the house is 6 x 4 m
    assert abs(vertical[1][1] - vertical[0][1]) / mm > 4.0
    assert abs(horizontal[1][0] - horizontal[0][0]) / mm > 6.0


def test_the_dxf_draws_it_with_a_chain_linetype_at_the_printed_size(tmp_path):
    import ezdxf

    (tmp_path / "r.toml").write_text(REGISTER)
    castor(tmp_path, HOUSE, "--sheets", "r.toml", "-o", "set.dxf")
    doc = ezdxf.readfile(tmp_path / "set.dxf")
    chained = doc.modelspace().query("LINE[linetype=='CASTOR_CHAIN_50']")
    assert len(chained) == 2
    # dash, gap, dot, gap: 12, 1.5, 0.5, 1.5 mm on paper, in metres at 1:50
    lengths = doc.linetypes.get("CASTOR_CHAIN_50").pattern_tags.compile()
    assert lengths[:4] == pytest.approx([0.6, 0.075, 0.025, 0.075])
    assert {round(e.dxf.lineweight) for e in chained} == {18}
    xs = sorted(round(e.dxf.start.x - e.dxf.end.x, 9) == 0 for e in chained)
    assert xs == [False, True]
