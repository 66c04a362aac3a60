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
import unicodedata

from castor.drawings.model import Drawing, Layer, view_for
from castor.drawings.cut import cut_loops, section_area
from castor.drawings.hidden import seen_lines

__all__ = ["Drawing", "Layer", "draw", "section_area", "sheet_of", "title_of"]


def draw(frame, section=None, view=None, scale: float = 100.0) -> Drawing:
    """The drawing of a mesh frame: cut by ``section`` (castor.settings.Section)
    if given, seen from ``view`` (castor.settings.View) otherwise."""
    seen = view_for(section, view)
    depth = seen.plane_depth(section)
    objects = [o for o in frame.objects if o.polygon_count]
    cuts = [cut_loops(o, seen, depth) if section is not None else [] for o in objects]
    lines = seen_lines(objects, seen, depth)
    layers = [Layer(o.name or f"object{k + 1}", c, l, p)
              for k, (o, c, (l, p)) in enumerate(zip(objects, cuts, lines))]
    return Drawing(layers, seen, scale, section)


def title_of(tree, title: str | None) -> str:
    """The sheet's title: --title, else the name of the '>' object, else the file's."""
    if title:
        # control characters have no place on a sheet (and XML refuses most)
        title = "".join(" " if unicodedata.category(c) in ("Cc", "Cs") else c for c in title)
        return title.strip() or "castor"
    if len(tree.objects) == 1 and tree.objects[0].name:
        return tree.objects[0].name
    return os.path.basename(tree.location.file) or "castor"


def sheet_of(tree, frame, settings, title: str | None = None, warn=None):
    """The frame drawn and laid on its sheet (castor.drawings.sheet.Sheet), as
    ``settings`` (castor.settings.DrawingSettings) ask, titled ``title``
    (--title); what a drawing format writes. ``warn(message)`` hears of
    dimensions left out; a drawing larger than its paper is a CastorError at
    the '>' command."""
    from castor.diagnostics import CastorError
    from castor.drawings.sheet import DoesNotFit, layout

    result = draw(frame, settings.section, settings.view, settings.scale)
    try:
        return layout(result, settings.sheet, title_of(tree, title), tree.where, warn)
    except DoesNotFit as exc:
        raise CastorError(str(exc), tree.location) from None
