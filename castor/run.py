"""The driver of ``castor``: evaluate the scene (castor.pipeline), have its frames
made, write them in order.

Frames are made by ``castor.jobs.make`` here (``--jobs 1``), in worker
processes (``--jobs N``) or on a Dask cluster (``--scheduler``). Whatever
makes them, the ``Sequencer`` writes each frame and every message in the
order a one-process run writes them: the interpreter's messages wait behind
the frames submitted before them, and a frame is written as soon as it and
every frame before it are done.
"""

from __future__ import annotations

import os
import sys
import threading
from collections import deque

from castor.diagnostics import (CastorError, LimitError, Reporter, TooManyErrors, UsageError,
                                shown_name)
from castor.failures import FrameFailure, SameError, failure_reason
from castor.jobs import FrameThread, Job, Result, make, make_deep
from castor.pipeline import evaluate, evaluated_frames  # noqa: F401 - tests and tools use it here
from castor.settings import EvaluationSettings, FrameSettings, ReadSettings, RunSettings, Source


class Sequencer:
    """Frames and messages out in order, however the frames are made."""

    def __init__(self, reporter: Reporter, output, settings: FrameSettings, executor=None,
                 window: int = 1):
        self.reporter = reporter
        self.output = output
        self.settings = settings
        self.executor = executor
        self.window = window  # frames in flight at most
        self.scheduled = executor is not None and hasattr(executor, "castor_client")
        self.stderr = reporter.stream
        self.pending: deque = deque()  # message text, or a future of a Result
        self.in_flight = 0
        self.lock = threading.RLock()
        self.ready = threading.Condition(self.lock)
        self.stopped = False
        self.handling = False  # a frame's own messages go out with it, not behind the queue
        self.owner = threading.current_thread()
        self.submitted = 0
        self.refused = False
        self.failure: Exception | None = None
        self.summaries: list[dict] = []
        self.gathered: list = []  # (number, location, part) of a file made from every frame
        self.held: FrameFailure | SameError | None = None  # frames that failed alike: said once
        self.frames: list = []  # mesh frames, when the output settings keep them
        self.warned: set = set()  # (message, location) of the frames' warnings said so far
        reporter.stream = self  # the interpreter's messages queue behind pending frames

    # --- the reporter writes here
    def write(self, text: str) -> None:
        with self.lock:
            if self.pending and not self.handling:
                self.pending.append(text)
            else:
                if not self.handling:
                    self._release()
                self.stderr.write(text)

    def flush(self) -> None:
        with self.lock:
            if not self.pending or self.handling:
                self.stderr.flush()

    # --- frames
    def submit(self, tree) -> None:
        if self.failure is not None:
            raise self.failure
        if self.stopped:
            raise TooManyErrors()
        self.submitted += 1
        refusal = self.output.refusal(self.submitted, tree.number, tree.location) \
            if self.output is not None else None
        if refusal is not None:
            if not self.refused:  # said once; the frames after it are not made
                self.refused = True
                self.reporter.error(refusal)
            return
        job = Job(tree, self.settings)
        if self.executor is None:
            from castor.progress import Progress

            with Progress(f"frame {tree.number} {tree.where}", self.stderr):
                result = make(job)
            with self.lock:
                self._handle(result)
            return
        with self.lock:
            while self.in_flight >= self.window:
                self.ready.wait()
            self.in_flight += 1
            if isinstance(self.executor, _process_pools()) or self.scheduled:
                future = self.executor.submit(make_deep, job)
            else:  # this process's thread: a long frame shows its progress
                future = self.executor.submit(_make_showing_progress, job, self.stderr)
            future.castor_tree = tree
            self.pending.append(future)
        future.add_done_callback(self._done)

    def _done(self, future) -> None:
        if not future.cancelled() and future.exception() is None:
            from castor.formats.output import track

            track(future.result().data)  # removed if the run is interrupted
        with self.lock:
            self.in_flight -= 1
            self.drain()
            self.ready.notify_all()

    def drain(self) -> None:
        """Write what is ready at the head of the queue."""
        with self.lock:
            while self.pending:
                head = self.pending[0]
                if isinstance(head, str):
                    self.pending.popleft()
                    self._release()
                    self.stderr.write(head)
                    continue
                if not head.done():
                    break
                self.pending.popleft()
                self._handle(_outcome(head))
            try:
                self.stderr.flush()
            except (BrokenPipeError, ValueError):
                pass

    def finish(self) -> None:
        """Wait for every frame in flight and write the rest."""
        with self.lock:
            while self.pending:
                head = self.pending[0]
                if isinstance(head, str) or head.done():
                    self.drain()
                    continue
                self.ready.wait(0.5)
                self.drain()
            self._release()
        self.reporter.stream = self.stderr
        if self.failure is not None:
            raise self.failure

    def _hold(self, result: Result) -> bool:
        """A frame that failed as the frames before it did is said with them, once
        (CLI.md: its process failed alike, or it met the same error, as over
        --max-polygons): True when ``result`` is such a failure, now held."""
        if self.stopped and result.errors:  # frames in flight when the run stopped
            return True
        unsaid = [w for w in result.warnings if w not in self.warned]  # (said once: _handle)
        if len(result.errors) != 1 or unsaid or result.data is not None or \
                result.gathered is not None or result.mesh is not None or \
                result.summary is not None or result.stats is not None:
            return False
        failure = result.errors[0]
        if not isinstance(failure, FrameFailure):
            failure = SameError(failure, (result.number,))
        if self.held is not None and not self.held.alike(failure):
            self._release()
        self.held = failure if self.held is None else self.held.joined(failure)
        if len(self.held.numbers) >= self.reporter.max_errors:  # as many as stop a run
            count = len(self.held.numbers)
            self._release()
            self.reporter.note(f"castor: the same error in {count} frames, stopping")
            self.stopped = True
        return True

    def _release(self) -> None:
        """Say the failure held, if any."""
        held, self.held = self.held, None
        if held is None:
            return
        handling, self.handling = self.handling, True
        try:
            self.reporter.error(held.said())
        except TooManyErrors:
            self.stopped = True
        finally:
            self.handling = handling

    def _handle(self, result: Result) -> None:
        if self._hold(result):
            return
        self._release()
        self.handling = True
        try:
            for message, location in result.warnings:  # a warning of every frame, once
                if (message, location) not in self.warned:
                    self.warned.add((message, location))
                    self.reporter.warning(message, location)
            for error in result.errors:
                self.reporter.error(error)
            if result.data is not None and self.output is not None:
                try:
                    self.output.put(result.number, result.data, result.companions,
                                    result.location)
                except CastorError as exc:
                    self.reporter.error(exc)
                except MemoryError:  # the frame's pieces are made as they are written
                    self.reporter.error(LimitError(
                        f"out of memory writing frame {result.number}; simplify the scene, "
                        f"raise the tolerance or lower --max-polygons", result.location))
            else:
                _discard(result.data)
                if self.output is not None and result.gathered is None and not result.errors:
                    self.reporter.error(self.output.unmade(result.number, result.location))
            if result.gathered is not None:
                self.gathered.append((result.number, result.location, result.gathered))
            if result.mesh is not None:
                self.frames.append(result.mesh)
            if result.summary is not None:
                self.summaries.append(result.summary)
            if result.stats is not None:
                self.reporter.note(result.stats)
        except TooManyErrors:
            self.stopped = True
        except Exception as exc:  # an output that cannot be written, a closed pipe
            if threading.current_thread() is self.owner:
                raise
            self.failure = exc  # raised again in the thread that runs the scene
            self.stopped = True
        finally:
            self.handling = False

    def discard_pending(self) -> None:
        """Remove the spooled files of frames made but never written (a run
        that stopped early)."""
        with self.lock:
            for head in self.pending:
                if not isinstance(head, str) and head.done() and not head.cancelled() \
                        and head.exception() is None:
                    _discard(head.result().data)
            self.pending.clear()


