"""Facet counts follow the size a curved surface has after its transformation,
in the plane of each circle (LANGUAGE.md §7; issue 18, item 10): a stretch
along a cylinder's axis adds no sides, and the error bound holds after any
non-uniform scale, judged on the written polygons against the true surface."""

import math

import numpy as np
import pytest

from tests.support.cli import frames_of

W = "1, 1, 1"


def sides(frame) -> int:
    """The side polygons of a lone cylinder, cone or revolved ring: all but
    its flat caps (the polygons with more than four corners)."""
    return sum(1 for p in frame.polygons if len(p.points) <= 4)


# --- the column of the issue -------------------------------------------------

@pytest.mark.parametrize("height", [0.1, 1, 3, 10, 100])
def test_a_column_gets_the_sides_its_radius_needs_whatever_its_height(height):
    (frame,) = frames_of(f"> @h(0.25, 0.25, {height}) !cy({W});\n")
    # r = 0.25 at t = 0.01: n = ceil(pi / acos(1 - 0.04)) = 12 (not 14, 26, 74, 242)
    assert len(frame.polygons) == 14
    assert sides(frame) == 12


def test_a_column_placed_through_a_named_object_and_turned_keeps_its_sides():
    scene = (f"c = !cy({W});\nl = @h(0.25, 0.25, 3) c;\n"
             "> c;\n> @h(0.25, 0.25, 3) c;\n> @rx(90) @h(0.25, 0.25, 3) c;\n"
             "> @rz(30) l;\n> @h(1, 1, 40) l;\n> @ry(90) @h(0.25, 0.25, 3) !cy(1, 1, 1);\n")
    counts = [sides(f) for f in frames_of(scene)]
    # a unit cylinder: 24 sides at the default tolerance (rounded down to 2^-6.75)
    assert counts == [24, 12, 12, 12, 12, 12]


def test_a_stretch_across_the_axis_does_count():
    wide, large, tall = frames_of(f"> @h(3, 1, 1) !cy({W});\n> @h(3) !cy({W});\n"
                                  f"> @h(1, 1, 3) !cy({W});\n")
    assert sides(tall) == 24
    # an ellipse 3 wide needs the sides of a circle of radius 3
    assert sides(wide) == sides(large) == 39


@pytest.mark.parametrize("primitive", [f"!co({W})", f"!rv({W}, 0.5, 0, 1, 0, 1, 1, 0.5, 1)"])
def test_cones_and_revolutions_ignore_a_stretch_along_their_axis(primitive):
    frames = frames_of("".join(f"> @h(0.5, 0.5, {h}) {primitive};\n" for h in (0.01, 1, 50)))
    counts = {len(f.polygons) for f in frames}
    assert len(counts) == 1


def test_a_sphere_made_into_a_spindle_gets_rings_not_segments():
    # a ball of radius 3 needs 55 x 28 quads; a spindle 0.25 wide and 3 high
    # needs the rings of the large radius but only the segments of the small one
    ball, spindle = frames_of(f"> @h(3) !sp({W});\n> @h(0.25, 0.25, 3) !sp({W});\n")
    assert len(spindle.polygons) < len(ball.polygons) / 2
    top = max(p.points[:, 2].max() for p in spindle.polygons)
    fan = [p for p in spindle.polygons if np.isclose(p.points[:, 2].max(), top)]
    # the segments around: about what the equator's radius 0.25 needs (12 for
    # its circle alone; a few more as the rings' gaps take part of the tolerance)
    assert 12 <= len(fan) <= 18


def test_a_local_tolerance_inside_a_named_object_is_in_its_units():
    # '@f' inside a named object used at a scale keeps meaning that object's units
    scene = f"a = @f(0.1) !sp({W});\n> a;\n> @h(3) a;\n> @h(1, 1, 3) a;\n"
    counts = [len(f.polygons) for f in frames_of(scene)]
    assert counts[0] == counts[1] == counts[2]


def test_the_counts_of_the_primitives_themselves():
    from castor.primitives import PRIMITIVES

    def diag(x, y, z):
        return (x, 0.0, 0.0, 0.0, y, 0.0, 0.0, 0.0, z)

    for kind, shape in (("cy", ()), ("co", ()), ("rv", (0.0, 0.0, 1.0, 0.0, 0.0, 1.0))):
        counts = {PRIMITIVES[kind].facet_counts(shape, diag(0.25, 0.25, h), 0.01)
                  for h in (0.1, 1, 10, 100)}
        assert counts == {(12,)}
    torus = PRIMITIVES["to"]
    flat, tall = (torus.facet_counts((0.2,), diag(1, 1, h), 0.01) for h in (0.2, 10))
    assert flat[0] == tall[0]  # the circles about the axis lie in the xy plane
    assert tall[1] > flat[1]  # the tube's circles stand upright
    assert PRIMITIVES["cu"].facet_counts((), diag(1, 2, 3), 0.01) == ()


# --- the error bound, after the transformation -------------------------------

def _closest_distances(points: np.ndarray, triangles: np.ndarray, reach: float) -> np.ndarray:
    """For each point, its distance to the nearest of the triangles (T, 3, 3),
    exact where that distance is at most reach, else a figure above reach (inf).
    Only the (point, triangle) pairs that can be that near are measured: a point
    within reach of a triangle lies within reach + its radius of its centroid."""
    from scipy.spatial import cKDTree

    centroids = triangles.mean(axis=1)
    radii = np.linalg.norm(triangles - centroids[:, None, :], axis=-1).max(axis=1)
    near = cKDTree(points).query_ball_point(centroids, radii + reach)
    counts = np.fromiter((len(found) for found in near), np.int64, len(near))
    which = np.repeat(np.arange(len(triangles)), counts)
    point_of = np.fromiter((i for found in near for i in found), np.int64, counts.sum())
    best = np.full(len(points), np.inf)
    for start in range(0, len(which), 65536):
        t, i = which[start:start + 65536], point_of[start:start + 65536]
        np.minimum.at(best, i, _point_triangle_distances(points[i], triangles[t]))
    return best


