"""A sheet takes every drawing that fits it, and the scale a refusal names fits
(issue 29, item 13).

`--sheet A4-portrait` refused a plan of 126 x 116 mm at 1:100 on a sheet that
holds 180 x 229 mm, naming 1:100 as the largest scale that fits: the title
block and the scale bar did not fit side by side on an upright A4, and the
scales offered were judged on the drawing alone. Every drawing here, on every
sheet, at every standard scale, is either laid out with everything inside the
border and nothing over the title block, or refused naming a scale at which
it is.
"""

import dataclasses

import numpy as np
import pytest

from castor.drawings import draw
from castor.drawings.sheet import (MARGIN, STANDARD_SCALES, TITLE_BLOCK, DoesNotFit, Lines,
                                   Shape, Text, layout)
from castor.options import parse_section, parse_sheet, parse_view
from castor.pipeline import frames
from castor.settings import MeshSettings, Source

HOUSE = """
plein = @h(10, 8, 3) !cu(0.9, 0.9, 0.8);
dedans = @t(0.3, 0.3, -1) @h(9.4, 7.4, 5) !cu(0.9, 0.9, 0.8);
porte = @t(4.5, -0.1, -0.1) @h(1, 0.5, 2.2) !cu(0.2, 0.4, 0.8);
maison = $D(plein, $U(dedans, porte));
> maison;
"""
WALL = "mur = @h(36, 0.3, 2.5) !cu(0.9, 0.9, 0.8);\n> mur;\n"  # long and low
TOWER = "tour = @h(3, 3, 24) !cu(0.9, 0.9, 0.8);\n> tour;\n"  # narrow and tall
SHEETS = ["A4", "A4-portrait", "A3", "A3-portrait", "A2-portrait"]


def mesh_of(scene: str):
    checked = frames(Source(text=scene, name="s.cas"), mesh=MeshSettings())
    assert checked.errors == 0, checked.printed
    return checked.meshes[0]


DRAWINGS = {
    "house plan": (HOUSE, parse_section("z=1.2"), None),
    "house front": (HOUSE, None, parse_view("front")),
    "wall plan": (WALL, parse_section("z=1"), None),
    "wall front": (WALL, None, parse_view("front")),
    "tower section": (TOWER, parse_section("x=1.5"), None),
    "tower front": (TOWER, None, parse_view("front")),
}


@pytest.fixture(scope="module")
def drawn():
    """Each drawing at 1:100 (its scale is set for each layout)."""
    out = {}
    for name, (scene, section, view) in DRAWINGS.items():
        out[name] = draw(mesh_of(scene), section, view, 100.0)
    return out


def at_scale(drawing, scale):
    return dataclasses.replace(drawing, scale=float(scale))


def points(items) -> np.ndarray:
    found = []
    for item in items:
        if isinstance(item, Lines):
            found.append(np.asarray(item.segments).reshape(-1, 2))
        elif isinstance(item, Shape):
            found.extend(np.asarray(loop).reshape(-1, 2) for loop in item.loops)
        elif isinstance(item, Text):
            found.append(np.array([[item.x, item.y]]))
    return np.concatenate(found) if found else np.zeros((0, 2))


def assert_laid_out_inside(sheet, paper):
    assert (sheet.width, sheet.height) == (paper.width, paper.height)
    everything = np.concatenate([points(g.items) for g in sheet.layers + sheet.groups])
    assert everything[:, 0].min() >= MARGIN - 1e-6 and everything[:, 1].min() >= MARGIN - 1e-6
    assert everything[:, 0].max() <= paper.width - MARGIN + 1e-6
    assert everything[:, 1].max() <= paper.height - MARGIN + 1e-6
    # nothing but the title block itself over the title block
    tx, ty = paper.width - MARGIN - TITLE_BLOCK[0], paper.height - MARGIN - TITLE_BLOCK[1]
    others = [g for g in sheet.layers + sheet.groups[:2]]
    bar = [i for i in sheet.groups[2].items if isinstance(i, Shape) and i.fill is not None
           or isinstance(i, Text) and i.text.endswith(" m")]
    inside = points([i for g in others for i in g.items] + bar)
    over = (inside[:, 0] > tx + 0.5) & (inside[:, 1] > ty + 0.5)
    assert not over.any(), inside[over][:5]


@pytest.mark.parametrize("sheet_name", SHEETS)
@pytest.mark.parametrize("name", list(DRAWINGS))
def test_every_scale_fits_or_names_one_that_does(drawn, name, sheet_name):
    paper = parse_sheet(sheet_name)
    laid = 0
    for scale in STANDARD_SCALES:
        drawing = at_scale(drawn[name], scale)
        try:
            sheet = layout(drawing, paper, "t", "s.cas:2")
        except DoesNotFit as exc:
            message = str(exc)
            assert f"does not fit on {sheet_name} at 1:{scale}" in message
            if "the largest scale that fits is" in message:
                named = float(message.split("--scale 1:")[1].split(",")[0])
                assert named > scale, message  # a smaller drawing, never the same scale
                assert_laid_out_inside(layout(at_scale(drawing, named), paper), paper)
            continue
        laid += 1
        assert_laid_out_inside(sheet, paper)
    assert laid, f"{name} fits {sheet_name} at no standard scale"


def test_an_upright_a4_takes_the_plan_that_fits_it(drawn):
    """The user's case: 126 x 116 mm at 1:100 on A4-portrait."""
    paper = parse_sheet("A4-portrait")
    sheet = layout(drawn["house plan"], paper, "maison", "s.cas:5")
    assert_laid_out_inside(sheet, paper)
    # the scale bar stands above the title block, not beside it
    bar = [i for i in sheet.groups[2].items if isinstance(i, Shape) and i.fill == "black"]
    ty = paper.height - MARGIN - TITLE_BLOCK[1]
    assert points(bar)[:, 1].max() < ty


def test_a_landscape_sheet_keeps_the_bar_beside_the_title_block(drawn):
    paper = parse_sheet("A3")
    sheet = layout(drawn["house plan"], paper, "maison", "s.cas:5")
    bar = [i for i in sheet.groups[2].items if isinstance(i, Shape) and i.fill == "black"]
    assert points(bar)[:, 1].max() == pytest.approx(paper.height - MARGIN - 8.0)


def test_a_refusal_says_what_does_not_fit(drawn):
    with pytest.raises(DoesNotFit) as refused:
        layout(at_scale(drawn["house plan"], 20), parse_sheet("A4-portrait"))
    assert str(refused.value) == (
        "the drawing does not fit on A4-portrait at 1:20 (526 x 436 mm; the sheet holds "
        "180 x 204 mm); the largest scale that fits is 1:100: --scale 1:100, or a larger --sheet")
