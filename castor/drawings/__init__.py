"""Drawings an architect prints: plans, sections and elevations.

A frame's solids are seen along one of the six orthographic directions;
with a section plane, everything between the viewer and the plane is taken
away, the cut regions become poché and what lies beyond is drawn with its
hidden parts removed. The result is a ``Drawing`` of plain arrays in
metres; castor.drawings.sheet lays it on paper with its dimensions, levels
and title block (a ``Sheet``), which the drawing formats of castor.formats
(svg, pdf, dxf) write out.
"""

from __future__ import annotations

import os
import re
import unicodedata

from castor.drawings.model import Drawing, Layer, view_for
from castor.drawings.cut import cut_loops, section_area
from castor.drawings.hidden import seen_lines

__all__ = ["Drawing", "DrawingSet", "Layer", "draw", "section_area", "set_of", "sheet_of",
           "title_of"]


def draw(frame, section=None, view=None, scale: float = 100.0) -> Drawing:
    """The drawing of a mesh frame: cut by ``section`` (castor.settings.Section)
    if given, seen from ``view`` (castor.settings.View) otherwise."""
    seen = view_for(section, view)
    depth = seen.plane_depth(section)
    sources = [k for k, o in enumerate(frame.objects) if o.polygon_count]
    objects = [frame.objects[k] for k in sources]
    cuts = [cut_loops(o, seen, depth) if section is not None else [] for o in objects]
    lines = seen_lines(objects, seen, depth)
    layers = [Layer(o.name or f"object{k + 1}", c, l, p, source)
              for k, (o, c, (l, p), source) in enumerate(zip(objects, cuts, lines, sources))]
    return Drawing(layers, seen, scale, section)


def plain(text: str) -> str:
    """A text for a sheet: control characters (which XML refuses) made spaces."""
    return "".join(" " if unicodedata.category(c) in ("Cc", "Cs") else c for c in text).strip()


def title_of(tree, title: str | None) -> str:
    """The sheet's title: --title, else the name of the '>' object, else the file's."""
    if title:
        return plain(title) or "castor"
    if len(tree.objects) == 1 and tree.objects[0].name:
        return tree.objects[0].name
    return os.path.basename(tree.location.file) or "castor"


def sheet_of(tree, frame, settings, title: str | None = None, warn=None, facetizer=None):
    """The frame drawn and laid on its sheet (castor.drawings.sheet.Sheet), as
    ``settings`` (castor.settings.DrawingSettings) ask, titled ``title``
    (--title); what a drawing format writes. ``warn(message)`` hears of
    dimensions left out; a drawing larger than its paper is a CastorError at
    the '>' command. With the facetizer that made ``frame`` and classes in the
    scene, the drawing shows what its elements are (castor.drawings.classes)."""
    from castor.diagnostics import CastorError
    from castor.drawings.sheet import DoesNotFit, layout

    result = draw(frame, settings.section, settings.view, settings.scale)
    result.fields = {name: plain(str(text)) for name, text in settings.fields if plain(str(text))}
    if facetizer is not None and tree.classes is not None:
        from castor.drawings.classes import classify
        from castor.quantities import Takeoff

        classify(result, Takeoff(tree, facetizer, warn=warn), warn)
    try:
        return layout(result, settings.sheet, title_of(tree, title), tree.where, warn)
    except DoesNotFit as exc:
        raise CastorError(str(exc), tree.location) from None


class DrawingSet:
    """A drawing register printed (--sheets): each sheet laid out, in the
    register's order, with the register and -o's path."""

    def __init__(self, register, entries: list, sheets: list, target: str | None,
                 number: int = 1, project: dict | None = None, title: str = ""):
        self.register = register  # castor.drawings.register.Register
        # the set's title without a project title: --title, or the '>' object's name
        self.title = title or (sheets[0].title if sheets else "castor")
        # the project's title block fields (project, number, drawn, checked,
        # revision): the register's [project], else the command line's
        self.project = project if project is not None else dict(register.project_fields())
        self.entries = entries  # its SheetEntry for each sheet
        self.sheets = sheets  # castor.drawings.sheet.Sheet ...
        # -o's path: a %d pattern gives a file per sheet (castor.formats.svg.sheet_files)
        self.target = target
        self.number = number  # the frame's: its first sheet's file takes it, the next ones follow


def set_of(tree, frame, settings, title: str | None = None, warn=None, facetizer=None,
           target: str | None = None) -> DrawingSet:
    """Every sheet of the register (``settings.register``) drawn from the frame
    and laid out; plans carry the set's section and elevation marks. A sheet
    whose drawing does not fit its paper is a CastorError at its line of the
    register, naming the scale that fits."""
    from castor.diagnostics import CastorError, Location
    from castor.drawings.marks import mark_plans
    from castor.drawings.sheet import DoesNotFit, layout

    register = settings.register
    takeoff = None
    if facetizer is not None and tree.classes is not None:
        from castor.quantities import Takeoff

        takeoff = Takeoff(tree, facetizer, warn=warn)  # shared by the sheets: solids made once
    drawings = []
    for entry in register.sheets:
        drawing = draw(frame, entry.section, entry.view, entry.scale)
        fields = tuple(settings.fields) + register.fields(entry)
        drawing.fields = {name: plain(str(text)) for name, text in fields if plain(str(text))}
        if takeoff is not None:
            from castor.drawings.classes import classify

            classify(drawing, takeoff, warn)
        drawings.append(drawing)
    mark_plans(drawings, register.sheets)
    sheets = []
    for entry, drawing in zip(register.sheets, drawings):
        try:
            sheets.append(layout(drawing, entry.paper, title_of(tree, title), tree.where, warn))
        except DoesNotFit as exc:
            # in the register's words: its scale and sheet keys, not the options
            words = re.sub(r"--scale (1:\d+), or a larger --sheet", r'scale = "\1", or a larger sheet',
                           str(exc)).replace("use a larger --sheet", "use a larger sheet")
            raise CastorError(f"sheet {entry.number} ({entry.drawing}): {words}",
                              Location(register.path, entry.line, 1)) from None
    project = {name: plain(str(text)) for name, text in
               tuple(settings.fields) + register.project_fields() if plain(str(text))}
    return DrawingSet(register, list(register.sheets), sheets, target, tree.number, project,
                      title_of(tree, title))
