"""The DXF set's paper-space layouts as another reader sees them: ezdxf's
drawing add-on (ezdxf.addons.drawing, its Frontend: separate code from the
writer) renders each layout with its VIEWPORT, and the model must come out
inside the viewport at the sheet's scale, with the pens' true widths, in
paper millimetres."""

from __future__ import annotations

import pytest

from tests.support.symbols import HOUSE, castor, register

REGISTER = register(("A-101", "plan z=1.2"), ("A-201", "section x=3", "1:100"))


def _rendered(doc, name: str) -> dict:
    """layer -> (its box in paper mm, its lineweights), as the add-on draws the layout."""
    from ezdxf.addons.drawing import Frontend, RenderContext
    from ezdxf.addons.drawing.recorder import Recorder
    from ezdxf.math import BoundingBox2d

    recorder = Recorder()
    Frontend(RenderContext(doc), recorder).draw_layout(doc.layouts.get(name))
    player = recorder.player()
    out: dict = {}
    for record in player.records:
        properties = player.properties[record.property_hash]
        box, pens = out.setdefault(properties.layer, (BoundingBox2d(), set()))
        box.extend(record.bbox())
        pens.add(round(properties.lineweight, 2))
    return out


@pytest.fixture(scope="module")
def set_dxf(tmp_path_factory):
    import ezdxf

    tmp_path = tmp_path_factory.mktemp("set")
    (tmp_path / "r.toml").write_text(REGISTER)
    castor(tmp_path, HOUSE, "--sheets", "r.toml", "-o", "set.dxf")
    return ezdxf.readfile(tmp_path / "set.dxf")


@pytest.mark.parametrize("name, size", [
    ("A-101", (6.0 / 50 * 1000, 4.0 / 50 * 1000)),  # the walls' 6 x 4 m at 1:50
    ("A-201", (5.0 / 100 * 1000, 3.2 / 100 * 1000)),  # the roof's 5 m, -0.2 .. 3.0 m at 1:100
])
def test_the_model_comes_out_at_the_sheets_scale_inside_its_viewport(set_dxf, name, size):
    drawn = _rendered(set_dxf, name)
    house, pens = drawn["maison"]
    assert house.size.x == pytest.approx(size[0], abs=0.01)
    assert house.size.y == pytest.approx(size[1], abs=0.01)
    assert 0.5 in pens  # the cut's outline at its true width on paper
    # inside the viewport's window on the paper, and inside the sheet's border
    viewport, = [v for v in set_dxf.layouts.get(name).query("VIEWPORT") if v.dxf.status != 1]
    cx, cy = viewport.dxf.center.x, viewport.dxf.center.y
    w, h = viewport.dxf.width, viewport.dxf.height
    assert cx - w / 2 <= house.extmin.x and house.extmax.x <= cx + w / 2
    assert cy - h / 2 <= house.extmin.y and house.extmax.y <= cy + h / 2
    border, _ = drawn["sheet"]
    assert (border.extmin.x, border.extmin.y) == pytest.approx((10, 10))
    assert (border.extmax.x, border.extmax.y) == pytest.approx((410, 287))
    # the dimensions, drawn by the reader from the DIMENSION entities, stand round the house
    dimensions, _ = drawn["dimensions"]
    assert dimensions.extmin.x < house.extmin.x and dimensions.extmax.y > house.extmax.y


def test_dashed_lines_in_a_viewport_are_3_mm_dashes_on_paper(set_dxf):
    # each scale's linetype is in model metres (3 mm and 1.5 mm at 1:N), so the
    # viewports must not rescale it as paper units ($PSLTSCALE 1, ezdxf's default,
    # made the roof's overhang 0.15 mm dashes at 1:50: a solid line). ezdxf's
    # drawing add-on ignores $PSLTSCALE, so this reads the file.
    assert set_dxf.header["$PSLTSCALE"] == 0
    dashed = {e.dxf.linetype for e in set_dxf.modelspace().query("LINE")
              if e.dxf.linetype.startswith("CASTOR_DASHED")}
    assert dashed == {"CASTOR_DASHED_50"}  # the roof's overhang, above the plan
    tags = set_dxf.linetypes.get("CASTOR_DASHED_50").pattern_tags.tags
    lengths = [t.value for t in tags if t.code == 49]
    assert [round(v * 1000 / 50, 6) for v in lengths] == [3.0, -1.5]
