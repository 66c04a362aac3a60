"""What the language server knows of a scene, from one ``Analysis``: plain functions.

Positions here are castor's: a file name as locations give it, a 1-based line
and a 1-based column (characters). The protocol's 0-based positions are
converted in ``server.py`` only. The word under the cursor is found by a small
tokenizer of the line (names, and the ``!``, ``@``, ``$`` of the vocabulary);
what it means comes from the pipeline's definitions, never from a second parse.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from castor.diagnostics import Location
from castor.language.vocabulary import BOOLEANS, PRIMITIVES, TRANSFORMS
from castor.lsp.evaluate import Analysis, macro_definitions, object_figures, parameters

_WORD = re.compile(r"[!@$]?[A-Za-z_]\w*")
_COMMENT_OR_WORD = re.compile(r"//[^\n]*|/\*.*?\*/|\"(?:[^\"\\\n]|\\.)*\"|[A-Za-z_]\w*", re.S)


@dataclass(frozen=True)
class Word:
    text: str  # as written, with its '!', '@' or '$'
    line: int
    start: int  # 1-based column of its first character
    end: int  # 1-based column just after it

    @property
    def name(self) -> str:
        return self.text.lstrip("!@$")


def word_at(text: str, line: int, column: int) -> Word | None:
    """The word at 1-based (line, column), or just before it."""
    lines = text.split("\n")
    if not 0 < line <= len(lines):
        return None
    source = lines[line - 1]
    for match in _WORD.finditer(source):
        if match.start() + 1 <= column <= match.end() + 1:
            return Word(match.group(), line, match.start() + 1, match.end() + 1)
    return None


def token_end(text: str | None, location: Location) -> int:
    """The 1-based column just after the token at ``location`` (for a range)."""
    if text is None:
        return location.column + 1
    lines = text.split("\n")
    if not 0 < location.line <= len(lines):
        return location.column + 1
    source = lines[location.line - 1]
    match = re.compile(r"[!@$]?\w+|\S").match(source, max(location.column - 1, 0))
    return match.end() + 1 if match else location.column + 1


def _before(a: Location, file: str, line: int, column: int) -> bool:
    return a.file == file and (a.line, a.column) <= (line, column)


def _point(analysis: Analysis, file: str, line: int, column: int) -> int:
    """The index in the definitions' order of the last one written before the cursor
    (-1: none)."""
    index = -1
    for k, d in enumerate(analysis.definitions):
        if _before(d.location, file, line, column):
            index = k
    return index


def definitions_of(analysis: Analysis, name: str, kind: str) -> list[Location]:
    return [d.location for d in analysis.definitions if d.kind == kind and d.name == name]


def macros(analysis: Analysis) -> dict[str, Location]:
    found: dict[str, Location] = {}
    for name, location in macro_definitions(analysis):
        found.setdefault(name, location)
    return found


def definition(analysis: Analysis, file: str, line: int, column: int) -> list[Location]:
    """Where the name under the cursor is defined: the definition in force there
    (the last before it), else the first; a macro's #define."""
    word = word_at(analysis.source_text(file) or "", line, column)
    if word is None or word.text[0] in "!@$":
        return []
    found = macros(analysis).get(word.name)
    if found is not None:
        return [found]
    kind = "parameter" if word.name[0].isupper() else "object"
    point = _point(analysis, file, line, column)
    places = [(k, d.location) for k, d in enumerate(analysis.definitions)
              if d.kind == kind and d.name == word.name]
    if not places:
        return []
    earlier = [loc for k, loc in places if k <= point and loc != Location(file, line, word.start)]
    return [earlier[-1] if earlier else places[0][1]]


def references(analysis: Analysis, file: str, line: int, column: int,
               declaration: bool = True) -> list[tuple[Location, int]]:
    """Every use of the name under the cursor in the scene's files (comments
    skipped), as (location, end column)."""
    word = word_at(analysis.source_text(file) or "", line, column)
    if word is None or word.text[0] in "!@$":
        return []
    defined = {(loc.file, loc.line, loc.column) for loc in
               definitions_of(analysis, word.name, "parameter")
               + definitions_of(analysis, word.name, "object")}
    out = []
    for name in _files(analysis):
        text = analysis.source_text(name)
        if text is None:
            continue
        starts = _line_starts(text)
        for match in _COMMENT_OR_WORD.finditer(text):
            if match.group() != word.name:
                continue
            number = _line_of(starts, match.start())
            location = Location(name, number, match.start() - starts[number - 1] + 1)
            if not declaration and (location.file, location.line, location.column) in defined:
                continue
            out.append((location, location.column + len(word.name)))
    return out


