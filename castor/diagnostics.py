"""Positions, errors and the reporter that prints them as compilers do.

Every stage raises a ``CastorError`` subclass carrying the ``Location`` of the
fault; only the ``Reporter`` writes to standard error, in the form
``FILE:LINE:COL: error: MESSAGE`` followed by the source line and a caret, so
that vi's quickfix list and other editors jump to it.
"""

from __future__ import annotations

import sys
from typing import NamedTuple

MAX_ERRORS = 50
# the exit status of a usage error (castor, castor-view, castor --serve): the
# command was given wrongly, as opposed to 1, errors in the input
USAGE_ERROR = 2


def shown_name(name: str) -> str:
    """A file name as castor shows and writes it: a byte that is not UTF-8
    (which Python keeps as a surrogate, '\\udce9') shown as '<0xe9>', as the
    command line's bad bytes are, so that messages and outputs are text."""
    if name.isascii():
        return name
    return "".join(f"<0x{ord(c) - 0xdc00:02x}>" if "\udc80" <= c <= "\udcff" else c
                   for c in name)


def counted(word: str, numbers) -> str:
    """The frames (or operands) a message concerns, as a reader counts them:
    'frame 3', 'frames 1 and 2', 'frames 1 to 9', 'frames 1, 4 and 7',
    '12 frames from 1 to 30'."""
    numbers = list(numbers)
    if len(numbers) == 1:
        return f"{word} {numbers[0]}"
    if len(numbers) > 2 and numbers == list(range(numbers[0], numbers[-1] + 1)):
        return f"{word}s {numbers[0]} to {numbers[-1]}"
    if len(numbers) > 6:
        return f"{len(numbers)} {word}s from {numbers[0]} to {numbers[-1]}"
    return f"{word}s " + ", ".join(map(str, numbers[:-1])) + f" and {numbers[-1]}"


class Location(NamedTuple):
    """A place in an original source file (after mapping cpp line markers)."""

    file: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.column}"


class CastorError(Exception):
    """An error in the user's input, reported at a location."""

    kind = "error"

    def __init__(self, message: str, location: Location | None = None):
        super().__init__(message)
        self.message = message
        self.location = location


class PreprocessError(CastorError):
    """A fault found by the C preprocessor pass (missing include, bad directive)."""


class CastorSyntaxError(CastorError):
    """Text that does not follow the grammar."""


class SceneError(CastorError):
    """A statement that parses but means nothing: unknown names, argument counts."""


class ArgumentCountError(SceneError):
    """A primitive or transformation given the wrong number of arguments;
    ``names``: the parameter names its arguments read (one of them may be a
    macro of an #include that could not be read, which would have given more)."""

    def __init__(self, message: str, location: Location | None = None,
                 names: frozenset = frozenset()):
        super().__init__(message, location)
        self.names = names


class UndefinedObject(SceneError):
    """A use of an object name that has no definition (``name``)."""

    def __init__(self, message: str, location: Location | None, name: str):
        super().__init__(message, location)
        self.name = name


class EvaluationError(CastorError):
    """A fault found while evaluating at a '>' command: undefined parameter, domain error."""


class GeometryError(CastorError):
    """A primitive or transformation whose values give no valid solid."""


class LimitError(CastorError):
    """A scene that exceeds one of castor's limits (polygons, operands, depth)."""


class Expansion(NamedTuple):
    """A macro use on a line: its expansion's span in the expanded line, its own span
    in the original line (0-based, end excluded), the macro and where it is defined."""

    start: int
    end: int
    use_start: int
    use_end: int
    macro: str
    defined_at: str


class LineExpansions(NamedTuple):
    original: str  # the line as written
    expansions: tuple[Expansion, ...]

    def locate(self, column: int) -> tuple[int, Expansion | None]:
        """The column in the original line of an expanded line's column, and the
        expansion it falls in (None outside every expansion)."""
        index = column - 1
        shift = 0
        for e in self.expansions:
            if index < e.start:
                break
            if index < e.end:
                return e.use_start + 1, e
            shift = e.use_end - e.end
        return index + shift + 1, None


class TooManyErrors(Exception):
    """Raised by the reporter once MAX_ERRORS errors have been printed."""


