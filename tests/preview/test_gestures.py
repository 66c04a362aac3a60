"""Gestures that write text (CLI.md, "Editing on screen"): castor.place and
castor.move give the smallest edits, which castor --check accepts, whose
numbers are short, which leave comments and every other frame as they were;
Undo is the inverse edit; what cannot be done is refused with a reason."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from castor.csg.tree import leaves
from castor.editing.commands import (Cache, CommandError, apply_workspace_edit,
                                     inverse_workspace_edit, measure, move, place, text_version)
from castor.editing.document import path_to_uri, read_file
from castor.pipeline import evaluated_frames

ROOT = Path(__file__).resolve().parents[2]


class Scene:
    """A scene file, and the gestures made on it as a page or an editor makes them."""

    def __init__(self, tmp_path: Path, text: str):
        self.path = tmp_path / "scene.cas"
        self.path.write_text(text)
        self.uri = path_to_uri(str(self.path))
        self.cache = Cache()

    @property
    def text(self) -> str:
        return self.path.read_text()

    def do(self, command, **arguments) -> dict:
        """Make the gesture and write its edit, as castor --serve does."""
        edit = command({"uri": self.uri, **arguments}, self.cache)
        new = apply_workspace_edit(edit, read_file)
        assert set(new) <= {self.uri}
        self.path.write_text(new[self.uri])
        return edit

    def castor(self, *options: str) -> subprocess.CompletedProcess:
        return subprocess.run([sys.executable, "-m", "castor", *options, str(self.path)],
                              capture_output=True, text=True, cwd=self.path.parent,
                              env={**os.environ, "PYTHONPATH": str(ROOT)})

    def check(self) -> None:
        done = self.castor("--check")
        assert done.returncode == 0 and done.stderr == "", done.stderr

    def summary(self) -> list:
        out = self.path.parent / "summary.json"
        done = self.castor("--summary", str(out))
        assert done.returncode == 0, done.stderr
        return json.loads(out.read_text())["frames"]

    def frames(self) -> list[str]:
        """Each frame of the polygon stream, as castor writes it."""
        stream = self.castor().stdout
        return ["frame " + part for part in stream.split("\nframe ")[1:]]


HOUSE = """/* a shed and a bench */
L = 4;     // length
abri = $U(@t(0, 0, 0) @h(L, 2, 0.2) !cu(0.7, 0.7, 0.7),   // the slab
          @t(0.1, 0.1, 0.2) @h(0.1, 0.1, 2.3) !cu(0.4, 0.4, 0.4));
