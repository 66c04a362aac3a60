"""A DXF's header extents come from castor's own box of the drawing, rounded to
the nanometre (issue 18, item 15: -6.999999999999999 where the scene says -7)."""

import re

from meshcheck import run


def _header_point(text: str, name: str) -> tuple[float, float, float]:
    found = re.search(rf"\${name}\s*\n\s*10\s*\n(.*)\n\s*20\s*\n(.*)\n\s*30\s*\n(.*)\n", text)
    assert found, name
    return tuple(float(v) for v in found.groups())


def test_the_extents_are_the_box_of_what_is_drawn(tmp_path):
    scene = tmp_path / "e.cas"
    # a corner at -6.999999999999999, one rounding away from -7
    scene.write_text("> @t(1e-15 - 7, -7, 0) @h(3) !cu(1, 1, 1), "
                     "@t(1.5, 0, 0) @h(0.7, 0.7, 1) !cu(1, 0, 0);\n")
    out = tmp_path / "e.dxf"
    run(str(scene), "--section", "z=1", "-o", str(out), check_status=0)
    text = out.read_text()
    assert _header_point(text, "EXTMIN") == (-7.0, -7.0, 0.0)
    assert _header_point(text, "EXTMAX") == (2.2, 0.7, 0.0)
    assert "6.99999" not in text.split("ENTITIES")[0]
