"""Evaluate the scene into frames the page can draw, with the diagnostics it gave.

The same path as ``castor`` itself (preprocess, reader, interpreter), in this
process, so that a save costs the evaluation only and not castor's start-up.
"""

from __future__ import annotations

import io
import time
from dataclasses import dataclass, field
from typing import Callable

from castor.diagnostics import CastorError, Location, Reporter, TooManyErrors


@dataclass(frozen=True)
class Diagnostic:
    """An error or a warning as the page lists it: ``FILE:LINE:COL: message``."""

    kind: str  # "error" or "warning"
    message: str
    location: Location | None = None
    text: str | None = None  # the source line, for a caret under the column

    def __str__(self) -> str:
        where = f"{self.location}: " if self.location else "castor: "
        return f"{where}{self.kind}: {self.message}"

    def as_json(self) -> dict:
        place = self.location
        return {"kind": self.kind, "message": self.message, "text": self.text,
                "file": place.file if place else None, "line": place.line if place else None,
                "column": place.column if place else None, "shown": str(self)}


@dataclass(frozen=True)
class DrawnFrame:
    """One frame as triangles: ``data`` holds float32 corners (nine numbers per
    triangle) then the uint32 number of each triangle's origin in ``origins``,
    little-endian, as the page's typed arrays read them."""

    number: int
    where: str  # FILE:LINE of the '>' command
    polygons: int
    triangles: int
    box: tuple[tuple[float, float, float], tuple[float, float, float]] | None
    origins: tuple[tuple[str, tuple[float, float, float]], ...]  # (path, colour)
    data: bytes = field(repr=False)
    sources: dict = field(default_factory=dict, repr=False, compare=False)  # path -> FILE:LINE:COL

    def as_json(self) -> dict:
        return {"number": self.number, "where": self.where, "polygons": self.polygons,
                "triangles": self.triangles, "box": self.box,
                "origins": [{"path": path, "colour": colour, "source": self.sources.get(path)}
                            for path, colour in self.origins]}


@dataclass(frozen=True)
class Job:
    """What to evaluate, from the command line."""

    files: tuple[str, ...]
    settings: object  # castor.interpreter.Settings
    defines: tuple[str, ...] = ()
    undefines: tuple[str, ...] = ()
    include_dirs: tuple[str, ...] = ()
    no_cpp: bool = False
    quiet: bool = False


@dataclass(frozen=True)
class Evaluation:
    frames: tuple[DrawnFrame, ...]
    diagnostics: tuple[Diagnostic, ...]
    included: tuple[str, ...]  # every file that #include opened
    seconds: float
    printed: str  # the diagnostics as castor prints them on standard error

    @property
    def errors(self) -> int:
        return sum(d.kind == "error" for d in self.diagnostics)


class Overtaken(Exception):
    """A newer save came while this evaluation ran: its result is not wanted."""


class _Collector(Reporter):
    """A reporter that keeps each diagnostic for the page, and its usual text."""

    def __init__(self, quiet: bool):
        super().__init__(stream=io.StringIO(), quiet=quiet)
        self.diagnostics: list[Diagnostic] = []

    def _keep(self, kind: str, message: str, location: Location | None) -> None:
        text = self.source_lines.get((location.file, location.line)) if location else None
        self.diagnostics.append(Diagnostic(kind, message, location,
                                           text.rstrip("\n") if text is not None else None))

    def error(self, err: CastorError) -> None:
        self._keep("error", err.message, err.location)
        super().error(err)

    def warning(self, message: str, location: Location | None = None) -> None:
        if not self.quiet:
            self._keep("warning", message, location)
        super().warning(message, location)