def _files(analysis: Analysis) -> list[str]:
    from castor.lsp.evaluate import _shown

    out = [analysis.file]
    for name in analysis.included:
        shown = _shown(name)
        if shown not in out:
            out.append(shown)
    for name in analysis.texts:
        if name not in out:
            out.append(name)
    return out


def _line_starts(text: str) -> list[int]:
    starts = [0]
    for match in re.finditer("\n", text):
        starts.append(match.end())
    return starts


def _line_of(starts: list[int], offset: int) -> int:
    import bisect

    return bisect.bisect_right(starts, offset)


def vocabulary_text(word: str) -> str | None:
    """What the vocabulary says of ``!cu``, ``@rz`` or ``$D``."""
    sigil, name = word[0], word[1:]
    if sigil == "!" and name in PRIMITIVES:
        p = PRIMITIVES[name]
        lines = [f"!{name}({p.form}): {p.title}", f"the unit solid: {p.solid}",
                 "R, G, B: the colour, each 0..1"]
        lines += [f"{a.name}: {a.meaning}" for a in p.arguments]
        if p.pairs:
            x, y = p.arguments_of_pairs
            lines.append(f"then the vertices as pairs {x}, {y} (at least three)")
        return "\n".join(lines)
    if sigil == "@" and name in TRANSFORMS:
        t = TRANSFORMS[name]
        return f"@{name}({t.form}): {t.title}\n{t.meaning}"
    if sigil == "$" and name in BOOLEANS:
        return (f"${name}(A, B, ...): {BOOLEANS[name]} of the operands"
                + (" (the first minus the others)" if name == "D" else "")
                + f"\n${name}[I = A, B, S](...): the {BOOLEANS[name]} of the body repeated")
    return None


def _short(line: str, most: int = 160) -> str:
    """A line as a hover shows it: at most ``most`` characters."""
    return line if len(line) <= most else line[:most - 1] + "…"


def _number(value) -> str:
    return "undefined" if value is None else f"{value:.10g}"


def hover(analysis: Analysis, file: str, line: int, column: int,
          figures=object_figures) -> tuple[str, Word] | None:
    """The hover text for the word under the cursor, and the word."""
    word = word_at(analysis.source_text(file) or "", line, column)
    if word is None:
        return None
    if word.text[0] in "!@$":
        text = vocabulary_text(word.text)
        return (text, word) if text else None
    name = word.name
    found = macros(analysis).get(name)
    if found is not None:
        source = (analysis.source_text(found.file) or "").split("\n")
        body = _short(source[found.line - 1].strip()) if 0 < found.line <= len(source) else ""
        return f"macro {name}, {found.file}:{found.line}\n{body}", word
    if name[0].isupper():
        return _parameter_hover(analysis, file, line, column, name), word
    return _object_hover(analysis, name, figures), word


def _parameter_hover(analysis, file, line, column, name) -> str | None:
    point = _point(analysis, file, line, column)
    value, where = None, None
    for k, d in enumerate(analysis.definitions):
        if d.kind == "parameter" and d.name == name and k <= point:
            value, where = d.value, d.location
    if where is None:
        if name in analysis.parameters:
            value = analysis.parameters[name]
            where = "at the end of the scene"
        else:
            return f"parameter {name}: not defined"
    else:
        where = f"as defined at {where.file}:{where.line}"
    text = f"{name} = {_number(value)} ({where})"
    for parameter in parameters(analysis)[0]:
        if parameter.name == name:
            described = parameter.annotation.text()
            if parameter.expression and parameter.expression != _number(parameter.value):
                text += f"\nfirst defined as {name} = {parameter.expression}"
            if parameter.group:
                text += f"\ngroup: {parameter.group}"
            if described:
                text += f"\n{described}"
    return text


