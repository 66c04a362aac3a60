"""One frame's work, done in this process, another process, or on a Dask cluster.

The interpreter hands each frame's evaluated CSG tree over as a ``Job``: plain,
picklable data with the settings of the stages that make it (castor.settings).
``make`` has the output's kind make the frame's product (castor.formats.kinds)
and its format's writer write it, and turns it into a ``Result``
(the bytes to write, the messages to print, the figures of --stats) in
whatever process runs it; the driver (castor.run) writes results in frame
order, so the output is the same byte for byte however the frames were made.
Each process keeps one facetizer (castor.formats.kinds.facetizer_for), whose
caches of shared subtrees (by key) and primitive shapes serve every frame it
makes. Nothing crosses between processes but plain data: the tree and its
settings one way, bytes, arrays and figures back.
"""

from __future__ import annotations

import threading
from collections import deque
from dataclasses import dataclass, field

from castor.csg.tree import FrameTree
from castor.diagnostics import CastorError, Location
from castor.settings import (RECURSION_LIMIT, STACK_BYTES, FrameSettings, OutputSettings,
                             started_thread)


@dataclass(frozen=True)
class Job:
    """One frame's work: its evaluated CSG tree and what to make of it, by stage."""

    tree: FrameTree
    settings: FrameSettings


@dataclass
class Result:
    number: int
    location: Location
    data: object = None  # the frame in its format: castor.formats.output.Data (None: nothing)
    companions: dict[str, bytes] = field(default_factory=dict)  # files beside it (.mtl)
    errors: list[CastorError] = field(default_factory=list)
    warnings: list[tuple[str, Location | None]] = field(default_factory=list)
    stats: str | None = None
    summary: dict | None = None
    # the frame's part of a file made from every frame at once (an animation's
    # frame, castor.formats.kinds.Framing), gathered by the driver
    gathered: object = None
    mesh: object = None  # the mesh frame, when the output settings keep it


# a frame of more polygons than this, made in a worker process, is written to
# a file in OutputSettings.spool rather than handed back as bytes through a pipe (a
# 5 M-polygon stream is about 700 MB, pickled and held twice on its way)
SPOOL_POLYGONS = 100_000


def make(job: Job) -> Result:
    """The frame's output, and what is to be said about it; never raises for
    an error of the scene (it is in the result)."""
    tree = job.tree
    result = Result(tree.number, tree.location)
    try:
        _make(tree, job.settings, result)
    except CastorError as exc:
        result.errors.append(exc)
        result.data = None
    except RecursionError:  # deeper than even castor's stack (STACK_BYTES) allows
        from castor.diagnostics import LimitError

        result.errors.append(LimitError("the frame's objects are nested too deeply to build; "
                                        "flatten the chain of named objects or operations",
                                        tree.location))
        result.data = None
    except MemoryError:
        from castor.diagnostics import LimitError

        result.errors.append(LimitError("out of memory for this frame; simplify the scene, "
                                        "raise the tolerance or lower --max-polygons",
                                        tree.location))
        result.data = None
    return result


def make_deep(job: Job) -> Result:
    """``make`` in a worker process (--jobs N, a Dask worker), on a thread with the
    stack and recursion limit of castor's own (castor.settings.STACK_BYTES): a
    worker's main thread has 8 MB and a limit of 1,000 calls, and a chain of
    2,000 named objects recursed past it (issue 29)."""
    import sys

    if sys.getrecursionlimit() < RECURSION_LIMIT:
        sys.setrecursionlimit(RECURSION_LIMIT)
    outcome: list = []

    def work() -> None:
        try:
            outcome.append(make(job))
        except BaseException as exc:  # raised again on the caller's thread
            outcome.append(exc)

    started_thread(work, "castor-frame", STACK_BYTES).join()
    if isinstance(outcome[0], BaseException):
        raise outcome[0]
    return outcome[0]


def _make(tree: FrameTree, settings: FrameSettings, result: Result) -> None:
    """The frame's product, made by its output's kind (castor.formats.kinds), then
    written by its format's writer: its bytes, or the part it gives to a file made
    from every frame at once (an animation)."""
    from castor.formats import FORMATS
    from castor.formats.kinds import MESH

    output = settings.output
    chosen = FORMATS.get(output.format) if output.format is not None else None
    kind = chosen.kind if chosen is not None else MESH  # no format: the mesh frame only
    product = kind.make(tree, settings, chosen, result)
    if chosen is None or product is None:
        return
    if chosen.gathers:
        result.gathered = product
        return
    result.data, result.companions = _encoded(product, kind, output, tree.number)


def _encoded(product, kind, output: OutputSettings, number: int):
    """The product's bytes in the output's format, and the files beside them: made
    a piece at a time as they are written (``output.pieces``), spooled to a file
    when large, else bytes."""
    from castor.formats import output as destination

    pieces, companions = destination.encode_pieces(product, output.format, output.target,
                                                   number=number, options=dict(output.options))
    if output.pieces:
        return pieces, companions  # made as they are written
    if output.spool is not None and kind.weight(product) > SPOOL_POLYGONS:
        return _spooled(pieces, product, output, number), companions
    return b"".join(pieces), companions


