"""Two declared storeys within 0.01 of each other are one storey, by one rule
(castor.quantities.one_per_level, applied by the take-off) that the --summary,
the IFC and the drawings all read: the lower names it, at its own level, and a
warning names both as written (docs/classes.md)."""

from __future__ import annotations

import json

import pytest

from castor.quantities import one_per_level, storeys_made_one
from tests.support.cli import run, write
from tests.support.drawings import Drawn
from tests.support.ifc import ifc_of

# issue 29's scene: A at 0 and B at 0.005, then an upper storey C at 3
SCENE = """\
R0 = 0;  // [storey "A"]
R1 = 0.005;  // [storey "B"]
R2 = 3;  // [storey "C"]
w = @h(5, 0.2, 3) !cu(1, 1, 1);  // [wall]
d = @t(1, -0.1, 0) @h(0.9, 0.4, 2.1) !cu(0.2, 0.2, 0.8);  // [door]
m = $D(w, d);  // [wall]
s = @t(0, 0, -0.2) @h(5, 4, 0.2) !cu(0.5, 0.5, 0.5);  // [slab floor]
r = @t(0, 0.2, 0) @h(5, 3.8, 2.8) !cu(1, 1, 1);  // [space "Room"]
u = @t(0, 0, R2) @h(5, 0.2, 3) !cu(1, 1, 1);  // [wall] upstairs
> $U(m, s, r, u);
"""


def _said(path) -> str:
    return (f"{path}:10:1: warning: storeys 'A' (level 0) and 'B' (level 0.005) are within "
            f"0.01 of each other: the model has one storey there, 'A'\n")


def test_the_summary_has_one_storey_at_the_level_and_its_elements_on_it(tmp_path):
    scene = write(tmp_path, "cls.cas", SCENE)
    out = tmp_path / "cls.json"
    status, _, err = run("--summary", str(out), "-o", str(tmp_path / "cls.stl"), str(scene))
    assert status == 0
    assert err.count("warning:") == 1 and _said(scene) in err, err
    frame = json.loads(out.read_text())["frames"][0]
    assert frame["storeys"] == [{"name": "A", "level": 0}, {"name": "C", "level": 3}]
    assert [(c["class"], c["storey"], c["count"]) for c in frame["classes"]] == [
        ("IfcSlab", "A", 1), ("IfcWall", "A", 1), ("IfcWall", "C", 1)]
    assert [(o["name"], o["storey"]) for o in frame["openings"]] == [("d", "A")]
    assert [(s["name"], s["storey"]) for s in frame["spaces"]] == [("Room", "A")]


def test_the_ifc_and_the_summary_agree_and_say_it_once(tmp_path):
    model, err = ifc_of(tmp_path, SCENE, "--summary", "s.json")
    assert err.count("warning:") == 1 and _said("s.cas") in err, err
    storeys = sorted(model.by_type("IfcBuildingStorey"), key=lambda s: s.Elevation)
    assert [(s.Name, s.Elevation) for s in storeys] == [("A", 0.0), ("C", 3.0)]
    contained = {rel.RelatingStructure.Name: sorted(e.Name for e in rel.RelatedElements)
                 for rel in model.by_type("IfcRelContainedInSpatialStructure")}
    assert contained == {"A": ["d", "s", "w"], "C": ["u"]}
    spaces = {rel.RelatingObject.Name: [s.Name for s in rel.RelatedObjects]
              for rel in model.by_type("IfcRelAggregates")
              if rel.RelatingObject.is_a("IfcBuildingStorey")}
    assert spaces == {"A": ["r"]}
    summary = json.loads((tmp_path / "s.json").read_text())["frames"][0]
    assert [(s["name"], s["level"]) for s in summary["storeys"]] == [
        (s.Name, s.Elevation) for s in storeys]


def test_a_plan_names_the_storey_the_model_has(tmp_path):
    scene = write(tmp_path, "cls.cas", SCENE)
    out = tmp_path / "plan.svg"
    status, _, err = run("--section", "z=1", "-o", str(out), str(scene))
    assert status == 0
    assert err.count("warning:") == 1 and _said(scene) in err, err
    assert "Plan z = 1.00, A ±0.00" in Drawn(out.read_bytes(), 100).texts["sheet"]


def test_storeys_apart_are_kept_and_not_said(tmp_path):
    scene = write(tmp_path, "apart.cas", SCENE.replace("R1 = 0.005;", "R1 = 0.02;"))
    out = tmp_path / "apart.json"
    status, _, err = run("--summary", str(out), "-o", str(tmp_path / "a.stl"), str(scene))
    assert (status, err) == (0, "")
    frame = json.loads(out.read_text())["frames"][0]
    assert [s["name"] for s in frame["storeys"]] == ["A", "B", "C"]
    # at 0, the elements are on A: B is 0.02 above them
    assert {c["storey"] for c in frame["classes"]} == {"A", "C"}


@pytest.mark.parametrize("storeys, kept, merged", [
    # the lower names the storey, whatever the order declared
    ([("B", 0.005), ("A", 0.0)], [("A", 0.0)], [(("A", 0.0), ("B", 0.005))]),
    # at one level: the first declared names it
    ([("B", 3.0), ("A", 3.0)], [("B", 3.0)], [(("B", 3.0), ("A", 3.0))]),
    # measured from the storey kept, not from the last one made one with it
    ([("A", 0.0), ("B", 0.008), ("C", 0.016)], [("A", 0.0), ("C", 0.016)],
     [(("A", 0.0), ("B", 0.008))]),
    # 0.01 apart is "within 0.01"; 0.011 is not
    ([("A", 0.0), ("B", 0.01), ("C", 0.021)], [("A", 0.0), ("C", 0.021)],
     [(("A", 0.0), ("B", 0.01))]),
])
def test_one_per_level(storeys, kept, merged):
    assert one_per_level(storeys) == (kept, merged)


def test_the_warning_names_both_levels_unless_they_read_the_same():
    assert storeys_made_one(("A", 0.0), ("B", 0.005)) == (
        "storeys 'A' (level 0) and 'B' (level 0.005) are within 0.01 of each other: the "
        "model has one storey there, 'A'")
    assert storeys_made_one(("Rez", 3.0), ("Sol", 3.0000001)) == (
        "storeys 'Rez' and 'Sol' are both at level 3: the model has one storey there, 'Rez'")
