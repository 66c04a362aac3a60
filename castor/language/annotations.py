"""Parameter annotations (LANGUAGE.md §10): the comment after a parameter's ';'.

The forms are those of OpenSCAD's customizer::

    /* [Walls] */          a group: the parameters after it, until the next group
    H = 2.9;  // [2.5:0.1:4] height of the walls    a slider (min:step:max)
    N = 3;    // [1:6] windows per side             a slider (min:max, step 1)
    T = 30;   // [20, 30, 45] roof pitch            a choice (also [10:small, 20:big])
    E = 0.2;  // thickness of the walls             a description only
    /* [Hidden] */         the parameters after it are not offered

They are read from the source text as written (the built-in preprocessor keeps
comments, but an annotation belongs to a file's line, so the original text is
read here): the pipeline says where each parameter is first defined, this
module says what the comment on that line means. A malformed annotation is a
warning at its position, never an error, and its parameter is a plain number.
"""

from __future__ import annotations

import math
import re
from typing import TYPE_CHECKING
from dataclasses import dataclass, field

from castor.diagnostics import Location

if TYPE_CHECKING:  # the classes' reader imports this module's comment finder
    from castor.language.classes import Classification, Problem

HIDDEN = "Hidden"

_GROUP = re.compile(r"/\*\s*\[([^\]\n]*)\]\s*\*/")
_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_IS_NUMBER = re.compile(rf"\s*({_NUMBER})\s*")


@dataclass
class Annotation:
    """What the comment on a parameter's line says of it."""

    description: str = ""
    minimum: float | None = None  # a slider: minimum, step, maximum
    step: float | None = None
    maximum: float | None = None
    choices: list[tuple[float, str]] | None = None  # a list: (value, label)

    @property
    def control(self) -> str:
        if self.choices is not None:
            return "choice"
        if self.minimum is not None:
            return "slider"
        return "number"

    def text(self) -> str:
        """The annotation in words, for a hover."""
        if self.choices is not None:
            what = "one of " + ", ".join(label for _, label in self.choices)
        elif self.minimum is not None:
            what = f"from {_plain(self.minimum)} to {_plain(self.maximum)} by {_plain(self.step)}"
        else:
            what = ""
        return "; ".join(part for part in (self.description, what) if part)


@dataclass
class Malformed:
    """A malformed annotation: a warning at its position, never an error."""

    message: str
    location: Location


@dataclass
class Parameter:
    """A parameter as a customizer offers it (``castor --params``)."""

    name: str
    value: float | None
    expression: str
    location: Location
    group: str | None
    annotation: Annotation = field(default_factory=Annotation)
    storey: str | None = None  # [storey "Name"] (LANGUAGE.md §11): a storey's floor level

    @property
    def hidden(self) -> bool:
        return self.group is not None and self.group.strip().lower() == HIDDEN.lower()

    def as_json(self) -> dict:
        a = self.annotation
        out = {"name": self.name, "value": _json_number(self.value),
               "expression": self.expression,
               "location": f"{self.location.file}:{self.location.line}",
               "group": self.group, "hidden": self.hidden, "control": a.control,
               "description": a.description}
        if a.control == "slider":
            out["range"] = {"min": a.minimum, "step": a.step, "max": a.maximum}
        if a.choices is not None:
            out["choices"] = [{"value": v, "label": label} for v, label in a.choices]
        if self.storey is not None:
            out["storey"] = self.storey
        return out


def _json_number(value):
    if value is None or not math.isfinite(value):
        return None
    return int(value) if value == int(value) and abs(value) < 2 ** 53 else value


def _plain(value: float | None) -> str:
    return "?" if value is None else f"{value:g}"


def comment_after_statement(line: str, start: int) -> tuple[str, int] | None:
    """The '//' comment after the ';' that ends the statement begun at column
    ``start`` (0-based) of ``line``, and the column (0-based) where its text
    starts; None when the line has none."""
    index = start
    while index < len(line):
        if line.startswith("/*", index):
            end = line.find("*/", index + 2)
            if end < 0:
                return None
            index = end + 2
            continue
        if line.startswith("//", index):
            return None  # a comment before the ';': the statement goes on below
        if line[index] == ";":
            rest = line[index + 1:]
            found = rest.find("//")
            if found < 0 or rest[:found].strip():
                return None
            begin = index + 1 + found + 2
            return line[begin:], begin
        index += 1
    return None