def _spooled(pieces, product, output: OutputSettings, number: int):
    """The frame's bytes written a piece at a time to a file in ``output.spool``
    (hidden, beside the output where it can be renamed into place); as bytes
    when that file cannot be written (a full disk)."""
    import os
    import tempfile

    from castor.formats import output as destination

    try:
        fd, path = tempfile.mkstemp(prefix=f".castor-{output.spool_owner}-", suffix=".tmp",
                                    dir=output.spool)
    except OSError:
        return b"".join(pieces)
    try:
        with os.fdopen(fd, "wb") as handle:
            for piece in pieces:
                handle.write(piece)
    except BaseException as exc:
        os.unlink(path)
        if not isinstance(exc, OSError):
            raise
        return b"".join(destination.encode_pieces(product, output.format, output.target,
                                                  number=number,
                                                  options=dict(output.options))[0])
    if output.spool_owner and not _alive(output.spool_owner):
        os.unlink(path)  # the driver was stopped: nobody will write or remove the file
        return b""
    return destination.Spooled(path)


def worker_started() -> None:
    """A worker process's first step: Ctrl-C is for the driver, which stops the
    workers itself (a worker would print a traceback otherwise), and a worker
    ends when its parent, the forkserver, does (it ends with castor), even if
    castor was killed outright."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    end_with_parent()


def end_with_parent() -> None:
    """This process is killed when its parent ends (Linux's PR_SET_PDEATHSIG):
    a worker when the forkserver does, castor's run when the process that
    waits for it does (castor.supervisor)."""
    import signal
    import sys

    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(1, signal.SIGKILL, 0, 0, 0)  # PR_SET_PDEATHSIG
        except (OSError, AttributeError):
            pass


def _alive(pid: int) -> bool:
    import os

    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:
        pass
    return True


class FrameFuture:
    """A frame submitted to the FrameThread: as much of concurrent.futures.Future
    as the Sequencer uses (done, result, exception, add_done_callback)."""

    __slots__ = ("_ready", "_finished", "_value", "_error", "_callbacks", "castor_tree")

    def __init__(self, ready: threading.Condition):
        self._ready = ready
        self._finished = False
        self._value = self._error = None
        self._callbacks: list = []
        self.castor_tree = None

    def done(self) -> bool:
        return self._finished

    def cancelled(self) -> bool:  # never: a frame submitted is made
        return False

    def exception(self) -> BaseException | None:
        with self._ready:
            while not self._finished:
                self._ready.wait()
        return self._error

    def result(self):
        error = self.exception()
        if error is not None:
            raise error
        return self._value

    def add_done_callback(self, callback) -> None:
        with self._ready:
            if not self._finished:
                self._callbacks.append(callback)
                return
        self._call(callback)

    def _set(self, value, error: BaseException | None) -> None:
        with self._ready:
            self._value, self._error, self._finished = value, error, True
            callbacks, self._callbacks = self._callbacks, []
            self._ready.notify_all()
        for callback in callbacks:
            self._call(callback)

    def _call(self, callback) -> None:
        try:
            callback(self)
        except Exception:  # as concurrent.futures does: said, and the thread goes on
            import logging

            logging.getLogger("concurrent.futures").exception(
                "exception calling callback for %r", self)


class FrameThread:
    """The executor of --jobs 1: one thread that makes the frames submitted, in
    order, while the scene's thread evaluates the next. A ThreadPoolExecutor of
    one worker does the same, but concurrent.futures imports logging and
    traceback (some 11 ms of every run that writes a frame)."""

    def __init__(self):
        self._ready = threading.Condition()
        self._queue: deque = deque()
        self._closed = False
        self._thread: threading.Thread | None = None

    def submit(self, function, *args) -> FrameFuture:
        future = FrameFuture(self._ready)
        with self._ready:
            if self._closed:
                raise RuntimeError("cannot submit a frame after the run has ended")
            self._queue.append((future, function, args))
            if self._thread is None:  # started at the first frame, as the pool's worker
                self._thread = threading.Thread(target=self._work, name="castor-frames_0",
                                                daemon=True)
                self._thread.start()
            self._ready.notify_all()
        return future

    def map(self, function, *lists):
        """``map``'s results, each call made on the thread (all submitted at once)."""
        futures = [self.submit(function, *args) for args in zip(*lists)]
        return (future.result() for future in futures)

    def shutdown(self, wait: bool = True) -> None:
        with self._ready:
            self._closed = True
            self._ready.notify_all()
        if wait and self._thread is not None:
            self._thread.join()

    def _work(self) -> None:
        while True:
            with self._ready:
                while not self._queue and not self._closed:
                    self._ready.wait()
                if not self._queue:
                    return
                future, function, args = self._queue.popleft()
            try:
                value = function(*args)
            except BaseException as exc:  # handed to whoever asks for the result
                future._set(None, exc)
            else:
                future._set(value, None)
