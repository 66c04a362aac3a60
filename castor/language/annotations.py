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
from dataclasses import dataclass, field

from castor.diagnostics import Location

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


def malformed(line: str, location: Location) -> Malformed | None:
    """The warning about the annotation on the line of a parameter's definition
    (``line``: its text; ``location``: where the definition starts), if malformed:
    what castor and castor --check say as they run."""
    comment = comment_after_statement(line, max(location.column - 1, 0))
    if comment is None:
        return None
    text, start = comment
    return parse_annotation(text, Location(location.file, location.line, start + 1))[1]


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
        annotation = Annotation()
        line = lines[location.line - 1]
        comment = comment_after_statement(line, max(location.column - 1, 0))
        if comment is not None:
            text, start = comment
            annotation, warning = parse_annotation(
                text, Location(location.file, location.line, start + 1))
            if warning is not None:
                warnings.append(warning)
        parameters.append(Parameter(name, value,
                                    expression_text(lines, location.line, location.column),
                                    location, group, annotation))
    return parameters, warnings
