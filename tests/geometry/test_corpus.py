"""The oracle's findings replayed: each scene in tests/corpus/ (the text the
oracle printed, its comment saying what it found) is run through castor and
every frame judged as the oracle judges one (tests/oracle/). A file with an
``// exact`` line is judged against exact booleans too (tests/oracle/exact.py,
pymeshlab): each frame's volume and area equal theirs; ``// volume N V``
gives frame N's volume. A new finding, once fixed, is one more file there."""

import re
from pathlib import Path

import pytest

from tests import oracle
from tests.oracle import exact
from tests.support.checks import check_closed
from tests.support.regularity import regularity_defects

CORPUS = Path(__file__).resolve().parents[1] / "corpus"


def _directives(text: str):
    """Whether the file asks for exact booleans, and its frames' volumes."""
    wants_exact = re.search(r"^// exact$", text, re.M) is not None
    volumes = {int(n): float(v) for n, v in re.findall(r"^// volume (\d+) (\S+)$", text, re.M)}
    return wants_exact, volumes


def test_the_corpus_is_there():
    assert len(sorted(CORPUS.glob("*.cas"))) >= 4


@pytest.mark.parametrize("path", sorted(CORPUS.glob("*.cas")), ids=lambda p: p.stem)
def test_a_finding_of_the_oracle_stays_fixed(path: Path):
    text = path.read_text()
    wants_exact, volumes = _directives(text)
    if wants_exact and not exact.available():
        pytest.skip("needs pymeshlab (exact booleans)")
    scene = oracle.read_scene(text)
    body = oracle.scene_text(scene)
    assert body in text, "the file's scene is not as the oracle prints it"
    frames, _ = oracle.castor_frames(body)
    figures = exact.frame_figures(scene) if wants_exact else [None] * len(frames)
    evaluated = list(oracle.Oracle(scene).frames())
    assert len(frames) == len(evaluated) == scene.frames()
    for frame, (solids, uses), truth in zip(frames, evaluated, figures):
        check_closed(frame)
        assert regularity_defects(frame) == []
        if truth is not None:
            volume, area = truth
            assert abs(frame.volume() - volume) < 1e-9
            assert abs(frame.area() - area) < 1e-7
        assert oracle.judge(frame, solids, uses,
                            exact=None if truth is None else (lambda truth=truth: truth)) == []
        if frame.number in volumes:
            assert abs(frame.volume() - volumes[frame.number]) < 1e-9
            assert truth is None or abs(truth[0] - volumes[frame.number]) < 1e-9


def test_the_oracle_reads_back_the_text_it_prints():
    """``read_scene`` is what the corpus stands on: every scene the generators
    make (wide and smooth ones too) printed, read back and printed again is
    the same text."""
    for wide in (False, True):
        for smooth in (False, True):
            for scene in oracle.scenes(60, 5, wide, smooth):
                text = oracle.scene_text(scene)
                assert oracle.scene_text(oracle.read_scene("// found\n" + text)) == text