def parse_annotation(text: str, location: Location) -> tuple[Annotation, Malformed | None]:
    """An annotation from a comment's text; ``location`` is where the text starts.
    A malformed bracket gives a plain number input and a warning."""
    stripped = text.strip()
    lead = len(text) - len(text.lstrip())
    if not stripped.startswith("["):
        return Annotation(description=stripped), None
    close = stripped.find("]")
    where = Location(location.file, location.line, location.column + lead)
    if close < 0:
        return Annotation(description=stripped), Malformed(
            "parameter annotation: '[' without its ']'; write [MIN:MAX], [MIN:STEP:MAX] "
            "or [A, B, C]", where)
    inside, description = stripped[1:close], stripped[close + 1:].strip()
    annotation = Annotation(description=description)
    problem = None
    if "," in inside:
        problem = _choices(inside, annotation)
    elif ":" in inside:
        problem = _range(inside, annotation)
    else:
        number = _IS_NUMBER.fullmatch(inside)
        if number and float(number[1]) > 0:
            annotation.minimum, annotation.step, annotation.maximum = 0.0, 1.0, float(number[1])
        else:
            problem = f"[{inside}] is neither a maximum, a range nor a list of choices"
    if problem is not None:
        return Annotation(description=description), Malformed(
            f"parameter annotation: {problem}; the parameter is offered as a number input",
            where)
    return annotation, None


def _range(inside: str, annotation: Annotation) -> str | None:
    parts = inside.split(":")
    numbers = [_IS_NUMBER.fullmatch(p) for p in parts]
    if len(parts) not in (2, 3) or not all(numbers):
        return (f"[{inside}] is not a range; write [MIN:MAX] or [MIN:STEP:MAX] with numbers")
    values = [float(m[1]) for m in numbers]
    if len(values) == 2:
        low, high = values
        step = 1.0
    else:
        low, step, high = values
    if not all(math.isfinite(v) for v in values):
        return f"[{inside}] has a number out of range"
    if low >= high:
        return f"the range [{inside}] has its minimum {low:g} not below its maximum {high:g}"
    if step <= 0:
        return f"the range [{inside}] has a step {step:g} that is not positive"
    annotation.minimum, annotation.step, annotation.maximum = low, step, high
    return None


def _choices(inside: str, annotation: Annotation) -> str | None:
    choices = []
    for part in inside.split(","):
        value, _, label = part.partition(":")
        number = _IS_NUMBER.fullmatch(value)
        if number is None:
            return (f"the choice '{part.strip()}' is not a number (castor's parameters are "
                    f"numbers; label one as [10:small, 20:large])")
        v = float(number[1])
        if not math.isfinite(v):
            return f"the choice '{part.strip()}' is out of range"
        choices.append((v, label.strip() or value.strip()))
    annotation.choices = choices
    return None


def groups_of(text: str) -> list[tuple[int, str]]:
    """The group markers of a file: (line number, group name), in order."""
    out = []
    for number, line in enumerate(text.split("\n"), 1):
        match = _GROUP.search(line)
        if match and line.strip().startswith("/*"):
            out.append((number, match[1].strip()))
    return out


def expression_text(lines: list[str], line: int, column: int) -> str:
    """The text of a definition's expression: from after its '=' (the definition
    starting at ``line``, ``column``, 1-based) to its ';', comments removed."""
    pieces = []
    index = line - 1
    at = column - 1
    started = False
    while 0 <= index < len(lines) and index < line - 1 + 50:
        text = lines[index]
        i = at
        while i < len(text):
            if text.startswith("/*", i):
                end = text.find("*/", i + 2)
                if end < 0:
                    break
                i = end + 2
                pieces.append(" ")
                continue
            if text.startswith("//", i):
                break
            ch = text[i]
            if not started:
                if ch == "=":
                    started = True
                i += 1
                continue
            if ch == ";":
                return " ".join("".join(pieces).split())
            pieces.append(ch)
            i += 1
        pieces.append(" ")
        index += 1
        at = 0
    return " ".join("".join(pieces).split())


