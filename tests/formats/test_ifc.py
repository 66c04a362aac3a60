"""IFC4 (castor/formats/ifc.py), read back with ifcopenshell: the schema, the
spatial structure a BIM program expects, names, classes, units, each element's
volume as ifcopenshell's own geometry (OpenCASCADE) computes it against
--summary, colours, the frame's parameters, and validation without an issue.
A second reader, web-ifc under node, where it is installed."""

import json
import os
import shutil
import subprocess
from collections import Counter
from pathlib import Path

import pytest

from tests.support.cli import run

ROOT = Path(__file__).resolve().parents[2]
HOUSE = ROOT / "examples" / "house.cas"

# several objects: one of one colour, one of two, an unnamed one, an empty one,
# polygons of more than four vertices (the prism), a parameter set from the
# command line and one read by a repetition
SCENE = """L = 4; H = 2.5;
mur = @h(L, 0.3, H) !cu(0.9, 0.9, 0.8);
dalle = $D(@t(-1, -1, -0.2) @h(L + 2, 3, 0.2) !cu(0.5, 0.5, 0.5),
           @t(1, 0, -0.5) @h(1, 1, 1) !cu(0.8, 0.2, 0.1));
poteau = @t(0, 2, 0) @h(0.2, 0.2, H) !pr(0.3, 0.3, 0.3, 6);
rien = $I(!cu(1, 0, 0), @t(5, 5, 5) !cu(0, 1, 0));
>[K = 1, 2] mur, dalle, @t(K, 0, 0) poteau, rien;
"""

ifcopenshell = pytest.importorskip("ifcopenshell")


def _summary(path):
    return json.loads(Path(path).read_text())["frames"]


def _open(path):
    return ifcopenshell.open(str(path))


def _issues(model, express_rules=True):
    import ifcopenshell.validate

    logger = ifcopenshell.validate.json_logger()
    ifcopenshell.validate.validate(model, logger, express_rules=express_rules)
    return logger.statements


def _volumes_and_colours(model):
    """Per element name (the elements of one name summed: a row of windows):
    the volume and the colours ifcopenshell's geometry (OpenCASCADE, with the
    placements and the openings applied) finds."""
    import ifcopenshell.geom
    import ifcopenshell.util.shape

    settings = ifcopenshell.geom.settings()
    settings.set("use-world-coords", True)
    found = {}
    for element in model.by_type("IfcElement"):
        if element.is_a("IfcOpeningElement"):
            continue
        shape = ifcopenshell.geom.create_shape(settings, element)
        colours = {tuple(round(c, 6) for c in (m.diffuse.r(), m.diffuse.g(), m.diffuse.b()))
                   for m in shape.geometry.materials}
        volume, seen = found.get(element.Name, (0.0, set()))
        found[element.Name] = (volume + ifcopenshell.util.shape.get_volume(shape.geometry),
                               seen | colours)
    return found


@pytest.fixture(scope="module")
def house(tmp_path_factory):
    where = tmp_path_factory.mktemp("house")
    # run from a directory of its own: castor names a file inside the directory it
    # runs in relatively (as cpp does), and the checkout may lie inside the default one
    run("-o", str(where / "house.ifc"), "--summary", str(where / "house.json"), str(HOUSE),
        check_status=0, cwd=where)
    return _open(where / "house.ifc"), _summary(where / "house.json")[0], where


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    where = tmp_path_factory.mktemp("scene")
    (where / "scene.cas").write_text(SCENE)
    status, out, err = run("-o", str(where / "scene-%d.ifc"), "--summary",
                           str(where / "scene.json"), "--ifc-class", "mur=IfcWall",
                           "--ifc-class", "dalle=slab", "--set", "H=2.7", "scene.cas",
                           cwd=where)
    assert status == 0, err
    return where, _summary(where / "scene.json")


