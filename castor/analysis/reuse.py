"""Statements parsed once, for the evaluations that follow one another in an editor.

A language server analyses the buffer again at each keystroke and the live
preview evaluates the scene again at each slider change: the statements are
nearly all the same each time, and parsing them (lark) is most of what is
left of an analysis once the preprocessor's pass is remembered
(castor.language.preprocess). ``ReusingInterpreter`` keeps what each
statement gave, by its text and where each of its lines comes from, and runs
that again instead of parsing when it would give the same:

- the statement parsed without a fault (a faulty one is parsed again, so that
  its messages are said as the parser says them);
- every object name it looked up still names the very node it named then (the
  parser shares a referenced object's node), so a statement after a changed
  definition is parsed again, and so are those that use what it defines.

Parameters are never looked up while parsing (they are evaluated when the
statement runs, with the values then in force: ``--set``, a slider), so a
slider change reuses every statement. The nodes reused are the same objects,
which keeps the facetizer's shared subtrees the same from one frame to the next.

The memory is bounded by the text of the statements it keeps (``MAX_TEXT``
characters in all, about what their nodes weigh: a statement's nodes grow as its
text), not only by their number: each version of a long statement typed in
(one of 40,000 cubes is 1.2 MB of text and 77 MB of nodes) would otherwise
stay alive. The statements used least recently go first.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass

from castor.diagnostics import CastorError
from castor.interpreter import Interpreter
from castor.language.parse import SkippedDefinition

# statements remembered (each with its nodes), and their text in all (characters):
# past either, the statements used least recently are forgotten. The text allowed
# is that of the largest buffer the language server analyses (documents.MAX_BUFFER),
# so that each statement of any one scene is kept; its nodes weigh some 70 bytes
# a character (a statement of 40,000 cubes: 1.2 MB of text, 77 MB of nodes)
MAX_STATEMENTS = 50_000
MAX_TEXT = 4_000_000


@dataclass(frozen=True, slots=True)
class _Parsed:
    items: tuple  # what the parser gave: ParamDef, ObjectDef, FrameCommand
    looked_up: tuple  # (name, node or None) of each object name the parser looked up
    parameters: tuple  # parameter names it added to the parser's (for --set's warning)


# (text, origins, first column) -> what it gave, the least recently used first
_remembered: dict[tuple, _Parsed] = {}
_weight = [0]  # the characters of the texts _remembered keeps
_lock = threading.Lock()


def forget() -> None:
    """Empty the memory (what a benchmark of the first evaluation starts from)."""
    with _lock:
        _remembered.clear()
        _weight[0] = 0


def remembered() -> tuple[int, int]:
    """How many statements the memory keeps, and their characters (for tests)."""
    with _lock:
        return len(_remembered), _weight[0]


def _recall(key: tuple) -> _Parsed | None:
    """What the statement ``key`` gave, now the most recently used."""
    with _lock:
        kept = _remembered.pop(key, None)
        if kept is not None:
            _remembered[key] = kept
        return kept


def _keep(key: tuple, parsed: _Parsed) -> None:
    """Remember a statement, forgetting the least recently used ones past the bounds
    (a statement longer than MAX_TEXT alone is not kept)."""
    size = len(key[0])
    if size > MAX_TEXT:
        return
    with _lock:
        old = _remembered.pop(key, None)
        if old is not None:
            _weight[0] -= size
        while _remembered and (len(_remembered) >= MAX_STATEMENTS
                               or _weight[0] + size > MAX_TEXT):
            oldest = next(iter(_remembered))
            del _remembered[oldest]
            _weight[0] -= len(oldest[0])
        _remembered[key] = parsed
        _weight[0] += size


class _LookedUp(dict):
    """The object table, noting which names the parser looks up, and what it finds."""

    __slots__ = ("noted",)

    def get(self, name, default=None):
        found = super().get(name, default)
        if self.noted is not None:
            self.noted.append((name, found))
        return found

    def __contains__(self, name) -> bool:
        found = super().__contains__(name)
        if self.noted is not None:
            self.noted.append((name, super().get(name)))
        return found


class ReusingInterpreter(Interpreter):
    """An Interpreter that parses a statement only when it has not the same
    statement, with the same objects under its names, from an earlier run."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        table = _LookedUp(self.tables.objects)
        table.noted = None
        self.tables.objects = table
        self.parser.tables = self.tables
        self.reused = 0  # statements not parsed again (for tests and benchmarks)

    def run(self, chunks, streaming: bool = True) -> None:
        if streaming:
            super().run(chunks, streaming)
            return
        try:
            for chunk in chunks:
                self._statement(chunk)
        except CastorError as exc:  # from the reader: an unterminated comment
            self.reporter.error(exc)

    def _statement(self, chunk) -> None:
        key = (chunk.text, chunk.origins, chunk.first_column)
        objects = self.tables.objects
        kept = _recall(key)
        if kept is not None and all(objects.get(name) is node for name, node in kept.looked_up):
            self.reused += 1
            sets = self.parser.param_sets
            for name in kept.parameters:
                if name not in sets:
                    sets[name] = frozenset((name,))
            for item in kept.items:
                self.execute(item)
            return
        noted: list = []
        names = set(self.parser.param_sets)
        items = []
        objects.noted = noted
        try:
            for item in self.parser.parse(chunk):  # each runs before the next is parsed
                items.append(item)
                objects.noted = None  # (what running it looks up is not the parser's)
                self.execute(item)
                objects.noted = noted
        finally:
            objects.noted = None
        if items and not any(isinstance(item, (CastorError, SkippedDefinition))
                             for item in items):
            _keep(key, _Parsed(tuple(items), tuple(noted),
                               tuple(set(self.parser.param_sets) - names)))
