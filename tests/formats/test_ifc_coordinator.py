"""The IFC model a BIM coordinator accepts (OUTPUT.md), read back with
ifcopenshell: storeys and containment, classes and predefined types, openings
voiding their walls and filled by doors and windows of their size, spaces, one
closed face set per element with its colour map, every base quantity against
the value of boxes known by hand, validation, the coordinator's IDS
(tests/formats/data/coordinator.ids, with ifctester), and what the model does
with scenes that leave it a choice."""

from __future__ import annotations

import json
import os
import subprocess
from collections import Counter
from pathlib import Path

import pytest

from tests.support.ifc import ifc_of

ifcopenshell = pytest.importorskip("ifcopenshell")

ROOT = Path(__file__).resolve().parents[2]
IDS = Path(__file__).resolve().parent / "data" / "coordinator.ids"

WALL, BLUE, GREY = (0.9, 0.9, 0.8), (0.2, 0.3, 0.8), (0.5, 0.5, 0.5)

# two storeys of boxes: a wall with a door, a wall above with a window, the
# first floor's slab, a room on the ground floor
TWO_STOREYS = """\
R0 = 0;  // [storey "Rez"]
R1 = 3;  // [storey "Etage"]
L = 5;
porte = @t(1, -0.1, 0) @h(1, 0.4, 2) !cu(0.2, 0.3, 0.8);  // [door hinge=right] entrance
fenetre = @t(3, -0.1, R1 + 1) @h(1.5, 0.4, 1) !cu(0.2, 0.3, 0.8);  // [window]
mur = $D(@h(L, 0.2, 3) !cu(0.9, 0.9, 0.8), porte);  // [wall] south wall
mur_haut = $D(@t(0, 0, R1) @h(L, 0.2, 3) !cu(0.9, 0.9, 0.8), fenetre);  // [wall]
dalle = @t(0, 0.2, R1 - 0.2) @h(L, 3.8, 0.2) !cu(0.5, 0.5, 0.5);  // [slab floor]
sejour = @t(0, 0.2, 0) @h(L, 3.8, 2.8) !cu(1, 1, 1);  // [space "Séjour"]
maison = $U(mur, mur_haut, dalle, sejour);
> maison;
"""


@pytest.fixture(scope="module")
def two_storeys(tmp_path_factory):
    where = tmp_path_factory.mktemp("two")
    return ifc_of(where, TWO_STOREYS)


def _named(model, cls="IfcProduct"):
    return {e.Name: e for e in model.by_type(cls)}


def _quantities(entity) -> dict:
    import ifcopenshell.util.element

    return {name: {k: v for k, v in values.items() if k != "id"}
            for name, values in ifcopenshell.util.element.get_psets(entity).items()}


def _issues(model, express_rules=True):
    """What ifcopenshell.validate finds: the schema, and the EXPRESS rules (slow)."""
    import ifcopenshell.validate

    logger = ifcopenshell.validate.json_logger()
    ifcopenshell.validate.validate(model, logger, express_rules=express_rules)
    return logger.statements


def test_one_storey_per_storey_each_element_contained_in_its_own(two_storeys):
    model, err = two_storeys
    assert "warning" not in err
    storeys = {s.Name: s for s in model.by_type("IfcBuildingStorey")}
    assert {n: s.Elevation for n, s in storeys.items()} == {"Rez": 0.0, "Etage": 3.0}
    # each storey placed at its level
    for s in storeys.values():
        assert s.ObjectPlacement.RelativePlacement.Location.Coordinates[2] == s.Elevation
    (building,) = model.by_type("IfcBuilding")
    (rel,) = building.IsDecomposedBy
    assert {s.Name for s in rel.RelatedObjects} == {"Rez", "Etage"}
    contained = {n: sorted(e.Name for r in s.ContainsElements for e in r.RelatedElements)
                 for n, s in storeys.items()}
    assert contained == {"Rez": ["mur", "porte"], "Etage": ["dalle", "fenetre", "mur_haut"]}
    spaces = {n: [o.Name for r in s.IsDecomposedBy for o in r.RelatedObjects]
              for n, s in storeys.items()}
    assert spaces == {"Rez": ["sejour"], "Etage": []}
    # every element in exactly one storey; openings in none (they void their wall)
    for e in model.by_type("IfcElement"):
        assert len(e.ContainedInStructure) == (0 if e.is_a("IfcOpeningElement") else 1)