def _make_showing_progress(job: Job, stream) -> Result:
    from castor.progress import Progress

    with Progress(f"frame {job.tree.number} {job.tree.where}", stream):
        return make(job)


def _discard(data) -> None:
    if data is not None and not isinstance(data, bytes):
        from castor.formats.output import discard

        discard(data)


def _outcome(future) -> Result:
    """A future's result; a frame whose process failed is reported, not raised."""
    tree = future.castor_tree
    try:
        return future.result()
    except BrokenPipeError:
        raise
    except Exception as exc:  # a worker that died, a cluster that went away
        result = Result(tree.number, tree.location)
        result.errors.append(FrameFailure((tree.number,), failure_reason(exc), tree.location))
        return result


def frames_here(how: RunSettings) -> bool:
    """Whether the run makes its frames in this process (--jobs 1, no --scheduler):
    the engine then holds the interpreter for as long as a boolean takes."""
    if how.check or how.scheduler is not None:
        return False
    return (how.jobs or os.cpu_count() or 1) <= 1


def executor_for(jobs: int, scheduler: str | None):
    """The executor for --jobs / --scheduler (None: make frames in this process)."""
    if scheduler is not None:
        try:
            from distributed import Client
        except ImportError:
            raise UsageError("error: --scheduler needs Dask's distributed package: "
                             "pip install '.[cluster]' in castor's directory") from None
        try:
            client = Client(scheduler, timeout="10s", set_as_default=False)
        except (OSError, TimeoutError, ValueError, TypeError) as exc:
            raise UsageError(f"error: cannot reach the Dask scheduler at '{scheduler}': {exc}") from None
        executor = client.get_executor(pure=False)
        executor.castor_client = client  # closed with the executor, at the end of the run
        return executor, max(1, sum(client.ncores().values()))
    if jobs == 0:
        jobs = os.cpu_count() or 1
    if jobs <= 1:
        # one thread that makes and writes the frames while this one evaluates the
        # next: the engine's booleans and the writing need no lock of Python's, so an
        # animation overlaps its stages even on one core's worth of jobs
        return FrameThread(), 1
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    # one engine thread in each worker: the workers share the cores between them
    # (manifold3d spreads a boolean over every core with OpenMP otherwise, and
    # N workers times N threads only wait on each other)
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    context = multiprocessing.get_context("forkserver")
    context.set_forkserver_preload(["castor.jobs", "castor.mesh.facetize"])
    from castor.jobs import worker_started

    executor = ProcessPoolExecutor(max_workers=jobs, mp_context=context,
                                   initializer=worker_started)
    _started.append(executor)
    return executor, jobs


