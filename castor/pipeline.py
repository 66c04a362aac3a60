"""The pipeline as a library: scene text in, evaluated frames out.

One function, ``evaluate``, runs the stages in order: read the source (files
or a text in memory), preprocess it (castor.language.preprocess), cut it into
statements (castor.language.reader) and interpret them (castor.interpreter),
which hands each frame's evaluated CSG tree on as its '>' command runs. The
command line (castor.run), the live preview (castor.serve.evaluation) and an
editor's language server (``check``) all call it, each with the settings of
the stages (castor.settings) and what to do with a frame; none of it imports
the command line.

What is made of a frame (its mesh, picture, drawing or file) is castor.jobs's
work, in this process or another; ``frames`` does it here for a whole source.
"""

from __future__ import annotations

import io
import os
import sys
import time
from typing import Callable, Iterator

from castor.diagnostics import (CollectingReporter, Diagnostic, Reporter, TooManyErrors,
                                UsageError, shown_name)
from castor.records import Record
from castor.settings import (RECURSION_LIMIT, STACK_BYTES, EvaluationSettings, FrameSettings,
                             MeshSettings, OutputSettings, ReadSettings, Source)


__all__ = ["Checked", "Overtaken", "STACK_BYTES", "RECURSION_LIMIT", "Source", "check",
           "evaluate", "evaluated_frames", "frames"]


class Overtaken(Exception):
    """The caller's ``cancelled()`` said so: a newer save (or keystroke) came while
    this evaluation ran, and its result is not wanted."""


def evaluate(source: Source, reporter: Reporter, on_frame: Callable | None, *,
             reading: ReadSettings = ReadSettings(),
             evaluation: EvaluationSettings | None = None,
             included: list[str] | None = None,
             unreadable: Callable[[str, str], None] | None = None,
             cancelled: Callable[[], bool] | None = None,
             interpreter: Callable | None = None):
    """Read, preprocess and interpret ``source``: each frame's evaluated CSG tree
    (castor.csg.tree.FrameTree) goes to ``on_frame`` as soon as its '>' command has run
    (None: evaluate only). Diagnostics go to ``reporter``; the run stops early
    only after too many errors. Returns the interpreter (its frame count, the
    parameters the scene uses).

    ``included`` receives the path of every file #include opened; a file that
    cannot be read goes to ``unreadable(name, reason)`` and is skipped, or
    raises UsageError when that is None; ``cancelled()``, when given, is asked
    between statements, and True raises Overtaken; ``interpreter``: a subclass of
    castor.interpreter.Interpreter to run instead (a language server's records
    what each statement defined)."""
    from castor.interpreter import Interpreter

    interpreter = (interpreter or Interpreter)(evaluation or EvaluationSettings(), reporter,
                                               on_frame)
    try:
        pieces = statements(source, reading, reporter, included, unreadable)
        if cancelled is not None:
            pieces = _unless(cancelled, pieces)
        interpreter.run(pieces, streaming=reading.no_cpp and source.streamed)
    except TooManyErrors:
        pass
    return interpreter


def statements(source: Source, reading: ReadSettings, reporter: Reporter,
               included: list[str] | None = None,
               unreadable: Callable[[str, str], None] | None = None):
    """The source's statements (castor.language.reader.Chunk), after the
    preprocessor unless ``reading.no_cpp``: then read as the lines arrive."""
    from castor.language.reader import Reader

    if reading.no_cpp:
        reader = Reader(reporter, directives_allowed=False)
        return reader.chunks(_lines(source, reader, unreadable))
    from castor.language.preprocess import preprocess

    sources = list(_texts(source, unreadable, reporter))
    # a file whose name is not UTF-8 is named as shown (castor.diagnostics.shown_name):
    # its own folder is searched for its #include "..." after the -I folders
    beside = [os.path.dirname(os.path.abspath(name)) for name in source.files or ()
              if name != "-" and shown_name(name) != name]
    text = preprocess(sources, list(reading.defines), list(reading.undefines),
                      list(reading.include_dirs) + beside, reporter, included)
    return Reader(reporter, directives_allowed=True).chunks(text.splitlines())


def _texts(source: Source, unreadable, reporter: Reporter) -> Iterator[tuple[str, str]]:
    """(name, text) of each input, whole; one that is not text is said and skipped."""
    from castor.language.reader import NotText, text_of

    for name, data in _inputs(source, unreadable):
        try:
            with data:
                yield name, text_of(name, data.read() if _textual(data) else data)
        except NotText as exc:
            reporter.error(exc)


def _lines(source: Source, reader, unreadable) -> Iterator:
    """The lines of the inputs as they arrive (for --no-cpp): standard input is
    read a line at a time, so that a statement runs before the next is typed.
    An input that is not text gives its error (NotText) in place of its lines."""
    from castor.language.reader import NotText, lines_of, text_of

    for name, data in _inputs(source, unreadable):
        reader.start_file(name)
        try:
            with data:
                if source.text is not None:
                    yield from text_of(name, source.text).splitlines(keepends=True)
                else:
                    yield from lines_of(name, data)
        except NotText as exc:
            yield exc


def _inputs(source: Source, unreadable) -> Iterator[tuple[str, object]]:
    """(name, stream) of each input: the text given, standard input (its bytes
    when it has them), or each file opened as bytes."""
    if source.text is not None:
        yield source.name, io.StringIO(source.text)
        return
    for name in source.files or ("-",):
        if name == "-":
            stdin = sys.stdin
            yield "<stdin>", _Borrowed(getattr(stdin, "buffer", stdin))
            continue
        handle = _open(name, unreadable)
        if handle is not None:
            yield shown_name(name), handle


