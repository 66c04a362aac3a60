"""The C preprocessor stage: the sources through one pass of cpp
(castor.language.cpp), or what a remembered pass gives for them.

The output keeps ``#line`` markers, which the reader follows so that every
position castor reports names the original file and line, inside included
files too.
"""

from __future__ import annotations

import os
import re
import threading
from collections import OrderedDict

from castor.diagnostics import Reporter
from castor.language.cpp import (Pass, SourceLines, escape, expansion_finder, run_pass,
                                 shown, unsaved)

__all__ = ["preprocess", "unsaved"]

# a directive, but not a line marker of an earlier cpp ('# 12 "file.cas" 1', '#line 12'),
# which the reader follows: text that went through cpp needs no second pass (whose
# own #line markers, after a run of blank lines, would count the lines of its
# input, not of the file the markers name)
_DIRECTIVE = re.compile(r"^[ \t]*#(?![ \t]*(?:line[ \t]+)?\d)", re.M)


# --- remembered passes -------------------------------------------------------
#
# A live preview evaluates the same text again at each slider change, and a
# language server analyses the buffer again at each keystroke, most of which
# touch no directive and no macro. pcpp is pure Python and takes a large part
# of an analysis, so a pass that said nothing (no error, no warning) is kept:
# the same sources again, with every #included file's text unchanged (and no
# file appeared where one was looked for), give its output at once; a new text
# of a single source whose changed lines, and the lines around them, hold no
# directive, no macro name, no quote, comment mark or backslash is the old
# output with those lines replaced (and the main file's later #line markers
# moved). Anything else is a full pass.

CACHED_PASSES = 4


_cache: "OrderedDict[tuple, Pass]" = OrderedDict()
_latest: dict[tuple, tuple] = {}  # (name, settings) -> the key of the last pass of that source
_cache_lock = threading.Lock()


def preprocess(sources: list[tuple[str, str]], defines: list[str], undefines: list[str],
               include_dirs: list[str], reporter: Reporter,
               included: list[str] | None = None) -> str:
    """Run the sources, in order, through one preprocessor; return its output.

    ``included``, when given, receives the path of every file that #include opened.
    A pass is not run again when a remembered one gives the same output (see above)."""
    if not defines and not any(_DIRECTIVE.search(text) or "\\\n" in text for _, text in sources):
        # No directive and no -D: cpp would change nothing (castor keeps the
        # comments), so skip the pure-Python pass and mark each file's start.
        return "".join(f'#line 1 "{escape(shown(name))}"\n{text}\n' for name, text in sources)
    settings = (tuple(defines), tuple(undefines), tuple(include_dirs), os.getcwd())
    key = (tuple(sources),) + settings
    kept = _remembered(key, settings)
    if kept is not None:
        if included is not None:
            included.extend(path for path, _ in kept.opened)
        reporter.expansions = kept.finder
        return kept.text
    said = (reporter.errors, reporter.warnings)
    text, done = run_pass(sources, defines, undefines, include_dirs, reporter, included)
    if done is not None and (reporter.errors, reporter.warnings) == said and not any(
            "__TIME__" in t or "__DATE__" in t for _, t in sources + list(done.opened)):
        done.sources = tuple(sources)
        _remember(key, settings, done)
    return text


def _remember(key: tuple, settings: tuple, done: Pass) -> None:
    with _cache_lock:
        _cache[key] = done
        _cache.move_to_end(key)
        while len(_cache) > CACHED_PASSES:
            _cache.popitem(last=False)
        if len(key[0]) == 1:
            _latest[(key[0][0][0],) + settings] = key


def _remembered(key: tuple, settings: tuple) -> Pass | None:
    """A remembered pass that gives these sources' output, or one patched from the
    last pass of the same single source; None: run the preprocessor."""
    with _cache_lock:
        kept = _cache.get(key)
        base = None
        if kept is None and len(key[0]) == 1:
            base = _cache.get(_latest.get((key[0][0][0],) + settings))
    if kept is not None:
        return kept if kept.fresh() else None
    if base is None or not base.fresh():
        return None
    name, text = key[0][0]
    try:
        patched = _patched(base, name, text)
    except (LookupError, ValueError):  # a layout it did not expect: a full pass
        patched = None
    if patched is not None:
        _remember(key, settings, patched)
    return patched


