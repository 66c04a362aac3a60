"""One thread that analyses the newest text of each document, and stops stale work at once.

An editor sends a new text at every keystroke. The worker keeps, for each
document, only the newest text not yet analysed; an analysis that a newer text
of its document overtakes is stopped where it stands, inside a statement as
well as between two (one statement of 40,000 cubes is seconds of parsing): the
worker raises ``Overtaken`` in its own thread (CPython delivers it at the next
bytecode the thread runs, castor's analysis being Python throughout). The
stopped analysis leaves nothing behind but the statements already remembered
(castor.analysis.reuse), which are whole.

The garbage collector's young generations see only what the running analysis
makes: the objects that were there before it (the scene graphs of the texts
analysed before, which castor.analysis.reuse keeps: some 80 MB of nodes for one
version of a statement of 40,000 cubes) are frozen while it runs (``gc.freeze``),
then go to the oldest generation (``gc.unfreeze``). Otherwise each collection of
the middle generation scanned the graphs of the two or three analyses before:
a pause of 1 to 3 s in every third analysis of such a statement.
"""

from __future__ import annotations

import collections
import ctypes
import gc
import threading
from dataclasses import dataclass, field
from typing import Callable

from castor.pipeline import Overtaken


@dataclass
class Submission:
    """A text to analyse: ``key`` names its document (newer texts of one key
    overtake older ones); ``payload`` is the caller's, handed back with the result."""

    key: str
    text: str
    name: str | None
    version: int = 0
    unsaved: dict[str, str] = field(default_factory=dict)  # path -> text of other buffers
    payload: object = None
    number: int = 0  # the worker's count of submissions


def _settle() -> None:
    """Nothing: a call, where CPython delivers an exception sent to this thread."""


class Stopper:
    """Stops at once the work one thread does for a number (a submission, a
    generation) as soon as that number is stale: ``begin`` and ``end`` around
    the work, in that thread; ``stop`` from any thread. An ``Overtaken`` sent is
    delivered inside the work or, at the latest, in ``end``."""

    def __init__(self):
        self.lock = threading.Lock()  # a C lock: no Python frame to interrupt
        self.thread: int | None = None
        self.number: int | None = None

    def begin(self, number: int) -> None:
        with self.lock:
            self.thread, self.number = threading.get_ident(), number

    def end(self) -> None:
        with self.lock:
            self.number = None
        _settle()  # an Overtaken sent before the line above is delivered here

    def stop(self, stale: Callable[[int], bool]) -> bool:
        """Stop the work now if ``stale(its number)``; whether it was stopped."""
        with self.lock:
            if self.number is None or not stale(self.number):
                return False
            self.number = None  # sent once
            ctypes.pythonapi.PyThreadState_SetAsyncExc(ctypes.c_ulong(self.thread),
                                                       ctypes.py_object(Overtaken))
            return True


class Worker:
    """Analyses each submission with ``analyse(submission, cancelled)`` and hands
    ``done(submission, analysis, problem)`` the result (``problem``, a message, when
    there is no analysis); a submission overtaken by a newer one of its key gives nothing."""

    def __init__(self, analyse: Callable, done: Callable, stack_bytes: int = 0):
        self.analyse, self.done = analyse, done
        self.queue = threading.Condition()
        self.pending: dict[str, Submission] = {}
        self.latest: dict[str, int] = {}  # key -> the number of its newest submission
        self.submitted = 0
        self.stopped = False
        self.running: Submission | None = None  # the submission being analysed
        self.stopper = Stopper()
        # ("started" | "stopped" | "finished", key, number) of the latest submissions
        self.log: collections.deque = collections.deque(maxlen=1000)
        from castor.settings import started_thread

        # deep scenes recurse deeply, as in castor
        self.thread = started_thread(self._loop, "castor-analysis", stack_bytes)

    def submit(self, submission: Submission) -> None:
        """Analyse ``submission`` soon; an older one of its key, pending or running, is dropped."""
        with self.queue:
            self.submitted += 1
            submission.number = self.submitted
            self.latest[submission.key] = submission.number
            self.pending[submission.key] = submission
            self.queue.notify()
        self._interrupt(lambda running: running.key == submission.key)

    def stop(self) -> None:
        with self.queue:
            self.stopped = True
            self.queue.notify()
        self._interrupt(lambda running: True)

    def overtaken(self, submission: Submission) -> bool:
        return self.stopped or self.latest.get(submission.key) != submission.number

    def _interrupt(self, which: Callable[[Submission], bool]) -> None:
        """Stop the running analysis now if ``which`` says it is stale."""
        def stale(number: int) -> bool:  # asked with the stopper's lock held
            submission = self.running
            return submission is not None and submission.number == number and which(submission) \
                and self.overtaken(submission)

        self.stopper.stop(stale)

    def _next(self) -> Submission | None:
        with self.queue:
            while not self.pending and not self.stopped:
                self.queue.wait()
            if self.stopped:
                return None
            return self.pending.pop(next(iter(self.pending)))

    def _loop(self) -> None:
        while True:
            try:
                submission = self._next()
                if submission is None:
                    return
                self._one(submission)
            except Overtaken:  # sent late, after the analysis it was meant for
                continue

    def _one(self, submission: Submission) -> None:
        self.log.append(("started", submission.key, submission.number))
        try:
            self.running = submission
            gc.freeze()  # what exists now is left out of the collections (see above)
            try:
                self.stopper.begin(submission.number)
                try:
                    if self.overtaken(submission):  # a newer one came before begin(): not stopped
                        raise Overtaken()
                    analysis = self.analyse(submission, lambda: self.overtaken(submission))
                    problem = None
                finally:
                    self.stopper.end()
            finally:  # (no Overtaken comes after end(): it is sent once, delivered there at the latest)
                gc.unfreeze()
        except Overtaken:
            self.log.append(("stopped", submission.key, submission.number))
            return
        except MemoryError:
            analysis, problem = None, "out of memory analysing the scene"
        except Exception as exc:  # a fault of castor's: said, and the worker goes on
            analysis, problem = None, (f"castor: internal error: {type(exc).__name__}: {exc} "
                                       f"(please report it with the scene)")
        if self.overtaken(submission):
            self.log.append(("stopped", submission.key, submission.number))
            return
        self.log.append(("finished", submission.key, submission.number))
        self.done(submission, analysis, problem)
