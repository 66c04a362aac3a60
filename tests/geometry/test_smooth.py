"""Smooth solids (LANGUAGE.md §7.1): castor.mesh.subdivide on its own, checked
against tests/oracle/reference_subdivision.py (written apart), and the ray–mesh spans
that pictures use for them."""

from __future__ import annotations

import numpy as np
import pytest

from castor.mesh import subdivide

from tests.oracle import reference_subdivision as reference


SMOOTH_VOLUME = 0.32747  # the Catmull–Clark limit of the unit cube


def box(sx=1.0, sy=1.0, sz=1.0):
    """A box [0, sx] x [0, sy] x [0, sz] as six quads, counter-clockwise from outside."""
    v = np.array([[x, y, z] for x in (0, sx) for y in (0, sy) for z in (0, sz)], float)
    f = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
    return v, np.arange(0, 25, 4), np.array(f).ravel()


def prism(n=6, height=1.0):
    """A regular n-gon prism of radius 1: two n-gons and n quads."""
    angle = np.arange(n) * 2 * np.pi / n
    ring = np.column_stack([np.cos(angle), np.sin(angle), np.zeros(n)])
    v = np.concatenate([ring, ring + [0, 0, height]])
    faces = [list(range(n - 1, -1, -1)), list(range(n, 2 * n))]
    faces += [[i, (i + 1) % n, n + (i + 1) % n, n + i] for i in range(n)]
    offsets = np.cumsum([0] + [len(f) for f in faces])
    return v, offsets, np.concatenate(faces)


def volume(vertices, triangles):
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6)


def closed(triangles):
    """Every directed edge once, and its reverse once: closed and oriented."""
    directed = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]])
    forward = {tuple(e) for e in directed.tolist()}
    return len(forward) == len(directed) and all((b, a) in forward for a, b in forward)


def test_a_cube_whose_edges_are_all_creases_is_the_cube():
    v, o, i = box()
    assert subdivide.smooth(v, o, i, 60, 0.001, 10 ** 6) is None  # the control mesh itself
    assert subdivide.smooth(v, o, i, 0, 0.001, 10 ** 6) is None
    assert subdivide.smooth(v, o, i, 89.9, 0.001, 10 ** 6) is None
    assert not subdivide.has_smooth_edges(v, o, i, 60)
    assert subdivide.has_smooth_edges(v, o, i, 90)


@pytest.mark.parametrize("tolerance", [0.1, 0.01, 0.001])
def test_the_smooth_cube_is_closed_inside_its_box_and_within_the_tolerance(tolerance):
    v, o, i = box()
    smooth = subdivide.smooth(v, o, i, 120, tolerance, 10 ** 7)
    assert closed(smooth.triangles)
    low, high = smooth.vertices.min(axis=0), smooth.vertices.max(axis=0)
    # the limit's face centres: 0.0802 = 13/162 in from each face of the cube
    assert np.allclose(low, 13 / 162) and np.allclose(high, 1 - 13 / 162)
    assert smooth.distance <= tolerance
    assert set(np.unique(smooth.faces)) == set(range(6))


def test_the_smooth_cube_converges():
    v, o, i = box()
    tolerances = (0.1, 0.01, 0.001, 0.0002)
    volumes = [volume(s.vertices, s.triangles) for s in
               (subdivide.smooth(v, o, i, 120, t, 10 ** 7) for t in tolerances)]
    # 0.2559, 0.3221, 0.3264, 0.32745: towards the Catmull–Clark limit of the
    # unit cube, 0.32747 (its facets are inside the limit, which is convex, so
    # the volumes rise), each within the tolerance times the area (4.4) of it
    assert volumes == sorted(volumes)
    assert volumes[-1] == pytest.approx(0.3275, abs=5e-4)
    errors = SMOOTH_VOLUME - np.array(volumes)
    assert (errors > -1e-6).all() and (errors <= 4.4 * np.array(tolerances)).all()
    assert all(later < earlier / 3 for earlier, later in zip(errors, errors[1:]))


