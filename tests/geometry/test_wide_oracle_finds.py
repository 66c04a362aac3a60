"""Scenes the oracle's wide generator found (issue 18, items 4 and 5), each
judged as the oracle judges a frame (tests/oracle.py) and against the
volume and area of exact booleans (tests/exact.py): never against castor's
own earlier output."""

import numpy as np
import pytest

import exact
import oracle
from meshcheck import check_closed, regularity_defects
from oracle import Bool, Param, Prim, Rep, Scene, Tf

needs_exact = pytest.mark.skipif(not exact.available(), reason="needs pymeshlab")


def _judged(scene: Scene):
    """castor's frames of the scene, the oracle's problems with each, and
    each frame's exact (volume, area)."""
    frames, _ = oracle.castor_frames(oracle.scene_text(scene))
    figures = exact.frame_figures(scene)
    problems = []
    for frame, (solids, uses), truth in zip(frames, oracle.Oracle(scene).frames(), figures):
        problems.append(oracle.judge(frame, solids, uses, exact=lambda truth=truth: truth))
    return frames, problems, figures


def _cube(colour):
    return Prim("cu", colour, ())


@needs_exact
def test_a_twin_in_a_turned_union_leaves_no_inward_sliver():
    """Six unit cubes 0.1 apart and a copy of the last in a union, turned by
    68.815° about (1, 1, -1) (wide oracle, seed 20): the engine leaves a fold
    on the top face, three layers of it facing out where two small triangles
    (1e-7) of U1.U4 lie turned in. Each triangle's side was told against the
    area of its face's largest triangle, so the small ones were taken as
    facing out, and stayed facing in once the sheet was cut: no sheet and no
    polygon facing in may be left."""
    row = Rep("U", "W", 6, Tf((("t", (Param("W", 0.1, 0.0), 0.0, 0.0)),), _cube((0.0, 0.0, 0.0))))
    twin = Tf((("t", (0.5, 0.0, 0.0)),), _cube((0.0, 0.5, 0.5)))
    scene = Scene([("frame", [Tf((("t", (-0.742, 0.519, 0.493)), ("r", (1.0, 1.0, -1.0, 68.815))),
                                 Bool("U", (row, twin)))])])
    (frame,), (problems,), ((volume, area),) = _judged(scene)
    check_closed(frame)
    assert abs(frame.volume() - volume) < 1e-9 and abs(volume - 1.5) < 1e-9
    assert abs(frame.area() - area) < 1e-7
    assert regularity_defects(frame) == []
    assert problems == []