def test_the_house_is_ifc4_with_the_spatial_structure(house):
    model, summary, _ = house
    assert model.schema == "IFC4"
    assert "ReferenceView" in model.header.file_description.description[0]
    (project,) = model.by_type("IfcProject")
    assert project.Name == "maison"  # the '>' object's name, with no --title
    (site,) = model.by_type("IfcSite")
    (building,) = model.by_type("IfcBuilding")
    (storey,) = model.by_type("IfcBuildingStorey")  # no storey, no floor slab: Level 0
    assert (storey.Name, storey.Elevation) == ("Level 0", 0.0)
    for whole, part in ((project, site), (site, building), (building, storey)):
        (rel,) = whole.IsDecomposedBy
        assert rel.is_a("IfcRelAggregates") and list(rel.RelatedObjects) == [part]
    (contained,) = storey.ContainsElements
    elements = [e for e in model.by_type("IfcElement") if not e.is_a("IfcOpeningElement")]
    assert set(contained.RelatedElements) == set(elements)
    # the classed objects of its annotations, and the rest of maison (the door leaf)
    assert Counter((e.is_a(), e.Name) for e in elements) == Counter({
        ("IfcBuildingElementProxy", "maison"): 1, ("IfcWall", "murs"): 1,
        ("IfcWall", "pignons"): 1, ("IfcRoof", "toit"): 1, ("IfcChimney", "cheminee"): 1,
        ("IfcSlab", "socle"): 1, ("IfcDoor", "porte_trou"): 1, ("IfcWindow", "fenetres_sud"): 2,
        ("IfcWindow", "fenetres_nord"): 2, ("IfcWindow", "fenetres_pignon"): 4})
    assert len(model.by_type("IfcOpeningElement")) == 9
    # its source: the definition of maison; the frame's, the '>' that names it
    lines = HOUSE.read_text().splitlines()
    defined = 1 + next(i for i, line in enumerate(lines) if line.startswith("maison ="))
    written = 1 + next(i for i, line in enumerate(lines) if line.startswith("> maison"))
    by_name = {e.Name: e for e in elements}
    assert by_name["maison"].Description == f"{HOUSE}:{defined}"
    murs = 1 + next(i for i, line in enumerate(lines) if line.startswith("murs ="))
    assert by_name["murs"].Description == f"the four walls ({HOUSE}:{murs})"
    assert summary["where"].endswith(f"house.cas:{written}")


def test_lengths_are_metres(house):
    model, _, _ = house
    units = {u.UnitType: (u.Prefix, u.Name) for u in model.by_type("IfcSIUnit")}
    assert units["LENGTHUNIT"] == (None, "METRE")
    assert units["AREAUNIT"] == (None, "SQUARE_METRE")
    assert units["VOLUMEUNIT"] == (None, "CUBIC_METRE")
    import ifcopenshell.util.unit

    assert ifcopenshell.util.unit.calculate_unit_scale(model) == 1.0


def test_the_house_validates_without_an_issue(house):
    model, _, _ = house
    assert _issues(model) == []


def _fillers_and_openings(element) -> bool:
    return element.is_a("IfcOpeningElement") or bool(element.FillsVoids)


def test_volumes_and_colours_read_back_as_summary_gives(house):
    model, summary, _ = house
    found = _volumes_and_colours(model)
    (maison,) = summary["objects"]
    # the elements share the object's solid out; the doors and windows are what
    # was cut from it
    parts = {e.Name for e in model.by_type("IfcElement") if not _fillers_and_openings(e)}
    assert sum(found[name][0] for name in parts) == pytest.approx(maison["volume"], rel=1e-9)
    # each element in its largest colour (ifcopenshell's geometry applies the
    # style, not the colour map); together, the house's colours but its blue
    # reveals, which are in the walls' colour maps
    colours = set().union(*(found[name][1] for name in parts))
    assert colours == {tuple(c["rgb"]) for c in maison["colours"]} - {(0.25, 0.45, 0.85)}
    assert all(len(found[name][1]) == 1 for name in parts)
    mapped = set()
    for element in model.by_type("IfcElement"):
        if element.is_a("IfcOpeningElement"):
            continue
        (item,) = element.Representation.Representations[0].Items
        (colour_map,) = item.HasColours
        mapped |= {tuple(round(c, 9) for c in rgb) for rgb in colour_map.Colours.ColourList}
    assert mapped == {tuple(c["rgb"]) for c in maison["colours"]}
    assert len(mapped) == 6


