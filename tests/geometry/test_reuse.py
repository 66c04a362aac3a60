"""A second frame after a parameter change that touches one subtree: what did
not change is neither evaluated by the engine nor regularized again (counted
by the process's caches, castor.mesh.caches), and the frame is the one a
fresh facetizer makes."""

from castor.mesh.caches import PROCESS
from castor.settings import EvaluationSettings

# two named objects far apart, each a union whose faces only touch
# (tests/geometry/test_oracle.py), with a fine cylinder so that each is a
# batch of its own (more than 256 triangles)
SCENE = """TOLERANCE = 0.0001;
W = 0;
gauche = $U(!py(1,0,0,4), @ry(45) !cu(1,0,0), @t(-0.5,-0.9,-0.1) !cu(1,0,0), @t(-0.6,0,-1) !cu(1,0,0),
            @t(-0.2, 0.5, -2 - W) @h(0.2, 0.2, 1.5) !cy(1, 0, 0));
droite = $U(!py(0,1,0,4), @ry(45) !cu(0,1,0), @t(-0.5,-0.9,-0.1) !cu(0,1,0), @t(-0.6,0,-1) !cu(0,1,0),
            @t(-0.2, 0.5, -2) @h(0.2, 0.2, 1.5) !cy(0, 1, 0));
> $U(gauche, @t(20, 0, 0) droite);
"""


def _scene(width: float):
    from castor.run import evaluated_frames

    [scene], said = evaluated_frames(SCENE, "reuse.cas", EvaluationSettings({"W": width}))
    assert not said, said
    return scene


def _reused() -> int:
    """Regularizations not made again: of parts known clean by their
    triangles and faces, and of parts seen before as they are."""
    return PROCESS.clean.hits + PROCESS.regular.hits


def _same(a, b) -> None:
    assert len(a.objects) == len(b.objects)
    for x, y in zip(a.objects, b.objects):
        assert (x.vertices == y.vertices).all() and (x.indices == y.indices).all()
        assert (x.offsets == y.offsets).all() and (x.origin_of == y.origin_of).all()
        assert [o.path for o in x.origins] == [o.path for o in y.origins]


def test_a_parameter_change_reuses_the_subtree_it_does_not_touch():
    from castor.mesh.facetize import Facetizer

    facetizer = Facetizer()
    first = facetizer.frame(_scene(0.0))
    # 'droite', moved, is looked at for sheets and flat triangles (regularized);
    # 'gauche', a copy of its triangles, is known clean by them (PROCESS.clean)
    assert len(PROCESS.regular) == 1
    solids, reused = PROCESS.solids.hits, _reused()
    changed = facetizer.frame(_scene(0.5))  # W moves the cylinder of 'gauche' only
    assert PROCESS.solids.hits - solids == 1  # 'droite' from the cache, 'gauche' made again
    assert _reused() - reused == 1  # 'droite''s regularization reused
    assert len(PROCESS.regular) == 2  # 'gauche', changed, regularized
    assert facetizer.counter.booleans == 1  # the union of 'gauche'
    assert changed.objects[0].vertices[:, 2].min() == first.objects[0].vertices[:, 2].min() - 0.5
    # what was reused gives what a facetizer starting from nothing gives
    _same(changed, Facetizer().frame(_scene(0.5)))


def test_the_same_frame_again_regularizes_nothing():
    from castor.mesh.facetize import Facetizer

    facetizer = Facetizer()
    first = facetizer.frame(_scene(0.0))
    reused = _reused()
    again = facetizer.frame(_scene(0.0))
    assert _reused() - reused == 2 and facetizer.counter.booleans == 0
    _same(again, first)