class Reporter:
    """Prints diagnostics and counts them; the one place that writes to stderr."""

    def __init__(self, stream=None, quiet: bool = False, max_errors: int = MAX_ERRORS):
        self.stream = stream if stream is not None else sys.stderr
        self.quiet = quiet
        self.max_errors = max_errors
        self.errors = 0
        self.warnings = 0
        # (file, line) -> text of that line, registered by the reader so that
        # the caret line shows what was parsed, even for standard input.
        self.source_lines: dict[tuple[str, int], str] = {}
        # set by the preprocessor: (file, line, expanded text) -> the macro uses of
        # a line it changed (LineExpansions), or None
        self.expansions = None
        # the #include files that could not be read (set by the preprocessor)
        self.unread_includes: list[str] = []
        # places whose error explains every other error there: a macro use left
        # unexpanded (its argument count), which its statement cannot parse
        self.explained: set[Location] = set()

    def explains(self, err: CastorError) -> bool:
        """Whether an error said at the place of ``err`` explains it (one message
        per cause): it is not said."""
        return bool(self.explained) and not isinstance(err, PreprocessError) and \
            err.location is not None and self._placed(err.location)[0] in self.explained

    def error(self, err: CastorError) -> None:
        if self.explains(err):
            return  # one message per cause
        self._keep("error", err.message, err.location)
        self.errors += 1
        self._emit("error", err.message, err.location)
        if self.errors >= self.max_errors:
            self._emit_plain(f"castor: too many errors ({self.errors}), stopping")
            raise TooManyErrors()

    def warning(self, message: str, location: Location | None = None) -> None:
        self.warnings += 1
        if not self.quiet:
            self._keep("warning", message, location)
            self._emit("warning", message, location)

    def note(self, message: str) -> None:
        self._emit_plain(message)

    def _keep(self, kind: str, message: str, location: Location | None) -> None:
        """What a reporter that keeps its diagnostics as data does with one."""

    def _placed(self, location: Location) -> tuple[Location, str | None, str | None]:
        """Where a place was written, through the macros of its line (as gcc
        points at a macro's use), the line as written, and the note naming the
        macro when the place is inside an expansion."""
        text = self.source_lines.get((location.file, location.line))
        mapped = None
        if self.expansions is not None:
            mapped = self.expansions(location.file, location.line, text)
        if mapped is None:
            return location, text, None
        column, expansion = mapped.locate(location.column)
        location = Location(location.file, location.line, column)
        note = None
        if expansion is not None:
            note = (f"{location}: note: in expansion of macro {expansion.macro}, "
                    f"defined at {expansion.defined_at}")
        return location, mapped.original, note

    def _emit(self, kind: str, message: str, location: Location | None) -> None:
        if location is None:
            self._emit_plain(f"castor: {kind}: {message}")
            return
        location, text, note = self._placed(location)
        lines = [f"{location}: {kind}: {message}"]
        if text is not None:
            text = text.rstrip("\n").expandtabs(1)
            if len(text) <= 300 and text.isprintable():
                lines.append(f" {text}")
                lines.append(" " + " " * max(location.column - 1, 0) + "^")
        if note is not None:
            lines.append(note)
        self._emit_plain("\n".join(lines))

    def _emit_plain(self, text: str) -> None:
        try:
            self.stream.write(text + "\n")
            self.stream.flush()
        except (BrokenPipeError, ValueError):
            pass


class UsageError(Exception):
    """A usage error found after the options were parsed (exit status ``USAGE_ERROR``):
    a file that cannot be read, a cluster that cannot be reached."""


class Diagnostic(NamedTuple):
    """An error or a warning as data, for a page or an editor: ``FILE:LINE:COL: message``."""

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


class CollectingReporter(Reporter):
    """A reporter that keeps each diagnostic as data, and its usual text in ``stream``
    (a string buffer): what the live preview and a language server publish."""

    def __init__(self, quiet: bool = False):
        import io

        super().__init__(stream=io.StringIO(), quiet=quiet)
        self.diagnostics: list[Diagnostic] = []

    def _keep(self, kind: str, message: str, location: Location | None) -> None:
        text = self.source_lines.get((location.file, location.line)) if location else None
        self.diagnostics.append(Diagnostic(kind, message, location,
                                           text.rstrip("\n") if text is not None else None))

    def unreadable(self, name: str, reason: str) -> None:
        """A scene file that cannot be read: an error without a place."""
        self.diagnostics.append(Diagnostic("error", f"cannot read '{name}': {reason}"))
        self.errors += 1
        self.note(f"castor: cannot read '{name}': {reason}")

    @property
    def printed(self) -> str:
        """The diagnostics as castor prints them on standard error."""
        return self.stream.getvalue()


# --- standard output failing

class ClosedStdout:
    """Standard output when castor was started without one: writing to it fails
    as writing to a closed descriptor does (EBADF), and is said so; a run that
    writes nothing there (--check, -o FILE) is not hindered."""

    def write(self, data) -> int:
        import errno

        raise OSError(errno.EBADF, "standard output is closed")

    def flush(self) -> None:
        pass

    def fileno(self) -> int:
        import io

        raise io.UnsupportedOperation("standard output is closed")

    def isatty(self) -> bool:
        return False

    @property
    def buffer(self):
        return self


# what writing a stream can fail with (a full disk or quota, a file too large, a
# device's error, a descriptor closed or non-blocking); a broken pipe is said apart
_WRITE_ERRORS = ("ENOSPC", "EDQUOT", "EFBIG", "EIO", "EBADF", "EAGAIN", "EPIPE")


def stdout_failed(outcome) -> bool:
    """Whether ``outcome`` is standard output failing: an OSError of writing a
    stream, naming no file (an OSError that names one, or of another kind, such
    as a file of castor's own missing, is not: an internal error)."""
    import errno

    return (isinstance(outcome, OSError) and outcome.filename is None
            and outcome.errno in {getattr(errno, name, None) for name in _WRITE_ERRORS} - {None})