def test_the_body_is_castors_polygons_one_closed_face_set(house):
    model, summary, _ = house
    for element in model.by_type("IfcElement"):
        (representation,) = element.Representation.Representations
        assert (representation.RepresentationIdentifier, representation.RepresentationType) \
            == ("Body", "Tessellation")
        (face_set,) = representation.Items
        assert face_set.is_a("IfcPolygonalFaceSet") and face_set.Closed
        edges = Counter((f.CoordIndex[k], f.CoordIndex[(k + 1) % len(f.CoordIndex)])
                        for f in face_set.Faces for k in range(len(f.CoordIndex)))
        assert set(edges.values()) == {1} and all((b, a) in edges for a, b in edges)
        if element.is_a("IfcOpeningElement"):
            assert not face_set.StyledByItem  # an opening is not drawn
            continue
        (styled,) = face_set.StyledByItem
        (style,) = styled.Styles
        assert style.is_a("IfcSurfaceStyle") and style.Side == "BOTH"
    faces = [f for s in model.by_type("IfcPolygonalFaceSet") for f in s.Faces]
    assert max(len(f.CoordIndex) for f in faces) > 3  # polygons, not triangles
    styles = model.by_type("IfcSurfaceStyle")
    assert len({s.Name for s in styles}) == len(styles)
    assert {s.Name for s in styles} >= {"dessus", "socle", "battant"}  # named as in OBJ


def test_the_parameters_are_a_property_set_on_the_project(house):
    model, _, _ = house
    import ifcopenshell.util.element

    (project,) = model.by_type("IfcProject")
    values = ifcopenshell.util.element.get_psets(project)["Castor_Parameters"]
    assert values["L"] == 9 and values["P"] == 6.5 and values["PENTE"] == 35
    assert values["TOLERANCE"] == 0.01 and "PI" not in values
    # the rest of maison, the door leaf, a proxy: castor's own volume and area
    (element,) = [e for e in model.by_type("IfcBuildingElementProxy")]
    quantities = ifcopenshell.util.element.get_psets(element)["Castor_Quantities"]
    assert quantities["Volume"] == pytest.approx(1.0 * 0.05 * 2.15, rel=1e-9)


def test_several_objects_classes_parameters_and_frames(scene):
    where, summary = scene
    assert sorted(os.listdir(where)) == ["scene-1.ifc", "scene-2.ifc", "scene.cas",
                                         "scene.json"]
    import ifcopenshell.util.element

    for number in (1, 2):
        model = _open(where / f"scene-{number}.ifc")
        record = summary[number - 1]
        assert _issues(model, express_rules=number == 1) == []  # the rules are slow
        (project,) = model.by_type("IfcProject")
        assert project.Name == "mur"  # the first named object
        parameters = ifcopenshell.util.element.get_psets(project)["Castor_Parameters"]
        assert parameters["H"] == 2.7 and parameters["L"] == 4 and parameters["K"] == number
        elements = {e.Name: e for e in model.by_type("IfcElement")}
        # the empty object has no element; the unnamed one is named as the meshes are
        assert sorted(elements) == ["dalle", "mur", "object3"]
        assert elements["mur"].is_a() == "IfcWall"
        assert elements["dalle"].is_a() == "IfcSlab"
        assert elements["object3"].is_a() == "IfcBuildingElementProxy"
        assert elements["mur"].Description == "scene.cas:2"
        assert elements["object3"].Description == "scene.cas:7"  # the >
        found = _volumes_and_colours(model)
        for obj in record["objects"]:
            if obj["polygons"] == 0:
                continue
            (body,) = elements[obj["name"]].Representation.Representations[0].Items
            assert body.Closed  # one closed surface, whatever its colours
            volume, colours = found[obj["name"]]
            assert volume == pytest.approx(obj["volume"], rel=1e-9)
            assert colours == {tuple(obj["colours"][0]["rgb"])}  # the largest: the style
            (colour_map,) = body.HasColours
            assert {tuple(round(c, 9) for c in rgb) for rgb in colour_map.Colours.ColourList} \
                == {tuple(c["rgb"]) for c in obj["colours"]}
        box = found["object3"]
        assert box[0] == pytest.approx(2.7 * 6 * 0.5 * 1 * 1 * (3 ** 0.5 / 2) * 0.2 ** 2, rel=1e-6)


def test_the_same_scene_gives_the_same_bytes_and_ids(tmp_path):
    paths = [tmp_path / "a" / "house.ifc", tmp_path / "b" / "house.ifc"]  # (the header names it)
    for path in paths:
        path.parent.mkdir()
        run("-o", str(path), str(HOUSE), check_status=0)
    assert paths[0].read_bytes() == paths[1].read_bytes()
    ids = [e.GlobalId for e in _open(paths[0]).by_type("IfcRoot")]
    assert len(ids) == len(set(ids))