banc = @t(1, 0.5, 0.2) @h(2, 0.4, 0.45) !cu(0.5, 0.3, 0.1);
> abri, banc;   // the first frame
> abri;
"""


def test_place_writes_a_short_named_object_before_the_command(tmp_path):
    scene = Scene(tmp_path, HOUSE)
    scene.do(place, frame=2, primitive="!cy", at=[2.2, 0.35, 0], size=[0.3, 0.3, 2.8])
    assert scene.text == HOUSE.replace(
        "> abri;", "poteau1 = @t(2.35, 0.5, 0) @h(0.15, 0.15, 2.8) !cy(0.8, 0.8, 0.8); "
                   "> abri, poteau1;")
    scene.check()
    objects = scene.summary()[1]["objects"]
    assert [o["name"] for o in objects] == ["abri", "poteau1"]
    (x0, y0, z0), (x1, y1, z1) = objects[1]["bbox"]  # a polygon's: within the tolerance in y
    assert (x0, z0, x1, z1) == (2.2, 0, 2.5, 2.8)
    assert (y0, y1) == pytest.approx((0.35, 0.65), abs=0.01)


def test_place_leaves_every_other_frame_byte_for_byte(tmp_path):
    scene = Scene(tmp_path, HOUSE)
    before = scene.frames()
    scene.do(place, frame=1, primitive="!cu", at=[5, 0, 0], size=[0.5, 0.5, 1],
             colour=[0.1, 0.2, 0.3])
    after = scene.frames()
    assert after[1] == before[1]
    assert after[0] != before[0] and "bloc1" in after[0]
    scene.do(place, frame=2, primitive="!sp", at=[5, 0, 0], size=[1, 1, 1])
    assert scene.frames()[0] == after[0]


def test_undo_gives_back_the_file_byte_for_byte(tmp_path):
    scene = Scene(tmp_path, HOUSE)
    edit = place({"uri": scene.uri, "frame": 1, "primitive": "!pr(6)", "at": [0, 0, 0],
                  "size": [1, 1, 1]}, scene.cache)
    undo = inverse_workspace_edit(edit, read_file)
    scene.path.write_text(apply_workspace_edit(edit, read_file)[scene.uri])
    assert "!pr(0.8, 0.8, 0.8, 6)" in scene.text
    scene.path.write_text(apply_workspace_edit(undo, read_file)[scene.uri])
    assert scene.text == HOUSE


def test_place_into_an_object_writes_in_its_coordinates(tmp_path):
    text = HOUSE.replace("> abri;", "> @rz(0) banc, @t(10, 0, 0) abri;")
    scene = Scene(tmp_path, text)
    scene.do(place, frame=2, primitive="!cu", at=[13.5, 1.5, 0.2], size=[1, 1, 1], into="abri")
    assert "bloc1 = @t(3.5, 1.5, 0.2) @h(1, 1, 1) !cu(0.8, 0.8, 0.8); abri = $U(" in scene.text
    assert "!cu(0.4, 0.4, 0.4), bloc1);" in scene.text
    scene.check()
    abri = scene.summary()[1]["objects"][1]
    assert abri["bbox"] == [[10, 0, 0], [14.5, 2.5, 2.5]]


def test_place_into_an_object_that_is_not_a_union_is_refused(tmp_path):
    scene = Scene(tmp_path, HOUSE)
    with pytest.raises(CommandError, match="'banc' is not a \\$U"):
        place({"uri": scene.uri, "frame": 1, "primitive": "!cu", "at": [0, 0, 0],
               "size": [1, 1, 1], "into": "banc"}, scene.cache)
    assert scene.text == HOUSE


def test_move_changes_the_literal_numbers_of_the_translation(tmp_path):
    scene = Scene(tmp_path, HOUSE)
    frames = evaluated_frames(HOUSE, str(scene.path))[0]
    source = [str(p.location) for p, _, path in leaves(frames[0].objects[1].root)][0]
    scene.do(move, frame=1, source=source, by=[0.2, -0.1, 0])
    assert scene.text == HOUSE.replace("banc = @t(1, 0.5, 0.2)", "banc = @t(1.2, 0.4, 0.2)")
    scene.check()
    assert scene.summary()[0]["objects"][1]["bbox"] == [[1.2, 0.4, 0.2], [3.2, 0.8, 0.65]]


def test_move_writes_numbers_short(tmp_path):
    text = "> @t(0.1, 0, 0) @h(1) !cu(1, 1, 1);\n"
    scene = Scene(tmp_path, text)
    scene.do(move, source=f"{scene.path}:1:23", by=[0.2, 0, 0])
    assert scene.text == "> @t(0.3, 0, 0) @h(1) !cu(1, 1, 1);\n"  # not 0.30000000000000004


def test_move_of_a_computed_position_adds_a_translation(tmp_path):
    scene = Scene(tmp_path, HOUSE)
    scene.do(move, frame=2, source=f"{scene.path}:3:37", by=[0, 0, 0.5])
    assert scene.text == HOUSE.replace("abri = $U(@t(0, 0, 0) @h(L, 2, 0.2)",
                                       "abri = $U(@t(0, 0, 0.5) @h(L, 2, 0.2)")
    text = "X = 3;\nplot = @t(X, 2 * X, 0) !cu(1, 1, 1);\n> plot;\n"
    scene = Scene(tmp_path, text)
    scene.do(move, source=f"{scene.path}:2:24", by=[1, 0, 0])
    assert scene.text == text.replace("plot = @t(X", "plot = @t(1, 0, 0) @t(X")
    scene.check()
    assert scene.summary()[0]["objects"][0]["bbox"] == [[4, 6, 0], [5, 7, 1]]


CAR = """roue = @h(0.3, 0.3, 0.1) !cy(0.1, 0.1, 0.1);   /* a wheel */
voiture = $U(@t(0, 0, 0.3) @h(2, 1, 0.5) !cu(0.8, 0.1, 0.1),
             @t(0.3, -0.1, 0.3) @rx(90) roue,
             @rz(90) roue);
