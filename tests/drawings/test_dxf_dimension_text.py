"""A DXF's dimension text is as high as its other text (the levels', the title
block's): DXF gives a text's capital height, the sheet's sizes are the em's, so
both are 0.72 x 2.5 mm on paper, as in the SVG and PDF."""

from __future__ import annotations

import pytest

from tests.support.symbols import HOUSE, dxf_of


@pytest.mark.parametrize("scale", ["1:50", "1:100"])
def test_dimension_text_is_as_high_as_the_levels_text(tmp_path, scale):
    doc = dxf_of(tmp_path, HOUSE, "--section", "x=3", "--scale", scale)
    n = float(scale.split(":")[1])
    style = doc.dimstyles.get("CASTOR")
    assert style.dxf.dimtxt == pytest.approx(2.5 * 0.72 * n / 1000)
    assert doc.header["$DIMTXT"] == pytest.approx(style.dxf.dimtxt)
    levels = [e.dxf.height for e in doc.modelspace().query("TEXT[layer=='levels']")]
    assert levels and levels == pytest.approx([style.dxf.dimtxt] * len(levels))
    # the dimensions' own blocks, as a CAD program shows them, say the same
    heights = set()
    for dimension in doc.modelspace().query("DIMENSION"):
        block = doc.blocks.get(dimension.dxf.geometry)
        heights |= {round(t.dxf.char_height, 9) for t in block.query("MTEXT")}
    assert heights == {round(style.dxf.dimtxt, 9)}
