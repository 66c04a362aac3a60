"""castor --serve and the classes of objects (LANGUAGE.md §11): each face the
page draws knows its element and class (castor.serve.layers), a face cut by a
subtracted primitive going to the element it lies on."""

from __future__ import annotations

import json

import numpy as np

from castor.serve.evaluation import Watched, evaluate
from castor.settings import Source


def _faces(text: str):
    """Each triangle's (path, element, class) and middle, of the scene's one frame."""
    result = evaluate(Watched(Source(text=text, name="scene.cas")))
    assert result.errors == 0, result.printed
    (frame,) = result.frames
    described = frame.as_json()["origins"]
    n = frame.triangles
    middles = np.frombuffer(frame.data, "<f4", n * 9).reshape(n, 3, 3).mean(axis=1)
    numbers = np.frombuffer(frame.data, "<u4", n, offset=n * 36)
    return [(described[k]["path"], described[k]["element"], described[k]["class"])
            for k in numbers], middles, frame


CUT_THROUGH_TWO = """
a = @h(1, 4, 2) !cu(1, 1, 1);                  // [wall]
b = @t(2, 0, 0) @h(1, 4, 2) !cu(1, 1, 1);      // [column]
trou = @t(0.5, 1, 0.5) @h(2, 1, 1) !cu(0, 0, 1);  // [window]
pied = @t(-1, -1, -0.2) @h(5, 6, 0.2) !cu(0.5, 0.5, 0.5);
> $U($D($U(a, b), trou), pied);
"""


def test_each_face_knows_its_element_and_class():
    faces, middles, frame = _faces(CUT_THROUGH_TWO)
    by_element = {}
    for (path, element, kind), middle in zip(faces, middles):
        by_element.setdefault((element, kind), []).append((path, middle))
    # the unclassed slab is the '>' object's own element (an expression's: object1)
    assert set(by_element) == {("a", "wall"), ("b", "column"), ("object1", None)}
    assert all("pied" in path for path, _ in by_element[("object1", None)])
    # the window's faces (its reveals) lie in both walls: each goes to the one it is on
    for element, low, high in (("a", 0.5, 1.0), ("b", 2.0, 2.5)):
        reveals = [m for path, m in by_element[(element, "wall" if element == "a" else "column")]
                   if "trou" in path]
        assert reveals, element
        assert all(low - 1e-6 <= m[0] <= high + 1e-6 for m in reveals)
    # the window's primitive is one origin per element in the page's table
    table = frame.as_json()["origins"]
    assert sorted((o["element"], o["class"]) for o in table if "trou" in o["path"]) == [
        ("a", "wall"), ("b", "column")]
    json.dumps(frame.as_json())  # as the page gets it


def test_a_scene_without_annotations_has_no_classes():
    faces, _, frame = _faces(CUT_THROUGH_TWO.replace("// [wall]", "").replace(
        "// [column]", "").replace("// [window]", ""))
    assert {kind for _, _, kind in faces} == {None}
    assert len(frame.as_json()["origins"]) == 4  # one per primitive, as before


def test_the_house_s_walls_roof_and_openings():
    with open("examples/house.cas", encoding="utf-8") as handle:
        faces, _, _ = _faces(handle.read())
    of = {}
    for path, element, kind in faces:
        of.setdefault(path, set()).add((element, kind))
    assert of["(maison).U1.D1.U1(murs).D1(plein)!cu"] == {("murs", "wall")}
    assert of["(maison).U3(toit).D1(dessus)!ex"] == {("toit", "roof")}
    assert of["(maison).U5(socle)!cu"] == {("socle", "slab")}
    assert of["(maison).U2(battant)!cu"] == {("maison", None)}  # the door leaf: unclassed
    # the door's cutter makes faces on the walls, not a door of its own
    assert of["(maison).U1.D2.U4(porte_trou)!cu"] == {("murs", "wall")}
    # the high gable windows cut the gables, the low ones the walls below them
    assert of["(maison).U1.D2.U3(fenetres_pignon).U3!cu"] == {("pignons", "wall")}
    assert of["(maison).U1.D2.U3(fenetres_pignon).U1!cu"] == {("murs", "wall")}
