"""Execute statements in order: define parameters and objects, write frames.

Parameter definitions are evaluated at once; objects keep their expressions
and are evaluated at each '>' command with the values then in force (late
binding). An error skips its statement and castor goes on, so that every
frame without an error is still written.
"""

from __future__ import annotations

import itertools
import math
import threading
import time
from dataclasses import dataclass, field
from typing import Callable, Iterable

from castor.diagnostics import CastorError, Reporter, TooManyErrors
from castor.language.expressions import evaluate
from castor.language.parse import Parser, SkippedDefinition
from castor.language.reader import Chunk
from castor.language.scene import Facetize, ObjectDef, ParamDef, Tables


# statements parsed by one call to the parser when the input is not streamed
BATCH = 500


@dataclass
class Settings:
    overrides: dict[str, float] = field(default_factory=dict)  # --set NAME=value
    tolerance: float | None = None
    max_polygons: int = 20_000_000
    check_only: bool = False
    stats: bool = False
    merge_polygons: bool = True  # False when the output format holds triangles only


class Interpreter:
    """Holds the symbol tables and runs statements against them."""

    def __init__(self, settings: Settings, reporter: Reporter, emit_frame: Callable | None):
        self.settings = settings
        self.reporter = reporter
        self.emit_frame = emit_frame
        self.tables = Tables()
        self.tables.parameters.update({"PI": math.pi, "TOLERANCE": 0.01})
        if settings.tolerance is not None:
            self.tables.parameters["TOLERANCE"] = settings.tolerance
        self.tables.parameters.update(settings.overrides)
        self.parser = Parser(self.tables)
        self._facetizer = None
        self.frames_attempted = 0
        self.frames_written = 0

    @property
    def facetizer(self):
        if self._facetizer is None:
            # imported here: numpy and manifold3d are only needed once a frame is made
            from castor.mesh.facetize import Facetizer

            self._facetizer = Facetizer(self.settings.max_polygons, self.settings.check_only,
                                        self.settings.merge_polygons)
        return self._facetizer

    def run(self, chunks: Iterable[Chunk], streaming: bool = True) -> None:
        """Execute every statement; stops early only after too many errors.

        Streaming, each statement runs as soon as its chunk arrives; otherwise
        chunks are parsed in batches, which is faster."""
        try:
            if streaming:
                for chunk in chunks:
                    for item in self.parser.parse(chunk):
                        self.execute(item)
                return
            iterator = iter(chunks)
            while True:
                batch = list(itertools.islice(iterator, BATCH))
                if not batch:
                    break
                self.parser.run_batch(batch, self.execute)
        except CastorError as exc:  # from the reader: an unterminated comment
            self.reporter.error(exc)

    def execute(self, item) -> None:
        try:
            if isinstance(item, CastorError):
                self.reporter.error(item)
            elif isinstance(item, SkippedDefinition):
                pass
            elif isinstance(item, ParamDef):
                self._define_parameter(item)
            elif isinstance(item, ObjectDef):
                self._define_object(item)
            elif isinstance(item, Facetize):
                self._facetize(item)
        except CastorError as exc:
            self.reporter.error(exc)

    def _define_parameter(self, statement: ParamDef) -> None:
        name = statement.name
        if name in self.settings.overrides:
            return  # --set wins over the scene's assignments, as openscad -D does
        if name == "TOLERANCE" and self.settings.tolerance is not None:
            return
        self.tables.parameters[name] = evaluate(statement.expr, self.tables.parameters)

    def _define_object(self, statement: ObjectDef) -> None:
        name = statement.name
        if name in self.tables.objects:
            self.reporter.warning(
                f"object '{name}' redefined; objects defined before keep the old definition",
                statement.location)
        self.tables.objects[name] = statement.node
        self.tables.broken.discard(name)

    def _facetize(self, statement: Facetize) -> None:
        from castor.mesh.facetize import repeat_values

        where = f"{statement.location.file}:{statement.location.line}"
        env = dict(self.tables.parameters)
        if statement.repeat is None:
            self._frame(statement, env, where)
            return
        values = repeat_values(statement.repeat, env)
        for value in values:
            env = dict(self.tables.parameters)
            env[statement.repeat.param] = value
            try:
                self._frame(statement, env, where)
            except CastorError as exc:
                self.reporter.error(exc)

    def _frame(self, statement: Facetize, env: dict, where: str) -> None:
        self.frames_attempted += 1
        number = self.frames_attempted
        with Progress(f"frame {number} {where}", self.reporter.stream):
            frame = self.facetizer.frame(statement.objects, env, number, where, statement.location)
        if self.settings.check_only:
            return
        if frame.polygon_count == 0:
            self.reporter.warning(f"frame {number} is empty: its objects have no volume",
                                  statement.location)
        if self.emit_frame is not None:
            self.emit_frame(frame, statement.location)
        self.frames_written += 1
        if self.settings.stats:
            from castor.quantities import stats_line

            s = self.facetizer.stats
            self.reporter.note(stats_line(frame, s.primitives, s.booleans, s.seconds))


class Progress:
    """A line on the terminal while a frame takes more than a second.

    Only when standard error is a terminal: never in a pipeline's logs. The
    line is cleared when the frame is done.
    """

    DELAY = 1.0

    def __init__(self, what: str, stream):
        self.what = what
        self.stream = stream
        self.shown = False
        self.done = threading.Event()
        self.thread = None

    def __enter__(self):
        try:
            terminal = self.stream.isatty()
        except (AttributeError, ValueError):
            terminal = False
        if terminal:
            self.thread = threading.Thread(target=self._run, daemon=True)
            self.thread.start()
        return self

    def _run(self):
        started = time.monotonic()
        if self.done.wait(self.DELAY):
            return
        spinner = "|/-\\"
        tick = 0
        while not self.done.wait(0.25):
            tick += 1
            self.stream.write(f"\rcastor: {self.what}: facetizing {spinner[tick % 4]} "
                              f"{time.monotonic() - started:.0f} s ")
            self.stream.flush()
            self.shown = True

    def __exit__(self, *exc):
        self.done.set()
        if self.thread is not None:
            self.thread.join()
            if self.shown:
                self.stream.write("\r\033[K")
                self.stream.flush()
        return False


def _count(n: int, one: str, many: str | None = None) -> str:
    return f"{n} {one if n == 1 else (many or one + 's')}"


__all__ = ["Interpreter", "Settings", "TooManyErrors"]
