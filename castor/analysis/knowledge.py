"""What is known of a scene, from one ``Analysis``: plain functions an editor's
requests are answered with (the word at a place, its definition, references,
renaming, hover text, completions, the outline).

Positions here are castor's: a file name as locations give it, a 1-based line
and a 1-based column (characters). The protocol's 0-based positions are
converted in castor.lsp.protocol only. The word under the cursor is found by a small
tokenizer of the line (names, and the ``!``, ``@``, ``$`` of the vocabulary);
what it means comes from the pipeline's definitions, never from a second parse.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from functools import lru_cache

from castor.analysis.scene import Analysis, macro_definitions, object_figures, parameters
from castor.diagnostics import Location
from castor.booleans import BOOLEANS
from castor.primitives import PRIMITIVES
from castor.transformations import TRANSFORMS

_WORD = re.compile(r"[!@$]?[A-Za-z_]\w*")
# a token, for a diagnostic's range; an annotation's bracket (LANGUAGE.md §11) is one: [wal]
_TOKEN = re.compile(r"\[[^\]\n]*\]|[!@$]?\w+|\S")
# a name as written (not the name of the vocabulary after '!', '@', '$', not a
# number's exponent), or a comment or a string, skipped
_COMMENT_OR_WORD = re.compile(
    r"//[^\n]*|/\*.*?\*/|\"(?:[^\"\\\n]|\\.)*\"|(?<![!@$\w.])[A-Za-z_]\w*", re.S)


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
    lines = _lines(text)
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
    lines = _lines(text)
    if not 0 < location.line <= len(lines):
        return location.column + 1
    source = lines[location.line - 1]
    match = _TOKEN.match(source, max(location.column - 1, 0))
    return match.end() + 1 if match else location.column + 1


@lru_cache(maxsize=4)
def _lines(text: str) -> list[str]:
    """A text's lines, split once for all the diagnostics and requests that read
    it (a diagnostic's range is asked of the same text for each diagnostic: a
    split each time made a thousand warnings of a 1 MB scene take seconds).
    The list is shared: never changed."""
    return text.split("\n")


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
    if kind == "parameter":
        repeated = repetition(analysis.source_text(file) or "", line, column, word.name)
        if repeated is not None:
            return [Location(file, *repeated[0])]
    point = _point(analysis, file, line, column)
    places = [(k, d.location) for k, d in enumerate(analysis.definitions)
              if d.kind == kind and d.name == word.name]
    if not places:
        return []
    earlier = [loc for k, loc in places if k <= point and loc != Location(file, line, word.start)]
    return [earlier[-1] if earlier else places[0][1]]


def repetition(text: str, line: int, column: int, name: str):
    """Where the repetition ``[NAME = A, B, S]`` of the statement at the cursor
    binds ``name``, as ((line, column), the bracket as written), or None."""
    starts = _line_starts(text)
    if not 0 < line <= len(starts):
        return None
    offset = starts[line - 1] + column - 1
    begin = text.rfind(";", 0, offset) + 1
    end = text.find(";", offset)
    statement = text[begin:end if end >= 0 else len(text)]
    match = re.search(r"\[\s*(" + re.escape(name) + r")\s*=[^\]]*\]", statement)
    if match is None:
        return None
    at = begin + match.start(1)
    number = _line_of(starts, at)
    return (number, at - starts[number - 1] + 1), " ".join(match.group().split())


def references(analysis: Analysis, file: str, line: int, column: int,
               declaration: bool = True) -> list[tuple[Location, int]]:
    """Every use of the name under the cursor in the scene's files (comments
    and strings skipped), as (location, end column)."""
    word = word_at(analysis.source_text(file) or "", line, column)
    if word is None or word.text[0] in "!@$":
        return []
    defined = {(loc.file, loc.line, loc.column) for loc in
               definitions_of(analysis, word.name, "parameter")
               + definitions_of(analysis, word.name, "object")}
    return [(location, end) for location, end, _ in _occurrences(analysis, word.name)
            if declaration or (location.file, location.line, location.column) not in defined]


def _occurrences(analysis: Analysis, word: str):
    """(location, end column, whether a '(' follows) of each ``word`` written
    in the scene's files, outside comments and strings."""
    for name in _files(analysis):
        text = analysis.source_text(name)
        if text is None:
            continue
        starts = _line_starts(text)
        for match in _COMMENT_OR_WORD.finditer(text):
            if match.group() != word:
                continue
            number = _line_of(starts, match.start())
            location = Location(name, number, match.start() - starts[number - 1] + 1)
            called = text[match.end():match.end() + 200].lstrip().startswith("(")
            yield location, location.column + len(word), called


def _files(analysis: Analysis) -> list[str]:
    """The scene's files as locations name them, each once."""
    from castor.analysis.scene import shown_name

    out, seen = [], set()
    for name in [analysis.file] + [shown_name(f) for f in analysis.included] + list(analysis.texts):
        real = name if name.startswith("<") else os.path.realpath(name)
        if real not in seen:
            seen.add(real)
            out.append(name)
    return out


class RenameError(ValueError):
    """A rename that cannot be made, and why (the editor shows it)."""