class _Borrowed:
    """Standard input in a ``with``: read, never closed."""

    def __init__(self, stream):
        self.stream = stream

    def __getattr__(self, name):
        return getattr(self.stream, name)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False


def _textual(data) -> bool:
    """A stream of str (an in-memory text, a test's standard input), not of bytes."""
    stream = data.stream if isinstance(data, _Borrowed) else data
    return isinstance(stream, io.TextIOBase)


def _open(name: str, unreadable):
    try:
        return open(name, "rb")
    except OSError as exc:
        if unreadable is None:
            raise UsageError(f"error: cannot read '{shown_name(name)}': {exc.strerror}") from None
        unreadable(shown_name(name), exc.strerror)
        return None


def _unless(cancelled: Callable[[], bool], pieces):
    for piece in pieces:
        if cancelled():
            raise Overtaken()
        yield piece


class Checked(Record):
    """What a source gave, with nothing written: its diagnostics as data and as
    castor prints them, its frames' evaluated CSG trees and, when facetized,
    their mesh frames (castor.mesh.frame.Frame)."""

    __slots__ = ("diagnostics", "trees", "meshes", "included", "printed", "seconds")

    def __init__(self, diagnostics: tuple[Diagnostic, ...], trees: tuple, meshes: tuple,
                 included: tuple[str, ...], printed: str, seconds: float):
        self.diagnostics = diagnostics
        self.trees = trees  # castor.csg.tree.FrameTree, one per frame without an error
        # castor.mesh.frame.Frame, when a MeshSettings was given (and no on_mesh)
        self.meshes = meshes
        self.included = included  # every file that #include opened
        self.printed = printed
        self.seconds = seconds

    @property
    def errors(self) -> int:
        return sum(d.kind == "error" for d in self.diagnostics)


def frames(source: Source, *, reading: ReadSettings = ReadSettings(),
           evaluation: EvaluationSettings | None = None, mesh: MeshSettings | None = None,
           quiet: bool = False, on_mesh: Callable | None = None,
           cancelled: Callable[[], bool] = lambda: False,
           reporter: CollectingReporter | None = None,
           interpreter: Callable | None = None,
           sized: Callable | None = None) -> Checked:
    """Evaluate ``source`` in this process and, with ``mesh``, facetize each frame
    (its errors, such as too many polygons, become diagnostics); nothing is
    written. ``on_mesh`` is given each mesh frame as it is made (and then the
    result keeps none: a long animation is not held whole); ``cancelled()``
    is asked between statements and frames (True raises Overtaken); ``reporter``:
    the caller's, to ask after the run where a place was written (through macros);
    ``interpreter``: as for ``evaluate``; ``sized(tree)``: the tree to facetize
    in place of each frame's (the live preview's facets sized to its camera),
    which ``trees`` keeps as evaluated."""
    started = time.perf_counter()
    reporter = reporter if reporter is not None else CollectingReporter(quiet)
    trees: list = []
    meshes: list = []
    included: list[str] = []
    settings = FrameSettings(output=OutputSettings(format=None, keep_mesh=True),
                             mesh=mesh or MeshSettings())

    def on_frame(tree) -> None:
        if cancelled():  # before the work of facetizing
            raise Overtaken()
        trees.append(tree)
        if mesh is None:
            return
        from castor.jobs import Job, make

        result = make(Job(tree if sized is None else sized(tree), settings))
        for message, location in result.warnings:
            reporter.warning(message, location)
        for error in result.errors:
            reporter.error(error)
        if result.mesh is not None:
            if cancelled():
                raise Overtaken()
            if on_mesh is not None:
                on_mesh(result.mesh)
            else:
                meshes.append(result.mesh)

    try:
        evaluate(source, reporter, on_frame, reading=reading, evaluation=evaluation,
                 included=included, unreadable=reporter.unreadable, cancelled=cancelled,
                 interpreter=interpreter)
    except Overtaken:
        raise
    except Exception:
        if cancelled():  # however the interpreter passed it on
            raise Overtaken() from None
        raise
    if cancelled():
        raise Overtaken()
    return Checked(tuple(reporter.diagnostics), tuple(trees), tuple(meshes), tuple(included),
                   reporter.printed, time.perf_counter() - started)


def check(text: str, path: str, *, reading: ReadSettings = ReadSettings(),
          evaluation: EvaluationSettings | None = None, mesh: MeshSettings | None = None,
          cancelled: Callable[[], bool] = lambda: False) -> Checked:
    """An editor buffer's diagnostics and evaluated frames, writing nothing: what a
    language server publishes as the user types. ``text`` is the buffer, ``path``
    its file (for messages, and for #include "..." beside it); with ``mesh``,
    each frame is facetized too (slower; a frame's polygon limit is checked)."""
    return frames(Source(text=text, name=path), reading=reading, evaluation=evaluation,
                  mesh=mesh, cancelled=cancelled)


def evaluated_frames(text: str, name: str = "<scene>",
                     settings: EvaluationSettings | None = None,
                     defines: tuple[str, ...] = ()) -> tuple[list, str]:
    """The evaluated CSG trees of a scene's frames, and what castor said (the
    diagnostics' text): the scene as data, for tests and for tools."""
    checked = frames(Source(text=text, name=name), reading=ReadSettings(defines=tuple(defines)),
                     evaluation=settings)
    return list(checked.trees), checked.printed
