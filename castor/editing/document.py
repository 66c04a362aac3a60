"""One evaluation of a scene for editing: its text, the statements as they
ran, the evaluated frames, and where each place is written.

A gesture works on the text as written, so a ``Document`` keeps what the
pipeline (castor.pipeline.evaluate) made of one version of a scene: every
object definition and '>' command in the order they ran, every frame's
evaluated tree, and the reporter that maps a position out of macro
expansions (a place inside one is written by a macro: it cannot be edited).
Files are named by URI outside (the language server's, the page's) and by
path inside (castor's locations).
"""

from __future__ import annotations

import os
from typing import Callable
from urllib.parse import quote, unquote, urlparse

from castor.diagnostics import CollectingReporter, Location
from castor.editing.text import digest
from castor.settings import ReadSettings, Source


class CommandError(Exception):
    """A command that cannot be done: bad arguments, or a gesture the text does
    not allow (the reason says why). Nothing was changed. A language server
    answers it as a JSON-RPC error with this message."""

    def __init__(self, message: str):
        super().__init__(message)
        self.message = message


def uri_to_path(uri: str) -> str:
    if uri.startswith("file:"):
        return unquote(urlparse(uri).path)
    return uri


def path_to_uri(path: str) -> str:
    return "file://" + quote(os.path.abspath(path))


# read(uri) -> the document's current text (an editor's buffer, else the file), or None
Reader = Callable[[str], "str | None"]


def read_file(uri: str) -> str | None:
    try:
        with open(uri_to_path(uri), encoding="utf-8", newline="") as handle:
            return handle.read()
    except OSError:
        return None


class Document:
    """What the pipeline made of one version of a scene's text."""

    def __init__(self, uri: str, text: str, read: Reader = read_file,
                 reading: ReadSettings = ReadSettings(), evaluation=None):
        """``evaluation``: castor.settings.EvaluationSettings, the ``--set``
        values (the live preview's panel's) the frames are made with."""
        self.uri = uri
        self.path = uri_to_path(uri)
        self.text = text
        self.version = digest(text)
        self.read = read
        self.reading = reading
        self.evaluation = evaluation
        self.frames: list = []  # castor.csg.tree.FrameTree, by number - 1
        self.statements: list = []  # ObjectDef and FrameCommand, in the order they ran
        self.objects: dict = {}  # name -> NamedNode, at the end
        self.files: list[str] = []  # the scene's own: the main file and those it includes
        self.included: dict[str, str] = {}  # included file -> digest of its text evaluated
        self.reporter = CollectingReporter(quiet=True)
        self._texts: dict[str, str | None] = {}
        self._prepared: dict[int, object] = {}

    def evaluate(self) -> "Document":
        from castor.interpreter import Interpreter
        from castor.language.scene import FrameCommand, ObjectDef
        from castor.pipeline import evaluate
        from castor.settings import EvaluationSettings

        document = self

        class Recording(Interpreter):
            def execute(self, item) -> None:
                if isinstance(item, (ObjectDef, FrameCommand)):
                    document.statements.append(item)
                super().execute(item)

        frames: list = []
        included: list[str] = []
        try:
            interpreter = evaluate(Source(text=self.text, name=self.path), self.reporter,
                                   frames.append, reading=self.reading,
                                   evaluation=self.evaluation or EvaluationSettings(),
                                   included=included,
                                   unreadable=self.reporter.unreadable, interpreter=Recording)
        except RecursionError:
            raise CommandError("the scene is nested too deeply to edit") from None
        self.frames = frames
        self.objects = dict(interpreter.tables.objects)
        self.files = [self.path] + [os.path.abspath(name) for name in included]
        self.included = {path: digest(self.file_text(path) or "") for path in self.files[1:]}
        return self

    def current(self) -> bool:
        """Whether the files it includes are still as they were evaluated."""
        return all(digest(self.read(path_to_uri(path)) or "") == known
                   for path, known in self.included.items())

    @property
    def errors(self) -> list:
        return [d for d in self.reporter.diagnostics if d.kind == "error"]

    def frame(self, number) -> object:
        if not isinstance(number, int) or isinstance(number, bool) or number < 1:
            raise CommandError(f"'frame' must be a frame number (1, 2, ...), not {number!r}")
        if number > len(self.frames):
            made = len(self.frames)
            raise CommandError(f"frame {number} does not exist: the scene makes {made} "
                               f"frame{'' if made == 1 else 's'}"
                               + (" (it has errors)" if self.errors else ""))
        return self.frames[number - 1]

    def facetize(self, frame) -> object:
        """The '>' command that made ``frame``."""
        from castor.language.scene import FrameCommand

        for statement in self.statements:
            if isinstance(statement, FrameCommand) and statement.location == frame.location:
                return statement
        raise CommandError(f"the '>' command of frame {frame.number} was not found")

    def definition(self, node) -> object | None:
        """The object definition that made the named node ``node``."""
        from castor.language.scene import ObjectDef

        for statement in self.statements:
            if isinstance(statement, ObjectDef) and statement.node is node:
                return statement
        return None

    # --- where things are written

    def file_of(self, location: Location) -> str:
        """The file a location is in, as a path."""
        if location.file == self.path:
            return self.path
        return os.path.abspath(location.file)

    def file_text(self, path: str) -> str | None:
        """A scene file's current text: the document's own, else what ``read`` gives."""
        if path == self.path:
            return self.text
        if path not in self._texts:
            self._texts[path] = self.read(path_to_uri(path))
        return self._texts[path]

    def written(self, location: Location) -> tuple[Location, bool]:
        """A location as written (out of macro expansions), and whether it lies
        inside a macro's expansion (then the text there is the macro's use)."""
        expansions = self.reporter.expansions
        if expansions is None:
            return location, False
        line = self.reporter.source_lines.get((location.file, location.line))
        mapped = expansions(location.file, location.line, line)
        if mapped is None:
            return location, False
        column, expansion = mapped.locate(location.column)
        return Location(location.file, location.line, column), expansion is not None

    def offset_of(self, location: Location) -> tuple[str, str, int]:
        """(path, its text, the offset) of a location outside every macro's
        expansion; CommandError where a macro writes it."""
        from castor.editing.text import offset

        written, in_macro = self.written(location)
        if in_macro:
            raise CommandError(f"{written}: this is written by a macro: edit the macro's "
                               f"use or its definition by hand")
        path = self.file_of(written)
        text = self.file_text(path)
        if text is None:
            raise CommandError(f"cannot read '{path}'")
        return path, text, offset(text, written.line - 1, written.column - 1)

    def source(self, location: Location) -> str:
        """``FILE:LINE:COL`` as written: what a snap names and a move takes."""
        return str(self.written(location)[0])

    def mesh(self, number: int):
        """The frame's mesh (castor.mesh.frame.Frame), made once: for measures."""
        self.frame(number)
        key = -number
        if key not in self._prepared:
            from castor.diagnostics import CastorError
            from castor.mesh.facetize import Facetizer

            try:
                self._prepared[key] = Facetizer().frame(self.frame(number))
            except CastorError as error:
                raise CommandError(error.message) from None
        return self._prepared[key]

    def prepared(self, number: int):
        """The frame made ready for snapping (castor.editing.snap.Prepared), once."""
        self.frame(number)
        if number not in self._prepared:
            from castor.editing.snap import prepare

            self._prepared[number] = prepare(self.frame(number), self.source)
        return self._prepared[number]


