"""Facetization and CSG: analytic volumes, closed outward surfaces, colours through booleans."""

import math

import numpy as np
import pytest

from tests.support.checks import check_solid
from tests.support.cli import frames_of, run
from tests.support.stream import parse_stream

W = "1, 1, 1"


def one(scene, *args):
    (frame,) = frames_of(scene, *args)
    check_solid(frame)
    return frame


def test_unit_sphere_at_fine_tolerance():
    frame = one(f"> !sp({W});\n", "--tolerance", "0.001")
    assert frame.volume() == pytest.approx(4 / 3 * math.pi, rel=0.004)
    points = np.concatenate([p.points for p in frame.polygons])
    assert np.abs(np.linalg.norm(points, axis=1) - 1).max() <= 0.001


@pytest.mark.parametrize("scene, volume, rel", [
    (f"> !cu({W});", 1.0, 1e-12),
    (f"> !cy({W});", math.pi, 0.004),
    (f"> !co({W});", math.pi / 3, 0.004),
    (f"> !to({W}, 0.25);", 2 * math.pi ** 2 * 0.0625, 0.004),
    (f"> !pr({W}, 6);", 3 * math.sqrt(3) / 2, 1e-12),
    (f"> !py({W}, 4);", 2 / 3, 1e-12),
    (f"> !ex({W}, 0,0, 2,0, 2,1, 1,1, 1,2, 0,2);", 3.0, 1e-12),   # L-shape, area 3
    (f"> !ex({W}, 0,0, 0,2, 1,2, 1,1, 2,1, 2,0);", 3.0, 1e-12),   # same, clockwise
    # a ring of inner radius 1, outer 2, height 1, by Pappus: area 1 x 2 pi x 1.5
    (f"> !rv({W}, 1,0, 2,0, 2,1, 1,1);", 3 * math.pi, 0.004),
    # a cone by revolution (profile touching the axis)
    (f"> !rv({W}, 0,0, 1,0, 0,1);", math.pi / 3, 0.004),
])
def test_primitive_volumes(scene, volume, rel):
    frame = one(scene + "\n", "--tolerance", "0.001")
    assert frame.volume() == pytest.approx(volume, rel=rel)


def test_cube_is_six_quads():
    frame = one(f"> !cu({W});\n")
    assert len(frame.polygons) == 6
    assert all(len(p.points) == 4 for p in frame.polygons)


def test_cylinder_caps_are_single_polygons():
    frame = one(f"> !cy({W});\n")
    caps = [p for p in frame.polygons if len(p.points) > 4]
    assert len(caps) == 2


def test_facets_follow_size_after_transformation():
    small = one(f"> !sp({W});\n")
    large = one(f"> @h(10) !sp({W});\n")
    assert len(large.polygons) > 5 * len(small.polygons)
    # non-uniform scale counts its largest factor
    flat = one(f"> @h(10, 1, 1) !sp({W});\n")
    assert len(flat.polygons) == len(large.polygons)


def test_local_tolerance_operator():
    coarse = one(f"> @f(0.5) !sp({W});\n")
    fine = one(f"> !sp({W});\n")
    assert len(coarse.polygons) < len(fine.polygons)
    scene_tol = one(f"TOLERANCE = 0.5;\n> !sp({W});\n")
    assert len(scene_tol.polygons) == len(coarse.polygons)


def test_minimum_eight_segments():
    frame = one(f"> !cy({W});\n", "--tolerance", "100")
    caps = [p for p in frame.polygons if len(p.points) > 4]
    assert [len(c.points) for c in caps] == [8, 8]


def test_two_cubes_sharing_a_face_unite_into_ten_quads():
    frame = one(f"> $U(!cu({W}), @t(1, 0, 0) !cu({W}));\n")
    assert len(frame.polygons) == 10
    assert all(len(p.points) == 4 for p in frame.polygons)
    assert not any(np.all(p.points[:, 0] == 1) for p in frame.polygons)
    assert frame.volume() == pytest.approx(2)


@pytest.mark.parametrize("other", ["@t(1, 0, 0)", "@t(1, 1, 0)", "@t(1, 1, 1)"])
def test_touching_solids_intersect_to_nothing(other):
    status, out, err = run("--no-cpp", stdin=f"> $I(!cu({W}), {other} !cu({W}));\n")
    assert status == 0
    (frame,) = parse_stream(out)
    assert frame.polygons == []
    assert "warning: frame 1 is empty" in err