_NEW_NAME = {"parameter": (re.compile(r"[A-Z][A-Za-z0-9_]*"),
                           "a parameter's name is an uppercase letter, then letters, digits, _"),
             "object": (re.compile(r"[a-z][A-Za-z0-9_]*"),
                        "an object's name is a lowercase letter, then letters, digits, _"),
             "macro": (re.compile(r"[A-Za-z_]\w*"), "a macro's name is letters, digits, _")}


def _kind(analysis: Analysis, name: str) -> tuple[str, Location] | None:
    """What ``name`` names in the scene ("macro", "parameter", "object") and where."""
    found = macros(analysis).get(name)
    if found is not None:
        return "macro", found
    for kind in ("parameter", "object"):
        places = definitions_of(analysis, name, kind)
        if places:
            return kind, places[0]
    return None


def renamable(analysis: Analysis, file: str, line: int, column: int) -> Word:
    """The name under the cursor, if it is an object, a parameter or a macro of the
    scene written outside a comment or a string; else RenameError."""
    text = analysis.source_text(file) or ""
    word = word_at(text, line, column)
    if word is not None and word.text[0] not in "!@$":
        starts = _line_starts(text)
        offset = starts[line - 1] + word.start - 1 if line <= len(starts) else -1
        inside = [m for m in _COMMENT_OR_WORD.finditer(text) if m.start() <= offset < m.end()]
        if inside and inside[0].group() == word.name and _kind(analysis, word.name):
            return word
    if word is None or word.text[0] in "!@$":
        raise RenameError("only an object, a parameter or a macro can be renamed")
    raise RenameError(f"'{word.name}' here is not an object, a parameter or a macro of the scene")


def rename(analysis: Analysis, file: str, line: int, column: int,
           new: str) -> list[tuple[Location, int]]:
    """The places where the name under the cursor is written (each to be
    replaced by ``new``) in the scene's files, never in comments or strings."""
    word = renamable(analysis, file, line, column)
    kind, _ = _kind(analysis, word.name)
    pattern, rule = _NEW_NAME[kind]
    if not pattern.fullmatch(new):
        raise RenameError(f"cannot rename {kind} {word.name} to '{new}': {rule}")
    if new == word.name:
        return []
    taken = _kind(analysis, new)
    if taken is not None:
        where = taken[1]
        raise RenameError(f"'{new}' already names a {taken[0]} ({where.file}:{where.line})")
    return [(location, end) for location, end, called in _occurrences(analysis, word.name)
            if not (kind == "object" and called)]  # sqrt(...) is a function, never an object


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
            x, y = p.pair_names
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
    from castor.analysis import classes

    annotated = classes.annotation_hover(analysis.source_text(file) or "", file, line, column,
                                         word.name, analysis)
    if annotated is not None:  # a word of the comment after a definition
        return (annotated, word) if annotated else None
    name = word.name
    found = macros(analysis).get(name)
    if found is not None:
        source = (analysis.source_text(found.file) or "").split("\n")
        body = _short(source[found.line - 1].strip()) if 0 < found.line <= len(source) else ""
        return f"macro {name}, {found.file}:{found.line}\n{body}", word
    if name[0].isupper():
        repeated = repetition(analysis.source_text(file) or "", line, column, name)
        if repeated is not None:
            return f"{name}: the variable of the repetition {repeated[1]}", word
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
    from castor.analysis.classes import class_of, described

    found = class_of(analysis, where)
    if found is not None and described(found):
        text += f"\n{described(found)}"
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
    # "primitive", "transform", "boolean", "parameter", "object", "macro"; in an
    # annotation (castor.analysis.classes): "class", "type", "setting", "value"
    kind: str
    insert: str
    snippet: str | None = None  # with its arguments as placeholders: cu(${1:R}, ...)


def _snippet(name: str, arguments: list[str]) -> str:
    holes = ", ".join(f"${{{k}:{a}}}" for k, a in enumerate(arguments, 1))
    return f"{name}({holes})"


def completions(analysis: Analysis | None, text: str, file: str, line: int,
                column: int, trigger: str | None = None) -> list[Completion]:
    """After '!', '@' or '$': the vocabulary; in a definition's annotation, after
    ``// [``, the classes and what they take (castor.analysis.classes); else the
    names defined before the cursor. Typing ``trigger`` '[' or '=' asks for
    the annotation's words only."""
    from castor.analysis.classes import ANNOTATION_TRIGGERS, offers

    offered = offers(text, file, line, column, analysis)
    if offered is not None:
        return [Completion(o.label, o.detail, o.documentation, o.kind, o.insert)
                for o in offered]
    if trigger in ANNOTATION_TRIGGERS:
        return []
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
    """The outline of one file: its parameters, objects (with their classes) and
    '>' commands, in order."""
    from castor.analysis.classes import class_of, outline_detail

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
            out.append(Symbol(d.name, "object", d.location, end,
                              outline_detail(class_of(analysis, d.location))))
        else:
            out.append(Symbol(source.strip()[:60] or ">", "frame", d.location, end, "frame"))
    return out
