"""``castor --check`` gives the warnings a run gives, and the language server
says what --check says.

``castor --check empty.cas`` (a difference that leaves nothing) printed nothing
while ``castor empty.cas`` warned "frame 1 is empty: its objects have no
volume"; a scene without a '>' command was silent under --check. --check never
facetizes: it says a frame is empty where its evaluated tree shows it
(castor.csg.emptiness), and never where a run would write polygons.
"""

import pytest

from castor.analysis.scene import analyse
from castor.settings import Source
from tests.support.cli import run_here

EMPTY = "a = $D(!cu(1,1,1), @s(2) !cu(1,1,1));\n> a;\n"
NO_FRAME = ("castor: warning: the scene has no '>' command, so nothing would be written; "
            "'> OBJECT;' writes an object's polygons\n")

# (object, whether a run finds its frame empty): --check says so of the first
# ones, and of none a run writes with polygons
CERTAIN = [
    "$D(!cu(1,1,1), @t(-1,-1,-1) @h(3) !cu(1,1,1))",
    "$D(!cu(1,1,1), !cu(1,1,1))",
    "$D(@t(0,0,1e-12) !cu(1,1,1), !cu(1,1,1))",
    "$D(@rz(45) !cu(1,1,1), @t(-0.71,0,0) @h(1.42,1.42,1) !cu(1,1,1))",
    "$D(!cu(1,1,1), $U(@t(-1,-1,-1) @h(3) !cu(1,1,1), !sp(1,1,1)))",
    "$D(!cu(1,1,1), $I(@t(-1,-1,-1) @h(3) !cu(1,1,1), @t(-2,-2,-2) @h(5) !cu(1,1,1)))",
    "$D(!cu(1,1,1), @s(89) !cu(1,1,1))",
    "$D(@s(120) !cu(1,1,1), !cu(1,1,1))",
    "$D(@t(0.6,1.5,0.3) @h(0.15,0.2,0.3) !cu(1,0,0), @s(80) @h(3,3,3) @rz(30) !cu(0,1,0))",
    "$D(!to(1,1,1,0.3), @t(-2,-2,-2) @h(5) !cu(1,1,1))",
    "$I(!cu(1,1,1), @t(1,0,0) !cu(1,1,1))",
    "$I(!sp(1,1,1), @t(5,0,0) !cy(1,1,1))",
    "$U($D(!cu(1,1,1), !cu(1,1,1)), $I(!cu(1,1,1), @t(3,0,0) !cu(1,1,1)))",
]
WRITTEN = [
    "$I(!cu(1,1,1), @t(0.999,0,0) !cu(1,1,1))",
    "$D(!cy(1,1,1), @t(-0.1,-0.1,-0.1) @h(1.2) !cu(1,1,1))",
    "$D(@rz(45) !cu(1,1,1), @t(-0.70,0,0) @h(1.40,1.42,1) !cu(1,1,1))",
    "$D(!cu(1,1,1), @s(120) !cu(1,1,1))",
    "$I(!sp(1,1,1), @t(1.0001,0,0) !sp(1,1,1))",
    "$D(@t(0.5,0.5,0.5) !sp(1,1,1), @h(1) !cu(1,1,1))",
    # a smoothed cube sheared (a scale across a turn, or @m) has obtuse edges,
    # which @s below 90 degrees rounds off: the box is not all subtracted
    "$D(@t(0.6,1.5,0.3) @h(0.15,0.2,0.3) !cu(1,0,0), @s(80) @h(1,3,1) @rz(30) !cu(0,1,0))",
    "$D(@t(1.0,0.92,0.3) @h(0.06,0.06,0.4) !cu(1,0,0), @s(70) @m(1,1,0,0, 0,1,0,0, 0,0,1,0) !cu(0,1,0))",
]


def warnings(err: str) -> list[str]:
    return [line for line in err.splitlines() if ": warning: " in line]


def check_and_run(tmp_path, monkeypatch, text: str):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "scene.cas").write_text(text)
    checked = run_here("--check", "scene.cas")
    made = run_here("-o", "scene.cps", "scene.cas")
    return checked, made


def test_an_empty_frame_is_warned_of_as_a_run_does(tmp_path, monkeypatch):
    checked, made = check_and_run(tmp_path, monkeypatch, EMPTY)
    assert checked == (0, "", "scene.cas:2:1: warning: frame 1 is empty: its objects have no "
                              "volume\n > a;\n ^\n")
    assert made[0] == 0 and made[2] == checked[2]


def test_each_empty_frame_of_an_animation(tmp_path, monkeypatch):
    text = "a = $D(!cu(1,1,1), @t(-1,-1,-1) @h(3) !cu(1,1,1));\n>[T = 1, 3] a;\n"
    checked, made = check_and_run(tmp_path, monkeypatch, text)
    assert [w.split(": warning: ")[1] for w in warnings(checked[2])] == [
        f"frame {k} is empty: its objects have no volume" for k in (1, 2, 3)]
    assert warnings(checked[2]) == warnings(made[2])


def test_a_scene_without_a_frame_command(tmp_path, monkeypatch):
    checked, made = check_and_run(tmp_path, monkeypatch, "m = @h(1, 1, 2) !cu(1,1,1);\n")
    assert checked == (0, "", NO_FRAME)
    assert made == (0, "", NO_FRAME.replace("would be written", "was written"))
    # with errors, the errors say it all
    status, _, err = run_here("--check", "-", stdin="M = ;\n")
    assert status == 1 and "no '>' command" not in err


@pytest.mark.parametrize("text", [EMPTY, "m = !cu(1,1,1);\n", "X = 1 +;\na = !cu(1,1,1);\n"
                                  "b = $I(a, @t(2,0,0) a);\n> b;\n> a;\n"])
def test_the_language_server_says_what_check_says(tmp_path, monkeypatch, text):
    _, err = check_and_run(tmp_path, monkeypatch, text)[0][1:]
    said = [line for line in err.splitlines()
            if ": warning: " in line or ": error: " in line]
    found = [f"{d.location}: {d.kind}: {d.message}" if d.location is not None
             else f"castor: {d.kind}: {d.message}"
             for d in analyse(Source(text=text, name=str(tmp_path / "scene.cas"))).diagnostics]
    assert found == said and found


@pytest.mark.parametrize("shape", CERTAIN)
def test_check_says_empty_where_the_tree_shows_it(tmp_path, monkeypatch, shape):
    checked, made = check_and_run(tmp_path, monkeypatch, f"a = {shape};\n> a;\n")
    assert "frame 1 is empty" in checked[2]
    assert warnings(checked[2]) == warnings(made[2])


@pytest.mark.parametrize("shape", WRITTEN)
def test_check_never_says_empty_where_a_run_writes_polygons(tmp_path, monkeypatch, shape):
    checked, made = check_and_run(tmp_path, monkeypatch, f"a = {shape};\n> a;\n")
    assert (checked[0], made[0]) == (0, 0)
    assert "is empty" not in made[2] and "is empty" not in checked[2]