def test_classes_types_names_and_descriptions(two_storeys):
    model, _ = two_storeys
    products = _named(model)
    assert products["mur"].is_a() == "IfcWall" and products["mur"].PredefinedType == "NOTDEFINED"
    assert products["dalle"].is_a() == "IfcSlab" and products["dalle"].PredefinedType == "FLOOR"
    assert products["porte"].is_a() == "IfcDoor"
    assert products["porte"].OperationType == "SINGLE_SWING_RIGHT"
    assert products["fenetre"].is_a() == "IfcWindow"
    assert products["mur"].Description == "south wall (s.cas:6)"
    assert products["mur_haut"].Description == "s.cas:7"
    assert products["porte"].Description == "entrance (s.cas:4)"
    space = products["sejour"]
    assert space.is_a() == "IfcSpace" and space.LongName == "Séjour"
    assert space.CompositionType == "ELEMENT"
    # each class's common property set with its Reference
    import ifcopenshell.util.pset

    template = ifcopenshell.util.pset.get_template("IFC4")
    for product in model.by_type("IfcProduct"):
        if product.is_a("IfcSpatialStructureElement") and not product.is_a("IfcSpace"):
            continue
        common = {k: v for k, v in _quantities(product).items() if k.startswith("Pset_")}
        ((name, values),) = common.items()
        assert name == f"Pset_{product.is_a()[3:]}Common"
        assert values == {"Reference": product.Name.removesuffix(" opening")}
        assert template.get_by_name(name) is not None


def test_openings_void_their_walls_and_are_filled_at_their_size(two_storeys):
    model, _ = two_storeys
    openings = model.by_type("IfcOpeningElement")
    assert len(openings) == 2
    seen = {}
    for opening in openings:
        (voids,) = opening.VoidsElements
        (fills,) = opening.HasFillings
        filler = fills.RelatedBuildingElement
        seen[filler.Name] = (voids.RelatingBuildingElement.Name, filler.OverallWidth,
                             filler.OverallHeight)
        assert opening.PredefinedType == "OPENING"
        # placed relative to its wall
        assert opening.ObjectPlacement.PlacementRelTo == \
            voids.RelatingBuildingElement.ObjectPlacement
    assert seen["porte"] == ("mur", pytest.approx(1.0), pytest.approx(2.0))
    assert seen["fenetre"] == ("mur_haut", pytest.approx(1.5), pytest.approx(1.0))


def _volumes(model) -> dict:
    """ifcopenshell's geometry: each element's volume, its openings applied."""
    import ifcopenshell.geom
    import ifcopenshell.util.shape

    settings = ifcopenshell.geom.settings()
    settings.set("use-world-coords", True)
    return {e.Name: ifcopenshell.util.shape.get_volume(
        ifcopenshell.geom.create_shape(settings, e).geometry)
        for e in model.by_type("IfcElement") if not e.is_a("IfcOpeningElement")}


def test_the_walls_keep_their_holes_and_the_voids_take_nothing_more(two_storeys):
    model, _ = two_storeys
    volumes = _volumes(model)
    assert volumes["mur"] == pytest.approx(5 * 0.2 * 3 - 1 * 0.2 * 2, rel=1e-9)
    assert volumes["mur_haut"] == pytest.approx(5 * 0.2 * 3 - 1.5 * 0.2 * 1, rel=1e-9)
    assert volumes["porte"] == pytest.approx(1 * 0.2 * 2, rel=1e-9)  # the wall's depth
    assert volumes["fenetre"] == pytest.approx(1.5 * 0.2 * 1, rel=1e-9)
    assert volumes["dalle"] == pytest.approx(5 * 3.8 * 0.2, rel=1e-9)


def _face_set(product):
    (representation,) = product.Representation.Representations
    assert (representation.RepresentationIdentifier, representation.RepresentationType) == (
        "Body", "Tessellation")
    (item,) = representation.Items
    assert item.is_a("IfcPolygonalFaceSet")
    return item


def _faces_and_areas(item):
    import numpy as np

    points = np.array(item.Coordinates.CoordList)
    faces = [[i - 1 for i in f.CoordIndex] for f in item.Faces]
    areas = []
    for face in faces:
        p = points[face]
        areas.append(np.linalg.norm(sum(np.cross(p[0] - p[k], p[0] - p[k + 1])
                                        for k in range(1, len(p) - 1))) / 2)
    return faces, areas


def test_each_body_is_one_closed_face_set_every_edge_used_twice(two_storeys):
    model, _ = two_storeys
    for product in model.by_type("IfcProduct"):
        if product.Representation is None:
            continue
        item = _face_set(product)
        assert item.Closed
        faces, _ = _faces_and_areas(item)
        directed = Counter((f[k], f[(k + 1) % len(f)]) for f in faces for k in range(len(f)))
        # each edge once each way: closed, and every face turned the same way
        assert set(directed.values()) == {1}, product.Name
        assert all((b, a) in directed for a, b in directed), product.Name