def evaluate(job: Job, cancelled: Callable[[], bool] = lambda: False) -> Evaluation:
    """Evaluate the scene files; raises Overtaken as soon as ``cancelled()`` says so
    (between statements and between frames)."""
    started = time.perf_counter()
    reporter = _Collector(job.quiet)
    frames: list[DrawnFrame] = []
    included: list[str] = []

    def on_frame(frame, sources: dict) -> None:
        if cancelled():
            raise Overtaken()
        frames.append(drawn(frame, sources))

    try:
        chunks = _checked(_chunks(job, reporter, included), cancelled)
        _interpret(job.settings, reporter, chunks, on_frame, cancelled)
    except Overtaken:
        raise
    except TooManyErrors:
        pass
    except Exception:
        if cancelled():  # however the interpreter passed it on
            raise Overtaken() from None
        raise
    if cancelled():
        raise Overtaken()
    return Evaluation(tuple(frames), tuple(reporter.diagnostics), tuple(included),
                      time.perf_counter() - started, reporter.stream.getvalue())


def _interpret(settings, reporter: Reporter, chunks, on_frame: Callable,
               cancelled: Callable[[], bool]) -> None:
    """The one place that knows the interpreter's interface: each frame's tree is
    made into its mesh here, in this process, whose facetizer keeps the shared
    subtrees of one save for the next."""
    from castor.interpreter import Interpreter
    from castor.jobs import Job, Spec, make

    spec = Spec(format=None, keep_mesh=True)

    def submit(scene) -> None:
        if cancelled():  # before the work of facetizing
            raise Overtaken()
        result = make(Job(scene, spec))
        for message, location in result.warnings:
            reporter.warning(message, location)
        for error in result.errors:
            reporter.error(error)
        if result.mesh is not None:
            from castor.lsp.evaluate import primitive_places  # where each face is written

            on_frame(result.mesh, primitive_places(scene, reporter))

    Interpreter(settings, reporter, submit).run(chunks, streaming=False)


def _chunks(job: Job, reporter: _Collector, included: list[str]):
    from castor.language.reader import Reader

    if job.no_cpp:
        reader = Reader(reporter, directives_allowed=False)
        for name in job.files:
            text = _read(name, reporter)
            if text is not None:
                reader.start_file(name)
                yield from reader.chunks(text.splitlines(keepends=True))
        return
    from castor.language.preprocess import preprocess

    sources = [(name, text) for name in job.files
               if (text := _read(name, reporter)) is not None]
    text = preprocess(sources, list(job.defines), list(job.undefines), list(job.include_dirs),
                      reporter, included)
    yield from Reader(reporter, directives_allowed=True).chunks(text.splitlines())


def _read(name: str, reporter: _Collector) -> str | None:
    try:
        with open(name, encoding="utf-8", errors="replace") as handle:
            return handle.read()
    except OSError as exc:
        reporter.diagnostics.append(Diagnostic("error", f"cannot read '{name}': {exc.strerror}"))
        reporter.errors += 1
        reporter.note(f"castor: cannot read '{name}': {exc.strerror}")
        return None


def _checked(chunks, cancelled: Callable[[], bool]):
    for chunk in chunks:
        if cancelled():
            raise Overtaken()
        yield chunk


def drawn(frame, sources: dict | None = None) -> DrawnFrame:
    """A castor.mesh.frame.Frame as triangles for the page; ``sources``: where
    each primitive is written, by its path."""
    import numpy as np

    from castor.mesh.polygons import fan_triangles

    corners, numbers, origins = [], [], []
    for obj in frame.objects:
        tris, polygon = fan_triangles(obj.offsets, obj.indices)
        corners.append(np.asarray(obj.vertices, dtype="<f4")[tris].reshape(-1, 9))
        numbers.append((np.asarray(obj.origin_of)[polygon] + len(origins)).astype("<u4"))
        origins.extend((o.path, tuple(float(c) for c in o.colour)) for o in obj.origins)
    positions = np.concatenate(corners) if corners else np.zeros((0, 9), "<f4")
    box = None
    if len(positions):
        points = np.concatenate([np.asarray(o.vertices, dtype=float) for o in frame.objects])
        box = (tuple(float(v) for v in points.min(axis=0)),
               tuple(float(v) for v in points.max(axis=0)))
    number_array = np.concatenate(numbers) if numbers else np.zeros(0, "<u4")
    return DrawnFrame(frame.number, frame.where, frame.polygon_count, len(positions), box,
                      tuple(origins), positions.tobytes() + number_array.tobytes(),
                      sources or {})