def long_box_with_a_pyramid_end(length=8):
    """A box [0, length] x [0, 1] x [0, 1], its sides cut in unit quads along
    x, under a pyramid at x = length (apex 0.4 out): polygons counter-clockwise
    from outside."""
    ring = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    v = np.array([[x, y, z] for x in range(length + 1) for y, z in ring], float)
    v = np.concatenate([v, [[length + 0.4, 0.5, 0.5]]])
    apex = len(v) - 1
    faces = [[3, 2, 1, 0]]
    faces += [[4 * x + k, 4 * x + 4 + k, 4 * x + 4 + (k + 1) % 4, 4 * x + (k + 1) % 4]
              for x in range(length) for k in range(4)]
    faces += [[4 * length + k, 4 * length + (k + 1) % 4, apex] for k in range(4)]
    centre = v.mean(axis=0)
    oriented = []
    for f in faces:
        p = v[f]
        normal = np.cross(p[1] - p[0], p[2] - p[0])
        outward = p.mean(axis=0) - [p.mean(axis=0)[0], 0.5, 0.5] if len(set(p[:, 0])) > 1 \
            else p.mean(axis=0) - centre
        if len(f) == 4 and len(set(p[:, 0])) == 1:
            outward = [p[0, 0] - centre[0], 0, 0]
        oriented.append(f if normal @ outward > 0 else f[::-1])
    offsets = np.cumsum([0] + [len(f) for f in oriented])
    return v, offsets, np.concatenate(oriented)


def test_only_what_is_far_from_the_limit_is_refined():
    # @s(70) on a long box under a pyramid: the box's edges (90 degrees) are
    # creases, the pyramid's (67 and 39) are not: the flat sides away from
    # the end have no gap to refine, the rounded end is refined; the pieces
    # meet without a crack (every edge once each way)
    v, o, i = long_box_with_a_pyramid_end()
    everywhere = subdivide.smooth(v, o, i, 70, 0.001, 10 ** 7)
    assert closed(everywhere.triangles)
    assert everywhere.distance <= 0.001
    # inside the control mesh (8 + 0.4 / 3), rounded at the end only
    assert 7.8 < volume(everywhere.vertices, everywhere.triangles) < 8 + 0.4 / 3
    x = everywhere.vertices[everywhere.triangles].mean(axis=1)[:, 0]
    # a uniform level has as many triangles on each unit of length; here the
    # sides far from the end keep the first level's (4 quads a control quad)
    assert (x < 5).sum() == 5 * 4 * 4 * 2 + 4 * 2 and (x > 7).sum() > 1000
    assert everywhere.levels >= 4


def test_levels_are_made_only_where_they_are_needed(monkeypatch):
    # a long box under a pyramid end, its sides cut in 200 unit quads each
    # side (805 control polygons), @s(70) at 1e-4: only the end is refined
    # past the first level. Whole levels would have made 1,646,592
    # triangles at the last one (refused under a limit of 1,000,000 before
    # levels followed the refinement); the parts made hold 52,288 written
    v, o, i = long_box_with_a_pyramid_end(200)
    made = []
    refine = subdivide._refine
    monkeypatch.setattr(subdivide, "_refine", lambda level: made.append(len(level.indices))
                        or refine(level))
    part = subdivide.smooth(v, o, i, 70, 1e-4, 1_000_000)
    assert closed(part.triangles) and part.distance <= 1e-4
    assert len(part.triangles) < 60_000 and max(made) < 100_000
    assert volume(part.vertices, part.triangles) == pytest.approx(199.8863, abs=1e-3)


def test_parts_give_the_surface_whole_levels_give(monkeypatch):
    """A prism, a box under a roof and a cube smoothed again after a cut
    (fine where the cut was), refined in parts and in whole levels: the same
    triangles at the same points."""
    v, o, i = box()
    v = np.concatenate([v, [[0.5, 0.5, 1.1]]])
    faces = [i[o[k]:o[k + 1]].tolist() for k in range(6) if k != 5]
    faces += [[1, 5, 8], [5, 7, 8], [7, 3, 8], [3, 1, 8]]
    roofed = (v, np.cumsum([0] + [len(f) for f in faces]), np.concatenate(faces))
    cases = [(prism(7), 65, 1e-3), (roofed, 30, 1e-4), (box(3, 1, 0.5), 120, 1e-3),
             (long_box_with_a_pyramid_end(6), 100, 1e-4)]
    results = []
    parts = []
    part = subdivide._part
    monkeypatch.setattr(subdivide, "_part", lambda level, keep: parts.append(keep.mean())
                        or part(level, keep))
    for mesh, angle, tolerance in cases:
        results.append(subdivide.smooth(*mesh, angle, tolerance, 10 ** 8))
    assert len(parts) >= 4 and min(parts) < 0.7  # refined in parts
    monkeypatch.setattr(subdivide, "_rings", lambda level, seed, count:
                        np.ones(len(level.faces), bool))
    for (mesh, angle, tolerance), part in zip(cases, results):
        whole = subdivide.smooth(*mesh, angle, tolerance, 10 ** 8)
        assert closed(part.triangles)
        assert np.array_equal(part.triangles, whole.triangles)
        assert np.abs(part.vertices - whole.vertices).max() < 1e-12


