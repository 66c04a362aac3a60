"""The text side of a gesture: positions, edits, short numbers and a small
tokenizer of the scene as written.

An edit is an LSP ``TextEdit`` (a range of 0-based lines and characters, and
the text that replaces it), so that a language server sends it as is in a
``workspace/applyEdit`` and the live preview applies it to the file with
``apply``; ``inverse`` gives the edits that undo it. ``tokens`` reads the
text as the user wrote it (comments and layout skipped, never changed), from
a statement's place on: where an operand starts, where a list ends, whether
an ``@t``'s numbers are literal.
"""

from __future__ import annotations

import hashlib
import re
from decimal import Decimal
from typing import Iterator, NamedTuple


class TextEdit(NamedTuple):
    """Replace the text from (line, character) to (end_line, end_character),
    0-based as the LSP counts them, by ``text``."""

    line: int
    character: int
    end_line: int
    end_character: int
    text: str

    def as_json(self) -> dict:
        return {"range": {"start": {"line": self.line, "character": self.character},
                          "end": {"line": self.end_line, "character": self.end_character}},
                "newText": self.text}

    @classmethod
    def from_json(cls, edit: dict) -> "TextEdit":
        start, end = edit["range"]["start"], edit["range"]["end"]
        return cls(int(start["line"]), int(start["character"]), int(end["line"]),
                   int(end["character"]), str(edit["newText"]))


def digest(text: str) -> str:
    """What names a version of a text: an edit made on another is refused."""
    return hashlib.sha256(text.encode("utf-8", "surrogatepass")).hexdigest()[:16]


def line_starts(text: str) -> list[int]:
    starts = [0]
    for match in re.finditer("\n", text):
        starts.append(match.end())
    return starts


def offset(text: str, line: int, character: int, starts: list[int] | None = None) -> int:
    """The offset in ``text`` of a 0-based (line, character)."""
    starts = starts if starts is not None else line_starts(text)
    if line >= len(starts):
        return len(text)
    end = starts[line + 1] - 1 if line + 1 < len(starts) else len(text)
    return min(starts[line] + character, end)


def position(text: str, at: int, starts: list[int] | None = None) -> tuple[int, int]:
    """The 0-based (line, character) of an offset."""
    import bisect

    starts = starts if starts is not None else line_starts(text)
    line = bisect.bisect_right(starts, at) - 1
    return line, at - starts[line]


def insertion(text: str, at: int, new: str, starts: list[int] | None = None) -> TextEdit:
    line, character = position(text, at, starts)
    return TextEdit(line, character, line, character, new)


def replacement(text: str, start: int, end: int, new: str,
                starts: list[int] | None = None) -> TextEdit:
    line, character = position(text, start, starts)
    end_line, end_character = position(text, end, starts)
    return TextEdit(line, character, end_line, end_character, new)


def apply(text: str, edits: list[TextEdit]) -> str:
    """The text with the edits made (their ranges in ``text``, not overlapping)."""
    starts = line_starts(text)
    spans = sorted(((offset(text, e.line, e.character, starts),
                     offset(text, e.end_line, e.end_character, starts), e.text) for e in edits),
                   key=lambda s: (s[0], s[1]))
    out, at = [], 0
    for start, end, new in spans:
        if start < at:
            raise ValueError("overlapping edits")
        out.append(text[at:start])
        out.append(new)
        at = end
    out.append(text[at:])
    return "".join(out)


def inverse(text: str, edits: list[TextEdit]) -> list[TextEdit]:
    """The edits that take ``apply(text, edits)`` back to ``text``: Undo."""
    starts = line_starts(text)
    spans = sorted(((offset(text, e.line, e.character, starts),
                     offset(text, e.end_line, e.end_character, starts), e.text) for e in edits),
                   key=lambda s: (s[0], s[1]))
    result = apply(text, edits)
    new_starts = line_starts(result)
    undo, shift = [], 0
    for start, end, new in spans:
        begin = start + shift
        undo.append(replacement(result, begin, begin + len(new), text[start:end], new_starts))
        shift += len(new) - (end - start)
    return undo


def short(x: float) -> str:
    """A number as short as it can be written and still mean ``x`` to within
    rounding (2.35, never 2.3500000000000001 nor 0.30000000000000004), with no
    exponent; "-" in front of a negative one."""
    x = float(x)
    if abs(x) < 1e-9:
        return "0"
    for digits in range(1, 18):
        text = f"{x:.{digits}g}"
        if abs(float(text) - x) <= 1e-11 * max(1.0, abs(x)):
            break
    if "e" in text or "E" in text:
        text = format(Decimal(text), "f")
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


class Token(NamedTuple):
    kind: str  # "number", "name", "primitive" (!cu), "transform" (@t), "boolean" ($U), "mark"
    text: str
    start: int  # offsets in the text
    end: int


_TOKEN = re.compile(r"""
    (?P<space>\s+)
  | (?P<comment>/\*.*?\*/|//[^\n]*)
  | (?P<number>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)
  | (?P<name>[A-Za-z_]\w*)
  | (?P<primitive>![a-z]\w*)
  | (?P<transform>@[a-z]\w*)
  | (?P<boolean>\$[A-Za-z]+)
  | (?P<mark>.)
""", re.VERBOSE | re.DOTALL)


def tokens(text: str, start: int) -> Iterator[Token]:
    """The tokens of ``text`` from ``start`` on, comments and blanks skipped;
    a preprocessor line (``#...`` first on its line) ends them."""
    at = start
    while at < len(text):
        match = _TOKEN.match(text, at)
        kind = match.lastgroup
        if kind == "mark" and match.group() == "#":
            line_start = text.rfind("\n", 0, at) + 1
            if not text[line_start:at].strip():
                return
        if kind not in ("space", "comment"):
            yield Token(kind, match.group(), match.start(), match.end())
        at = match.end()


def number_at(tokens_ahead: list[Token], k: int) -> tuple[float, int, int, int] | None:
    """A literal number (with a '-' in front or not) starting at token ``k``:
    its value, its start and end offsets and the index of the token after it."""
    sign = 1.0
    start = None
    if k < len(tokens_ahead) and tokens_ahead[k].text in "-+" and tokens_ahead[k].kind == "mark":
        sign = -1.0 if tokens_ahead[k].text == "-" else 1.0
        start = tokens_ahead[k].start
        k += 1
    if k >= len(tokens_ahead) or tokens_ahead[k].kind != "number":
        return None
    token = tokens_ahead[k]
    return sign * float(token.text), token.start if start is None else start, token.end, k + 1
