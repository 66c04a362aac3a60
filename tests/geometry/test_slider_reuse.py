"""The live preview's slider on the bus shelter (castor.serve.evaluation.evaluate,
its caches kept from one value to the next): a step reuses what the new
value did not change — the engine's booleans of unchanged operands
(caches.PROCESS.booleans), the sheets cut out of unchanged planes (.planes),
the polygons of unchanged faces and parts (.groups, .merged) — counted by
the caches' hits, and the frames it shows are byte for byte those of an
evaluation that starts from nothing."""

from pathlib import Path

from castor.mesh.caches import PROCESS, Bounded
from castor.settings import EvaluationSettings, Source

ROOT = Path(__file__).resolve().parents[2]
SHELTER = ROOT / "examples" / "bus_shelter.cas"


def _evaluate(value: float, name: str = "LA"):
    from castor.serve.evaluation import Watched, evaluate

    result = evaluate(Watched(Source((str(SHELTER),)),
                              evaluation=EvaluationSettings(overrides={name: value}), quiet=True))
    assert result.errors == 0, result.printed
    return result.frames


def _forget_everything() -> None:
    for cache in vars(PROCESS).values():
        if isinstance(cache, Bounded):
            cache.clear()


def _hits() -> dict:
    return {name: cache.hits for name, cache in vars(PROCESS).items()
            if isinstance(cache, Bounded)}


def _same(stepped, fresh) -> None:
    assert len(stepped) == len(fresh) == 3
    for shown, made in zip(stepped, fresh):
        assert shown.polygons == made.polygons and shown.triangles == made.triangles
        assert shown.origins == made.origins
        assert shown.data == made.data


def test_a_slider_step_reuses_what_it_did_not_change_and_shows_a_fresh_frame():
    _evaluate(5.0)
    before = _hits()
    stepped = _evaluate(5.3)
    hits = {name: count - before[name] for name, count in _hits().items()}
    # the traffic light's three frames: the second and third unite the same
    # operands as the first (only a lamp's colour changes) and are merged as it was
    assert hits["booleans"] >= 2 and hits["merged"] >= 2 and hits["regular"] >= 2
    # inside the first frame's one part (the street touches everything): the
    # planes with sheets and the faces that the shelter's length does not move
    assert hits["planes"] >= 10 and hits["groups"] >= 300
    _forget_everything()
    _same(stepped, _evaluate(5.3))
    # the shelter did get longer: the frame's box is the street's, so compare
    # the triangles themselves with the first value's
    assert stepped[0].data != _evaluate(5.0)[0].data


def test_sheets_cut_in_unchanged_planes_are_cut_as_before():
    """The street lamp's height moves no face on the pavement: the planes
    where the posts, the kerb and the bollards only touch the pavement, whose
    sheets are cut out with new points on their edges, are cut as in the
    frame before (what the cut made, renumbered), and the frame is a fresh one."""
    from castor.mesh import sheets

    replayed = []
    again = sheets._Resolver._replayed

    def noted(resolver, done, *rest):
        taken = again(resolver, done, *rest)
        replayed.append((taken, len(done.points), len(done.replaced)))
        return taken

    _evaluate(5.0, "HL")
    sheets._Resolver._replayed = noted
    try:
        stepped = _evaluate(5.2, "HL")
    finally:
        sheets._Resolver._replayed = again
    assert all(taken for taken, _, _ in replayed)
    assert sum(points > 0 and cut > 0 for _, points, cut in replayed) >= 2
    # the same two values with what the step reused forgotten before it
    _forget_everything()
    _evaluate(5.0, "HL")
    for name in ("booleans", "planes", "regular", "merged", "groups"):
        getattr(PROCESS, name).clear()
    _same(stepped, _evaluate(5.2, "HL"))
    # from nothing: the same triangles and origins (a primitive's template
    # made afresh for the new height is numbered after the others, and the
    # engine gives its triangles in another order: main's template cache)
    _forget_everything()
    for shown, made in zip(stepped, _evaluate(5.2, "HL")):
        assert _rows(shown) == _rows(made)


def _rows(frame) -> list:
    """A drawn frame's triangles, each its corners and its origin, sorted."""
    import numpy as np

    corners = np.frombuffer(frame.data[:36 * frame.triangles], "<f4").reshape(-1, 9)
    numbers = np.frombuffer(frame.data[36 * frame.triangles:], "<u4")
    return sorted(zip(map(bytes, corners), (frame.origins[n] for n in numbers.tolist())))
