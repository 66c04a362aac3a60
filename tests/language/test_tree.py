"""The evaluated CSG tree: what each '>' becomes as data (castor.csg.tree)."""

import os
import pickle
import subprocess
import sys
from pathlib import Path

import pytest

from castor.csg import tree
from castor.run import evaluated_frames
from tests.support.cli import frames_of, run
from tests.support.stream import parse_stream

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((ROOT / "examples").glob("*.cas"))


def _trees(path):
    trees, said = evaluated_frames(path.read_text(), str(path))
    return trees


def test_car_tree_has_its_matrices_colours_paths_and_one_shared_wheel():
    [frame] = _trees(ROOT / "examples" / "car.cas")
    [car] = frame.objects
    assert car.name == "voiture"
    leaves = list(tree.leaves(car.root))
    paths = [path for _, _, path in leaves]
    assert paths == ["(voiture).U1(caisse)!cu", "(voiture).U2(cabine)!cu",
                     "(voiture).U3(roue)!cy", "(voiture).U4(roue)!cy",
                     "(voiture).U5(roue)!cy", "(voiture).U6(roue)!cy"]
    body = leaves[0][0]
    assert body.colour == (0.8, 0.1, 0.1) and body.kind == "cu"
    # the body: @t(0, 0, 0.35) @h(4, 1.6, 1): a 4 x 1.6 x 1 box raised by 0.35
    assert body.matrix == (4.0, 0.0, 0.0, 0.0, 0.0, 1.6, 0.0, 0.0, 0.0, 0.0, 1.0, 0.35)
    wheels = [n for n in car.root.shared.child.operands if n.shared.name == "roue"]
    assert len(wheels) == 4 and len({w.shared.key for w in wheels}) == 1
    assert len({id(w.shared) for w in wheels}) == 1  # one object, referenced four times
    # each wheel placed by its own matrix: translations of the scene's @t
    assert sorted((w.matrix[3], w.matrix[7]) for w in wheels) == [
        (0.8, 0.0), (0.8, 1.85), (3.2, 0.1), (3.2, 1.75)]


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_every_example_tree_names_the_paths_and_colours_of_its_polygons(path):
    trees = _trees(path)
    status, out, err = run(str(path))
    frames = parse_stream(out)
    assert [t.number for t in trees] == [f.number for f in frames]
    for scene, frame in zip(trees, frames):
        colours = {}
        for obj in scene.objects:
            for leaf, _, full in tree.leaves(obj.root):
                colours[full] = leaf.colour
        for polygon in frame.polygons:
            assert polygon.path in colours
            assert polygon.colour == pytest.approx(colours[polygon.path])


def test_trees_pickle_and_keys_are_the_same_in_every_process():
    scene = (ROOT / "examples" / "house.cas").read_text()
    [frame] = evaluated_frames(scene, "house.cas")[0]
    again = pickle.loads(pickle.dumps(frame))
    assert tree.dump(again) == tree.dump(frame)
    code = ("import sys; from castor.run import evaluated_frames; from castor.csg import tree;"
            "f = evaluated_frames(sys.stdin.read(), 'house.cas')[0][0];"
            "print(sorted(f.shared()))")
    keys = set()
    for seed in ("1", "2"):
        out = subprocess.run([sys.executable, "-c", code], input=scene, capture_output=True,
                             text=True, env={**os.environ, "PYTHONHASHSEED": seed}, check=True)
        keys.add(out.stdout)
    assert keys == {f"{sorted(frame.shared())}\n"}


def test_four_hundred_trees_are_one_shared_subtree():
    scene = ("arbre = $U(@h(0.1, 0.1, 1) !cy(0.4, 0.3, 0.2), @t(0, 0, 1) !sp(0.2, 0.6, 0.2));\n"
             "foret = $U[I = 0, 19]($U[J = 0, 19](@t(3 * I, 3 * J, 0) arbre));\n> foret;\n")
    [frame] = evaluated_frames(scene)[0]
    shared = frame.shared()
    assert sorted(s.name for s in shared.values()) == ["arbre", "foret"]
    assert len(list(tree.leaves(frame.objects[0].root))) == 800
    assert len(pickle.dumps(frame)) < 200_000


def test_late_binding_gives_a_new_key_only_where_a_parameter_read_changes():
    scene = ("L = 1;\nfixe = !cu(1, 0, 0);\nmobile = @h(L, 1, 1) !cu(0, 1, 0);\n"
             "> $U(fixe, @t(2, 0, 0) mobile);\nL = 2;\n> $U(fixe, @t(2, 0, 0) mobile);\n")
    one, two = evaluated_frames(scene)[0]
    first, second = ({s.name: key for key, s in f.shared().items()} for f in (one, two))
    assert first["fixe"] == second["fixe"]
    assert first["mobile"] != second["mobile"]


def test_mirror_and_matrix_compose_into_the_leaf():
    [frame] = evaluated_frames("> @t(1, 2, 3) @h(-1, 1, 1) @m(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 2, 0)"
                               " !cu(1, 1, 1);\n")[0]
    [(leaf, matrix, path)] = list(tree.leaves(frame.objects[0].root))
    assert path == "!cu" and frame.objects[0].name == "object1"
    assert matrix == (-1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 2.0, 0.0, 0.0, 2.0, 3.0)


def test_every_error_of_a_frame_is_reported():
    trees, said = evaluated_frames("> @h(LARG, 1, 1) @t(0, HAUT, 0) !cu(1, 1, 1);\n", "e.cas")
    assert trees == []
    assert "e.cas:1:6: error: parameter 'LARG' is not defined" in said
    assert "e.cas:1:24: error: parameter 'HAUT' is not defined" in said


def test_an_error_in_every_frame_of_a_repetition_is_said_once_with_its_frames():
    scene = "a = @t(X, 0, 0) !cu(1, 1, 1);\n>[T = 0, 1, 0.1] a;\n"
    trees, said = evaluated_frames(scene, "r.cas")
    assert said.count("error:") == 1
    assert "r.cas:1:8: error: parameter 'X' is not defined (in frames 1 to 11)" in said


def test_a_definition_that_reads_a_repetition_variable_says_how_to_write_it():
    scene = "LG = 2;\nDX = -LG * T;\na = @t(T, 0, 0) !cu(1, 1, 1);\n>[T = 0, 1, 0.5] a;\n"
    trees, said = evaluated_frames(scene, "d.cas")
    assert len(trees) == 3
    assert ("d.cas:2:12: error: parameter 'T' is not defined; parameter definitions are "
            "evaluated at once, where they stand") in said
    assert "#define DX" in said


def test_stream_and_tree_agree_on_frames_of_a_repetition():
    frames = frames_of("x = @t(T, 0, 0) !cu(1, 1, 1);\n>[T = 0, 1, 0.5] x;\n")
    trees = evaluated_frames("x = @t(T, 0, 0) !cu(1, 1, 1);\n>[T = 0, 1, 0.5] x;\n")[0]
    corners = [[m[3] for _, m, _ in tree.leaves(t.objects[0].root)] for t in trees]
    assert [[f.box()[0][0]] for f in frames] == corners == [[0.0], [0.5], [1.0]]