> voiture;
"""


def test_move_of_a_primitive_used_twice_moves_the_use_under_the_cursor(tmp_path):
    scene = Scene(tmp_path, CAR)
    wheel = f"{scene.path}:1:26"
    with pytest.raises(CommandError, match="used 2 times"):
        move({"uri": scene.uri, "source": wheel, "by": [1, 0, 0]}, scene.cache)
    scene.do(move, source=wheel, path="(voiture).U2(roue)!cy", by=[1, 0, 0])
    assert scene.text == CAR.replace("@t(0.3, -0.1, 0.3) @rx(90) roue",
                                     "@t(1.3, -0.1, 0.3) @rx(90) roue")
    scene.do(move, source=wheel, path="(voiture).U3(roue)!cy", by=[0, 2, 0])
    assert "             @t(0, 2, 0) @rz(90) roue);" in scene.text
    placed = {path: m for p, m, path in leaves(
        evaluated_frames(scene.text, str(scene.path))[0][0].objects[0].root)}
    assert placed["(voiture).U2(roue)!cy"][3] == pytest.approx(1.3)
    assert placed["(voiture).U3(roue)!cy"][7] == pytest.approx(2.0)


def test_move_inside_a_repetition_is_refused_with_the_reason(tmp_path):
    text = "rangee = $U[I = 0, 3](@t(I * 2, 5, 0) !cy(0.5, 0.5, 0.5));\n> rangee;\n"
    scene = Scene(tmp_path, text)
    with pytest.raises(CommandError, match="one of the copies a repetition makes"):
        move({"uri": scene.uri, "source": f"{scene.path}:1:39", "path": "(rangee).U2!cy",
              "by": [1, 0, 0]}, scene.cache)
    assert scene.text == text
    # the object that holds it moves
    scene.do(move, source=f"{scene.path}:1:1", path="(rangee)", by=[1, 0, 0])
    assert scene.text == text.replace("> rangee;", "> @t(1, 0, 0) rangee;")


def test_move_on_an_animation_frame_edits_the_definition_its_frames_share(tmp_path):
    text = "porte = @rz(90 * T) @h(1, 0.1, 2) !cu(0.5, 0.3, 0.1);\n>[T = 0, 1] porte;\n"
    scene = Scene(tmp_path, text)
    scene.do(move, frame=2, source=f"{scene.path}:1:35", by=[0, 0, 0.25])
    assert scene.text == text.replace("porte = @rz", "porte = @t(0, 0, 0.25) @rz")
    scene.check()
    assert [f["objects"][0]["bbox"][0][2] for f in scene.summary()] == [0.25, 0.25]


def test_an_edit_on_an_older_text_is_refused(tmp_path):
    scene = Scene(tmp_path, HOUSE)
    version = text_version(HOUSE)
    scene.path.write_text(HOUSE.replace("L = 4;", "L = 5;"))
    with pytest.raises(CommandError, match="the text changed"):
        place({"uri": scene.uri, "version": version, "primitive": "!cu", "at": [0, 0, 0],
               "size": [1, 1, 1]}, scene.cache)
    assert scene.text == HOUSE.replace("L = 4;", "L = 5;")


@pytest.mark.parametrize("arguments, message", [
    ({"primitive": "!xx", "at": [0, 0, 0], "size": [1, 1, 1]}, "unknown primitive '!xx'"),
    ({"primitive": "!cu", "at": [0, 0, 0], "size": [1, 0, 1]}, "size"),
    ({"primitive": "!pr(N)", "at": [0, 0, 0], "size": [1, 1, 1]}, "plain numbers"),
    ({"primitive": "!pr", "at": [0, 0, 0], "size": [1, 1, 1]}, "takes"),
    ({"primitive": "!cu", "at": [0, 0], "size": [1, 1, 1]}, "'at' must be three numbers"),
    ({"primitive": "!cu", "at": [0, 0, 0], "size": [1, 1, 1], "frame": 3}, "frame 3"),
    ({"primitive": "!cu", "at": [0, 0, 0], "size": [1, 1, 1], "name": "abri"}, "already used"),
    ({"primitive": "!cu", "at": [0, 0, 0], "size": [1, 1, 1], "colour": [2, 0, 0]}, "colour"),
])
def test_bad_places_are_refused(tmp_path, arguments, message):
    scene = Scene(tmp_path, HOUSE)
    with pytest.raises(CommandError, match=message):
        place({"uri": scene.uri, **arguments}, scene.cache)
    assert scene.text == HOUSE


@pytest.mark.parametrize("arguments, message", [
    ({"source": "nowhere", "by": [1, 0, 0]}, "FILE:LINE:COL"),
    ({"source": "scene.cas:99:1", "by": [1, 0, 0]}, "no primitive or object use"),
    ({"source": "scene.cas:3:37", "by": [1, 0]}, "'by' must be three numbers"),
    ({"source": "scene.cas:3:37", "by": [1, 0, 0], "path": "(abri).U7!cu"}, "no primitive"),
])
def test_bad_moves_are_refused(tmp_path, arguments, message):
    scene = Scene(tmp_path, HOUSE)
    with pytest.raises(CommandError, match=message):
        move({"uri": scene.uri, **arguments}, scene.cache)
    assert scene.text == HOUSE


def test_measure_gives_distances_volumes_and_boxes_and_edits_nothing(tmp_path):
    scene = Scene(tmp_path, HOUSE)
    assert measure({"from": [1, 2, 3], "to": [4, 6, 3]}, scene.cache) == {
        "distance": 5.0, "dx": 3.0, "dy": 4.0, "dz": 0.0}
    banc = measure({"uri": scene.uri, "object": "banc"}, scene.cache)
    assert banc["volume"] == pytest.approx(2 * 0.4 * 0.45)
    assert banc["box"] == [[1, 0.5, 0.2], [3, 0.9, pytest.approx(0.65)]]
    assert scene.text == HOUSE


def test_measure_a_face_of_the_evaluated_solid(tmp_path):
    """The top of two blocks side by side is one face (6 x 2); a hole cut through
    it takes its area away; a sphere's face is measured on its facets."""
    scene = Scene(tmp_path, "> $D($U(@h(4, 2, 1) !cu(1, 1, 1), @t(4, 0, 0) @h(2, 2, 1) "
                            "!cu(1, 1, 1)), @t(1, 0.5, -1) @h(1, 1, 3) !cu(0, 0, 1)), "
                            "@t(10, 0, 0) @h(2) !sp(1, 0, 0);\n")
    top = measure({"uri": scene.uri, "origin": [5.1, 1.3, 9], "direction": [0, 0, -1]},
                  scene.cache)
    assert top["area"] == pytest.approx(6 * 2 - 1) and top["exact"] is True
    ball = measure({"uri": scene.uri, "origin": [10.3, -9, 0.2], "direction": [0, 1, 0]},
                   scene.cache)
    assert ball["exact"] is False and ball["path"] == "!sp"
    assert ball["area"] == pytest.approx(4 * 3.141592653589793 * 4, rel=0.02)


