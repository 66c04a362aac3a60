"""--ifc-class NAME=CLASS naming a space (a room, never built): the model keeps
it an IfcSpace and says the option is ignored, once, naming the option and the
object (it was silently ignored)."""

from __future__ import annotations

import pytest

from tests.support.cli import run, write

ifcopenshell = pytest.importorskip("ifcopenshell")

SCENE = """\
mur = @h(5, 0.2, 3) !cu(0.9, 0.9, 0.8);  // [wall]
sejour = @t(0, 0.2, 0) @h(5, 3.8, 2.8) !cu(1, 1, 1);  // [space "Sejour"]
maison = $U(mur, sejour);
> maison;
"""


def test_a_space_made_a_wall_by_the_option_stays_a_space_and_is_said(tmp_path):
    scene = write(tmp_path, "sp.cas", SCENE)
    out = tmp_path / "sp.ifc"
    status, _, err = run("-o", str(out), "--ifc-class", "sejour=IfcWall",
                         "--ifc-class", "mur=IfcWall", str(scene))
    assert status == 0
    assert err == (f"{scene}:4:1: warning: --ifc-class sejour=IfcWall: 'sejour' is a space "
                   "(a room, left out of the solids: LANGUAGE.md §11), so it stays an "
                   "IfcSpace; the option is ignored\n > maison;\n ^\n"), err
    model = ifcopenshell.open(str(out))
    assert [s.Name for s in model.by_type("IfcSpace")] == ["sejour"]
    assert [w.Name for w in model.by_type("IfcWall")] == ["mur"]


def test_a_door_filling_an_opening_made_a_window_by_the_option_is_said(tmp_path):
    scene = write(tmp_path, "door.cas", """\
porte = @t(1, -0.1, 0) @h(0.9, 0.5, 2.1) !cu(0.2, 0.3, 0.8);  // [door]
mur = $D(@h(4, 0.3, 2.5) !cu(0.9, 0.9, 0.8), porte);  // [wall]
> mur;
""")
    out = tmp_path / "door.ifc"
    status, _, err = run("-o", str(out), "--ifc-class", "porte=IfcWindow", str(scene))
    assert status == 0
    assert err == (f"{scene}:3:1: warning: --ifc-class porte=IfcWindow: 'porte' is a door "
                   "filling an opening (LANGUAGE.md §11), so it stays an IfcDoor; the option "
                   "is ignored\n > mur;\n ^\n"), err
    model = ifcopenshell.open(str(out))
    assert [d.Name for d in model.by_type("IfcDoor")] == ["porte"]
    assert not model.by_type("IfcWindow")


def test_the_option_is_said_once_for_all_the_frames_of_an_animation(tmp_path):
    # one IFC file per frame: it was said once per frame (the same words, the same place)
    scene = write(tmp_path, "anim.cas", SCENE.replace("> maison;", ">[T = 0, 2] @rz(T) maison;"))
    status, _, err = run("-o", str(tmp_path / "anim%d.ifc"), "--ifc-class", "sejour=IfcWall",
                         str(scene))
    assert status == 0, err
    assert err.count("warning:") == 1, err
    assert "'sejour' is a space (a room, left out of the solids" in err
    assert sorted(p.name for p in tmp_path.glob("anim*.ifc")) == ["anim1.ifc", "anim2.ifc",
                                                                   "anim3.ifc"]
