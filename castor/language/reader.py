"""Cut the (preprocessed) input into statements, keeping track of positions.

The reader consumes lines one at a time, so that with ``--no-cpp`` a statement
is executed as soon as its ';' arrives. It understands cpp's line markers
(``# 12 "file.cas" 1 3`` and ``#line 12 "file.cas"``) and records, for every
line of a statement, which original file and line it came from. Comments are
skipped while looking for the ';' that ends a statement (the grammar skips
them again when parsing).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Iterable, Iterator

from castor.diagnostics import CastorError, Location, PreprocessError, Reporter

_MARKER = re.compile(r'\s*#\s*(?:line\s+)?(\d+)(?:\s+"((?:[^"\\]|\\.)*)")?[^\n]*$')
_DIRECTIVE = re.compile(r"\s*#\s*([A-Za-z_]*)")
_SCAN = re.compile(r"/\*|//|;")
_END_COMMENT = re.compile(r"\*/")


@dataclass(frozen=True, slots=True)
class Chunk:
    """The text of one statement and where each of its lines came from."""

    text: str
    origins: tuple[tuple[str, int], ...]  # (file, line) for each line of text
    first_column: int  # columns of the first line start after this many characters

    def location(self, line: int, column: int) -> Location:
        """Map a 1-based (line, column) inside the chunk to the original file."""
        if line == 1:
            file, original = self.origins[0]
            return Location(file, original, column + self.first_column)
        file, original = self.origins[min(max(line, 1), len(self.origins)) - 1]
        return Location(file, original, column)

    def end_location(self) -> Location:
        """Just after the last character that is not blank."""
        lines = self.text.split("\n")
        for index in range(len(lines) - 1, -1, -1):
            stripped = lines[index].rstrip()
            if stripped:
                return self.location(index + 1, len(stripped) + 1)
        return self.location(1, 1)


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
