"""Drawings an architect prints: plans, sections and elevations.

A frame's solids are seen along one of the six orthographic directions;
with a section plane, everything between the viewer and the plane is taken
away, the cut regions become poché and what lies beyond is drawn with its
hidden parts removed. The result is a ``Drawing`` of plain arrays in
metres, which the drawing formats of castor.formats (svg, dxf) write out.
"""

from __future__ import annotations

from castor.drawings.model import Drawing, Layer, View, view_for
from castor.drawings.cut import cut_loops, section_area
from castor.drawings.hidden import seen_lines

__all__ = ["Drawing", "Layer", "View", "draw", "section_area"]


def draw(frame, section=None, view=None, scale: float = 100.0) -> Drawing:
    """The drawing of a mesh frame: cut by ``section`` (castor.options.Section)
    if given, seen from ``view`` (castor.options.View) otherwise."""
    seen = view_for(section, view)
    depth = seen.plane_depth(section)
    objects = [o for o in frame.objects if o.polygon_count]
    cuts = [cut_loops(o, seen, depth) if section is not None else [] for o in objects]
    lines = seen_lines(objects, seen, depth)
    layers = [Layer(o.name or f"object{k + 1}", c, l)
              for k, (o, c, l) in enumerate(zip(objects, cuts, lines))]
    return Drawing(layers, seen, scale)

