"""Parameter annotations (LANGUAGE.md §10), castor --params, and -p FILE -P NAME."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from castor.diagnostics import Location
from castor.language.annotations import parse_annotation

ROOT = Path(__file__).resolve().parents[2]

SCENE = """\
/* [Walls] */
H = 2.9;          // [2.5:0.1:4] height of the walls
N = 3;            // [1:6] windows per side
TOIT = 30;        // [20, 30, 45] roof pitch
EP = 0.2 * 1;     // thickness of the walls
BAD = 1;          // [4:0.1:2.5] inverted
/* [Hidden] */
Z = 2; // [a:b]
H = H + 1;
b = @t(N, 0, 0) @h(1, EP * 10, H) !cu(1, 0, 0);
> b;
"""


def castor(*args, cwd: Path, stdin: str | None = None):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-m", "castor", *args], cwd=cwd, env=env,
                          input=stdin, capture_output=True, text=True, timeout=120)


@pytest.fixture
def scene(tmp_path: Path) -> Path:
    (tmp_path / "s.cas").write_text(SCENE)
    return tmp_path


@pytest.mark.parametrize("text, control, fields", [
    ("[2.5:0.1:4] height", "slider", {"minimum": 2.5, "step": 0.1, "maximum": 4.0}),
    ("[1:6] windows", "slider", {"minimum": 1.0, "step": 1.0, "maximum": 6.0}),
    ("[20, 30, 45] pitch", "choice", {"choices": [(20.0, "20"), (30.0, "30"), (45.0, "45")]}),
    ("[10:small, 20:large]", "choice", {"choices": [(10.0, "small"), (20.0, "large")]}),
    (" just words", "number", {"description": "just words"}),
])
def test_annotation_forms(text, control, fields):
    annotation, warning = parse_annotation(text, Location("f.cas", 1, 12))
    assert warning is None
    assert annotation.control == control
    for key, value in fields.items():
        assert getattr(annotation, key) == value


@pytest.mark.parametrize("text, column, words", [
    ("[4:0.1:2.5] x", 12, "minimum 4 not below its maximum 2.5"),
    ("[a:b]", 12, "[a:b] is not a range"),
    ("  [1:0:3]", 14, "step 0 that is not positive"),
    ("[1, two]", 12, "'two' is not a number"),
    ("[1:3", 12, "'[' without its ']'"),
])
def test_malformed_annotation_is_a_warning_at_its_position(text, column, words):
    annotation, warning = parse_annotation(text, Location("f.cas", 3, 12))
    assert annotation.control == "number"
    assert words in warning.message
    assert warning.location == Location("f.cas", 3, column)


def test_params_json(scene: Path):
    run = castor("--params", "s.cas", cwd=scene)
    assert run.returncode == 0, run.stderr
    found = {p["name"]: p for p in json.loads(run.stdout)["parameters"]}
    assert list(found) == ["H", "N", "TOIT", "EP", "BAD", "Z"]  # first definitions only
    h = found["H"]
    assert h == {"name": "H", "value": 2.9, "expression": "2.9", "location": "s.cas:2",
                 "group": "Walls", "hidden": False, "control": "slider",
                 "description": "height of the walls",
                 "range": {"min": 2.5, "step": 0.1, "max": 4.0}}
    assert found["TOIT"]["choices"] == [{"value": v, "label": str(v)} for v in (20, 30, 45)]
    assert found["EP"]["expression"] == "0.2 * 1" and found["EP"]["control"] == "number"
    assert found["Z"]["hidden"] and found["Z"]["group"] == "Hidden"
    assert found["BAD"]["control"] == "number"
    warnings = [line for line in run.stderr.splitlines() if ": warning: " in line]
    assert warnings[0].startswith("s.cas:6:22: warning: parameter annotation: the range")
    assert warnings[1].startswith("s.cas:8:11: warning: parameter annotation: [a:b]")


@pytest.mark.parametrize("options", [("--check",), ("--check", "--no-cpp"), ("-o", "s.obj")])
def test_castor_warns_of_a_malformed_annotation_once_as_params_does(scene: Path, options):
    """castor and castor --check say what --params says of the annotations, once
    per parameter (at its first definition), through macros too."""
    text = SCENE.replace("Z = 2; // [a:b]", "#define ZED 2\nZ = ZED; // [a:b]")
    if "--no-cpp" in options:
        text = SCENE
    (scene / "s.cas").write_text(text)
    run = castor(*options, "s.cas", cwd=scene)
    assert run.returncode == 0, run.stderr
    warnings = [line for line in run.stderr.splitlines() if ": warning: " in line]
    line = 8 if "--no-cpp" in options else 9
    assert len(warnings) == 2, run.stderr
    assert warnings[0].startswith("s.cas:6:22: warning: parameter annotation: the range")
    assert warnings[1].startswith(f"s.cas:{line}:{11 if line == 8 else 13}: warning: "
                                  f"parameter annotation: [a:b]")
    params = castor("--params", "s.cas", cwd=scene) if "--no-cpp" not in options else None
    if params is not None:
        assert [w for w in params.stderr.splitlines() if ": warning: " in w] == warnings
    assert "warning" not in castor(*options, "-q", "s.cas", cwd=scene).stderr  # -q: quiet


def test_params_with_set_and_included_file(tmp_path: Path):
    (tmp_path / "part.cas").write_text("/* [Part] */\nW = 2; // [1:5] width\n")
    (tmp_path / "main.cas").write_text('#include "part.cas"\nL = W * 2;\n')
    run = castor("--params", "--set", "W=3", "main.cas", cwd=tmp_path)
    found = {p["name"]: p for p in json.loads(run.stdout)["parameters"]}
    assert found["W"]["location"].endswith("part.cas:2")
    assert found["W"]["value"] == 3 and found["W"]["group"] == "Part"
    assert found["L"]["value"] == 6 and found["L"]["expression"] == "W * 2"


def _frames(*args, cwd: Path) -> bytes:
    run = castor(*args, "-f", "off", cwd=cwd)
    assert run.returncode == 0, run.stderr
    return run.stdout.encode()


def test_parameter_set_gives_the_frames_of_the_equivalent_sets(scene: Path):
    (scene / "s.json").write_text(json.dumps({
        "parameterSets": {"tall": {"H": "3.5", "N": 4, "EP": "0.25"}, "low": {"H": "2.6"}},
        "fileFormatVersion": "1"}))
    given = _frames("-p", "s.json", "-P", "tall", "s.cas", cwd=scene)
    assert given == _frames("--set", "H=3.5", "--set", "N=4", "--set", "EP=0.25", "s.cas",
                            cwd=scene)
    assert given != _frames("s.cas", cwd=scene)
    # an explicit --set wins over the set's value
    assert _frames("-p", "s.json", "-P", "tall", "--set", "H=2.6", "s.cas", cwd=scene) == \
        _frames("--set", "H=2.6", "--set", "N=4", "--set", "EP=0.25", "s.cas", cwd=scene)


def test_house_set_gives_the_frames_of_sets(tmp_path: Path):
    (tmp_path / "house.json").write_text(json.dumps({
        "parameterSets": {"big": {"H": "3.2", "L": "10"}}, "fileFormatVersion": "1"}))
    house = str(ROOT / "examples" / "house.cas")
    assert _frames("-p", "house.json", "-P", "big", house, cwd=tmp_path) == \
        _frames("--set", "H=3.2", "--set", "L=10", house, cwd=tmp_path)


@pytest.mark.parametrize("content, set_name, words", [
    (None, "x", "cannot read the parameter file 'p.json': No such file or directory"),
    ("{oops", "x", "the parameter file 'p.json' is not JSON"),
    ('{"sets": {}}', "x", "has no \"parameterSets\" object"),
    ('{"parameterSets": {"a": {"H": "1"}, "b": {}}}', "c",
     "no parameter set 'c' in 'p.json' (sets in the file: a, b)"),
    ('{"parameterSets": {"a": {"Q": "1"}}}', "a",
     "names Q, which the scene does not define (its parameters: BAD, EP, H, N, TOIT, Z)"),
    ('{"parameterSets": {"a": {"H": "1+1"}}}', "a", "gives H the value '1+1', which is not a number"),
])
def test_parameter_file_errors_list_what_there_is(scene: Path, content, set_name, words):
    if content is not None:
        (scene / "p.json").write_text(content)
    run = castor("-p", "p.json", "-P", set_name, "s.cas", cwd=scene)
    assert run.returncode == 2
    assert run.stdout == ""
    assert run.stderr.startswith("castor: error: ")
    assert words in run.stderr
    assert "Traceback" not in run.stderr


def test_p_and_P_go_together(scene: Path):
    (scene / "p.json").write_text('{"parameterSets": {"a": {}, "b": {}}}')
    run = castor("-p", "p.json", "s.cas", cwd=scene)
    assert run.returncode == 2 and "needs -P NAME" in run.stderr and "a, b" in run.stderr
    run = castor("-P", "a", "s.cas", cwd=scene)
    assert run.returncode == 2 and "give the file with -p FILE" in run.stderr


def test_saved_set_is_read_back(tmp_path: Path):
    from castor.analysis.customizer import load_set, save_set

    path = tmp_path / "house.json"
    save_set(str(path), "one", {"H": 3.2, "N": 4.0})
    save_set(str(path), "two", {"H": 0.1 + 0.2})
    document = json.loads(path.read_text())
    assert document["fileFormatVersion"] == "1"
    assert document["parameterSets"]["one"] == {"H": "3.2", "N": "4"}
    assert load_set(str(path), "two") == {"H": 0.1 + 0.2}