def test_roof_standing_on_walls_merges():
    scene = """
    murs = @h(4, 3, 2.5) !cu(0.9, 0.9, 0.85);
    toit = @t(2, 1.5, 2.5) @rz(45) @h(2.9, 2.9, 1.5) !py(0.6, 0.2, 0.1, 4);
    > $U(murs, toit);
    """
    frame = one(scene)
    # On the plane z = 2.5 only the eaves remain: the roof's square base
    # (side 2.9 * sqrt 2) minus the 4 x 3 top of the walls, facing down.
    level = [p for p in frame.polygons if np.all(p.points[:, 2] == 2.5)]
    assert sum(p.points.shape[0] and _area(p.points) for p in level) == pytest.approx(2 * 2.9 ** 2 - 12)
    assert all(_normal(p.points)[2] < 0 for p in level)
    assert {p.path for p in level} == {"U2(toit)!py"}


def _normal(points):
    return np.cross(points, np.roll(points, -1, axis=0)).sum(axis=0)


def _area(points):
    return float(np.linalg.norm(_normal(points))) / 2


def test_drilled_block_has_red_bore():
    scene = """
    bloc = @h(2, 2, 1) !cu(1, 1, 1);
    trou = @t(1, 1, -1) @h(0.5, 0.5, 3) !cy(1, 0, 0);
    > $D(bloc, trou);
    """
    frame = one(scene, "--tolerance", "0.001")
    red = frame.area(colour=(1, 0, 0))
    n = len([p for p in frame.polygons if p.colour == (1.0, 0.0, 0.0)])
    # the bore: a prism of n sides inscribed in a circle of radius 0.5, height 1
    assert red == pytest.approx(n * 2 * 0.5 * math.sin(math.pi / n) * 1, rel=1e-9)
    assert frame.volume() == pytest.approx(4 - n / 2 * 0.25 * math.sin(2 * math.pi / n), rel=1e-9)
    assert {p.path for p in frame.polygons if p.colour == (1, 0, 0)} == {"D2(trou)!cy"}


def test_window_reveals_are_blue_with_the_right_area():
    scene = """
    mur = @h(4, 0.2, 3) !cu(0.9, 0.9, 0.85);
    fenetre = @t(1, -0.1, 1) @h(1.2, 0.4, 1) !cu(0.2, 0.3, 0.9);
    maison = $D(mur, fenetre);
    > maison;
    """
    frame = one(scene)
    # four reveals, 0.2 deep, around a 1.2 x 1 opening
    assert frame.area(colour=(0.2, 0.3, 0.9)) == pytest.approx(2 * (1.2 + 1) * 0.2)
    assert {p.path for p in frame.polygons} == {"(maison).D1(mur)!cu", "(maison).D2(fenetre)!cu"}
    assert frame.volume() == pytest.approx(4 * 0.2 * 3 - 1.2 * 0.2 * 1)
    # the wall's front face is a handful of convex polygons, not a fan of triangles
    front = [p for p in frame.polygons if np.all(p.points[:, 1] == 0)]
    assert 4 <= len(front) <= 8


def test_car_union_volume():
    scene = """
    roue = @h(0.35, 0.35, 0.25) !cy(0.1, 0.1, 0.1);
    caisse = @t(0, 0, 0.35) @h(4, 1.6, 1) !cu(0.8, 0.1, 0.1);
    voiture = $U(caisse, @t(0.8, 0, 0.35) @rx(90) roue, @t(0.8, 1.85, 0.35) @rx(90) roue,
                 @t(3.2, 0.1, 0.35) @rx(90) roue, @t(3.2, 1.75, 0.35) @rx(90) roue);
    > voiture;
    """
    frame = one(scene)
    (wheel,) = frames_of("> @h(0.35, 0.35, 0.25) !cy(0.1, 0.1, 0.1);\n")
    w = wheel.volume()
    # two wheels outside; two sink 0.1 of their 0.25 into the body, and the
    # body starts at the axle's height, so half of that slice is inside
    expected = 4 * 1.6 * 1 + 2 * w + 2 * w * (1 - 0.5 * 0.1 / 0.25)
    assert frame.volume() == pytest.approx(expected, rel=1e-9)
    assert len(frame.colours()) == 2