def test_colours_per_face_and_the_largest_as_the_style(two_storeys):
    model, _ = two_storeys
    products = _named(model)
    expected = {
        # the wall: its box's surface less the door's hole in front, back and bottom;
        # the reveals (two sides and the head) in the door's blue
        "mur": {WALL: 2 * (5 * 0.2 + 5 * 3 + 0.2 * 3) - 2 * 2 - 0.2, BLUE: 2 * 2 * 0.2 + 0.2},
        "porte": {BLUE: 2 * (1 * 0.2 + 1 * 2 + 0.2 * 2)},  # the door in its own colour
        "dalle": {GREY: 2 * (5 * 3.8 + 5 * 0.2 + 3.8 * 0.2)},
    }
    for name, areas in expected.items():
        item = _face_set(products[name])
        (colour_map,) = item.HasColours
        colours = [tuple(round(c, 9) for c in rgb) for rgb in colour_map.Colours.ColourList]
        _, face_areas = _faces_and_areas(item)
        assert len(colour_map.ColourIndex) == len(item.Faces)
        found = Counter()
        for index, area in zip(colour_map.ColourIndex, face_areas):
            found[colours[index - 1]] += area
        assert found.keys() == areas.keys()
        for colour, area in areas.items():
            assert found[colour] == pytest.approx(area, rel=1e-9), (name, colour)
        (styled,) = item.StyledByItem
        (style,) = styled.Styles
        shading = style.Styles[0].SurfaceColour
        largest = max(areas, key=areas.get)
        assert (shading.Red, shading.Green, shading.Blue) == pytest.approx(largest)


def test_base_quantities_are_the_boxes(two_storeys):
    model, _ = two_storeys
    products = _named(model)
    q = {name: _quantities(products[name]) for name in
         ("mur", "mur_haut", "dalle", "porte", "fenetre", "sejour")}
    wall = q["mur"]["Qto_WallBaseQuantities"]
    assert wall == pytest.approx({"Length": 5, "Width": 0.2, "Height": 3, "GrossVolume": 3.0,
                                  "NetVolume": 2.6, "NetSideArea": 15 - 2}, rel=1e-9)
    upper = q["mur_haut"]["Qto_WallBaseQuantities"]
    assert upper == pytest.approx({"Length": 5, "Width": 0.2, "Height": 3, "GrossVolume": 3.0,
                                   "NetVolume": 2.7, "NetSideArea": 15 - 1.5}, rel=1e-9)
    assert q["dalle"]["Qto_SlabBaseQuantities"] == pytest.approx(
        {"Width": 0.2, "NetArea": 19.0, "GrossVolume": 3.8, "NetVolume": 3.8}, rel=1e-9)
    assert q["porte"]["Qto_DoorBaseQuantities"] == pytest.approx(
        {"Width": 1, "Height": 2, "Area": 2}, rel=1e-9)
    assert q["fenetre"]["Qto_WindowBaseQuantities"] == pytest.approx(
        {"Width": 1.5, "Height": 1, "Area": 1.5}, rel=1e-9)
    assert q["sejour"]["Qto_SpaceBaseQuantities"] == pytest.approx(
        {"Height": 2.8, "NetFloorArea": 19.0, "NetVolume": 5 * 3.8 * 2.8}, rel=1e-9)
    # no other quantity set on them
    for values in q.values():
        assert [k for k in values if k.startswith("Qto_") or k.startswith("Castor_")] == [
            k for k in values if k.startswith("Qto_")]


def test_quantities_and_properties_are_those_the_templates_name(two_storeys, tmp_path):
    import ifcopenshell.util.pset

    template = ifcopenshell.util.pset.get_template("IFC4")
    pavilion = ROOT / "examples" / "pavilion.cas"
    models = [two_storeys[0], ifc_of(tmp_path, pavilion.read_text())[0]]
    kinds = {"IfcQuantityLength": "Q_LENGTH", "IfcQuantityArea": "Q_AREA",
             "IfcQuantityVolume": "Q_VOLUME"}
    for model in models:
        for qto in model.by_type("IfcElementQuantity"):
            if qto.Name == "Castor_Quantities":
                continue
            known = {t.Name: t.TemplateType for t in template.get_by_name(qto.Name)
                     .HasPropertyTemplates}
            for quantity in qto.Quantities:
                assert known[quantity.Name] == kinds[quantity.is_a()], (qto.Name, quantity.Name)
            (rel,) = qto.DefinesOccurrence
            (entity,) = rel.RelatedObjects
            applicable = template.get_by_name(qto.Name).ApplicableEntity
            assert entity.is_a(applicable.split("/")[0])