# the process pools this run started, and the directories their workers spool
# frames into: what ``end_processes`` stops and cleans when the run is stopped
_started: list = []
_spools: list[str] = []


def end_processes() -> None:
    """Stop at once every process this run started, and remove what they were
    writing: castor was interrupted (Ctrl-C, SIGTERM) and is about to exit.

    The workers are killed (they may be deep in the engine, deaf to anything
    gentler), then the forkserver they came from; the multiprocessing
    semaphores are released so that the resource tracker, which ends when the
    last of us has, has nothing to report."""
    import glob
    import signal

    pids = []
    for executor in _started:
        pids.extend(process.pid for process in list((getattr(executor, "_processes", None)
                                                       or {}).values()))
    try:
        from multiprocessing import forkserver

        pids.append(forkserver._forkserver._forkserver_pid)
    except (ImportError, AttributeError):
        pass
    for pid in pids:
        if pid:
            try:
                os.kill(pid, signal.SIGKILL)
            except OSError:
                pass
    for pid in pids:  # gone before their half-written spooled frames are removed
        if pid:
            try:
                os.waitpid(pid, 0)
            except OSError:
                pass
    for directory in _spools:
        for path in glob.glob(os.path.join(glob.escape(directory), f".castor-{os.getpid()}-*")):
            try:
                os.unlink(path)
            except OSError:
                pass
    release_processes()


def release_processes() -> None:
    """Release what multiprocessing still holds (its named semaphores), as its
    exit handler would: castor ends with os._exit or by SIGPIPE, which skip it,
    and the resource tracker would then warn of \"leaked semaphore objects\"."""
    import sys as _sys

    if "multiprocessing" not in _sys.modules:
        return
    from multiprocessing import util

    try:
        util._run_finalizers(0)
    except Exception:
        pass


def run(source: Source, reporter: Reporter, *, reading: ReadSettings = ReadSettings(),
        evaluation: EvaluationSettings | None = None, settings: FrameSettings = FrameSettings(),
        how: RunSettings = RunSettings()) -> int:
    """Read, interpret and write: the whole run of ``castor``, its exit status
    (0, or 1 when the input had errors). A usage error found on the way (a file
    that cannot be read) raises UsageError."""
    from castor.formats import FORMATS
    from castor.formats.output import Output

    evaluation = evaluation or EvaluationSettings()
    _check_readable(source)
    chosen = FORMATS[settings.output.format]
    output = None if how.check else Output(settings.output.target, chosen.name)  # --check: none
    executor, workers = (None, 1) if how.check else executor_for(how.jobs, how.scheduler)
    settings = _carried(settings, executor, how)
    sequencer = Sequencer(reporter, output, settings, executor, window=2 * max(1, workers or 1))
    if output is not None:
        output.start()
    try:
        interpreter = evaluate(source, reporter, None if how.check else sequencer.submit,
                               reading=reading, evaluation=evaluation)
        try:
            sequencer.finish()
        except TooManyErrors:
            pass
        _warn_after_run(chosen, settings, evaluation, interpreter, reporter)
        if how.check:
            interpreter.warn_if_no_frame()
        elif interpreter.frames_attempted == 0 and not reporter.errors:
            from castor.interpreter import NO_FRAME

            reporter.warning(NO_FRAME.format("was"))
        _write_gathered(chosen, settings, sequencer, executor, output)
    except BaseException:
        if output is not None:
            output.abandon()  # a single stream file half made stays out of place
        raise
    finally:
        _end(executor)
        sequencer.discard_pending()
    try:
        _write_summary(how, sequencer)
        if output is not None and not output.finish(reporter.errors > 0,
                                                    interpreter.frames_attempted):
            reporter.note(f"castor: {settings.output.target} not written: there were errors "
                          f"and no frame")
    except BaseException:
        if output is not None:
            output.abandon()
        raise
    return 1 if reporter.errors else 0


