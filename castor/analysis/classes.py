"""What an editor knows of the classes of a scene's objects (LANGUAGE.md §11):
the class each object definition's annotation gives it (for hover and the
outline), and the words that may come next in an annotation being written
(for completion).

The table of classes and the reading of an annotation are
castor.language.classes' (``CLASSES``) and castor.language.annotations' ``object_classes``; this module only
asks them, with the text as the editor holds it. Positions are castor's
(1-based lines and columns), as in castor.analysis.knowledge.
"""

from __future__ import annotations

import re
from typing import NamedTuple

from castor.analysis.scene import Analysis
from castor.diagnostics import Location
from castor.language.classes import BY_NAME, CLASSES, STOREY, ClassInfo

# an object's or a parameter's definition on one line, then '//' and the annotation begun
_ONE_LINE = re.compile(r"^\s*(?P<name>[A-Za-z_]\w*)\s*=[^;]*;\s*(?:/\*.*?\*/\s*)*//(?P<rest>.*)$")


class Classified(NamedTuple):
    """What the annotation of one object definition says: its class, or what is wrong."""

    classification: object  # castor.language.classes.Classification, or None
    problem: object  # castor.language.classes.Problem, or None


def object_classes(analysis: Analysis) -> dict[tuple[str, int, int], Classified]:
    """The class of each annotated object definition (castor.analysis.scene.
    object_classes), by the place of its name (FILE, LINE, COLUMN); kept on the
    analysis (it does not change)."""
    kept = analysis.__dict__.get("object_classes")
    if kept is not None:
        return kept
    from castor.analysis import scene

    found = {(where.file, where.line, where.column): Classified(classification, problem)
             for _, where, classification, problem in scene.object_classes(analysis)}
    analysis.__dict__["object_classes"] = found
    return found


def class_of(analysis: Analysis, location: Location) -> Classified | None:
    """What the annotation of the definition whose name is at ``location`` says."""
    return object_classes(analysis).get((location.file, location.line, location.column))


def described(found: Classified) -> str:
    """An object's class in words, for a hover: ``class: wall (IfcWall)``, its
    predefined type, settings, long name and description each on a line."""
    c = found.classification
    if c is None:
        return f"unclassed: {found.problem.message}" if found.problem is not None else ""
    lines = [f"class: {c.short} ({c.ifc_class})"]
    if c.predefined:
        lines.append(f"predefined type: {c.predefined}")
    if c.settings:
        lines.append("settings: " + ", ".join(f"{k}={v}" for k, v in c.settings))
    if c.long_name:
        lines.append(f"long name: {c.long_name}")
    if c.description:
        lines.append(f"description: {c.description}")
    return "\n".join(lines)


def outline_detail(found: Classified | None) -> str:
    """An object's detail in the outline: its class as annotated, else ``object``."""
    if found is None or found.classification is None:
        return "object"
    return found.classification.text()


def class_text(info: ClassInfo) -> str:
    """What a class is, for a completion's documentation or a hover."""
    lines = [f"{info.ifc} ({info.short})"]
    types = [t for t in info.types if t not in ("userdefined", "notdefined")]
    if types:
        lines.append("types: " + ", ".join(types))
    for s in info.settings:
        lines.append(f"{s.name}={'|'.join(s.values)} (default {s.default})")
    if info.role == "opening":
        lines.append("subtracted from an element ($D), it makes an opening in it")
    elif info.role == "space":
        lines.append('a room, never built: [space "Name"]')
    return "\n".join(lines)


class Offer(NamedTuple):
    """A word an annotation may take next: what castor.analysis.knowledge.Completion
    is made of."""

    label: str
    detail: str
    documentation: str
    kind: str  # "class", "type", "setting", "value"
    insert: str


def _annotation_before(text: str, file: str, line: int, column: int,
                       analysis: Analysis | None):
    """The annotation written before the cursor, from just after its '[', and
    whether its line's definition is a parameter's; None when the cursor is not
    in a bracket opened just after a definition's '//'."""
    lines = text.split("\n")
    if not 0 < line <= len(lines):
        return None
    source = lines[line - 1]
    before = source[:max(column - 1, 0)]
    comment = _comment_start(lines, line, analysis, file)
    if comment is None or comment[0] > len(before):
        return None
    start, name = comment
    opened = before[start:].lstrip()
    if not opened.startswith("[") or "]" in opened:
        return None
    return opened[1:], name[:1].isupper()