def test_a_large_solid_gets_as_many_levels_as_its_size_needs():
    small = subdivide.smooth(*box(0.05, 0.05, 0.05), 120, 0.001, 10 ** 7)
    large = subdivide.smooth(*box(5, 5, 5), 120, 0.001, 10 ** 7)
    assert small.levels < large.levels
    assert small.distance <= 0.001 and large.distance <= 0.001
    # the same shape, scaled
    assert volume(large.vertices, large.triangles) == pytest.approx(0.3275 * 125, rel=1e-3)


def test_positions_agree_with_the_reference_subdivision():
    for (v, o, i), angle in ((box(), 120), (box(2, 1, 0.5), 120), (prism(6), 45), (prism(5), 100)):
        points = [tuple(p) for p in v.tolist()]
        faces = [tuple(i[o[k]:o[k + 1]].tolist()) for k in range(len(o) - 1)]
        expected, _faces = reference.smooth(points, faces, angle, 2)
        level = subdivide._control(v, o, i, np.arange(len(o) - 1), angle)
        level = subdivide._refine(subdivide._refine(level))
        got = subdivide.limit_positions(level)
        assert sorted(map(tuple, np.round(got, 9).tolist())) == \
            sorted(map(tuple, np.round(np.array(expected), 9).tolist()))


def test_a_prism_keeps_its_creases():
    # @s(45) on a hexagonal prism: the rims (90 degrees) are creases, the
    # sides (60 degrees) smooth: the caps stay flat, in their planes, and the
    # rims become curves between them
    v, o, i = prism(6)
    smooth = subdivide.smooth(v, o, i, 65, 0.001, 10 ** 7)
    assert closed(smooth.triangles)
    z = smooth.vertices[:, 2]
    assert z.min() == 0 and z.max() == 1  # the caps did not move
    bottom = smooth.triangles[(z[smooth.triangles] == 0).all(axis=1)]
    assert len(bottom) > 0 and set(np.unique(smooth.faces[
        (z[smooth.triangles] == 0).all(axis=1)])) == {0}
    side = (z > 0) & (z < 1)
    radius = np.hypot(smooth.vertices[side, 0], smooth.vertices[side, 1])
    # the side rounds inside the hexagon, outside the B-spline rim curve's
    # inscribed circle
    assert radius.max() < 1 and radius.min() >= 0.8
    # every vertex of a rim is on the B-spline curve of the hexagon: inside it
    assert volume(smooth.vertices, smooth.triangles) < 3 * np.sqrt(3) / 2


def test_corners_stay_put():
    # a box under a low pyramid roof, @s(30): the box's edges (and the eaves,
    # 79 degrees) are creases, the roof's hips (16 degrees) smooth. The eight
    # corners meet three creases each: they stay where they are; the apex
    # rounds down; the walls stay in their planes
    v, o, i = box()
    v = np.concatenate([v, [[0.5, 0.5, 1.1]]])
    faces = [i[o[k]:o[k + 1]].tolist() for k in range(6) if k != 5]  # no top (1, 5, 7, 3)
    faces += [[1, 5, 8], [5, 7, 8], [7, 3, 8], [3, 1, 8]]
    offsets = np.cumsum([0] + [len(f) for f in faces])
    smooth = subdivide.smooth(v, offsets, np.concatenate(faces), 30, 0.001, 10 ** 7)
    assert closed(smooth.triangles)
    written = {tuple(p) for p in smooth.vertices.tolist()}
    assert all(tuple(p) in written for p in v[:8].tolist())
    assert 1.0 < smooth.vertices[:, 2].max() < 1.1
    low, high = smooth.vertices.min(axis=0), smooth.vertices.max(axis=0)
    assert np.array_equal(low, [0, 0, 0]) and np.array_equal(high[:2], [1, 1])
    # a pentagonal prism @s(80): rims (90 degrees) creases, sides (72) smooth:
    # the caps stay flat, the side rounds
    smooth = subdivide.smooth(*prism(5), 80, 0.001, 10 ** 7)
    assert closed(smooth.triangles)
    assert smooth.vertices[:, 2].min() == 0 and smooth.vertices[:, 2].max() == 1
    # @s(60): every edge of the prism a crease, nothing changes
    assert subdivide.smooth(*prism(5), 60, 0.01, 10 ** 7) is None