def settings_key(evaluation) -> tuple:
    """What of castor.settings.EvaluationSettings changes a scene's frames."""
    if evaluation is None:
        return ((), None)
    return tuple(sorted(evaluation.overrides.items())), evaluation.tolerance


class Cache:
    """The last documents evaluated, by URI, version of their text and the
    values of the parameters set (``--set``, the preview's panel): a snap as
    the cursor moves reuses the evaluation and the prepared frame."""

    def __init__(self, read: Reader = read_file, reading: ReadSettings = ReadSettings(),
                 size: int = 4, evaluation=None):
        self.read = read
        self.reading = reading
        self.size = size
        self.evaluation = evaluation  # EvaluationSettings, or None: the scene's own values
        self._documents: dict[tuple[str, str], Document] = {}
        import threading

        # the preview's server answers each request on a thread of its own
        self._lock = threading.Lock()

    def document(self, uri: str) -> Document:
        if not isinstance(uri, str) or not uri:
            raise CommandError("'uri' must name the scene's file")
        text = self.read(uri)
        if text is None:
            raise CommandError(f"cannot read '{uri_to_path(uri)}'")
        key = (uri, digest(text), settings_key(self.evaluation))
        with self._lock:
            document = self._documents.get(key)
            if document is None or not document.current():
                document = Document(uri, text, self.read, self.reading,
                                    self.evaluation).evaluate()
                if len(self._documents) >= self.size:
                    self._documents.pop(next(iter(self._documents)))
                self._documents[key] = document
        return document

    def using(self, evaluation) -> "Cache":
        """The same cache (its documents shared), evaluating with ``evaluation``
        (castor.settings.EvaluationSettings: the frame shown's ``--set`` values)."""
        import copy

        other = copy.copy(self)
        other.evaluation = evaluation
        return other