def definition_comment(line_of, location: Location) -> tuple[str, Location, bool] | None:
    """The '//' comment after the ';' that ends the definition starting at
    ``location`` (the ';' may be on a later line), where its text starts, and
    whether another statement stands before the definition on that line (an
    annotation then says nothing of it: LANGUAGE.md §11). None when there is
    no such comment, or when another statement follows on its line (the
    comment is that one's). ``line_of(file, number)``: a line's text or None."""
    number, index = location.line, max(location.column - 1, 0)
    first = line_of(location.file, number)
    if first is None:
        return None
    before = first[:index]
    for _ in range(MAX_LINES):
        line = line_of(location.file, number)
        if line is None:
            return None
        while True:
            mark = _MARK.search(line, index)
            if mark is None or mark.group() == "//":
                break  # (a comment inside the statement: it goes on below)
            if mark.group() == "/*":
                end = line.find("*/", mark.end())
                if end < 0:
                    return None
                index = end + 2
                continue
            rest = line[mark.end():]
            found = rest.find("//")
            if found < 0 or _without_comments(rest[:found]).strip():
                return None
            begin = mark.end() + found + 2
            crowded = number == location.line and bool(_without_comments(before).strip())
            return line[begin:], Location(location.file, number, begin + 1), crowded
        number += 1
        index = 0
    return None


_MARK = re.compile(r"/\*|//|;")
MAX_LINES = 200  # a definition's ';' is looked for this far below its name


def _without_comments(text: str) -> str:
    return re.sub(r"/\*.*?\*/", " ", text)


def outside(annotation: Annotation, value: float | None) -> str | None:
    """What is wrong when a slider's or a list's parameter holds a value the
    control cannot show (``H = 9; // [1:0.5:5]``), or None."""
    if value is None or not math.isfinite(value):
        return None
    slack = 1e-9 * max(1.0, abs(value))
    if annotation.choices is not None:
        if any(abs(value - v) <= slack for v, _ in annotation.choices):
            return None
        listed = ", ".join(_plain(v) for v, _ in annotation.choices)
        return f"the value {_plain(value)} is not among the choices {listed}"
    if annotation.minimum is not None and not (
            annotation.minimum - slack <= value <= annotation.maximum + slack):
        return (f"the value {_plain(value)} is outside the slider's range "
                f"{_plain(annotation.minimum)} to {_plain(annotation.maximum)}")
    return None


def read_comment(text: str, location: Location, value: float | None = None,
                 crowded: bool = False) -> tuple[Annotation, str | None, Malformed | None]:
    """A parameter's comment (``location``: where its text starts): its
    annotation, the storey it declares (LANGUAGE.md §11) and what is wrong
    with it, a value out of the control's reach included. ``crowded``: another
    statement stands before the definition on its line (a storey is then not
    said of it)."""
    from castor.language.classes import is_class_annotation, read_parameter_annotation

    if is_class_annotation(text):
        storey, problem = read_parameter_annotation("", text, location)
        lead = text.lstrip()
        close = lead.find("]")
        description = lead[close + 1:].strip() if close >= 0 else ""
        annotation = Annotation(description=description)
        if crowded:
            at = Location(location.file, location.line,
                          location.column + len(text) - len(text.lstrip()))
            return annotation, None, Malformed(
                "annotation: this line holds more than one statement, so the annotation does "
                "not say which it is for; put the definition on a line of its own", at)
        if problem is not None:
            return annotation, None, Malformed(problem.message, problem.location)
        return annotation, storey.name, None
    annotation, warning = parse_annotation(text, location)
    if warning is None:
        wrong = outside(annotation, value)
        if wrong is not None:
            lead = len(text) - len(text.lstrip())
            warning = Malformed(f"parameter annotation: {wrong}; the parameter is offered as a "
                                f"number input",
                                Location(location.file, location.line, location.column + lead))
            annotation = Annotation(description=annotation.description)
    return annotation, None, warning