def test_the_same_solid_every_time():
    first = subdivide.smooth(*prism(7), 60, 0.002, 10 ** 7)
    second = subdivide.smooth(*prism(7), 60, 0.002, 10 ** 7)
    assert np.array_equal(first.vertices, second.vertices)
    assert np.array_equal(first.triangles, second.triangles)
    assert np.array_equal(first.faces, second.faces)


def test_refused_before_it_explodes():
    with pytest.raises(subdivide.SubdivisionLimit) as caught:
        subdivide.smooth(*box(100, 100, 100), 120, 1e-6, 100_000)
    assert caught.value.limit == 100_000
    assert "more than the limit of 100,000" in str(caught.value)
    assert "GB" in str(caught.value)


# --- rays against the refined facets (castor.pictures.mesh_rays) ------------------


def cube_triangles():
    v, o, i = box()
    quads = i.reshape(-1, 4)
    return v, np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])


def test_rays_against_a_cube_mesh():
    from castor.pictures.mesh_rays import MeshRays

    v, t = cube_triangles()
    rays = MeshRays(v, t)
    o = np.array([[0.5, 0.5, 5.0], [0.25, 0.75, -3.0], [2.0, 2.0, 2.0], [0.3, 0.4, 0.5],
                  [0.5, 0.5, 0.5]])
    d = np.array([[0, 0, -2.0], [0, 0, 1.0], [0, 0, -1.0], [1.0, 0, 0], [1.0, 1.0, 1.0]])
    spans, faces = rays.spans(o, d)
    assert spans.shape == (5, 2)
    assert np.allclose(spans[0], [2.0, 2.5], atol=1e-6)  # t in units of d
    assert np.allclose(spans[1], [3.0, 4.0], atol=1e-6)
    assert np.isinf(spans[2]).all()  # misses
    assert np.allclose(spans[3], [-0.3, 0.7], atol=1e-6)  # the whole line, behind too
    assert np.allclose(spans[4], [-0.5, 0.5], atol=1e-6)  # through two corners
    normal = rays.normal(o[:2] + spans[:2, :1] * d[:2], faces[:2, 0])
    assert normal[0, 2] > 0 and normal[1, 2] < 0  # the top, then the bottom face
    assert np.allclose(np.cross(normal[0], [0, 0, 1]), 0)


def test_rays_through_two_shells_and_a_cavity():
    from castor.pictures.mesh_rays import MeshRays

    v, t = cube_triangles()
    inner = (v - 0.5) * 0.5 + 0.5  # a cavity: the small cube turned inside out
    far = v + [3, 0, 0]
    vertices = np.concatenate([v, inner, far])
    triangles = np.concatenate([t, t[:, ::-1] + 8, t + 16])
    spans, _ = MeshRays(vertices, triangles).spans(np.array([[-1.0, 0.5, 0.5]]),
                                                   np.array([[1.0, 0, 0]]))
    assert np.allclose(spans[0], [1, 1.25, 1.75, 2, 4, 5], atol=1e-6)


