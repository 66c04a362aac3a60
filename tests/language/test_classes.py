"""What an object is (LANGUAGE.md §11): the table of classes, the reading of the
annotations on objects' and parameters' lines, and the warnings of bad ones."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from castor.diagnostics import Location
from castor.language.classes import BY_NAME, CLASSES, read_object_annotation

ROOT = Path(__file__).resolve().parents[2]


def castor(*args, cwd: Path, stdin: str | None = None):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-m", "castor", *args], cwd=cwd, env=env,
                          input=stdin, capture_output=True, text=True, timeout=120)


def read(text: str):
    return read_object_annotation(text, Location("f.cas", 4, 30))


def test_the_table_declares_each_class_once_with_valid_defaults():
    assert len({c.ifc for c in CLASSES}) == len(CLASSES)
    assert len({c.short for c in CLASSES}) == len(CLASSES)
    for info in CLASSES:
        assert info.ifc.startswith("Ifc")
        for setting in info.settings:
            assert setting.default in setting.values
    for word in ("wall", "slab", "roof", "door", "window", "stair", "column", "beam",
                 "railing", "covering", "furniture", "space", "ifcwall", "ifcbuildingelementproxy"):
        assert word in BY_NAME


@pytest.mark.parametrize("text, ifc, predefined, settings, name, description", [
    (" [wall] façades", "IfcWall", None, (), None, "façades"),
    ("[slab floor]", "IfcSlab", "floor", (), None, ""),
    ("[IfcSlab ROOF] top", "IfcSlab", "roof", (), None, "top"),
    ("[door hinge=right swing=out]", "IfcDoor", None, (("hinge", "right"), ("swing", "out")),
     None, ""),
    ("[door]", "IfcDoor", None, (("hinge", "left"), ("swing", "in")), None, ""),
    ('[space "Séjour"] living', "IfcSpace", None, (), "Séjour", "living"),
    ('[space "Salle [A]"]', "IfcSpace", None, (), "Salle [A]", ""),
    ("[stair straight_run_stair]", "IfcStair", "straight_run_stair", (), None, ""),
])
def test_annotation_forms(text, ifc, predefined, settings, name, description):
    classification, problem = read(text)
    assert problem is None
    assert classification.ifc_class == ifc
    assert classification.predefined == predefined
    if settings:
        assert classification.settings == settings
    assert classification.long_name == name
    assert classification.description == description


def test_a_comment_without_a_bracket_is_no_class():
    assert read(" the walls") == (None, None)


SCENE = """\
R0 = 0;      // [storey "Rez"]
R1 = 3.0;    // [storey "Étage"]
H = 9; // [1:0.5:5]
N = 7; // [1, 2, 3]
K = 2; // [wall]
murs = @h(10, 8, 2.8) !cu(1,1,1);   // [wall] façades
p = @h(1,1,1) !cu(1,1,1); // [wal]
q = @h(1,1,1) !cu(1,1,1); // [door hinge=lft]
r = @h(1,1,1) !cu(1,1,1); // [door hnge=left]
s = @h(1,1,1) !cu(1,1,1); // [slab flor]
t = @h(1,1,1) !cu(1,1,1); // [storey "x"]
u = @h(1,1,1) !cu(1,1,1); // [space "Séjour]
v = !cu(1,1,1); w = !cu(1,1,1); // [wall]
> murs; // [wall]
M = 1; // [1:5]
"""

WARNINGS = [
    "s.cas:3:11: warning: parameter annotation: the value 9 is outside the slider's range "
    "1 to 5; the parameter is offered as a number input",
    "s.cas:4:11: warning: parameter annotation: the value 7 is not among the choices 1, 2, 3; "
    "the parameter is offered as a number input",
    "s.cas:5:11: warning: annotation: a class ([wall]) is for an object's definition (a "
    "lowercase name); a parameter can only be a storey's level: [storey \"Name\"]",
    "s.cas:7:30: warning: annotation: unknown class 'wal' (did you mean wall?); the object is "
    "unclassed",
    "s.cas:8:30: warning: annotation: door's hinge is left|right, not 'lft' (did you mean "
    "left?); the object is unclassed",
    "s.cas:9:30: warning: annotation: unknown setting 'hnge' of door (did you mean hinge?); "
    "door has hinge, swing; the object is unclassed",
    "s.cas:10:30: warning: annotation: 'flor' is not a type of slab (did you mean floor?); the "
    "types of slab: floor, roof, landing, baseslab; the object is unclassed",
    "s.cas:11:30: warning: annotation: [storey] is for a parameter that holds a floor level "
    "(R1 = 3.0; // [storey \"Étage\"]), not an object; the object is unclassed",
    "s.cas:12:37: warning: annotation: the quoted name is never closed; write it between two "
    "'\"', as in [space \"Séjour\"]",
    "s.cas:13:36: warning: annotation: this line holds more than one statement, so the "
    "annotation does not say which it is for; put the definition of 'w' on a line of its own",
    "s.cas:14:12: warning: annotation: a '>' command is not a definition; an annotation says "
    "what an object or a parameter is: put it on the line of its definition",
]


@pytest.mark.parametrize("options", [("--check",), ("--check", "--no-cpp")])
def test_bad_annotations_are_warnings_at_their_position(tmp_path: Path, options):
    (tmp_path / "s.cas").write_text(SCENE)
    run = castor(*options, "s.cas", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    warnings = [line for line in run.stderr.splitlines() if ": warning: " in line]
    assert warnings == WARNINGS


def test_annotations_change_no_byte_of_the_output(tmp_path: Path):
    plain = "\n".join(line.split("//")[0] for line in SCENE.splitlines()) + "\n"
    (tmp_path / "a.cas").write_text(SCENE)
    (tmp_path / "b.cas").write_text(plain)
    a = castor("-q", "-f", "off", "a.cas", cwd=tmp_path)
    b = castor("-q", "-f", "off", "b.cas", cwd=tmp_path)
    assert a.returncode == b.returncode == 0
    assert a.stdout == b.stdout and a.stdout


def test_params_lists_the_storeys(tmp_path: Path):
    (tmp_path / "s.cas").write_text(SCENE)
    run = castor("--params", "s.cas", cwd=tmp_path)
    found = {p["name"]: p for p in json.loads(run.stdout)["parameters"]}
    assert found["R0"]["storey"] == "Rez" and found["R1"]["storey"] == "Étage"
    assert found["R1"]["control"] == "number"
    assert "storey" not in found["H"]
    assert found["H"]["control"] == "number"  # its value is out of the slider's reach
    assert found["M"]["control"] == "slider"
    warned = [line for line in run.stderr.splitlines() if ": warning: " in line]
    assert WARNINGS[0] in warned and WARNINGS[1] in warned


def test_object_classes_for_an_editor():
    from castor.language.annotations import object_classes

    lines = SCENE.split("\n")
    definitions = [("murs", Location("s.cas", 6, 1)), ("p", Location("s.cas", 7, 1)),
                   ("w", Location("s.cas", 13, 17))]
    found = object_classes(definitions, lambda file, n: lines[n - 1] if n <= len(lines) else None)
    (murs, _, wall, none), (p, _, unclassed, problem), (w, _, _, crowded) = found
    assert (murs, wall.ifc_class, wall.description, none) == ("murs", "IfcWall", "façades", None)
    assert unclassed is None and problem.location == Location("s.cas", 7, 30)
    assert "did you mean wall?" in problem.message
    assert "more than one statement" in crowded.message


def test_storeys_a_crowded_line_and_a_storey_without_a_name(tmp_path: Path):
    (tmp_path / "s.cas").write_text('R0 = 0; R1 = 3; // [storey "x"]\nK = 1; // [storey]\n'
                                    "w = @h(1, 1, 1) !cu(1, 1, 1);\n> w;\n")
    run = castor("--params", "s.cas", cwd=tmp_path)
    found = {p["name"]: p.get("storey") for p in json.loads(run.stdout)["parameters"]}
    assert found == {"R0": None, "R1": None, "K": "K"}
    assert run.stderr.splitlines()[0] == (
        "s.cas:1:20: warning: annotation: this line holds more than one statement, so the "
        "annotation does not say which it is for; put the definition on a line of its own")
    check = castor("--check", "s.cas", cwd=tmp_path)
    assert check.stderr.splitlines()[0] == run.stderr.splitlines()[0]
    assert check.stderr.count("warning") == 1


def test_an_ifc_name_misspelt_is_suggested_as_ifc_writes_it():
    _, problem = read("[IfcWal]")
    assert "(did you mean IfcWall?)" in problem.message


from hypothesis import given, settings, strategies as st  # noqa: E402


@settings(max_examples=300, deadline=None)
@given(st.text(alphabet='[]"= wallsdoorhinge=leftstorey1:,./\\té', max_size=40))
def test_no_annotation_text_breaks_the_reader(text):
    from castor.language.annotations import read_comment

    classification, problem = read(text)
    assert classification is None or problem is None
    annotation, storey, warning = read_comment(text, Location("f.cas", 1, 10), 3.0)
    assert annotation.control in ("number", "slider", "choice")


def test_the_analysis_gives_each_object_its_class():
    from castor.analysis.scene import analyse, object_classes
    from castor.settings import Source

    analysis = analyse(Source(text=SCENE, name="s.cas"))
    found = {name: (where.line, c.ifc_class if c else None, p.message if p else None)
             for name, where, c, p in object_classes(analysis)}
    assert found["murs"] == (6, "IfcWall", None)
    assert found["p"][:2] == (7, None) and "did you mean wall?" in found["p"][2]
    assert "v" not in found  # its line's annotation is w's, which is warned about
    assert "more than one statement" in found["w"][2]