def malformed(line: str, location: Location, value: float | None = None) -> Malformed | None:
    """The warning about the annotation on the line of a parameter's definition
    (``line``: its text; ``location``: where the definition starts; ``value``:
    the parameter's value there, None when not known), if any: what castor and
    castor --check say as they run."""
    comment = comment_after_statement(line, max(location.column - 1, 0))
    if comment is None:
        return None
    text, start = comment
    return read_comment(text, Location(location.file, location.line, start + 1), value,
                        _crowded(line, location))[2]


def _crowded(line: str, location: Location) -> bool:
    """Whether a statement stands before the one starting at ``location`` on its line."""
    return bool(_without_comments(line[:max(location.column - 1, 0)]).strip())


def storey_of(line: str, location: Location) -> str | None:
    """The storey name a parameter's annotation declares (``[storey "Étage"]``),
    "" for ``[storey]`` without a name, None when it declares none."""
    comment = comment_after_statement(line, max(location.column - 1, 0))
    if comment is None or "storey" not in comment[0]:
        return None
    text, start = comment
    return read_comment(text, Location(location.file, location.line, start + 1), None,
                        _crowded(line, location))[1]


def annotate(definitions, source_text) -> tuple[list[Parameter], list[Malformed]]:
    """The parameters a customizer offers, from the pipeline's definitions.

    ``definitions``: (name, location, value) of each parameter definition in the
    order they ran; ``source_text(file)``: the file's text as written, or None.
    Each parameter is taken at its first definition."""
    parameters: list[Parameter] = []
    warnings: list[Malformed] = []
    seen: set[str] = set()
    lines_of: dict[str, list[str] | None] = {}
    groups: dict[str, list[tuple[int, str]]] = {}
    for name, location, value in definitions:
        if name in seen:
            continue
        seen.add(name)
        if location.file not in lines_of:
            text = source_text(location.file)
            lines_of[location.file] = text.split("\n") if text is not None else None
            groups[location.file] = groups_of(text) if text is not None else []
        lines = lines_of[location.file]
        if lines is None or not 0 < location.line <= len(lines):
            parameters.append(Parameter(name, value, "", location, None))
            continue
        group = None
        for number, title in groups[location.file]:
            if number < location.line:
                group = title
        annotation, storey = Annotation(), None
        line = lines[location.line - 1]
        comment = comment_after_statement(line, max(location.column - 1, 0))
        if comment is not None:
            text, start = comment
            annotation, storey, warning = read_comment(
                text, Location(location.file, location.line, start + 1), value,
                _crowded(line, location))
            if warning is not None:
                warnings.append(warning)
            if storey == "":
                storey = name
        parameters.append(Parameter(name, value,
                                    expression_text(lines, location.line, location.column),
                                    location, group, annotation, storey))
    return parameters, warnings


def object_classes(definitions, line_of) -> list[tuple[str, Location, Classification | None,
                                                       Problem | None]]:
    """The class of each object definition of a scene, for an editor (hover,
    outline, completion, warnings as you type): ``definitions`` are (name,
    location of the name) of the object definitions, ``line_of(file, number)``
    a line's text as written. Only the definitions with a bracketed annotation
    are listed, with what it says or what is wrong with it."""
    from castor.language.classes import Problem, read_object_annotation

    found = []
    for name, location in definitions:
        comment = definition_comment(line_of, location)
        if comment is None or not comment[0].lstrip().startswith("["):
            continue
        text, at, crowded = comment
        if crowded:
            lead = len(text) - len(text.lstrip())
            found.append((name, location, None, Problem(
                f"annotation: this line holds more than one statement, so the annotation does "
                f"not say which it is for; put the definition of '{name}' on a line of its own",
                at._replace(column=at.column + lead))))
            continue
        classification, problem = read_object_annotation(text, at)
        found.append((name, location, classification, problem))
    return found
