"""The marks a plan of a drawing set carries (CLI.md, the drawing register):
each section's cut line, short and heavy beyond the drawing at both ends,
with arrows for the direction looked in and the section's sheet number; each
elevation's mark, a triangle on the side it is seen from pointing at the
building, with its sheet number. In page metres, sized in paper mm."""

from __future__ import annotations

import numpy as np

from castor.drawings.classes import Label, Stroke, Symbols

GAP, LENGTH, ARROW = 3.0, 7.0, 2.5  # mm: from the drawing, the cut line's ends, arrows
BEYOND = 27.0  # mm from the drawing to an elevation mark's tip: past the dimension chains
# an elevation is seen from: the side of the plan it stands on, and the way it looks
ELEVATIONS = {"front": ("bottom", (0.0, 1.0)), "back": ("top", (0.0, -1.0)),
              "left": ("left", (1.0, 0.0)), "right": ("right", (-1.0, 0.0))}


def mark_plans(drawings: list, entries) -> None:
    """Every plan of the set gets the marks of the set's sections and elevations."""
    for drawing in drawings:
        if drawing.section is None or drawing.section.axis != "z":
            continue
        if drawing.symbols is None:
            drawing.symbols = Symbols()
        k = drawing.scale / 1000.0  # metres per paper millimetre
        (x0, y0), (x1, y1) = drawing.box()
        for entry in entries:
            if entry.section is not None and entry.section.axis in "xy":
                _section_mark(drawing.symbols, entry, (x0, y0, x1, y1), k)
            elif entry.section is None and entry.view is not None:
                _elevation_mark(drawing.symbols, entry, (x0, y0, x1, y1), k)


def _section_mark(symbols, entry, box, k: float) -> None:
    x0, y0, x1, y1 = box
    v = entry.section.value
    if entry.section.axis == "x":  # seen looking towards +x
        if not x0 <= v <= x1:
            return
        ends = [((v, y0 - GAP * k), (v, y0 - (GAP + LENGTH) * k)),
                ((v, y1 + GAP * k), (v, y1 + (GAP + LENGTH) * k))]
        look = np.array([1.0, 0.0])
    else:  # y: towards +y
        if not y0 <= v <= y1:
            return
        ends = [((x0 - GAP * k, v), (x0 - (GAP + LENGTH) * k, v)),
                ((x1 + GAP * k, v), (x1 + (GAP + LENGTH) * k, v))]
        look = np.array([0.0, 1.0])
    for inner, outer in ends:
        outer = np.array(outer)
        symbols.strokes.append(Stroke(np.array([inner, outer]), pen=0.5))
        tip = outer + look * ARROW * 1.6 * k
        side = np.array([-look[1], look[0]]) * ARROW * 0.5 * k
        symbols.strokes.append(Stroke(np.array([outer, tip, tip - look * ARROW * k + side, tip,
                                                tip - look * ARROW * k - side]), pen=0.25))
        # the sheet number beyond the arrow's tip, clear of the cut line
        from castor.drawings.sheet import text_width

        reach = (text_width(entry.number, 2.5) / 2 + 1.0) if look[0] else 2.5
        at = tip + look * reach * k
        symbols.labels.append(Label((float(at[0]), float(at[1])), (entry.number,), 2.5))


def _elevation_mark(symbols, entry, box, k: float) -> None:
    x0, y0, x1, y1 = box
    side, look = ELEVATIONS[entry.view.name]
    middle = {"bottom": ((x0 + x1) / 2, y0), "top": ((x0 + x1) / 2, y1),
              "left": (x0, (y0 + y1) / 2), "right": (x1, (y0 + y1) / 2)}[side]
    look = np.array(look)
    tip = np.array(middle) - look * BEYOND * k
    base = tip - look * 4.0 * k
    across = np.array([-look[1], look[0]]) * 3.0 * k
    symbols.strokes.append(Stroke(np.array([tip, base + across, base - across]), pen=0.25,
                                  closed=True))
    at = base - look * 3.0 * k
    symbols.labels.append(Label((float(at[0]), float(at[1])), (entry.number,), 2.5))
