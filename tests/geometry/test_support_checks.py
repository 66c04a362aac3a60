"""The oracle's winding test (tests/support/winding.py): the ray count it makes
on a closed surface is the solid-angle sum, point for point, and it still
sees a sheet, a fold and an open surface."""

import numpy as np
import pytest

from tests.support import regularity, stream, winding


def _box(low, high, flip=False):
    """A box's 12 triangles, outward (inward with ``flip``)."""
    (x0, y0, z0), (x1, y1, z1) = low, high
    v = np.array([[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
                  [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]], float)
    faces = [(0, 3, 2), (0, 2, 1), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
             (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]
    t = v[np.array(faces)]
    return t[:, ::-1] if flip else t


def _sphere(subdivisions=3, centre=(0, 0, 0), radius=1.0):
    trimesh = pytest.importorskip("trimesh")
    mesh = trimesh.creation.icosphere(subdivisions=subdivisions, radius=radius)
    return mesh.vertices[mesh.faces] + np.array(centre)


def _probes(rng, count, scale):
    points = rng.uniform(-scale, scale, (count, 3))
    # and points on the grid lines of the boxes, where rays meet edges
    grid = rng.choice([-1.0, -0.5, 0.0, 0.5, 1.0, 0.25], (count, 3))
    return np.vstack([points, grid + 1e-9 * rng.normal(size=(count, 3))])


@pytest.mark.parametrize("surface", ["box", "touching boxes", "sphere", "box with cavity",
                                     "sheet", "sphere in box"])
def test_ray_count_is_the_solid_angle_sum(surface):
    rng = np.random.default_rng(7)
    triangles = {
        "box": lambda: _box((-1, -1, -1), (1, 1, 1)),
        "touching boxes": lambda: np.vstack([_box((-1, -1, -1), (0, 0, 0)),
                                             _box((0, 0, 0), (1, 1, 1))]),
        "sphere": lambda: _sphere(),
        "box with cavity": lambda: np.vstack([_box((-1, -1, -1), (1, 1, 1)),
                                              _box((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5), True)]),
        # two boxes sharing a face, both kept: a sheet inside (winding 2)
        "sheet": lambda: np.vstack([_box((-1, -1, -1), (1, 1, 0)), _box((-1, -1, 0), (1, 1, 1)),
                                    _box((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5))]),
        "sphere in box": lambda: np.vstack([_box((-1, -1, -1), (1, 1, 1)),
                                            _sphere(2, radius=0.5)]),
    }[surface]()
    points = _probes(rng, 400, 1.3)
    assert winding._closed_vertex_ids(triangles) is not None
    fast = winding.winding_numbers(triangles, points)
    slow = winding._solid_angle_winding(triangles, points)
    assert np.abs(fast - slow).max() < 1e-6, (fast - slow)[np.abs(fast - slow) > 1e-6][:5]
    assert np.allclose(fast, np.round(fast))


def test_an_open_surface_keeps_its_fractional_number():
    triangles = _box((-1, -1, -1), (1, 1, 1))[:-1]  # one triangle missing
    assert winding._closed_vertex_ids(triangles) is None
    w = winding.winding_numbers(triangles, np.array([[0.0, 0.0, 0.0]]))
    assert 0.9 < w[0] < 1.0


def test_a_sheet_in_a_frame_of_many_polygons_is_found_quickly():
    """Two coincident faces turned towards each other between two boxes, in a
    frame that also holds a finely faceted sphere (thousands of triangles):
    the sheet is reported, and the test takes seconds, not minutes."""
    import time

    sphere = _sphere(5, centre=(5, 0, 0))  # 20,480 triangles
    polygons = [stream.Polygon(points=tri, colour=(1, 1, 1), path="!sp") for tri in sphere]
    for box in (_box((-1, -1, -1), (1, 1, 0)), _box((-1, -1, 0), (1, 1, 1))):
        polygons += [stream.Polygon(points=tri, colour=(1, 0, 0), path="!cu") for tri in box]
    frame = stream.Frame(1, "test", polygons)
    started = time.perf_counter()
    defects = regularity.sheet_defects(frame)
    elapsed = time.perf_counter() - started
    assert len(defects) == 4, defects  # the four triangles of the two coincident faces
    assert all("!cu" in d for d in defects)
    assert elapsed < 20, elapsed


def _random_polygons(count=3000, seed=3):
    """Polygons of every kind polygon_defects tells apart: fine, turning
    twice, bent, with a repeated vertex, winding twice, too small."""
    rng = np.random.default_rng(seed)
    polygons = []
    for k in range(count):
        n = int(rng.integers(1, 8))
        kind = k % 6
        angle = rng.uniform(0, 2 * np.pi, n)
        if kind != 1:
            angle = np.sort(angle)
        points = np.column_stack([np.cos(angle), np.sin(angle), np.zeros(n)])
        if kind == 2:
            points[:, 2] = rng.normal(0, 1e-6, n)
        if kind == 3 and n > 2:
            points[1] = points[0]
        if kind == 4 and n > 2:
            points = np.vstack([points, points])
        if kind == 5:
            points *= 1e-9
        turn = np.linalg.qr(rng.normal(size=(3, 3)))[0]
        polygons.append(stream.Polygon("!p", (1, 1, 1), points @ turn.T + rng.normal(size=3)))
    return polygons


def test_the_frames_polygon_defects_are_each_polygons():
    polygons = _random_polygons()
    one_by_one = {i: d for i, p in enumerate(polygons) if (d := regularity.polygon_defects(p))}
    at_once = dict(regularity.frame_polygon_defects(stream.Frame(1, "test", polygons)))
    assert len(one_by_one) > 2000 and set(one_by_one) == set(at_once)

    def kinds(defects):  # "winds 0.00 times" or "-0.00": a sum of angles near 0
        return [d.replace("-0.00", "0.00") for d in defects]

    assert all(kinds(one_by_one[i]) == kinds(at_once[i]) for i in one_by_one)


def test_shells_of_zero_volume_are_found_among_many():
    polygons = [stream.Polygon("!sp", (1, 1, 1), t) for t in _sphere(4)]
    # a flat shell: a square twice, turned each way (volume 0)
    square = np.array([[3, 0, 0], [4, 0, 0], [4, 1, 0], [3, 1, 0]], float)
    polygons += [stream.Polygon("!sq", (1, 0, 0), square),
                 stream.Polygon("!sq", (1, 0, 0), square[::-1])]
    polygons += [stream.Polygon("!cu", (0, 1, 0), t) for t in _box((5, 5, 5), (6, 6, 6))]
    defects = regularity.shell_defects(stream.Frame(1, "test", polygons))
    assert defects == ["a shell of 2 polygons has volume 0 for area 2"]
