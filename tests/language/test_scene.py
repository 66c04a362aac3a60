"""The scene graph: late binding, repetition, sharing, redefinition, paths, transforms."""

import pytest

from tests.support.checks import check_solid
from tests.support.cli import frames_of, run
from tests.support.stream import parse_stream

CUBE = "!cu(0.5, 0.5, 0.5)"


def test_late_binding_gives_two_different_frames():
    scene = f"""
    L = 1;
    a = @h(L, 1, 1) {CUBE};
    > a;
    L = 3;
    > a;
    """
    one, two = frames_of(scene)
    assert one.volume() == pytest.approx(1)
    assert two.volume() == pytest.approx(3)


def test_repeated_facetize_gives_five_frames():
    frames = frames_of(f"x = @t(T, 0, 0) {CUBE};\n>[T = 0, 1, 0.25] x;\n")
    assert [f.number for f in frames] == [1, 2, 3, 4, 5]
    assert [f.box()[0][0] for f in frames] == [0, 0.25, 0.5, 0.75, 1]


def test_repetition_with_slack_and_negative_step():
    frames = frames_of(f"s = $U[I = 0, 1, 0.1](@t(30 * I, 0, 0) {CUBE});\n> s;\n"
                       f"r = $U[I = 3, 1, -1](@t(2 * I, 0, 0) {CUBE});\n> r;\n")
    assert frames[0].volume() == pytest.approx(11)
    assert frames[1].volume() == pytest.approx(3)


def test_repetition_binds_named_objects_and_restores():
    scene = f"""
    I = 100;
    marche = @t(0, I * 0.28, I * 0.17) @h(1.2, 0.30, 0.17) {CUBE};
    escalier = $U[I = 0, 15](marche);
    > escalier;
    > marche;
    """
    stairs, step = frames_of(scene)
    check_solid(stairs)
    assert stairs.box()[1][1] == pytest.approx(15 * 0.28 + 0.30)
    assert step.box()[0][1] == pytest.approx(28)  # I is 100 again


def test_transform_order_and_exact_rotation():
    (frame,) = frames_of(f"> @t(5, 0, 0) @rz(90) {CUBE};\n")
    box = frame.box()
    assert box.tolist() == [[4, 0, 0], [5, 1, 1]]


def test_negative_homothety_keeps_outward_orientation():
    (frame,) = frames_of(f"> @h(-1, 2, 3) {CUBE};\n")
    check_solid(frame)
    assert frame.volume() == pytest.approx(6)
    assert frame.box().tolist() == [[-1, 0, 0], [0, 2, 3]]


def test_matrix_transformation():
    (frame,) = frames_of(f"> @m(0, -1, 0, 2,  1, 0, 0, 0,  0, 0, -2, 0) {CUBE};\n")
    check_solid(frame)
    assert frame.volume() == pytest.approx(2)
    assert frame.box().tolist() == [[1, 0, -2], [2, 1, 0]]


def test_rotation_about_axis():
    (frame,) = frames_of(f"> @r(0, 0, 1, 90) {CUBE};\n> @rx(90) {CUBE};\n> @ry(90) {CUBE};\n"
                         .split("\n")[0] + "\n")
    assert frame.box().tolist() == [[-1, 0, 0], [0, 1, 1]]
    rx, ry = frames_of(f"> @rx(90) {CUBE};\n> @ry(90) {CUBE};\n")
    assert rx.box().tolist() == [[0, -1, 0], [1, 0, 1]]
    assert ry.box().tolist() == [[0, 0, -1], [1, 1, 0]]


def test_redefinition_warns_and_keeps_old_nodes():
    scene = f"a = {CUBE};\nb = @t(0, 0, 0) a;\na = @h(2) {CUBE};\n> b;\n> a;\n"
    status, out, err = run("--no-cpp", stdin=scene)
    assert status == 0
    assert "<stdin>:3:1: warning: object 'a' redefined" in err
    b, a = parse_stream(out)
    assert b.volume() == pytest.approx(1)
    assert a.volume() == pytest.approx(8)


def test_quiet_hides_warnings():
    status, out, err = run("--no-cpp", "-q", stdin=f"a = {CUBE};\na = {CUBE};\n")
    assert status == 0 and err == ""


def test_paths_name_named_nodes_and_operands():
    scene = """
    roue = @h(0.3, 0.3, 0.1) !cy(0.1, 0.1, 0.1);
    carrosserie = @h(4, 1.6, 1) !cu(0.8, 0.1, 0.1);
    voiture = $U(carrosserie, @t(1, -0.1, 0.3) @rx(90) roue, @t(3, -0.1, 0.3) @rx(90) roue);
    > voiture;
    """
    (frame,) = frames_of(scene)
    assert frame.paths() == {"(voiture).U1(carrosserie)!cu", "(voiture).U2(roue)!cy",
                             "(voiture).U3(roue)!cy"}


def test_set_overrides_scene_assignment():
    scene = f"L = 1;\n> @h(L, 1, 1) {CUBE};\n"
    status, out, err = run("--no-cpp", "--set", "L=2+1", stdin=scene)
    assert status == 0
    assert parse_stream(out)[0].volume() == pytest.approx(3)


def test_tolerance_parameter_is_predefined():
    (frame,) = frames_of(f"> @h(TOLERANCE * 100) {CUBE};\n")
    assert frame.box()[1][0] == pytest.approx(1.0)


def test_several_objects_in_one_frame_stay_separate():
    (frame,) = frames_of(f"a = {CUBE};\n> a, @t(0.5, 0, 0) a;\n")
    assert len(frame.polygons) == 12
    assert frame.volume() == pytest.approx(2)
