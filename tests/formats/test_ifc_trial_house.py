"""A new user's two-storey house in IFC: the upper floor, a slab with a stairwell
inside a ring of walls and above a stair, gets its Width and a body of its own
(only its faces, its points, its colour); one surface style per colour, named
as OBJ names the materials; the header names the file written."""

from __future__ import annotations

import pytest

from tests.support.cli import run
from tests.support.ifc import ifc_of
from tests.support.scenes import TRIAL_HOUSE as HOUSE


GRIS = (0.6, 0.6, 0.6)


def _rgb(style) -> tuple[float, float, float]:
    """An IfcSurfaceStyle's colour."""
    colour = style.Styles[0].SurfaceColour
    return colour.Red, colour.Green, colour.Blue


def _slab(model, name: str):
    import ifcopenshell.util.element as element

    [slab] = [e for e in model.by_type("IfcSlab") if e.Name == name]
    [item] = slab.Representation.Representations[0].Items
    return element.get_psets(slab, qtos_only=True)["Qto_SlabBaseQuantities"], item


@pytest.mark.parametrize("thickness", ["0.3", "0.25"])
def test_a_slab_with_a_well_in_its_walls_gets_its_width_and_its_own_body(tmp_path, thickness):
    model, said = ifc_of(tmp_path, HOUSE, "--set", f"E={thickness}", name="b.ifc")
    quantities, item = _slab(model, "floor1")
    assert quantities["Width"] == 0.25
    # its volume: the slab less its well, nothing else taken
    inner = (10 - 2 * float(thickness)) * (6 - 2 * float(thickness))
    assert quantities["NetVolume"] == pytest.approx((inner - 1.1 * 17 * 0.25) * 0.25, rel=1e-9)
    # only its own faces: all its points on its bottom or its top (the storey
    # "Upper" at 3.2, the slab's top), none of the stair's or the walls' points
    z = [p[2] for p in item.Coordinates.CoordList]
    assert all(abs(h) < 1e-9 or abs(h + 0.25) < 1e-9 for h in z), sorted(set(z))
    # in its own colour only, neither the walls' white nor the stair's wood
    [colours] = item.HasColours
    assert [tuple(c) for c in colours.Colours.ColourList] == [GRIS]
    [styled] = item.StyledByItem
    assert _rgb(styled.Styles[0]) == GRIS


def test_the_walls_and_the_stair_keep_their_own_colours(tmp_path):
    model, _ = ifc_of(tmp_path, HOUSE, name="b.ifc")
    for name, colour in (("walls0", (0.9, 0.9, 0.85)), ("stair", (0.5, 0.35, 0.2))):
        [element] = [e for e in model.by_type("IfcProduct") if e.Name == name]
        [item] = element.Representation.Representations[0].Items
        [styled] = item.StyledByItem
        assert _rgb(styled.Styles[0]) == colour
        # the floor slab they touch leaves no grey on them
        assert GRIS not in [tuple(c) for c in item.HasColours[0].Colours.ColourList]


def test_one_surface_style_per_colour_named_as_obj_names_it(tmp_path):
    model, _ = ifc_of(tmp_path, HOUSE, name="b.ifc")
    styles = {s.Name: _rgb(s) for s in model.by_type("IfcSurfaceStyle")}
    assert len(model.by_type("IfcSurfaceStyle")) == len(set(styles.values())) == 4
    run("-q", "-o", str(tmp_path / "b.obj"), str(tmp_path / "s.cas"), check_status=0)
    materials = {}
    for line in (tmp_path / "b.mtl").read_text().splitlines():
        if line.startswith("newmtl "):
            name = line.split()[1]
        elif line.startswith("Kd "):
            materials[name] = tuple(float(c) for c in line.split()[1:])
    assert set(styles) == set(materials) == {"base", "shell", "door1", "step"}
    for name, colour in styles.items():
        assert colour == pytest.approx(materials[name], abs=1e-6)
    # every element's style is one of them: the blue of the door and the windows is door1's
    blue = [s for s in model.by_type("IfcStyledItem")
            if _rgb(s.Styles[0]) == (0.2, 0.4, 0.9)]
    assert blue and {s.Styles[0].Name for s in blue} == {"door1"}


def test_the_header_names_the_file_written(tmp_path):
    (tmp_path / "out").mkdir()
    model, _ = ifc_of(tmp_path, HOUSE, name="out/b.ifc")
    assert model.header.file_name.name == "b.ifc"
    text = (tmp_path / "out" / "b.ifc").read_text()
    assert "FILE_NAME('b.ifc'," in text and "house.ifc" not in text