def test_the_preview_writes_only_the_scenes_own_files(tmp_path):
    from castor.editing.commands import write_workspace_edit

    (tmp_path / "parts.cas").write_text("/* parts */\nbloc = @t(1, 0, 0) !cu(1, 1, 1);\n")
    scene = Scene(tmp_path, '#include "parts.cas"\n> bloc;\n')
    edit = move({"uri": scene.uri, "source": f"{tmp_path / 'parts.cas'}:2:20", "by": [0, 1, 0]},
                scene.cache)
    undo = write_workspace_edit(edit, scene.cache, scene.uri)
    assert (tmp_path / "parts.cas").read_text() == \
        "/* parts */\nbloc = @t(1, 1, 0) !cu(1, 1, 1);\n"
    write_workspace_edit(undo, scene.cache, scene.uri)
    assert (tmp_path / "parts.cas").read_text() == \
        "/* parts */\nbloc = @t(1, 0, 0) !cu(1, 1, 1);\n"
    # the included file changes: each gesture sees it as it is
    for _ in range(2):
        edit = move({"uri": scene.uri, "source": f"{tmp_path / 'parts.cas'}:2:20",
                     "by": [1, 0, 0]}, scene.cache)
        write_workspace_edit(edit, scene.cache, scene.uri)
    assert "bloc = @t(3, 0, 0) !cu" in (tmp_path / "parts.cas").read_text()
    other = tmp_path / "other.cas"
    other.write_text("x")
    with pytest.raises(CommandError, match="not one of the scene's files"):
        write_workspace_edit({"changes": {path_to_uri(str(other)): []}}, scene.cache, scene.uri)
    assert other.read_text() == "x"