_MAIN_MARKER = re.compile(r'#line (\d+) "((?:[^"\\]|\\.)*)"$')
_IDENTIFIER = re.compile(r"[A-Za-z_]\w*")
_UNSAFE = ("#", "\\", '"', "'", "/*", "*/", "\r", "??", "\f", "\v")


_COMMENT_MARKS = re.compile(r"/\*|\*/|//")


def _plain(line: str, macros: frozenset) -> bool:
    """A line the preprocessor gives as it is, wherever it stands among plain lines."""
    if any(mark in line for mark in _UNSAFE) or line != line.rstrip():
        return False  # (pcpp drops the blanks at the end of a line in a comment)
    return not any(word in macros or word.startswith("__") for word in _IDENTIFIER.findall(line))


def _patched(base: Pass, name: str, new_text: str) -> Pass | None:
    """The output for ``new_text`` from the pass of the source's previous text,
    when the lines that changed are plain among plain lines (see above)."""
    old, new = _lines(base.sources[0][1]), _lines(new_text)
    if not old or not new:
        return None
    first, tail = _common_ends(old, new)
    removed, added = old[first:len(old) - tail], new[first:len(new) - tail]
    if not removed and not added:
        return None
    macros = base.macro_names()
    if not _plain_change(removed, added, macros):
        return None
    shift = len(added) - len(removed)
    if shift and "__LINE__" in new_text:
        return None
    around = _around(old, first, len(old) - tail, macros)
    if around is None:
        return None
    lines = base.text.split("\n")
    found = _main_lines(lines)
    if found is None:
        return None
    marker, where = found
    before, after, directives = around
    if not _given_in_order(old, lines, where, before, after, directives):
        return None
    # and the change is among lines that are given (not in a block #if leaves out):
    # next to a plain line, or in place of one that is not blank
    if not (before not in directives or (after < len(old) and after not in directives)
            or any(line.strip() for line in removed)):
        return None
    if shift and any(location.file == _unescaped(marker) and location.line > first
                     for location in base.p.definitions.values()):
        return None  # a #define after the change would have moved
    out = _spliced(lines, where, old, first, removed, added, directives)
    if out is None or (shift and not _markers_moved(out, marker, shift,
                                                    _start(where, old, first, removed,
                                                           directives) + len(added))):
        return None
    sources = ((name, new_text),)
    finder = expansion_finder(base.p, SourceLines(list(sources)))
    return Pass("\n".join(out), base.opened, base.missing, base.p, finder, base.given, sources)


def _common_ends(old: list[str], new: list[str]) -> tuple[int, int]:
    """How many lines the two texts share at their start, and then at their end."""
    first = 0
    while first < min(len(old), len(new)) and old[first] == new[first]:
        first += 1
    tail = 0
    while tail < min(len(old), len(new)) - first and old[-1 - tail] == new[-1 - tail]:
        tail += 1
    return first, tail


def _plain_change(removed: list[str], added: list[str], macros: frozenset) -> bool:
    """Whether every line removed and added is plain; comments are allowed where
    they stay as they were (a value changed before its comment)."""
    marks = [_COMMENT_MARKS.findall(line) for line in removed]
    if any(marks):
        if len(added) != len(removed) or marks != [_COMMENT_MARKS.findall(line)
                                                   for line in added]:
            return False
        if any(line != line.rstrip() for line in removed + added):
            return False
        removed = [_COMMENT_MARKS.sub(" ", line).rstrip() for line in removed]
        added = [_COMMENT_MARKS.sub(" ", line).rstrip() for line in added]
    return all(_plain(line, macros) for line in removed + added)


def _around(old: list[str], first: int, end: int, macros: frozenset):
    """The nearest lines that are not blank on either side of the change (old
    lines ``first`` to ``end``): plain lines, or whole directives (an #include,
    an #endif) that cannot reach into the change. (before, after, the indexes
    that are directives), or None."""
    before = first - 1
    while before >= 0 and not old[before].strip():
        before -= 1
    if before < 0:
        return None  # (pcpp drops the empty lines at a file's start)
    after = end
    while after < len(old) and not old[after].strip():
        after += 1
    directives = set()
    for k in (before, after):
        if k >= len(old) or _plain(_uncommented(old[k]), macros):
            continue
        if not _whole_directive(old[k]):
            return None
        directives.add(k)
    return before, after, directives