def _engine_booleans(scene: str) -> list[int]:
    """The boolean operations each frame sends to the engine (one facetizer)."""
    from castor.mesh.facetize import Facetizer
    from castor.run import evaluated_frames

    frames, said = evaluated_frames(scene)
    facetizer = Facetizer()
    counts = []
    for frame in frames:
        facetizer.frame(frame)
        counts.append(facetizer.counter.booleans)
    return counts


def test_disjoint_operands_skip_the_engine():
    scene = f"> $U(!cu({W}), @t(3, 0, 0) !cu({W}));\n> $D(!cu({W}), @t(3, 0, 0) !cu({W}));\n"
    assert _engine_booleans(scene) == [0, 0]
    status, out, err = run("--no-cpp", "--stats", stdin=scene)
    assert status == 0
    lines = [l for l in err.splitlines() if l.startswith("castor: frame")]
    # --stats counts the scene's booleans, not the engine's work
    assert "1 boolean operation," in lines[0] and "1 boolean operation," in lines[1]
    union, diff = parse_stream(out)
    assert union.volume() == pytest.approx(2) and diff.volume() == pytest.approx(1)


def test_stats_line():
    status, out, err = run("--no-cpp", "--stats", stdin=f"> $U(!cu({W}), @t(1, 0, 0) !cu({W}));\n")
    line = err.splitlines()[0]
    assert line.startswith("castor: frame 1 <stdin>:1: 2 primitives, 1 boolean operation, "
                           "10 polygons, 12 vertices, volume 2, area 10, box 0 0 0 to 2 1 1, ")


def test_shared_tree_is_facetized_once():
    scene = """
    arbre = $U(@h(0.1, 0.1, 1) !cy(0.4, 0.2, 0), @t(0, 0, 1.3) @h(0.5) !sp(0, 0.6, 0));
    rangee = $U[J = 0, 19](@t(2 * J, 0, 0) arbre);
    foret = $U[I = 0, 19](@t(0, 2 * I, 0) rangee);
    > foret;
    """
    assert _engine_booleans(scene) == [1]  # the tree's own union, once
    status, out, err = run("--no-cpp", "--stats", stdin=scene)
    assert status == 0
    line = err.splitlines()[0]
    assert " 3 boolean operations," in line  # arbre's, rangee's and foret's unions
    (frame,) = parse_stream(out)
    (tree,) = frames_of(scene.replace("> foret;", "> arbre;"))
    assert frame.volume() == pytest.approx(400 * tree.volume(), rel=1e-9)
    assert len(frame.paths()) == 400 * 2 or len(frame.paths()) == 800


def test_polygon_limit_stops_an_exploding_graph():
    lines = ["a0 = !sp(1, 1, 1);"]
    for i in range(1, 31):
        lines.append(f"a{i} = $U(a{i - 1}, @t({2 ** (i - 1) * 3}, 0, 0) a{i - 1});")
    lines.append("> a30;")
    status, out, err = run("--no-cpp", stdin="\n".join(lines) + "\n")
    assert status == 1
    # refused from an estimate, before anything is built
    assert ("error: the frame would need about 1,204,738,326,528 polygons, more than "
            "--max-polygons 20,000,000") in err
    assert parse_stream(out) == []
    # a smaller explosion passes the estimate and is stopped while it is built
    lines[-1] = "> a5;"
    status, out, err = run("--no-cpp", "--max-polygons", "10000", stdin="\n".join(lines) + "\n")
    assert status == 1
    assert "the frame needs more than 10000 polygons (--max-polygons)" in err


def test_deep_nesting_works_or_errors():
    scene = "> " + "@t(0.001, 0, 0) " * 10000 + f"!cu({W});\n"
    (frame,) = frames_of(scene)
    assert frame.box()[0][0] == pytest.approx(10)
    nested = "> " + "$U(" * 3000 + f"!cu({W})" + ")" * 3000 + ";\n"
    (frame,) = frames_of(nested)
    assert frame.volume() == pytest.approx(1)
