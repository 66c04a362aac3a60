"""Cut the (preprocessed) input into statements, keeping track of positions.

The reader consumes lines one at a time, so that with ``--no-cpp`` a statement
is executed as soon as its ';' arrives. It understands cpp's line markers
(``# 12 "file.cas" 1 3`` and ``#line 12 "file.cas"``) and records, for every
line of a statement, which original file and line it came from. Comments are
skipped while looking for the ';' that ends a statement (the grammar skips
them again when parsing).
"""

from __future__ import annotations

import codecs
import re
from dataclasses import dataclass
from typing import Iterable, Iterator

from castor.diagnostics import CastorError, Location, PreprocessError, Reporter

_MARKER = re.compile(r'\s*#\s*(?:line\s+)?(\d+)(?:\s+"((?:[^"\\]|\\.)*)")?[^\n]*$')
_DIRECTIVE = re.compile(r"\s*#\s*([A-Za-z_]*)")
_SCAN = re.compile(r"/\*|//|;")
_END_COMMENT = re.compile(r"\*/")
_new_tuple = tuple.__new__  # Location(...) without the Python call of its __new__


@dataclass(frozen=True, slots=True)
class Chunk:
    """The text of one statement and where each of its lines came from."""

    text: str
    origins: tuple[tuple[str, int], ...]  # (file, line) for each line of text
    first_column: int  # columns of the first line start after this many characters

    def location(self, line: int, column: int) -> Location:
        """Map a 1-based (line, column) inside the chunk to the original file
        (made as the tuple it is: the parser asks this of every number and name)."""
        if line == 1:
            file, original = self.origins[0]
            return _new_tuple(Location, (file, original, column + self.first_column))
        file, original = self.origins[min(max(line, 1), len(self.origins)) - 1]
        return _new_tuple(Location, (file, original, column))

    def end_location(self) -> Location:
        """Just after the last character that is not blank."""
        lines = self.text.split("\n")
        for index in range(len(lines) - 1, -1, -1):
            stripped = lines[index].rstrip()
            if stripped:
                return self.location(index + 1, len(stripped) + 1)
        return self.location(1, 1)


# --- the input as text --------------------------------------------------------
#
# Files are read as bytes and decoded here, a block at a time, so that input
# that is not text (an image, random bytes) is refused at its first byte that
# is not UTF-8, once, in the time it takes to read it: never taken apart byte
# by byte by the preprocessor and the grammar (issue 29, item 1). Bytes that
# are UTF-8 but mostly control characters are not text either; a stray one
# (a NUL in an #include's name) is left to the messages at its place.

BLOCK = 1 << 20
# A UTF-8 byte-order mark (EF BB BF) that an editor put at the start of a file:
# skipped, as GNU cpp does, and not counted as a column of line 1 (vi does not)
BOM = "\ufeff"
_CONTROL = re.compile("[\x00-\x08\x0e-\x1f\x7f]")  # not tab, line ends, form feed
CONTROLS_ALLOWED = 16  # and at most one character in a hundred


class NotText(CastorError):
    """An input whose bytes are not UTF-8 text: said once, and the input is skipped."""


def _not_text(name: str, line: int, before: str, what: str, hint: str = "") -> NotText:
    """The error for the first byte that makes the input not text: ``before``,
    the text before it from the start of line ``line``."""
    line += before.count("\n")
    column = len(before) - (before.rfind("\n") + 1) + 1
    return NotText(f"the input is not text ({what}){hint}", Location(name, line, column))


def _undecoded(name: str, line: int, before: str, exc: UnicodeError) -> NotText:
    """NotText at the first byte that is not UTF-8 (in bytes being decoded, or in
    a str that kept it as a surrogate)."""
    if isinstance(exc, UnicodeDecodeError):
        done = exc.object[:max(exc.start, 0)].decode("utf-8", "replace")
        what = f"byte 0x{exc.object[exc.start]:02x}" if exc.start < len(exc.object) else \
            "its last bytes"
    else:
        done = exc.object[:exc.start]
        code = ord(exc.object[exc.start])
        what = f"byte 0x{code - 0xdc00:02x}" if 0xdc80 <= code <= 0xdcff else f"U+{code:04X}"
    start = exc.object[:2]
    if not before and line == 1 and not done and start in (
            b"\xff\xfe", b"\xfe\xff", "\udcff\udcfe", "\udcfe\udcff"):
        return _not_text(name, line, before, f"{what} is not UTF-8",
                         "; castor reads UTF-8 text: this one starts as UTF-16 does, and "
                         "converts with iconv -f utf-16 -t utf-8")
    return _not_text(name, line, before + done, f"{what} is not UTF-8",
                     "; castor reads UTF-8 text: a scene written in Latin-1 converts with "
                     "iconv -f latin1 -t utf-8")


class _Controls:
    """The control characters met so far in an input read piece by piece."""

    def __init__(self, name: str):
        self.name = name
        self.seen = 0  # control characters
        self.length = 0  # characters

    def add(self, text: str, line: int, before: str) -> None:
        """Count ``text``, which comes after ``before`` on line ``line``; NotText
        when control characters make what was read so far no text."""
        first = _CONTROL.search(text)
        self.length += len(text)
        if first is None:
            return
        self.seen += len(_CONTROL.findall(text, first.start()))
        if self.seen > CONTROLS_ALLOWED and self.seen * 100 > self.length:
            raise _not_text(self.name, line, before + text[:first.start()],
                            f"control character U+{ord(first.group()):04X}, and "
                            f"{self.seen - 1} more")