def test_a_smooth_cube_within_the_tolerance_measured_with_rays():
    # the limit surface (a much finer level) against the written triangles,
    # along rays from the centre (farther than the distance across)
    from castor.pictures.mesh_rays import MeshRays

    v, o, i = box()
    for tolerance in (0.01, 0.001):
        smooth = subdivide.smooth(v, o, i, 120, tolerance, 10 ** 7)
        finer = subdivide.smooth(v, o, i, 120, tolerance / 30, 10 ** 8)
        assert finer.levels >= smooth.levels + 2
        sample = finer.vertices[:: max(1, len(finer.vertices) // 50000)]
        direction = sample - 0.5
        spans, _ = MeshRays(smooth.vertices, smooth.triangles).spans(
            np.full_like(sample, 0.5), direction)
        radial = (1 - spans[:, 1]) * np.linalg.norm(direction, axis=1)
        assert np.isfinite(spans[:, 1]).all()
        # the written facets are inside the (convex) limit, by at most the tolerance
        assert radial.min() > -1e-6 and tolerance / 10 < radial.max() <= tolerance


# --- @s in the language: meshes, booleans, errors, pictures, drawings ----------------

from tests.support.cli import frames_of, run  # noqa: E402
from tests.support.regularity import regularity_defects  # noqa: E402

def test_a_cube_smoothed_at_60_degrees_is_the_cube_and_at_0_nothing_changes():
    plain, creased, zero = (frames_of(f"> {prefix}!cu(1, 0, 0);")[0]
                            for prefix in ("", "@s(60) ", "@s(0) "))
    assert len(creased.polygons) == 6 and creased.volume() == pytest.approx(1.0, abs=1e-12)
    status, with_zero, _ = run("--no-cpp", stdin="> @s(0) $D(!cy(1, 0, 0), @h(0.5) !sp(0, 1, 0));")
    status, without, _ = run("--no-cpp", stdin="> $D(!cy(1, 0, 0), @h(0.5) !sp(0, 1, 0));")
    assert with_zero == without
    assert [p.points.tolist() for p in zero.polygons] == [p.points.tolist() for p in plain.polygons]


def test_a_smooth_cube_is_closed_regular_inside_the_cube_and_converges():
    volumes = []
    for tolerance in ("0.01", "0.001"):
        frame = frames_of("> @s(120) !cu(0.2, 0.4, 0.6);", "--tolerance", tolerance)[0]
        # (the winding test for sheets is quadratic: at 768 polygons, not 12,288)
        assert regularity_defects(frame, sheets=tolerance == "0.01") == []
        low, high = frame.box()
        assert np.allclose(low, 13 / 162) and np.allclose(high, 1 - 13 / 162)
        assert frame.colours() == {(0.2, 0.4, 0.6)} and frame.paths() == {"!cu"}
        volumes.append(frame.volume())
    assert volumes[0] < volumes[1] < SMOOTH_VOLUME
    assert volumes[1] == pytest.approx(SMOOTH_VOLUME, abs=3 * 0.001)


def test_a_smooth_solid_cut_and_a_smooth_union():
    text = """
        pierre = @s(120) @h(2, 1, 1) !cu(0.8, 0.6, 0.4);
        trou = @t(1, 0.5, 0.5) @h(0.3, 0.3, 1) !cy(0.2, 0.4, 0.9);
        > $D(pierre, trou);
        > @s(150) $U(!cu(1, 0, 0), @t(0.5, 0.5, 0.5) @h(0.3, 0.3, 1) !cy(0, 1, 0));
        > $U(pierre, @t(3, 0, 0) pierre);
    """
    cut, union, twice = frames_of(text)
    for frame in (cut, union, twice):
        assert regularity_defects(frame) == []
    # the cut faces take the cutter's colour and path
    assert cut.colours() == {(0.8, 0.6, 0.4), (0.2, 0.4, 0.9)}
    assert cut.area(colour=(0.2, 0.4, 0.9)) > 0 and "D2(trou)!cy" in cut.paths()
    whole = frames_of("> @s(120) @h(2, 1, 1) !cu(0.8, 0.6, 0.4);")[0]
    assert 0 < whole.volume() - cut.volume() < np.pi * 0.09
    # the union's seam is smoothed: each face keeps its operand's colour
    assert union.colours() == {(1.0, 0.0, 0.0), (0.0, 1.0, 0.0)}
    assert union.box()[1][2] > 1.0  # the cylinder stands out of the cube, rounded
    # a named smooth solid used twice is the same solid moved
    assert twice.volume() == pytest.approx(2 * whole.volume(), rel=1e-9)


def test_a_smooth_solid_smoothed_again_is_refined_where_it_must_be():
    # the oracle's case (seed 5, case 12) that took minutes: @s(180) over a
    # boolean of smooth solids; their facets are already within the
    # tolerance of the new limit and are not cut four times more per level
    # (uniform levels wrote 73,536 polygons here, 2 million in the oracle's)
    text = "> @s(150) $U(@s(120) @h(2) !cu(1, 0, 0), @t(1.5, 0, 0) !cu(0, 1, 0));"
    frame = frames_of(text)[0]
    assert regularity_defects(frame) == []
    assert len(frame.polygons) < 12_000
    assert frame.volume() == pytest.approx(3.09, abs=0.05)


def test_a_smooth_union_of_smooth_solids_has_no_slivers_turned_over():
    # the smooth oracle's seed 11 (batch 0, scene 33, frame 3): @s(100) over
    # a union of two copies of a boolean of smooth solids. The union's
    # polygons beside its seams are slivers (three corners almost on one
    # line), and Catmull–Clark's limit surface folds over itself along them
    # (the reference subdivision's too): 4 triangles a hair wide faced
    # inward, each with winding 1 on both sides. They are taken out
    text = """S33P0 = 0.5;
s33o0 = $I[S33R3 = 0, 1]($U(@s(170.0) @t((0.25 * S33R3 + 0.0), 0.0, (0.0 * S33R3 + 0.0)) !pr(0.5, 0.0, 0.0, 6.0), @s(180.0) @rx(180.0) !we(1.0, 1.0, 1.0), $I[S33R1 = 0, 1](@t((1.0 * S33R1 + 0.0), 0.0, 0.0) @s(30.0) !cu(0.0, 0.0, 0.0)), @s(140.0) @h(1.0, (-1.0), (-2.0)) @rz(45.0) @r(0.0, 1.0, 0.0, 60.0) !pr(0.0, 0.0, 0.5, 3.0)));
> @s(100.0) $U(@t(0.5, (0.5 * S33P0 + (-0.235)), 0.0) s33o0, @h(1.0, (-2.0), 2.0) s33o0);
"""
    frame = frames_of(text)[0]
    assert regularity_defects(frame) == []
    assert frame.volume() == pytest.approx(6.7721, abs=2e-3)


def test_slivers_turned_over_lose_a_side():
    # a closed pillow: a square fanned from a point above it and from one
    # below; the upper point moved far across the square's far side turns one
    # triangle over, folded against its neighbours. A side of it goes, and
    # nothing is turned over any more
    positions = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                          [0.5, 1.5, 0.1], [0.5, 0.5, -0.5]], float)
    triangles = np.array([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4],
                          [1, 0, 5], [2, 1, 5], [3, 2, 5], [0, 3, 5]])
    faces = np.repeat([0, 1], 4)
    normal = np.array([[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]])
    assert subdivide.turned(positions, triangles, faces, normal).tolist() == [False] * 2 + [
        True] + [False] * 5
    kept, kept_faces = subdivide.unturned(positions, triangles, faces, normal,
                                          np.zeros(6, bool))
    assert not subdivide.turned(positions, kept, kept_faces, normal).any()
    assert 4 <= len(kept) < 8 and closed(kept)
    # moved only a hair past the side, the triangle faces away from its
    # control face but folds against nothing: a surface that turns, kept
    positions[4] = [0.5, 1.001, 0.1]
    assert not subdivide.turned(positions, triangles, faces, normal).any()


