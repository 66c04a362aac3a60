"""An element is cut only by the earlier operands of a union it shares a volume
with: a floor slab that only touches its ring of walls and the stair in its
well is its own solid, without their faces, points and colours; one that runs
into the walls is still cut by them. A slab's Width is its thickness when its
faces are its top, its bottom and upright sides. An IFC body loses the points
that are a corner of no face."""

from __future__ import annotations

import numpy as np
import pytest

from castor.pipeline import evaluated_frames

SCENE = """
#define GRIS 0.6, 0.6, 0.6
E = 0.3;
shell = $D(@h(10, 6, 3.2) !cu(0.9, 0.9, 0.85), @t(E, E, -0.1) @h(10 - 2 * E, 6 - 2 * E, 3.4) !cu(0.9, 0.9, 0.85));
walls = shell;  // [wall]
step = @t(8.7, 0.8 + I * 0.25, 0) @h(1, 0.25, (I + 1) * 3.2 / 17) !cu(0.5, 0.35, 0.2);
stair = $U[I = 0, 16](step);  // [stair]
well = @t(8.6, 0.8, 2.85) @h(1.1, 4.25, 0.45) !cu(GRIS);
floor1 = $D(@t(E, E, 2.95) @h(10 - 2 * E, 6 - 2 * E, 0.25) !cu(GRIS), well);  // [slab floor]
wide = $D(@t(0, 0, 2.95) @h(10, 6, 0.25) !cu(GRIS), well);  // [slab floor]
step2 = @t(0, 0, 3.2) @h(5, 6, 0.1) !cu(GRIS);
stepped = $U(@t(0, 0, 2.95) @h(10, 6, 0.25) !cu(GRIS), step2);  // [slab]
house = $U(walls, stair, FLOOR);
> house;
"""


def _takeoff(floor: str):
    from castor.mesh.facetize import Facetizer
    from castor.quantities import Takeoff

    [scene], said = evaluated_frames(SCENE.replace("FLOOR", floor))
    assert "error" not in said
    facetizer = Facetizer()
    facetizer.frame(scene)
    return scene, Takeoff(scene, facetizer, polygons=True)


def _uses(node) -> set[str]:
    from castor.csg import tree

    if type(node) is tree.Use:
        child = node.shared.child
        return {node.shared.name} | (set() if child is None else _uses(child))
    if type(node) is tree.Boolean:
        return set().union(*(_uses(o) for o in node.operands))
    return set()


def _element(takeoff, name: str):
    [element] = [e for e in takeoff.elements if e.name == name]
    return element


def test_a_slab_that_only_touches_the_walls_and_the_stair_is_not_cut_by_them():
    from castor.csg.elements import element_tree

    scene, takeoff = _takeoff("floor1")
    floor = _element(takeoff, "floor1")
    assert "walls" not in _uses(element_tree(scene, floor)) and \
        "stair" not in _uses(element_tree(scene, floor))
    solid = takeoff.solid(floor)
    assert {o.colour for o in solid.origins} == {(0.6, 0.6, 0.6)}
    assert all("floor1" in o.path for o in solid.origins)
    assert takeoff.figures(floor).volume == pytest.approx((9.4 * 5.4 - 1.1 * 4.25) * 0.25)


def test_a_slab_that_runs_into_the_walls_is_still_cut_by_them():
    from castor.csg.elements import element_tree

    scene, takeoff = _takeoff("wide")
    wide = _element(takeoff, "wide")
    assert "walls" in _uses(element_tree(scene, wide))
    # the walls keep what they share; the stair, in the well, is not taken
    assert "stair" not in _uses(element_tree(scene, wide))
    assert takeoff.figures(wide).volume == pytest.approx((9.4 * 5.4 - 1.1 * 4.25) * 0.25)


@pytest.mark.parametrize("floor, width", [("floor1", 0.25), ("wide", 0.25), ("stepped", None)])
def test_a_slab_has_a_width_where_its_faces_are_its_top_bottom_and_sides(floor, width):
    from castor.bim import measures

    _, takeoff = _takeoff(floor)
    element = _element(takeoff, floor)
    found = dict((q.name, q.value) for q in measures.slab(
        takeoff.solid(element), takeoff.figures(element), 0.0))
    assert found.get("Width") == (None if width is None else pytest.approx(width, abs=1e-12))


def _cube_with(points: dict, faces: list):
    vertices = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                         [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]]
                        + list(points.values()), float)
    offsets = np.cumsum([0] + [len(f) for f in faces])
    return vertices, offsets, np.array([v for f in faces for v in f])


def _edges(vertices, offsets, indices) -> list:
    found = []
    for p in range(len(offsets) - 1):
        ring = [tuple(vertices[v]) for v in indices[offsets[p]:offsets[p + 1]]]
        found += list(zip(ring, ring[1:] + ring[:1]))
    return sorted(found)


def test_a_point_that_is_a_corner_of_no_face_leaves_the_body():
    from castor.formats._ifc_body import without_straight_points

    # 8: the middle of the edge 1-2, in the bottom and in the side x = 1
    vertices, offsets, indices = _cube_with({8: (1, 0.5, 0)}, [
        [0, 3, 2, 8, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 8, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]])
    new_offsets, new_indices, kept = without_straight_points(vertices, offsets, indices)
    assert kept.tolist() == [True] * 8 + [False]
    assert np.diff(new_offsets).tolist() == [4] * 6
    edges = _edges(vertices[kept], new_offsets, new_indices)
    assert sorted((b, a) for a, b in edges) == edges  # each edge used once each way


def test_a_point_that_is_a_corner_of_a_face_stays():
    from castor.formats._ifc_body import without_straight_points

    # the side x = 1 cut in two at y = 0.5: 8 and 9 are corners of its halves
    vertices, offsets, indices = _cube_with({8: (1, 0.5, 0), 9: (1, 0.5, 1)}, [
        [0, 3, 2, 8, 1], [4, 5, 9, 6, 7], [0, 1, 5, 4], [1, 8, 9, 5], [8, 2, 6, 9],
        [2, 3, 7, 6], [3, 0, 4, 7]])
    new_offsets, new_indices, kept = without_straight_points(vertices, offsets, indices)
    assert kept is None and new_indices is indices