def _comment_start(lines: list[str], line: int, analysis: Analysis | None, file: str):
    """Where the text of the '//' comment after a definition on this line starts
    (0-based), and the definition's name; a definition written over several
    lines is found among the analysis's (its lines as the editor holds them)."""
    source = lines[line - 1] if 0 < line <= len(lines) else ""
    match = _ONE_LINE.match(source)
    if match is not None:
        return match.start("rest"), match["name"]
    if analysis is None:
        return None
    from castor.language.annotations import definition_comment

    above = [d for d in analysis.definitions if d.kind in ("object", "parameter")
             and d.location.file == file and d.location.line < line]
    if not above:
        return None
    last = max(above, key=lambda d: (d.location.line, d.location.column))
    found = definition_comment(
        lambda _, number: lines[number - 1] if 0 < number <= len(lines) else None,
        last.location)
    if found is not None and found[1].line == line and not found[2]:
        return found[1].column - 1, last.name
    return None


# the characters whose typing asks an editor for completions in an annotation
ANNOTATION_TRIGGERS = ("[", "=")


def offers(text: str, file: str, line: int, column: int,
           analysis: Analysis | None = None) -> list[Offer] | None:
    """The words an annotation may take at the cursor: after ``// [`` the classes
    (short and IFC names; ``storey`` on a parameter's line), after a class its
    predefined types and its settings ``key=``, after ``key=`` its values. None
    when the cursor is not in an annotation."""
    found = _annotation_before(text, file, line, column, analysis)
    if found is None:
        return None
    written, parameter = found
    if written.count('"') % 2:
        return []  # inside a quoted name
    words = re.findall(r'"[^"]*"|[^\s"]+', written)
    typing = not written or not written[-1].isspace()
    done = words[:-1] if typing and words else words
    if not done:
        if parameter:
            return [Offer(STOREY, "a storey's floor level", 'R1 = 3.0; // [storey "Étage"]',
                          "class", STOREY)]
        return _class_offers()
    info = BY_NAME.get(done[0].lower())
    if info is None:
        return []
    current = words[-1] if typing and words else ""
    if "=" in current:
        key = current.partition("=")[0].lower()
        setting = next((s for s in info.settings if s.name == key), None)
        if setting is None:
            return []
        return [Offer(value, f"{info.short}'s {setting.name}",
                      "the default" if value == setting.default else "", "value", value)
                for value in setting.values]
    given = {w.partition("=")[0].lower() for w in done[1:] if "=" in w}
    typed = any(w.lower() in info.types for w in done[1:])
    out = [] if typed else [Offer(t, f"predefined type of {info.short}", info.ifc, "type", t)
                            for t in info.types]
    out += [Offer(f"{s.name}=", f"{s.name}={'|'.join(s.values)}", f"default {s.default}",
                  "setting", f"{s.name}=") for s in info.settings if s.name not in given]
    return out


def _class_offers() -> list[Offer]:
    out = []
    for info in CLASSES:
        documentation = class_text(info)
        out.append(Offer(info.short, info.ifc, documentation, "class", info.short))
        out.append(Offer(info.ifc, info.short, documentation, "class", info.ifc))
    return out


def annotation_hover(text: str, file: str, line: int, column: int, word: str,
                     analysis: Analysis | None) -> str | None:
    """The hover of a word in the comment after a definition: inside its
    annotation, what the class is, or what a type or setting of it means; ""
    for any other word of the comment (it names nothing of the scene); None
    outside such a comment."""
    lines = text.split("\n")
    source = lines[line - 1] if 0 < line <= len(lines) else ""
    comment = _comment_start(lines, line, analysis, file)
    if comment is None or comment[0] > column - 1:
        return None
    bracket = source[comment[0]:]
    lead = len(bracket) - len(bracket.lstrip())
    inside, closed, _ = bracket.lstrip()[1:].partition("]")
    if not bracket.lstrip().startswith("[") or (
            closed and column - 1 > comment[0] + lead + 1 + len(inside)):
        return ""  # the description, or a comment that is no annotation
    head = (inside.split() or [""])[0]
    info = BY_NAME.get(head.lower())
    if info is None:
        return "a storey: the parameter's value is its floor level" \
            if head.lower() == STOREY else ""
    if word.lower() == head.lower():
        return class_text(info)
    if word.lower() in info.types:
        return f"{word.lower()}: a predefined type of {info.ifc}"
    setting = next((s for s in info.settings if s.name == word.lower()
                    or word.lower() in s.values), None)
    if setting is not None:
        return (f"{info.short}'s {setting.name}: {'|'.join(setting.values)} "
                f"(default {setting.default})")
    return ""
