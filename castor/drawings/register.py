"""The drawing register (CLI.md, ``--sheets FILE``): the studio's list of
sheets, in TOML, that one run prints as a set.

```toml
[project]
title = "Maison Dupont"      # the title block's fields, for every sheet
number = "2026-014"
drawn = "MB"
checked = "PM"
revision = "B"
sheet = "A3"                 # defaults for every sheet
scale = "1:50"

[[sheet]]
number = "A-101"
title = "Plan du rez-de-chaussée"
drawing = "plan z=1.2"       # plan z=H | section x=V | section y=V | elevation front|back|left|right
```

Read with tomllib; an unknown key, drawing or size, or a value that is not
text, is a usage error (a ValueError) naming the register's line.
"""

from __future__ import annotations

import re
from typing import NamedTuple

PROJECT_KEYS = ("title", "number", "drawn", "checked", "revision", "sheet", "scale")
SHEET_KEYS = ("number", "title", "drawing", "sheet", "scale", "revision")
DRAWINGS = "plan z=H, section x=V, section y=V or elevation front|back|left|right"


class SheetEntry(NamedTuple):
    """One sheet of the register."""

    number: str
    title: str
    drawing: str  # as written: "plan z=1.2"
    section: object  # castor.settings.Section, or None (an elevation)
    view: object  # castor.settings.View
    scale: float
    paper: object  # castor.settings.Paper, or None (as large as the drawing)
    revision: str
    line: int  # of its [[sheet]] header


class Register(NamedTuple):
    path: str
    project: dict  # title, number, drawn, checked, revision (texts given)
    sheets: tuple  # SheetEntry ...

    def project_fields(self) -> tuple[tuple[str, str], ...]:
        """The [project]'s title block fields given, named as the command line's
        (castor.settings.DrawingSettings.fields: ``title`` is ``project``)."""
        fields = {"project": self.project.get("title", ""),
                  "number": self.project.get("number", ""),
                  "drawn": self.project.get("drawn", ""),
                  "checked": self.project.get("checked", ""),
                  "revision": self.project.get("revision", "")}
        return tuple((k, v) for k, v in fields.items() if v)

    def overridden(self, fields) -> list[str]:
        """Of the command line's title block fields (name, text) (--project ...),
        the names of those the register gives another value of, for every
        sheet or some: where it gives one, the register's is printed."""
        given = dict(self.project_fields())
        return [name for name, text in fields if given.get(name, text) != text
                or (name == "revision" and any(e.revision not in ("", text) for e in self.sheets))]

    def fields(self, entry: SheetEntry) -> tuple[tuple[str, str], ...]:
        """The title block's fields of one sheet (castor.settings.DrawingSettings.fields)."""
        fields = {**dict(self.project_fields()), "revision": entry.revision,
                  "sheet_number": entry.number, "sheet_title": entry.title}
        return tuple((k, v) for k, v in fields.items() if v)


def _lines(text: str) -> dict:
    """Where each key stands: (table, index, key) -> line number, the tables'
    own headers under key None."""
    where: dict = {}
    table, index = "", -1
    counts: dict[str, int] = {}
    for number, line in enumerate(text.splitlines(), 1):
        stripped = line.strip()
        header = re.match(r"\[\[\s*([^\]]+?)\s*\]\]", stripped) or re.match(r"\[\s*([^\]]+?)\s*\]",
                                                                             stripped)
        if header:
            table = header[1]
            index = counts.get(table, 0)
            counts[table] = index + 1
            where[(table, index, None)] = number
            continue
        key = re.match(r'("[^"]*"|[A-Za-z0-9_-]+)\s*=', stripped)
        if key:
            where.setdefault((table, index, key[1].strip('"')), number)
    return where


def _closest(word: str, choices) -> str:
    import difflib

    found = difflib.get_close_matches(word, list(choices), 1, 0.6)
    return f" (did you mean {found[0]}?)" if found else ""


class _Reader:
    """Checks a register's values, each mistake a ValueError at its line."""

    def __init__(self, path: str, text: str):
        self.path = path
        self.where = _lines(text)

    def fail(self, table, index, key, message):
        where = self.where
        line = where.get((table, index, key)) or where.get((table, index, None)) or 1
        raise ValueError(f"{self.path}:{line}: {message}")

    def text(self, table, index, key, value) -> str:
        if not isinstance(value, (str, int, float)) or isinstance(value, bool):
            self.fail(table, index, key, f"'{key}' takes text, such as {key} = \"...\"")
        return str(value)

    def keys(self, table, index, values: dict, known: tuple, header: str) -> None:
        for key, value in values.items():
            if key not in known:
                self.fail(table, index, key, f"unknown key '{key}' in {header}"
                          f"{_closest(key, known)}; it takes {', '.join(known)}")
            self.text(table, index, key, value)

    def paper_and_scale(self, table, index, values: dict, fallback):
        paper, scale = fallback
        if "sheet" in values:
            try:
                paper = parse_sheet(self.text(table, index, "sheet", values["sheet"]))
            except ValueError:
                self.fail(table, index, "sheet", f"unknown sheet size '{values['sheet']}': A4, "
                          "A3, A2, A1 or A0 (landscape), or A3-portrait ...")
        if "scale" in values:
            try:
                scale = parse_scale(self.text(table, index, "scale", values["scale"]))
            except ValueError:
                self.fail(table, index, "scale", f"scale takes 1:N such as \"1:50\", not "
                          f"'{values['scale']}'")
        return paper, scale

    def drawing(self, index, values: dict):
        """The section and view a sheet's ``drawing`` names."""
        from castor.settings import View

        if "drawing" not in values:
            self.fail("sheet", index, None, f"the sheet has no drawing: drawing = \"{DRAWINGS}\"")
        drawing = str(values["drawing"]).strip()
        match = re.fullmatch(r"(plan|section|elevation)\s+(.+)", drawing, re.IGNORECASE)
        try:
            if not match:
                raise ValueError
            kind, rest = match[1].lower(), match[2].strip()
            if kind == "elevation":
                if rest.lower() not in ("front", "back", "left", "right"):
                    raise ValueError
                return drawing, None, View(rest.lower(), 0.0, 0.0)
            section = parse_section(rest)
            if (kind == "plan") != (section.axis == "z"):
                raise ValueError
            return drawing, section, None
        except ValueError:
            self.fail("sheet", index, "drawing", f"unknown drawing '{drawing}': {DRAWINGS}")