def test_title_and_format_option(tmp_path):
    status, out, err = run("-f", "ifc", "--title", "Maison d'Arrêt", str(HOUSE))
    assert status == 0, err
    model = ifcopenshell.file.from_string(out)
    assert model.by_type("IfcProject")[0].Name == "Maison d'Arrêt"
    # no named object: the file's name
    (tmp_path / "cube.cas").write_text("> !cu(1, 1, 1);\n")
    status, out, err = run("-f", "ifc", "cube.cas", cwd=tmp_path)
    assert status == 0, err
    assert ifcopenshell.file.from_string(out).by_type("IfcProject")[0].Name == "cube"


def test_one_file_one_frame(tmp_path):
    (tmp_path / "scene.cas").write_text(SCENE)
    status, out, err = run("-o", "scene.ifc", "scene.cas", cwd=tmp_path)
    assert status == 1
    assert "ifc output holds one frame" in err and "scene-%03d.ifc" in err


@pytest.mark.parametrize("args, message", [
    (["--ifc-class", "mur=IfcWal"], "'IfcWal' is not an IFC4 element class; use one of "
                                     "IfcWall, IfcSlab, IfcRoof, IfcWindow, IfcDoor"),
    (["--ifc-class", "mur"], "--ifc-class takes NAME=CLASS with an object NAME"),
    (["--ifc-class", "=IfcWall"], "--ifc-class takes NAME=CLASS"),
    (["--ifc-class", "mur=IfcOpeningElement"], "is not an IFC4 element class"),
])
def test_ifc_class_usage_errors(args, message):
    status, out, err = run("-o", "x.ifc", *args, stdin="")
    assert status == 2
    assert f"castor: error: " in err and message in err


def test_element_classes_are_the_schemas():
    from castor.formats.ifc import COMMON_CLASSES, ELEMENT_CLASSES, element_class

    schema = ifcopenshell.ifcopenshell_wrapper.schema_by_name("IFC4")
    expected = set()

    def walk(declaration, skipped=False):
        for sub in declaration.subtypes():
            skip = skipped or sub.name() in ("IfcFeatureElement", "IfcVirtualElement")
            if not (sub.is_abstract() or skip or sub.name().endswith(("StandardCase",
                                                                     "ElementedCase"))):
                expected.add(sub.name())
            walk(sub, skip)

    walk(schema.declaration_by_name("IfcElement"))
    assert set(ELEMENT_CLASSES) == expected
    assert set(COMMON_CLASSES) <= expected
    assert element_class("wall") == element_class("IFCWALL") == "IfcWall"


# castor run with ifcopenshell hidden, as where it is not installed: an import of it
# fails (the registry leaves out a format module whose own import fails)
HIDDEN = ("import sys; sys.modules['ifcopenshell'] = None; sys.argv[0] = 'castor'; "
          "from castor import cli; sys.exit(cli.main(sys.argv[1:]))")


def _without_ifcopenshell(*args, cwd):
    result = subprocess.run([os.sys.executable, "-c", HIDDEN, *args], capture_output=True,
                            text=True, cwd=cwd, env={**os.environ, "PYTHONPATH": str(ROOT)},
                            timeout=300)
    assert "Traceback" not in result.stderr, result.stderr
    return result.returncode, result.stdout, result.stderr


def test_without_ifcopenshell_the_error_says_what_to_install(tmp_path):
    from castor.formats import ifc

    assert ifc.installed()  # here it is
    for args in (["-o", "house.ifc"], ["-f", "ifc"], ["-o", "house-%d.ifc", "--title", "M"]):
        status, out, err = _without_ifcopenshell(*args, str(HOUSE), cwd=tmp_path)
        assert status == 2 and out == ""
        assert ("castor: error: writing IFC needs ifcopenshell, which is not installed; "
                "pip install '.[ifc]' in castor's directory, or pip install "
                "'ifcopenshell>=0.8'") in err
        assert "invalid choice" not in err  # the format is still known
    assert os.listdir(tmp_path) == []
    # the other formats, and --ifc-class checked, as before
    status, out, err = _without_ifcopenshell("-o", "house.glb", "--ifc-class", "maison=wall",
                                             str(HOUSE), cwd=tmp_path)
    assert status == 0, err
    assert os.listdir(tmp_path) == ["house.glb"]
    status, out, err = _without_ifcopenshell("--help", cwd=tmp_path)
    assert status == 0 and "--ifc-class" in out and "{cps," in out and "ifc" in out


