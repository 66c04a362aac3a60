"""What the oracle's wide generator found (issue 18, items 4 and 5) that is
checked here rather than replayed: a twin's face numbers, the judge on a thin
triangle, a needle castor must not leave. The findings that are a scene and
the oracle's judgement (against exact booleans) are files in tests/corpus/,
replayed by test_corpus.py."""

import numpy as np

from tests.support.checks import check_closed
from tests.support.regularity import regularity_defects


def test_a_copy_of_a_template_for_a_twin_keeps_its_face_numbers():
    """A use told apart from its twin enters the engine as a copy of its
    template under an ID of its own; the engine's ``as_original`` numbered
    that copy's faces afresh, so every check of a result holding it found
    its triangles off the faces they named (a prism's, a cube's)."""
    from castor.mesh import checks, instances, primitives

    for kind, shape in (("pr", (4.0,)), ("cu", ()), ("py", (5.0,)), ("we", ())):
        template = instances.template(primitives.build(kind, shape, 0.01))
        use = instances.Placed(template, np.array([[0.9, 0.1, 0, 1], [-0.1, 0.9, 0, 2],
                                                   [0, 0, 1.1, 3]]))
        twin = use.distinguished()
        assert twin.id != template.id
        assert checks.off_faces(twin.in_engine()) == 0, kind


def test_the_judge_reads_a_thin_triangle_far_from_the_origin_as_planar():
    """A triangle of castor's (wide oracle, seed 22: a turned row of cubes in
    a shared object, moved), 2.3e-4 long and 1.4e-7 wide at x = -2: its
    normal taken about the origin was 2 % off (the rounding of coordinates
    of 2), so the judge found its own corners 2.4e-7 off its plane."""
    from tests.support.regularity import polygon_defects
    from tests.support.stream import Polygon

    corners = np.array([[-2.0175520307082437, -0.3671558291210445, -0.3993812032469618],
                        [-2.0173210497029217, -0.3671575394512535, -0.3993866435291141],
                        [-2.0173211902126096, -0.3671575383501424, -0.39938664015685066]])
    assert polygon_defects(Polygon("U3!cu", (0.5, 0.0, 0.0), corners)) == []


def test_a_flattened_turned_row_leaves_no_needle():
    """Eleven cubes 0.1 apart turned by 356.731° about (0.5, 1, 1) and
    flattened to half their height (wide oracle, seed 32): a triangle of
    U11 0.3 long and 3.8e-7 wide at one end (twice its area 8.8e-13 of its
    long side squared) was left, flat by castor's own test: its flip would
    turn the neighbour over (itself a needle 2.5e-7 high), and collapsing
    its short edge either way turned over a triangle at the third corner of
    the small triangle across it (1.9e-7 from both ends). That corner goes
    onto one end first, then the short edge: no polygon of zero area
    (LANGUAGE.md §7), the volume exact."""
    from tests.support.cli import frames_of

    (frame,) = frames_of("> @h(1.0, 1.0, 0.5) @r(0.5, 1.0, 1.0, 356.731) "
                         "$U[W = 0, 10](@t(0.1 * W, 0.0, 0.0) !cu(1.0, 0.0, 0.0));\n")
    check_closed(frame)
    assert abs(frame.volume() - 0.5 * 2.0) < 1e-9
    assert regularity_defects(frame) == []