def test_valid_and_the_coordinators_ids_is_met(two_storeys, tmp_path):
    from ifctester import ids, reporter

    pavilion = ifc_of(tmp_path, (ROOT / "examples" / "pavilion.cas").read_text())[0]
    for model in (two_storeys[0], pavilion):
        assert _issues(model) == []
        specification = ids.open(str(IDS))
        specification.validate(model)
        report = reporter.Json(specification).report()
        failed = [s["name"] for s in report["specifications"] if not s["status"]]
        assert failed == [] and report["status"] is True


def test_global_ids_stay_when_a_parameter_changes(tmp_path):
    first, _ = ifc_of(tmp_path, TWO_STOREYS, name="a.ifc")
    second, _ = ifc_of(tmp_path, TWO_STOREYS, "--set", "L=6", name="b.ifc")
    ids = [{(e.is_a(), e.Name): e.GlobalId for e in m.by_type("IfcRoot") if e.Name}
           for m in (first, second)]
    assert ids[0] == ids[1]
    assert _quantities(_named(second)["mur"])["Qto_WallBaseQuantities"]["Length"] == \
        pytest.approx(6)
    first_bytes = (tmp_path / "a.ifc").read_bytes()
    again, _ = ifc_of(tmp_path, TWO_STOREYS, name="a.ifc")  # (the header names the file)
    assert (tmp_path / "a.ifc").read_bytes() == first_bytes


# --- scenes that leave the model a choice: the sensible one, said


def test_a_door_cut_from_two_walls_opens_both_and_fills_one(tmp_path):
    model, err = ifc_of(tmp_path, """\
porte = @t(4.5, -0.1, 0) @h(1, 0.4, 2) !cu(0.2, 0.3, 0.8);  // [door]
mur1 = @h(5, 0.2, 3) !cu(0.9, 0.9, 0.8);  // [wall]
mur2 = @t(5, 0, 0) @h(5, 0.2, 3) !cu(0.9, 0.9, 0.8);  // [wall]
murs = $D($U(mur1, mur2), porte);
> murs;
""")
    assert "door 'porte' is cut from 2 elements (mur1, mur2): each has an opening, and the " \
           "door fills the one in 'mur1'" in err
    voided = {o.VoidsElements[0].RelatingBuildingElement.Name: [
        f.RelatedBuildingElement.Name for f in o.HasFillings]
        for o in model.by_type("IfcOpeningElement")}
    assert voided == {"mur1": ["porte"], "mur2": []}
    volumes = _volumes(model)
    assert volumes["mur1"] == pytest.approx(3 - 0.5 * 0.2 * 2, rel=1e-9)
    assert volumes["mur2"] == pytest.approx(3 - 0.5 * 0.2 * 2, rel=1e-9)
    assert volumes["porte"] == pytest.approx(1 * 0.2 * 2, rel=1e-9)
    assert _issues(model) == []


def test_an_opening_in_an_unclassed_object_voids_a_proxy(tmp_path):
    model, err = ifc_of(tmp_path, """\
porte = @t(1, -0.1, 0) @h(1, 0.4, 2) !cu(0.2, 0.3, 0.8);  // [door]
> $D(@h(5, 0.2, 3) !cu(0.9, 0.9, 0.8), porte);
""")
    assert "door 'porte' is cut from 'object1', which has no class: its opening voids an " \
           "IfcBuildingElementProxy; annotate it // [wall]" in err
    (opening,) = model.by_type("IfcOpeningElement")
    host = opening.VoidsElements[0].RelatingBuildingElement
    assert host.is_a() == "IfcBuildingElementProxy" and host.Name == "object1"
    assert opening.HasFillings[0].RelatedBuildingElement.Name == "porte"
    assert _volumes(model)["object1"] == pytest.approx(3 - 0.4, rel=1e-9)
    assert _issues(model) == []


def test_a_space_below_every_storey_is_on_the_lowest(tmp_path):
    model, err = ifc_of(tmp_path, """\
R0 = 0;  // [storey "Rez"]
R1 = 3;  // [storey "Etage"]
mur = @h(5, 0.2, 3) !cu(0.9, 0.9, 0.8);  // [wall]
cave = @t(0, 0, -3) @h(5, 4, 2.5) !cu(1, 1, 1);  // [space "Cave"]
> $U(mur, cave);
""")
    assert "space 'cave' is below every storey (its floor at -3, the lowest storey at 0): " \
           "it is on 'Rez'" in err
    (space,) = model.by_type("IfcSpace")
    assert space.Decomposes[0].RelatingObject.Name == "Rez"
    # its coordinates still the scene's: the storey's placement plus its own
    assert _quantities(space)["Qto_SpaceBaseQuantities"]["NetVolume"] == pytest.approx(50)
    assert _issues(model, express_rules=False) == []