def _check_readable(source: Source) -> None:
    """A scene file that cannot be read is a usage error, before any work."""
    for name in source.files:
        if name != "-" and (not os.access(name, os.R_OK) or os.path.isdir(name)):
            reason = "no such file" if not os.path.exists(name) else \
                "it is a directory" if os.path.isdir(name) else "permission denied"
            raise UsageError(f"error: cannot read '{shown_name(name)}': {reason}")


def _carried(settings: FrameSettings, executor, how: RunSettings) -> FrameSettings:
    """The settings, with how a frame's bytes travel to the writer: made a piece at
    a time as they are written (in this process), or spooled beside the output by
    a worker process when large."""
    out = settings.output
    if executor is None or (how.scheduler is None and not isinstance(executor, _process_pools())):
        return settings.replace(output=out.replace(pieces=True))  # one piece in memory
    if how.scheduler is None:
        spool = _spool_directory(out.target)
        _spools.append(spool)
        return settings.replace(output=out.replace(spool=spool, spool_owner=os.getpid()))
    return settings


def _end(executor) -> None:
    """The workers end before castor does: none outlives it."""
    if executor is not None:
        executor.shutdown(wait=True)
        client = getattr(executor, "castor_client", None)
        if client is not None:
            client.close()


def _process_pools() -> type | tuple:
    """ProcessPoolExecutor, to tell a pool of processes by; () (nothing is one) where
    its module was never imported, so none was made: a thread's run needs no import."""
    module = sys.modules.get("concurrent.futures.process")
    return module.ProcessPoolExecutor if module is not None else ()


def _spool_directory(target: str | None) -> str:
    """Where worker processes write large frames: beside the output file, so that
    a frame of its own is renamed into place; else the temporary directory."""
    import tempfile

    from castor.formats.output import frame_path, has_pattern, is_device

    if target is None:
        return tempfile.gettempdir()
    first = frame_path(target, 1) if has_pattern(target) else target
    if is_device(first):
        return tempfile.gettempdir()
    return os.path.dirname(os.path.abspath(first))


def _warn_unused_overrides(overrides, interpreter, reporter) -> None:
    """A --set NAME that the scene never assigns nor uses is most likely a typo."""
    from castor.language.parse import suggestion

    names = interpreter.parser.parameter_names() | {"PI", "TOLERANCE"}  # always in use
    for name in overrides:
        if name not in names:
            reporter.warning(f"--set {name}: the scene neither assigns nor uses a parameter "
                             f"'{name}'{suggestion(name, names - set(overrides))}")


def _warn_after_run(chosen, settings: FrameSettings, evaluation: EvaluationSettings,
                    interpreter, reporter) -> None:
    """What only the whole scene tells: a --set of no parameter, the output's own
    warnings (an --ifc-class of no object)."""
    _warn_unused_overrides(evaluation.overrides, interpreter, reporter)
    objects = set(interpreter.tables.objects) | interpreter.tables.broken
    for message in chosen.kind.after_run(settings, objects):
        reporter.warning(message)


def _write_gathered(chosen, settings: FrameSettings, sequencer: Sequencer, executor,
                    output) -> None:
    """A file made from every frame at once (an animation), through the output as
    any file: its kind makes it from the frames' parts, in the run's processes."""
    if not sequencer.gathered or output is None:
        return
    number, location, _ = sequencer.gathered[0]
    parts = [part for _, _, part in sequencer.gathered]
    try:
        product = chosen.kind.gather(parts, settings, map if executor is None else executor.map)
    except (BrokenPipeError, MemoryError):
        raise
    except Exception as exc:  # a worker that died, a cluster that went away
        sequencer.reporter.error(FrameFailure(tuple(n for n, _, _ in sequencer.gathered),
                                              failure_reason(exc), location))
        return
    from castor.formats.output import encode_pieces

    data, companions = encode_pieces(product, chosen.name, settings.output.target, number=number,
                                     options=dict(settings.output.options))
    output.put(number, data, companions, location)


def _write_summary(how: RunSettings, sequencer: Sequencer) -> None:
    """The take-off, written once for the whole run."""
    if how.summary is not None and not how.check:
        from castor.formats.output import write_atomically
        from castor.quantities import Summary

        summary = Summary()
        summary.frames.extend(sequencer.summaries)
        if how.summary == "-":  # standard output, which the frames went elsewhere than
            sys.stdout.buffer.write(summary.text().encode("utf-8"))
            sys.stdout.buffer.flush()
            return
        write_atomically(how.summary, summary.text().encode("utf-8"))