def _point_triangle_distances(p: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """The distance of each point p[k] to the triangle triangles[k]."""
    a, b, c = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    ab, ac = b - a, c - a
    ap, bp, cp = p - a, p - b, p - c
    d1, d2 = (ab * ap).sum(-1), (ac * ap).sum(-1)
    d3, d4 = (ab * bp).sum(-1), (ac * bp).sum(-1)
    d5, d6 = (ab * cp).sum(-1), (ac * cp).sum(-1)
    va = d3 * d6 - d5 * d4
    vb = d5 * d2 - d1 * d6
    vc = d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        # inside the face, by barycentric coordinates
        denom = va + vb + vc
        v, w = vb / denom, vc / denom
        q = a + v[:, None] * ab + w[:, None] * ac
        inside = (va >= 0) & (vb >= 0) & (vc >= 0) & (denom > 0)
        dist = np.where(inside, np.linalg.norm(p - q, axis=-1), np.inf)
        # else the nearest point of one of the three edges
        for e0, e1 in ((a, b), (b, c), (c, a)):
            edge = e1 - e0
            t = np.clip(((p - e0) * edge).sum(-1) / (edge * edge).sum(-1), 0, 1)
            dist = np.minimum(dist, np.linalg.norm(p - (e0 + t[:, None] * edge), axis=-1))
    return dist


def _triangles(frame) -> np.ndarray:
    return np.array([(p.points[0], p.points[i], p.points[i + 1])
                     for p in frame.polygons for i in range(1, len(p.points) - 1)])


def _surface(kind: str, n: int, rng) -> np.ndarray:
    """Points of a unit primitive's curved surface: a grid that passes
    between the facets' corners, and random points."""
    u = np.concatenate([(np.arange(4 * n) + 0.5) / (4 * n), rng.random(4 * n)])
    v = np.concatenate([(np.arange(n) + 0.5) / n, rng.random(n)])
    u, v = (g.ravel() for g in np.meshgrid(u, v))
    theta = 2 * np.pi * u
    if kind == "cy":
        return np.column_stack([np.cos(theta), np.sin(theta), v])
    if kind == "co":
        return np.column_stack([(1 - v) * np.cos(theta), (1 - v) * np.sin(theta), v])
    if kind == "sp":
        phi = np.pi * v
        return np.column_stack([np.sin(phi) * np.cos(theta), np.sin(phi) * np.sin(theta),
                                np.cos(phi)])
    if kind == "to":
        psi, k = 2 * np.pi * v, 0.3
        r = 1 + k * np.cos(psi)
        return np.column_stack([r * np.cos(theta), r * np.sin(theta), k * np.sin(psi)])
    # !rv(..., 0.5, 0, 1, 0.5, 0.5, 1): the slanted sides of a diamond ring
    r = np.where(v < 0.5, 0.5 + v, 1.5 - v)
    z = v
    return np.column_stack([r * np.cos(theta), r * np.sin(theta), z])


PRIMITIVE_TEXT = {"cy": f"!cy({W})", "co": f"!co({W})", "sp": f"!sp({W})",
                  "to": f"!to({W}, 0.3)", "rv": f"!rv({W}, 0.5, 0, 1, 0.5, 0.5, 1)"}


def _rotation(rng) -> np.ndarray:
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    return q * np.sign(np.diag(r))


@pytest.mark.parametrize("kind", ["cy", "co", "sp", "to", "rv"])
def test_no_point_of_a_stretched_surface_is_farther_than_the_tolerance(kind):
    rng = np.random.default_rng({"cy": 1, "co": 2, "sp": 3, "to": 4, "rv": 5}[kind])
    cases, lines = [], []
    for k in range(4):
        # a stretch along random axes, factors 0.25 .. 4, then turned; the
        # last two placed through named objects (the stretch above a subtree)
        scale = np.exp(rng.uniform(math.log(0.25), math.log(4), 3))
        linear = _rotation(rng) @ np.diag(scale) @ _rotation(rng)
        tolerance = float(rng.choice([0.01, 0.03]))
        rows = np.column_stack([linear, rng.uniform(-2, 2, 3)])
        matrix = ", ".join(repr(float(x)) for x in rows.ravel())
        if k < 2:
            lines.append(f"> @f({tolerance}) @m({matrix}) {PRIMITIVE_TEXT[kind]};")
        else:
            # '@f' above the named object: the tolerance in scene units
            lines.append(f"p{k} = @h(1, 1, 1.5) {PRIMITIVE_TEXT[kind]};")
            lines.append(f"> @f({tolerance}) @m({matrix}) @h(1, 1, {1 / 1.5!r}) p{k};")
        cases.append((np.column_stack([linear, rows[:, 3]]), tolerance))
    frames = frames_of("\n".join(lines) + "\n")
    assert len(frames) == len(cases)
    for frame, (affine, tolerance) in zip(frames, cases):
        unit = _surface(kind, 12, rng)
        points = unit @ affine[:, :3].T + affine[:, 3]
        worst = _closest_distances(points, _triangles(frame), 2 * tolerance).max()
        assert worst <= tolerance * (1 + 1e-6), (kind, affine, tolerance, worst)
        # and not many times finer than asked: the counts follow the stretch
        assert worst >= tolerance / 20, (kind, affine, tolerance, worst)