# the smooth oracle's seed 51 (batch 0, scene 6): a unit cube under a strong
# shear (@m), @s(140); its eight corners and six faces
SHEARED = np.array([
    [2.3166004, -1.2417024, -0.0656602], [2.5012004, -2.2243024, -0.0854602],
    [2.2315504, -1.2946524, 0.3724398], [2.4161504, -2.2772524, 0.3526398],
    [-0.2727996, -1.6991024, -1.5100602], [-0.0881996, -2.6817024, -1.5298602],
    [-0.3578496, -1.7520524, -1.0719602], [-0.1732496, -2.7346524, -1.0917602]])
SHEARED_FACES = [(6, 2, 0, 4), (1, 3, 7, 5), (0, 1, 5, 4), (4, 5, 7, 6), (3, 2, 6, 7), (1, 0, 2, 3)]


def distances(points, vertices, triangles):
    """Each point's distance to the nearest of the triangles."""
    import trimesh

    corners = vertices[triangles]
    best = np.full(len(points), np.inf)
    for start in range(0, len(points), 200):
        chunk = points[start:start + 200]
        near = trimesh.triangles.closest_point(np.tile(corners, (len(chunk), 1, 1)),
                                               np.repeat(chunk, len(corners), axis=0))
        gap = np.linalg.norm(near - np.repeat(chunk, len(corners), axis=0), axis=1)
        best[start:start + 200] = gap.reshape(len(chunk), -1).min(axis=1)
    return best