# the values as the command line's options take them (castor.options parses
# those; a register is read below the command line, so here again)
def parse_sheet(text: str):
    from castor.settings import PAPER_SIZES, Paper

    match = re.fullmatch(r"\s*(A[0-4])(-portrait)?\s*", text, re.IGNORECASE)
    if not match:
        raise ValueError(text)
    size = match[1].upper()
    width, height = PAPER_SIZES[size]
    return Paper(f"{size}-portrait", height, width) if match[2] else Paper(size, width, height)


def parse_scale(text: str) -> float:
    import math

    match = re.fullmatch(r"\s*1\s*:\s*(\S+)\s*", text)
    try:
        value = float(match[1]) if match else math.nan
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and value > 0):
        raise ValueError(text)
    return value


def parse_section(text: str):
    import math

    from castor.settings import Section

    match = re.fullmatch(r"\s*([xyzXYZ])\s*=\s*(\S+)\s*", text)
    if not match:
        raise ValueError(text)
    value = float(match[2])  # a ValueError when it is no number
    if not math.isfinite(value):
        raise ValueError(text)
    return Section(match[1].lower(), value)


def _read(path: str) -> tuple[str, dict]:
    try:
        import tomllib
    except ImportError:  # Python 3.10: the same module, as tomli (pyproject.toml)
        import tomli as tomllib

    try:
        with open(path, "rb") as handle:
            raw = handle.read()
    except OSError as exc:
        raise ValueError(f"--sheets: cannot read {path}: {exc.strerror or exc}") from None
    try:
        text = raw.decode("utf-8")
        if text.startswith("\ufeff"):  # a byte-order mark (Notepad's): skipped, as in scenes
            text = text[1:]
        return text, tomllib.loads(text)
    except UnicodeDecodeError:
        raise ValueError(f"--sheets: {path} is not UTF-8 text") from None
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(_syntax(path, text, str(exc))) from None


def _syntax(path: str, text: str, said: str) -> str:
    """tomllib's message (``Illegal character '\\n' (at line 2, column 16)``) in
    the register's other errors' form: ``PATH:LINE:COL: what``."""
    match = re.fullmatch(r"(.*?)\s*\(at line (\d+), column (\d+)\)", said, re.DOTALL)
    if match:
        what, line, column = match[1], int(match[2]), int(match[3])
    else:  # "(at end of document)"
        what = re.sub(r"\s*\(at end of document\)$", "", said)
        lines = text.splitlines() or [""]
        line, column = len(lines), len(lines[-1]) + 1
    what = what[:1].lower() + what[1:]
    hint = " (is a string's closing quote missing?)" if what == "illegal character '\\n'" else ""
    return f"{path}:{line}:{column}: not valid TOML: {what}{hint}"


def parse_register(path: str) -> Register:
    """The register in the TOML file ``path``; ValueError (a usage error) at a
    line that names an unknown key, drawing or size."""
    text, data = _read(path)
    reader = _Reader(path, text)
    for name in data:
        if name not in ("project", "sheet"):
            reader.fail(name, 0, None, f"unknown table [{name}]"
                        f"{_closest(name, ('project', 'sheet'))}; a register has [project] and "
                        "[[sheet]] tables")
    project = data.get("project", {})
    if not isinstance(project, dict):
        reader.fail("", -1, "project", "'project' is a table: [project]")
    sheets = data.get("sheet", [])
    if not isinstance(sheets, list) or not sheets:
        reader.fail("", -1, None, "a register lists its sheets as [[sheet]] tables, at least one")
    reader.keys("project", 0, project, PROJECT_KEYS, "[project]")
    defaults = reader.paper_and_scale("project", 0, project, (None, 100.0))
    entries = []
    for index, values in enumerate(sheets):
        if not isinstance(values, dict):
            reader.fail("sheet", index, None, "each sheet is a [[sheet]] table")
        reader.keys("sheet", index, values, SHEET_KEYS, "[[sheet]]")
        drawing, section, view = reader.drawing(index, values)
        paper, scale = reader.paper_and_scale("sheet", index, values, defaults)
        entries.append(SheetEntry(str(values.get("number", index + 1)), str(values.get("title", "")),
                                  drawing, section, view, scale, paper,
                                  str(values.get("revision", project.get("revision", ""))),
                                  reader.where.get(("sheet", index, None), 1)))
    numbers = [e.number for e in entries]
    for index, entry in enumerate(entries):
        if numbers.index(entry.number) != index:
            reader.fail("sheet", index, "number", f"sheet number '{entry.number}' is given twice")
    kept = {k: str(v) for k, v in project.items() if k not in ("sheet", "scale")}
    return Register(path, kept, tuple(entries))