def test_two_storeys_at_one_level_are_one(tmp_path):
    model, err = ifc_of(tmp_path, """\
A = 0;  // [storey "Rez"]
B = 0;  // [storey "Sol"]
C = 3;  // [storey "Etage"]
mur = @h(5, 0.2, 3) !cu(0.9, 0.9, 0.8);  // [wall]
> mur;
""")
    assert "storeys 'Rez' and 'Sol' are both at level 0: the model has one storey there, " \
           "'Rez'" in err
    storeys = model.by_type("IfcBuildingStorey")
    assert sorted((s.Name, s.Elevation) for s in storeys) == [("Etage", 3.0), ("Rez", 0.0)]
    (wall,) = model.by_type("IfcWall")
    assert wall.ContainedInStructure[0].RelatingStructure.Name == "Rez"


def test_a_class_the_reference_view_lacks_is_written_as_the_class_it_has(tmp_path):
    model, err = ifc_of(tmp_path, "m = @h(4, 0.2, 2.5) !cu(1, 1, 1);\n> m;\n",
                        "--ifc-class", "m=IfcWallStandardCase")
    assert "--ifc-class m=IfcWallStandardCase: buildingSMART's IFC4 Reference View has no " \
           "IfcWallStandardCase" in err and "'m' is written as an IfcWall" in err
    (wall,) = model.by_type("IfcElement")
    assert wall.is_a() == "IfcWall"
    assert err.count("warning") == 1  # said once, not once per frame
    assert _issues(model, express_rules=False) == []


def _web_ifc():
    """The directory where `npm install web-ifc` was run (CASTOR_WEB_IFC), or None."""
    import shutil

    directory = os.environ.get("CASTOR_WEB_IFC")
    if not directory or not shutil.which("node"):
        return None
    return directory if (Path(directory) / "node_modules" / "web-ifc").is_dir() else None


@pytest.mark.skipif(_web_ifc() is None, reason="web-ifc not installed (set CASTOR_WEB_IFC)")
def test_web_ifc_finds_the_storeys_elements_openings_and_colours(tmp_path):
    """The second reader (benchmarks/webifc_model.js) sees the pavilion as
    ifcopenshell does."""
    model, _ = ifc_of(tmp_path, (ROOT / "examples" / "pavilion.cas").read_text())
    result = subprocess.run(["node", str(ROOT / "benchmarks" / "webifc_model.js"),
                             str(tmp_path / "s.ifc")], capture_output=True, text=True,
                            cwd=_web_ifc(), timeout=300)
    assert result.returncode == 0, result.stderr
    read = json.loads(result.stdout)
    expected = {s.Name: (s.Elevation, sorted(f"{e.is_a()} {e.Name}" for r in s.ContainsElements
                                              for e in r.RelatedElements),
                         sorted(f"IfcSpace {o.Name}" for r in s.IsDecomposedBy
                                for o in r.RelatedObjects))
                for s in model.by_type("IfcBuildingStorey")}
    assert {s["name"]: (s["elevation"], sorted(s["elements"]), sorted(s["spaces"]))
            for s in read["storeys"]} == expected
    assert expected["Étage"][2] == ["IfcSpace bureau", "IfcSpace chambre"]
    assert sorted((o["voids"], o["filled_by"]) for o in read["openings"]) == sorted(
        (f"IfcWall {o.VoidsElements[0].RelatingBuildingElement.Name}",
         f"{o.HasFillings[0].RelatedBuildingElement.is_a()} "
         f"{o.HasFillings[0].RelatedBuildingElement.Name}")
        for o in model.by_type("IfcOpeningElement"))
    assert len(read["openings"]) == 7
    volumes = _volumes(model)
    for key, element in read["elements"].items():
        cls, name, number = key.split(" ")
        entity = model.by_id(int(number[1:]))
        (colour,) = {tuple(c) for c in element["colours"]}  # the style's: the largest
        style = entity.Representation.Representations[0].Items[0].StyledByItem[0].Styles[0]
        rgb = style.Styles[0].SurfaceColour
        assert colour == pytest.approx((rgb.Red, rgb.Green, rgb.Blue), abs=1e-6)
        if model.by_type("IfcElement") and sum(e.Name == name for e in model.by_type(cls)) == 1:
            assert element["volume"] == pytest.approx(volumes[name], rel=1e-5)
