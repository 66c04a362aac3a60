"""The garbage collector during the analyses of the language server
(castor.analysis.worker): what existed before an analysis is left out of the
collections while it runs, so that a collection of the middle generation does
not scan the scene graphs of the analyses before it (issue 29, item 11: with
three versions of a statement of 40,000 cubes kept, one analysis in three
paused 1 to 3 s in one collection). Counted, not timed."""

from __future__ import annotations

import gc
import threading

from castor.analysis.worker import Submission, Worker


def _run(texts: list[str]) -> list[tuple[int, int]]:
    """For each text analysed: the objects frozen while it ran, and after it."""
    during: list[int] = []
    after: list[int] = []
    finished = threading.Event()
    kept = []  # what each analysis leaves, alive, as the reuse memory keeps graphs

    def analyse(submission, cancelled):
        during.append(gc.get_freeze_count())
        kept.append([[k] for k in range(1_000)])
        return submission.text

    def done(submission, analysis, problem):
        after.append(gc.get_freeze_count())
        if len(after) == len(texts):
            finished.set()

    worker = Worker(analyse, done)
    try:
        for number, text in enumerate(texts):
            worker.submit(Submission(f"doc{number}", text, None))
        assert finished.wait(30)
    finally:
        worker.stop()
    return list(zip(during, after))


def test_what_existed_before_an_analysis_is_frozen_while_it_runs_and_only_then():
    assert gc.get_freeze_count() == 0
    counts = _run(["a", "b", "c"])
    # each analysis ran with the objects before it frozen (those the ones before
    # it left among them: more each time), and none stayed frozen after it
    assert all(during > 1_000 for during, _ in counts), counts
    assert counts[1][0] > counts[0][0] + 1_000 and counts[2][0] > counts[1][0] + 1_000, counts
    assert [after for _, after in counts] == [0, 0, 0]
    assert gc.get_freeze_count() == 0
