"""A DXF's header extents come from castor's own figures (the sheet's paper in
metres), rounded to the nanometre: never -6.999999999999999 where the scene
says -7."""

import re

from tests.support.cli import run


def _header_point(text: str, name: str) -> tuple[float, float, float]:
    found = re.search(rf"\${name}\s*\n\s*10\s*\n(.*)\n\s*20\s*\n(.*)\n\s*30\s*\n(.*)\n", text)
    assert found, name
    return tuple(float(v) for v in found.groups())


def test_the_extents_hold_what_is_drawn_to_the_nanometre(tmp_path):
    scene = tmp_path / "e.cas"
    # a corner at -6.999999999999999, one rounding away from -7
    scene.write_text("> @t(1e-15 - 7, -7, 0) @h(3) !cu(1, 1, 1), "
                     "@t(1.5, 0, 0) @h(0.7, 0.7, 1) !cu(1, 0, 0);\n")
    out = tmp_path / "e.dxf"
    run(str(scene), "--section", "z=1", "-o", str(out), check_status=0)
    text = out.read_text()
    low, high = _header_point(text, "EXTMIN"), _header_point(text, "EXTMAX")
    assert low[0] < -7 and low[1] < -7 and high[0] > 2.2 and high[1] > 0.7  # the sheet holds all
    for value in low + high:
        assert value == round(value, 9)
    assert "6.99999" not in text.split("ENDSEC")[0]  # the header