def text_of(name: str, data) -> str:
    """The whole of an input (a binary file, or a str already decoded) as text,
    its line ends as Python's text files give them; NotText at the first byte
    that is not UTF-8, or when control characters make it no text (at the
    first block that does: garbage is never read whole)."""
    controls = _Controls(name)
    if isinstance(data, str):
        try:
            data.encode("utf-8")
        except UnicodeEncodeError as exc:
            raise _undecoded(name, 1, "", exc) from None
        controls.add(data, 1, "")
        return data[1:] if data.startswith(BOM) else data
    decoder = codecs.getincrementaldecoder("utf-8")()
    parts: list[str] = []
    while True:
        block = data.read(BLOCK)
        try:
            part = decoder.decode(block, final=not block)
        except UnicodeDecodeError as exc:
            raise _undecoded(name, 1, "".join(parts), exc) from None
        if _CONTROL.search(part):
            controls.add(part, 1, "".join(parts))
        else:
            controls.length += len(part)
        parts.append(part)
        if not block:
            break
    text = "".join(parts)
    if text.startswith(BOM):  # a byte-order mark is no character of the scene
        text = text[1:]
    if "\r" in text:  # as a text file's universal newlines
        text = text.replace("\r\n", "\n").replace("\r", "\n")
    return text


def lines_of(name: str, data) -> Iterator[str]:
    """An input's lines as they arrive (a binary stream read a line at a time, or
    a text stream), each ending in '\\n' as Python's text files give them;
    NotText, raised when the line that makes it no text is reached (the lines
    before it are given first)."""
    number = 1
    controls = _Controls(name)
    decoder = codecs.getincrementaldecoder("utf-8")()
    pending = ""
    while True:
        piece = data.readline(BLOCK)
        final = not piece
        try:
            if isinstance(piece, bytes):
                text = decoder.decode(piece, final=final)
                if "\r" in text:  # as a text file's universal newlines
                    text = text.replace("\r\n", "\n").replace("\r", "\n")
            else:
                text = piece
                text.encode("utf-8")
        except UnicodeError as exc:
            raise _undecoded(name, number, pending, exc) from None
        if number == 1 and not pending and text.startswith(BOM):
            text = text[1:]  # a byte-order mark is no character of the scene
        controls.add(text, number, pending)
        lines = (pending + text).split("\n")
        pending = lines.pop()
        for line in lines:
            yield line + "\n"
            number += 1
        if final:
            if pending:
                yield pending
            return


def _unescape(name: str) -> str:
    return re.sub(r"\\(.)", r"\1", name)


class Reader:
    """Turns lines into statement chunks; reports bad directives and comments."""

    def __init__(self, reporter: Reporter, file: str = "<stdin>", directives_allowed: bool = False):
        self.reporter = reporter
        self.file = file
        self.line = 0  # original line number of the line just read
        self.directives_allowed = directives_allowed

    def start_file(self, file: str) -> None:
        """The next line read is line 1 of ``file`` (used when joining files)."""
        self.file = file
        self.line = 0

    def chunks(self, lines: Iterable[str]) -> Iterator[Chunk]:
        pending: list[str] = []
        origins: list[tuple[str, int]] = []
        first_column = 0
        has_text = False
        comment_start: Location | None = None  # inside /* ... */ when set
        source_lines = self.reporter.source_lines

        for raw in lines:
            if isinstance(raw, NotText):  # the rest of that input is not read
                self.reporter.error(raw)
                pending, origins, has_text, comment_start = [], [], False, None
                continue
            text = raw.rstrip("\r\n")
            if comment_start is None and text.lstrip().startswith("#"):
                self._directive(text)
                continue
            self.line += 1
            origin = (self.file, self.line)
            source_lines[origin] = text
            if not pending:
                first_column = 0
            consumed = 0  # characters of this line already given to a chunk
            pos = 0
            while True:
                if comment_start is not None:
                    end = _END_COMMENT.search(text, pos)
                    if end is None:
                        break
                    comment_start = None
                    pos = end.end()
                    continue
                found = _SCAN.search(text, pos)
                segment_end = found.start() if found else len(text)
                if not has_text and not text[pos:segment_end].isspace() and pos < segment_end:
                    has_text = True
                if found is None or found.group() == "//":
                    break
                if found.group() == "/*":
                    comment_start = Location(self.file, self.line, consumed + found.start() + 1)
                    pos = found.end()
                    continue
                # a ';' ends the statement; the rest of the line starts the next
                end = found.end()
                pending.append(text[:end])
                origins.append(origin)
                yield Chunk("\n".join(pending), tuple(origins), first_column)
                pending, origins, has_text = [], [], False
                consumed += end
                first_column = consumed
                text = text[end:]
                pos = 0
            pending.append(text)
            origins.append(origin)

        if comment_start is not None:
            raise PreprocessError("unterminated comment: '/*' has no matching '*/'", comment_start)
        if has_text:
            yield Chunk("\n".join(pending), tuple(origins), first_column)

    def _directive(self, text: str) -> None:
        marker = _MARKER.match(text)
        if marker:
            self.line = int(marker.group(1)) - 1
            if marker.group(2) is not None:
                self.file = _unescape(marker.group(2))
            return
        self.line += 1
        self.reporter.source_lines[(self.file, self.line)] = text
        name = _DIRECTIVE.match(text).group(1) or text.strip()
        column = text.index("#") + 1
        location = Location(self.file, self.line, column)
        if self.directives_allowed:
            message = f"unknown preprocessor directive '#{name}'"
        else:
            message = (f"preprocessor directive '#{name}' with --no-cpp; "
                       "run castor without --no-cpp, or pass the file through cpp first")
        self.reporter.error(CastorError(message, location))
