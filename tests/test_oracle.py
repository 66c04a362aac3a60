"""castor against the differential oracle (tests/oracle.py): a few hundred
random scenes, many per castor process; the long run is
`python tests/oracle.py --cases 3000`."""

import numpy as np
import pytest

import oracle
from meshcheck import parse_stream

# Sheets that manifold3d leaves where faces only touch, and that castor does
# not yet remove (see test_known_sheets): judged there, not here.
KNOWN = {"winding"}


@pytest.mark.parametrize("seed", [11, 12, 13, 14, 15])
def test_random_scenes_agree_with_the_oracle(seed):
    scenes = oracle.scenes(50, seed)
    failures = oracle.check_scenes(scenes)
    found = [(number, p, oracle.scene_text(scene)) for scene, number, problems in failures
             for p in problems if oracle.kind_of(p) not in KNOWN]
    assert found == [], found[0]


def test_the_oracle_sees_a_wrong_volume_and_a_wrong_path():
    """The judge itself can fail: feed it a frame that is not the scene's."""
    scene = oracle.Scene([("param", "P", 1.0),
                          ("frame", [oracle.Bool("U", (oracle.Prim("cu", (1.0, 0.0, 0.0), ()),
                                                        oracle.Tf((("t", (0.5, 0.0, 0.0)),),
                                                                  oracle.Prim("cu", (0.0, 1.0, 0.0), ()))))])])
    (solids, uses), = list(oracle.Oracle(scene).frames())
    text = ("castor-polygons 1\nframe 1 x:1\n"
            + "".join(f"poly U3!cu 1 0 0 4 {' '.join(map(repr, q.ravel().tolist()))}\n"
                      for q in _cube_faces(2.0))
            + "endframe 1 6\n")
    (frame,) = parse_stream(text)
    problems = oracle.judge(frame, solids, uses)
    kinds = {oracle.kind_of(p) for p in problems}
    assert {"volume", "area", "box", "names no"} <= kinds


def _cube_faces(size):
    c = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                  [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float) * size
    faces = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [1, 2, 6, 5], [0, 4, 7, 3]]
    return [c[f] for f in faces]


SHEETS = [
    # a cube and a prism turned so that an edge of the cube lies in a face of the prism
    "s = @ry(180) @ry(45) !pr(0.5, 0.5, 0, 3); > $U(!cu(0, 1, 0.5), s);",
    # issue 8, 1: a pyramid's base, a cube's top and a turned cube's edge meet in z = 0
    "x = $U(!py(1,0,0,4), @ry(45) !cu(1,0,0), @t(-0.5,-0.9,-0.1) !cu(1,0,0), "
    "@t(-0.6,0,-1) !cu(1,0,0)); > x;",
]


@pytest.mark.xfail(strict=True, reason="manifold3d leaves a fold where faces only touch, "
                                       "and castor does not remove it yet")
@pytest.mark.parametrize("scene", SHEETS)
def test_known_sheets(scene):
    from meshcheck import frames_of, sheet_defects
    (frame,) = frames_of(scene + "\n")
    assert sheet_defects(frame) == []
