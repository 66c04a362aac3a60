"""Coincident twins whose runs the engine cannot keep apart (issue 18, item 4;
LANGUAGE.md §8): found by the oracle's wide generator (seed 19).

Where one primitive stands at one place in two operands, castor renames the
runs of one twin inside a result of the engine; where that is refused, or
leads the engine astray, both twins keep one ID and placement, and
provenance names each triangle after the twin whose cut parity matches the
way it faces (provenance.facing_twins). These tests pin the paths, colours
and volumes of the exact polygons concerned."""

import subprocess
import sys

import numpy as np

from tests.support.checks import check_closed, check_convex_planar
from tests.support.cli import frames_of
from tests.support.regularity import regularity_defects
from tests.support.stream import newell, parse_stream

# (P ∪ cube) − (P' ∪ a turned row): every face of the prism left is cut by P'
PRISM_TWINS = """
s10o0 = @r(0.5, 1.0, 1.0, 13.0) $U[W = 0, 2](@t(W, 0.0, 0.0) !cu(0.0, 0.0, 1.0));
s10o1 = $D($U(@r(0.0, 1.0, 0.0, 90.0) @t(0.0, 1.5, -0.5) !pr(0.25, 0.5, 0.0, 8.0),
              $U[W = 0, 1](!cu(0.5, 0.5, 0.0))),
           $U(@r(0.0, 1.0, 0.0, 90.0) @t(0.0, 1.5, -0.5) !pr(0.0, 0.5, 0.0, 8.0),
              $U[R = 0, 1](s10o0)));
> s10o1;
"""

# (C ∪ W) ∩ (C' ∪ a turned pair of cubes): the twin C' renamed inside the
# engine's union made the engine's intersection lose 8e-4 of volume
WEDGE_TWINS = """
s = $I($U(@r(1.0, 1.0, 1.0, 90.0) !cu(0.5, 1.0, 1.0), @rz(-90.0) !we(0.0, 0.5, 0.5)),
       $U(@r(1.0, 1.0, 1.0, 90.0) !cu(0.5, 0.0, 0.5),
          @r(0.5, 1.0, -1.0, 13.0) $U(!cu(0.5, 1.0, 1.0), @t(-1.0, 0.0, 0.0) !cu(0.0, 0.5, 0.5))));
> s;
"""


def _solid(frame):
    check_closed(frame)
    check_convex_planar(frame)
    assert frame.volume() > 0
    assert regularity_defects(frame) == []


def test_the_prisms_cut_faces_are_the_cutters():
    """What is left of the prism's faces faces inward (into the cube): they
    are the subtrahend's prism P', in its colour, never the minuend's P."""
    (frame,) = frames_of(PRISM_TWINS)
    _solid(frame)
    assert abs(frame.volume() - 0.10308592183836096) < 1e-9
    prism = [p for p in frame.polygons if p.path.endswith("!pr")]
    assert len(prism) == 2
    assert {(p.path, p.colour) for p in prism} == {("(s10o1).D2.U1!pr", (0.0, 0.5, 0.0))}
    # the prism's axis is x after the turn: its faces' normals have no x part,
    # and they face the axis (y = 1.5, z = 0), into the cavity
    for p in prism:
        normal = newell(p.points)
        centre = p.points.mean(axis=0)
        assert abs(normal[0]) < 1e-9 * np.linalg.norm(normal)
        assert np.dot(normal[1:], np.array([1.5, 0.0]) - centre[1:]) > 0


def test_twins_renamed_apart_leave_the_engines_volume_alone():
    """The intersection's volume is manifold3d's of the same operands
    (1.06814715…, which exact booleans confirm), and each polygon named
    after the wedge lies on a face of the wedge, facing as it does."""
    (frame,) = frames_of(WEDGE_TWINS)
    _solid(frame)
    assert abs(frame.volume() - 1.0681471535313836) < 1e-9
    assert abs(frame.area() - 7.301655676722051) < 1e-9
    # the wedge's outward planes turned by -90° about z: (x, y, z) -> (y, -x, z)
    planes = [((0, 0, -1), 0), ((0, 1, 0), 0), ((-1, 0, 0), 0), ((1, 0, 0), 1),
              ((0, -2 ** -0.5, 2 ** -0.5), 2 ** -0.5)]
    wedge = [p for p in frame.polygons if p.path.endswith("!we")]
    assert wedge
    for p in wedge:
        assert any(np.abs(p.points @ np.array(n) - d).max() < 1e-9
                   and newell(p.points) @ np.array(n) > 0 for n, d in planes), p.points


_NOT_RENAMED = ("import sys, castor.mesh.adapter as a; a.with_run_ids = lambda m, ids: None; "
                "from castor.cli import main; sys.argv = ['castor', '--no-cpp', '-q']; main()")


def test_twins_the_engine_keeps_under_one_id_are_named_by_the_way_they_face():
    """With no renaming of runs at all (as when the engine refuses the
    rebuilt copy), the rule alone names the cut faces: the cavity's faces
    come from the cutter D2.D1 (cut away once: facing inward), the outer
    faces from D1.U3 or D1.U2 (facing outward)."""
    scene = ("C = 0.083; > $D($U[I = 2, 0, -1](@h(1 + abs(I) * 0.25) !cu(C, 0.2, 1 - C)), "
             "$D(!cu(0.3, 0.5, 0.9), @rz(15) !cu(0.9, 0.9, 0.85)));\n")
    done = subprocess.run([sys.executable, "-c", _NOT_RENAMED], input=scene, text=True,
                          capture_output=True, timeout=120)
    assert done.returncode == 0, done.stderr
    (frame,) = parse_stream(done.stdout)
    _solid(frame)
    cut = []
    for p in frame.polygons:
        n = newell(p.points)
        for axis in range(3):
            if np.allclose(p.points[:, axis], 1.0, atol=1e-9) and n[axis] < -0.5 * np.linalg.norm(n):
                cut.append(p)
    assert cut
    assert {(p.path, p.colour) for p in cut} == {("D2.D1!cu", (0.3, 0.5, 0.9))}
    chosen = {id(p) for p in cut}
    outer = [p for p in frame.polygons if id(p) not in chosen]
    assert not any(p.path == "D2.D1!cu" for p in outer
                   if np.allclose(p.points[:, 2], 0.0, atol=1e-9))