def _object_hover(analysis, name, figures) -> str | None:
    places = definitions_of(analysis, name, "object")
    if not places:
        return f"object {name}: not defined"
    where = places[-1]
    source = (analysis.source_text(where.file) or "").split("\n")
    first = _short(source[where.line - 1].strip()) if 0 < where.line <= len(source) else ""
    text = f"object {name}, {where.file}:{where.line}\n{first}"
    summary = figures(analysis, name)
    if summary and "refused" in summary:
        text += f"\nbox and volume not made: {summary['refused']}"
    elif summary:
        for obj in summary.get("objects", []):
            low, high = obj["bbox"] if obj.get("bbox") else (None, None)
            if low is not None:
                text += ("\nbox " + " ".join(f"{v:.6g}" for v in low) + " to "
                         + " ".join(f"{v:.6g}" for v in high))
            text += f"\nvolume {obj['volume']:.6g}"
    return text


@dataclass(frozen=True)
class Completion:
    label: str
    detail: str
    documentation: str
    kind: str  # "primitive", "transform", "boolean", "parameter", "object", "macro"
    insert: str
    snippet: str | None = None  # with its arguments as placeholders: cu(${1:R}, ...)


def _snippet(name: str, arguments: list[str]) -> str:
    holes = ", ".join(f"${{{k}:{a}}}" for k, a in enumerate(arguments, 1))
    return f"{name}({holes})"


def completions(analysis: Analysis | None, text: str, file: str, line: int,
                column: int) -> list[Completion]:
    """After '!', '@' or '$': the vocabulary; else the names defined before the cursor."""
    lines = text.split("\n")
    source = lines[line - 1] if 0 < line <= len(lines) else ""
    before = source[:max(column - 1, 0)]
    match = re.search(r"([!@$])(\w*)$", before)
    if match:
        sigil = match.group(1)
        if sigil == "!":
            return [Completion(name, f"!{name}({p.form})", f"{p.title}: {p.solid}", "primitive",
                               name, _snippet(name, p.form.split(", ")[:p.count]))
                    for name, p in PRIMITIVES.items()]
        if sigil == "@":
            return [Completion(name, f"@{name}({t.form})", f"{t.title}: {t.meaning}", "transform",
                               name, _snippet(name, t.form.split(" or ")[-1].split(", ")))
                    for name, t in TRANSFORMS.items()]
        return [Completion(name, f"${name}(A, B, ...)", what, "boolean", name,
                           _snippet(name, ["A", "B"])) for name, what in BOOLEANS.items()]
    if analysis is None:
        return []
    out: dict[str, Completion] = {}
    point = _point(analysis, file, line, column)
    for k, d in enumerate(analysis.definitions):
        if k > point and analysis.file == file:
            break
        if d.kind == "parameter":
            out.setdefault(d.name, Completion(d.name, f"parameter = {_number(d.value)}", "",
                                              "parameter", d.name))
        elif d.kind == "object":
            out.setdefault(d.name, Completion(d.name, "object", "", "object", d.name))
    for name, location in macros(analysis).items():
        if location.file != file or location.line < line:
            out.setdefault(name, Completion(name, f"macro, {location.file}:{location.line}", "",
                                            "macro", name))
    return list(out.values())


@dataclass(frozen=True)
class Symbol:
    name: str
    kind: str  # "parameter", "object", "frame"
    location: Location
    end: int
    detail: str


def symbols(analysis: Analysis, file: str) -> list[Symbol]:
    """The outline of one file: its parameters, objects and '>' commands, in order."""
    out = []
    text = analysis.source_text(file)
    lines = (text or "").split("\n")
    for d in analysis.definitions:
        if d.location.file != file:
            continue
        source = lines[d.location.line - 1] if 0 < d.location.line <= len(lines) else ""
        end = len(source.rstrip()) + 1
        if d.kind == "parameter":
            out.append(Symbol(d.name, "parameter", d.location, end, f"= {_number(d.value)}"))
        elif d.kind == "object":
            out.append(Symbol(d.name, "object", d.location, end, "object"))
        else:
            out.append(Symbol(source.strip()[:60] or ">", "frame", d.location, end, "frame"))
    return out