def test_castor_starts_without_importing_ifcopenshell(tmp_path):
    probe = ("import sys; from castor import cli; cli._arguments(['-o', 'x.ifc', "
             "'--ifc-class', 'a=IfcWall']); print('ifcopenshell' in sys.modules)")
    result = subprocess.run([os.sys.executable, "-c", probe], capture_output=True, text=True,
                            cwd=tmp_path, env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert result.stdout.strip() == "False", result.stderr


def _web_ifc():
    """The directory where `npm install web-ifc` was run (CASTOR_WEB_IFC), or None."""
    directory = os.environ.get("CASTOR_WEB_IFC")
    if not directory or not shutil.which("node"):
        return None
    return directory if (Path(directory) / "node_modules" / "web-ifc").is_dir() else None


@pytest.mark.skipif(_web_ifc() is None, reason="web-ifc not installed (set CASTOR_WEB_IFC)")
def test_web_ifc_reads_the_house_as_ifcopenshell_does(house, tmp_path):
    model, summary, where = house
    result = subprocess.run(["node", str(ROOT / "benchmarks" / "webifc_read.js"),
                             str(where / "house.ifc"), str(tmp_path / "house.obj")],
                            capture_output=True, text=True, cwd=_web_ifc(), timeout=300)
    assert result.returncode == 0, result.stderr
    read = {e["name"]: e for e in json.loads(result.stdout)}  # (by name: windows summed)
    found = _volumes_and_colours(model)
    assert read.keys() == {e.Name for e in model.by_type("IfcElement")
                           if not e.is_a("IfcOpeningElement")}
    for name, element in read.items():
        (cls,) = {e.is_a() for e in model.by_type("IfcElement") if e.Name == name}
        assert element["class"] == cls
        # web-ifc's vertices are single precision; its colour the style's
        assert element["volume"] == pytest.approx(found[name][0], rel=1e-5)
        assert {tuple(c) for c in element["colours"]} == found[name][1]


def test_each_face_starts_at_a_true_corner():
    import numpy as np

    from castor.formats.ifc import true_corner_first

    # a square with a vertex in the middle of each edge, starting at one of them,
    # and a triangle that needs no turn
    vertices = np.array([[1, 0, 0], [2, 0, 0], [2, 1, 0], [2, 2, 0], [1, 2, 0], [0, 2, 0],
                         [0, 1, 0], [0, 0, 0], [5, 5, 5]], float)
    offsets = np.array([0, 8, 11])
    indices = np.array([7, 0, 1, 2, 3, 4, 5, 6, 8, 0, 1])  # its second vertex is straight
    turned = true_corner_first(vertices, offsets, indices)
    ring = [7, 0, 1, 2, 3, 4, 5, 6]
    assert turned[:8].tolist() in [ring[k:] + ring[:k] for k in range(8)]  # the same polygon
    assert turned[:8].tolist() != ring
    a, b, c = vertices[turned[:3]]
    assert np.linalg.norm(np.cross(b - a, c - b)) > 0.5  # a true corner at its second vertex
    assert turned[8:].tolist() == [8, 0, 1]


def test_the_quick_entities_are_create_entitys(tmp_path, monkeypatch):
    """The writer's quick entities (ifc_body.entity_maker) give the bytes that
    ifcopenshell's create_entity gives."""
    from castor.formats import _ifc_body as ifc_body, ifc
    from castor.mesh.facetize import Facetizer
    from castor.pipeline import evaluated_frames

    pavilion = ROOT / "examples" / "pavilion.cas"
    for text, name in ((SCENE, "scene.cas"), (pavilion.read_text(), str(pavilion))):
        (scene, *_), said = evaluated_frames(text, name)
        frame = Facetizer().frame(scene)
        quick = ifc.export(scene, frame)
        with monkeypatch.context() as patched:
            patched.setattr(ifc_body, "entity_maker", lambda f: f.create_entity)
            assert ifc.export(scene, frame, facetizer=Facetizer()) == quick


def test_an_empty_frame_is_a_valid_model_without_elements():
    status, out, err = run("--no-cpp", "-f", "ifc",
                           stdin="> $I(!cu(1, 0, 0), @t(5, 5, 5) !cu(0, 1, 0));\n")
    assert status == 0 and "frame 1 is empty" in err
    model = ifcopenshell.file.from_string(out)
    assert len(model.by_type("IfcElement")) == 0
    assert len(model.by_type("IfcBuildingStorey")) == 1
    assert model.by_type("IfcProject")[0].Name == "castor"  # standard input has no name
    assert _issues(model, express_rules=False) == []