@pytest.mark.parametrize("tolerance", [0.01, 0.002])
def test_a_sheared_smooth_cube_is_within_the_tolerance_of_its_limit(tolerance):
    # the limit surface turns past its control faces' normals near their
    # corners (smooth all the same): those triangles were taken for folded
    # slivers and collapsed, and the facets stopped 0.022 below the limit's
    # top at the tolerance 0.01. Judged by the reference subdivision's limit
    # points (four levels), each within the tolerance of the written facets
    faces = [tuple(f) for f in SHEARED_FACES]
    expected, _faces = reference.smooth([tuple(p) for p in SHEARED.tolist()], faces, 140, 4)
    expected = np.array(expected)
    smooth = subdivide.smooth(SHEARED, np.arange(0, 25, 4), np.array(faces).ravel(), 140,
                              tolerance, 10 ** 7)
    assert closed(smooth.triangles)
    assert smooth.vertices[:, 2].max() == pytest.approx(expected[:, 2].max(), abs=tolerance)
    assert distances(expected, smooth.vertices, smooth.triangles).max() <= tolerance


def test_a_bad_angle_is_reported_where_it_is_written():
    for angle, shown in (("200", "200"), ("-1", "-1")):
        status, _, err = run("--no-cpp", "--check", stdin=f"\n> @t(1, 0, 0) @s({angle}) !cu(1, 0, 0);")
        assert status == 1
        assert f"<stdin>:2:15: error: the angle of '@s' must lie between 0 and 180 degrees, not {shown}" in err
    status, _, err = run("--no-cpp", stdin="> @s(1, 2) !cu(1, 0, 0);")
    assert status == 1 and "'@s' takes 1 argument" in err


def test_a_smoothing_too_fine_is_refused_before_it_is_made():
    status, _, err = run("--no-cpp", "--max-polygons", "20000", "--tolerance", "1e-6",
                         stdin="> @s(120) @h(10) !cu(1, 0, 0);")
    assert status == 1
    assert "<stdin>:1:3: error: '@s(120)': smoothing would need at least" in err
    assert "GB" in err and "raise the tolerance" in err


def test_a_smoothing_small_in_fact_is_not_refused():
    # @s(150) over a union holding a smooth solid: its facets are already
    # near the new limit, and only the seam is refined. Whole levels made
    # 73,600 triangles and were refused under --max-polygons 20,000; the
    # parts made now hold fewer, and 5,794 polygons are written. A
    # smoothing too fine in fact is still refused (the test above)
    status, out, err = run("--no-cpp", "--stats", "--max-polygons", "20000",
                           stdin="> @s(150) $U(@s(120) @h(2) !cu(1, 0, 0), "
                                 "@t(1.5, 0, 0) !cu(0, 1, 0));")
    assert status == 0, err
    assert "5794 polygons" in err and "volume 3.0675" in err


def test_the_tree_has_a_node_for_it():
    from castor.csg import tree

    frame = scene_frames("> @t(5, 0, 0) @s(90.5) @h(2) !cu(1, 0, 0);")[0]
    root = frame.objects[0].root
    assert isinstance(root, tree.Smooth) and root.angle == 90.5
    assert root.matrix[3] == 5 and root.operand.matrix[0] == 2
    assert "@s(90.5) @m(1, 0, 0, 5" in tree.dump(frame)


def scene_frames(text):
    from castor.run import evaluated_frames

    frames, said = evaluated_frames(text, "<scene>")
    assert "error" not in said, said
    return frames