def _given_in_order(old: list[str], lines: list[str], where: dict, before: int, after: int,
                    directives: set) -> bool:
    """Whether from one side of the change to the other each line is in the
    output as it is, in order."""
    previous = None
    for k in range(before, min(after, len(old) - 1) + 1):
        if k in directives:
            previous = None
            continue
        at = where.get(k + 1)
        if at is None and not old[k].strip():
            previous = None  # an empty line pcpp gave as a #line marker
            continue
        if at is None or lines[at] != old[k] or (previous is not None and at != previous + 1):
            return False
        previous = at
    return True


def _start(where: dict, old: list[str], first: int, removed: list[str],
           directives: set) -> int | None:
    """The output line where the change goes."""
    if removed or (first < len(old) and first not in directives and first + 1 in where):
        return where[first + 1]
    if first - 1 not in directives and first in where:
        return where[first] + 1
    return None


def _spliced(lines: list[str], where: dict, old: list[str], first: int, removed: list[str],
             added: list[str], directives: set) -> list[str] | None:
    """The output with the removed lines replaced by the added ones, or None."""
    start = _start(where, old, first, removed, directives)
    if start is None:
        return None
    rest = lines[start + len(removed):]
    if any(line.strip() for line in rest):
        if all(line.startswith("#") for line in rest if line.strip()):
            return None
        out = lines[:start] + added + rest
        if not added and start > 0 and out[start - 1].startswith("#") and \
                out[start].startswith("#"):
            del out[start - 1]  # a marker for lines no longer there, as pcpp leaves none
        return out
    # the end of the output, whose empty lines pcpp drops
    if rest != ["", ""]:
        return None
    out = lines[:start] + added
    while out and not out[-1].strip():
        out.pop()
    if not out or out[-1].startswith("#"):
        return None
    return out + rest


def _markers_moved(out: list[str], marker: str, shift: int, start: int) -> bool:
    """The main file's #line markers after the change moved by ``shift`` lines,
    in place; False when another directive stands there."""
    for k in range(start, len(out)):
        line = out[k]
        if line.startswith("#"):
            match = _MAIN_MARKER.match(line)
            if match is None:
                return False
            if match[2] == marker:
                out[k] = f'#line {int(match[1]) + shift} "{marker}"'
    return True


_COMMENTS = (re.compile(r"/\*.*?\*/"), re.compile(r"//.*$"), re.compile(r"^.*?\*/"),
             re.compile(r"/\*.*$"))


def _uncommented(line: str) -> str:
    """A line without its comments (what a comment that goes on from the line
    before ends, what one that goes on to the next begins): a macro's name in a
    comment beside a change is harmless."""
    for comment in _COMMENTS:
        line = comment.sub(" ", line)
    return line.rstrip()


def _whole_directive(line: str) -> bool:
    """A directive that ends on its line: no continuation, no comment left open."""
    if not line.lstrip().startswith("#") or "\\" in line or "\r" in line:
        return False
    rest = _COMMENTS[1].sub(" ", _COMMENTS[0].sub(" ", line))
    return "/*" not in rest and "*/" not in rest


def _lines(text: str) -> list[str]:
    """A source's lines without the empty ones at its end (which pcpp drops)."""
    lines = text.split("\n")
    while lines and not lines[-1]:
        lines.pop()
    return lines


def _unescaped(name: str) -> str:
    return re.sub(r"\\(.)", r"\1", name)


def _main_lines(lines: list[str]) -> tuple[str, dict[int, int]] | None:
    """The first file's name in the output's markers, and for each of its lines
    the output line that holds it; None when the output has other directives."""
    if not lines:
        return None
    first = _MAIN_MARKER.match(lines[0])
    if first is None:
        return None
    marker = first[2]
    where: dict[int, int] = {}
    current, number = marker, 0
    for k, line in enumerate(lines):
        if line.startswith("#"):
            match = _MAIN_MARKER.match(line)
            if match is None:
                return None
            current, number = match[2], int(match[1])
            continue
        if current == marker:
            where[number] = k
        number += 1
    return marker, where