def test_gestures_on_the_bus_shelter_keep_it_clean(tmp_path):
    """Seven files, macros, repetitions and '#ifdef': a snapped primitive moved in
    an included file, a new object placed in the animation's '>' (in the #else)."""
    import shutil

    shutil.copy(ROOT / "examples" / "bus_shelter.cas", tmp_path)
    shutil.copytree(ROOT / "examples" / "bus_shelter", tmp_path / "bus_shelter")
    scene = Scene.__new__(Scene)
    scene.path, scene.cache = tmp_path / "bus_shelter.cas", Cache()
    scene.uri = path_to_uri(str(scene.path))
    before = {p.name: p.read_text() for p in (tmp_path / "bus_shelter").iterdir()}
    # the road's surface, under a ray straight down in front of the shelter
    from castor.editing.commands import snap

    found = snap({"uri": scene.uri, "frame": 2, "origin": [3.13, -3.52, 30],
                  "direction": [0, 0, -1], "pixelSize": 0.01}, scene.cache)
    assert found["path"] == "(arret).U1(decor).U1(rue).U1(chaussee)!cu"
    assert found["point"][2] == pytest.approx(0.0, abs=1e-12)
    edit = move({"uri": scene.uri, "frame": 2, "source": found["source"],
                 "path": found["path"], "by": [0, 0, -0.02]}, scene.cache)
    (street,) = edit["changes"]
    assert street.endswith("/bus_shelter/street.cas")
    after = apply_workspace_edit(edit, read_file)[street]
    (tmp_path / "bus_shelter" / "street.cas").write_text(after)
    scene.do(place, frame=3, primitive="!cu", at=[1, -2, 0], size=[0.4, 0.4, 1.2])
    assert "bloc1 = @t(1, -2, 0) @h(0.4, 0.4, 1.2) !cu(0.8, 0.8, 0.8); " \
           ">[PHASE = 0, 2] arret, bloc1;" in scene.text
    scene.check()
    changed = [name for name, text in before.items()
               if (tmp_path / "bus_shelter" / name).read_text() != text]
    assert changed == ["street.cas"]


_values = st.one_of(st.none(), st.booleans(), st.integers(-5, 5), st.text(max_size=6),
                    st.sampled_from(["!pr(2)", "!to(1.5)", "!ex(0, 0, 1, 0)", "(abri).U9!cu",
                                     "abri", "banc", "!sp", "B ad"]),
                    st.floats(allow_nan=True, allow_infinity=True),
                    st.lists(st.one_of(st.floats(-1e12, 1e12), st.integers(-3, 3),
                                       st.text(max_size=2)), max_size=4))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.sampled_from(["castor.snap", "castor.place", "castor.move", "castor.measure"]),
       st.dictionaries(st.sampled_from(["frame", "origin", "direction", "pixel", "pixelSize",
                                        "from", "distance", "primitive", "at", "size",
                                        "colour", "name", "into", "source", "by", "path",
                                        "to", "object", "version"]), _values, max_size=2))
def test_no_arguments_make_a_traceback(tmp_path, command, arguments):
    from castor.editing.commands import execute

    path = tmp_path / "scene.cas"
    path.write_text(HOUSE)
    good = {"castor.snap": {"origin": [3, -4, 5], "direction": [0, 1, -1], "pixel": 0.001},
            "castor.place": {"primitive": "!cu", "at": [0, 0, 0], "size": [1, 1, 1]},
            "castor.move": {"source": f"{path}:3:37", "by": [1, 0, 0]},
            "castor.measure": {"from": [0, 0, 0], "to": [1, 1, 1]}}[command]
    try:
        execute(command, {"uri": path_to_uri(str(path)), **good, **arguments}, Cache())
    except CommandError:
        pass
    assert path.read_text() == HOUSE