def test_a_smoothed_box_seen_from_above_is_rounded():
    from castor.settings import View
    from castor.pictures import picture
    from castor.settings import PictureSettings

    def cover(text):
        spec = PictureSettings(size=(120, 120), sun=None, view=View("top", 0, 0))
        image = picture(scene_frames(text)[0], spec)
        covered = np.any(image != 255, axis=2)
        rows, columns = np.flatnonzero(covered.any(axis=1)), np.flatnonzero(covered.any(axis=0))
        square = covered[rows[0]:rows[-1] + 1, columns[0]:columns[-1] + 1]
        return square.mean(), square

    box_fill, _ = cover("> @h(2, 2, 1) !cu(0.8, 0.6, 0.4);")
    smooth_fill, square = cover("> @s(120) @h(2, 2, 1) !cu(0.8, 0.6, 0.4);")
    assert box_fill > 0.99
    # a rounded square: the corners are empty, the middle of each side full
    assert 0.79 * 0.95 < smooth_fill < 0.95  # 0.79: nearly a disc (pi / 4 = 0.785)
    n = len(square)
    assert not square[0, 0] and not square[-1, -1] and square[n // 2, 0] and square[0, n // 2]


def test_its_front_elevation_has_no_facet_lines():
    from castor.drawings import draw
    from castor.mesh.facetize import Facetizer
    from castor.settings import View

    frame = scene_frames("> @s(120) @h(2, 1, 1) !cu(0.8, 0.6, 0.4);")[0]
    meshes = Facetizer().frame(frame)
    assert meshes.polygon_count > 500
    lines = np.concatenate([layer.lines.reshape(-1, 2, 2)
                            for layer in draw(meshes, view=View("front", 0, 0)).layers])
    length = np.linalg.norm(lines[:, 1] - lines[:, 0], axis=1).sum()
    low, high = lines.reshape(-1, 2).min(axis=0), lines.reshape(-1, 2).max(axis=0)
    # the outline of a convex silhouette is shorter than its box's perimeter
    # and longer than its inscribed ellipse's: a line between two facets
    # anywhere would add to it
    assert np.pi / 2 * (high - low).sum() * 0.9 < length <= 2 * (high - low).sum()


def test_the_oracles_smooth_solids_agree_with_castors():
    from tests import oracle

    for prim, angle in ((oracle.Prim("cu", (1.0, 0.0, 0.0), ()), 135.0),
                        (oracle.Prim("pr", (1.0, 0.0, 0.0), (6.0,)), 100.0),
                        (oracle.Prim("py", (1.0, 0.0, 0.0), (5.0,)), 170.0)):
        reference = oracle.smooth_solid(prim, np.eye(4), angle).volume()
        text = f"> @s({angle}) {oracle.text(prim)};"
        frame = frames_of(text, "--tolerance", "0.001")[0]
        assert frame.volume() == pytest.approx(reference, rel=0.01)
    # every edge a crease: the oracle's smooth solid is the primitive itself
    assert oracle.smooth_solid(oracle.Prim("pr", (1.0, 0.0, 0.0), (6.0,)), np.eye(4), 30.0) is None


def test_the_oracle_looks_for_sheets_in_its_smooth_objects_too():
    # the smooth oracle's seed 11 (batch 50, scene 14) frame 3: a difference
    # whose operands hold the oracle's own @s(170) wedge; manifold3d's result
    # keeps a sheet (area 41.76, a box 0.9 wider, the same volume as
    # castor's 33.69): its area and box are not the truth, and the frame is
    # judged on castor's surface. It was reported as castor's failure, and
    # asking exact.py (which knows no smooth solid) about it crashed the run
    from tests import oracle

    scene = oracle.scenes(50, 11 * 1_000_003 + 50, False, True)[14]
    assert oracle.check_scenes([scene], exact=True) == []
    assert len(oracle.UNSURE) >= 1


def test_the_oracle_allows_a_thin_smooth_intersection_its_tolerance():
    # the smooth oracle's seed 42 (batch 50, scene 3) frame 1: the
    # intersection of two smooth scaled cubes side by side is a lens 0.03
    # thick; at the tolerance 0.01 castor's area is 0.4323, converging to
    # the limit's 0.4663 (0.4614 at 0.001), the oracle's four levels 0.4575:
    # 5.5 % apart, within what a cut face's edge moved by the tolerance makes
    from tests import oracle

    scene = oracle.scenes(50, 42 * 1_000_003 + 50, False, True)[3]
    assert oracle.check_scenes([scene], exact=True) == []


def test_its_picture_with_edges_has_no_facet_lines():
    from castor.settings import View
    from castor.pictures import picture
    from castor.settings import PictureSettings

    frame = scene_frames("> @s(120) @h(2, 2, 1) !cu(0.8, 0.6, 0.4);")[0]
    plain, edged = (picture(frame, PictureSettings(size=(160, 120), sun=None, edges=edges,
                                                   view=View("top", 0, 0)))
                    for edges in (False, True))
    covered = np.any(plain != 255, axis=2)
    rows, columns = np.flatnonzero(covered.any(axis=1)), np.flatnonzero(covered.any(axis=0))
    h, w = rows[-1] - rows[0], columns[-1] - columns[0]  # the middle half, far from the outline
    inside = (slice(rows[0] + h // 4, rows[-1] - h // 4), slice(columns[0] + w // 4,
                                                                columns[-1] - w // 4))
    # inside the outline the edges change nothing: the facets are one surface
    changed = np.any(plain[inside] != edged[inside], axis=2)
    assert changed.mean() < 0.002
    # and the outline is drawn
    assert np.any(plain != edged)
