"""The marks a plan of a drawing set carries (CLI.md, the drawing register):
each section's cut line, short and heavy beyond the drawing at both ends,
joined across the plan by a thin long-dashed dotted line (ISO 128), with
arrows for the direction looked in and the section's sheet number; each
elevation's mark, a triangle on the side it is seen from pointing at the
building, with its sheet number. In page metres, sized in paper mm.

Marks stand beyond the dimension chains on their side (GAP mm past the
outermost), so that no mark or its number touches a chain's line or value;
an elevation's mark that would meet a mark already placed on its side moves
along that side until it is clear."""

from __future__ import annotations

import numpy as np

from castor.drawings.classes import Label, Stroke, Symbols

GAP, LENGTH, ARROW = 3.0, 7.0, 2.5  # mm: past the chains, the cut line's ends, arrows
CHAIN_PEN = 0.18  # mm: the cut line between its heavy ends
LABEL = 2.5  # mm: the sheet numbers' height
# an elevation is seen from: the side of the plan it stands on, and the way it looks
ELEVATIONS = {"front": ("bottom", (0.0, 1.0)), "back": ("top", (0.0, -1.0)),
              "left": ("left", (1.0, 0.0)), "right": ("right", (-1.0, 0.0))}


def mark_plans(drawings: list, entries) -> None:
    """Every plan of the set gets the marks of the set's sections and elevations."""
    from castor.drawings.sheet import annotation_depths

    for drawing in drawings:
        if drawing.section is None or drawing.section.axis != "z":
            continue
        if drawing.symbols is None:
            drawing.symbols = Symbols()
        k = drawing.scale / 1000.0  # metres per paper millimetre
        (x0, y0), (x1, y1) = drawing.box()
        depth = annotation_depths(drawing)
        for entry in entries:  # the sections first: the elevations' marks make way
            if entry.section is not None and entry.section.axis in "xy":
                _section_mark(drawing.symbols, entry, (x0, y0, x1, y1), k, depth)
        for entry in entries:
            if entry.section is None and entry.view is not None:
                _elevation_mark(drawing.symbols, entry, (x0, y0, x1, y1), k, depth)


def _label_box(at, text: str, k: float) -> np.ndarray:
    """The page box of a sheet number centred at ``at`` (its middle line)."""
    from castor.drawings.sheet import text_width

    w, h = text_width(text, LABEL) / 2 * k, LABEL * 0.7 * k
    return np.array([(at[0] - w, at[1] - h), (at[0] + w, at[1] + h)])


def _section_mark(symbols, entry, box, k: float, depth: dict) -> None:
    x0, y0, x1, y1 = box
    v = entry.section.value
    if entry.section.axis == "x":  # seen looking towards +x
        if not x0 <= v <= x1:
            return
        b, t = (depth["bottom"] + GAP) * k, (depth["top"] + GAP) * k
        ends = [((v, y0 - b), (v, y0 - b - LENGTH * k)), ((v, y1 + t), (v, y1 + t + LENGTH * k))]
        look = np.array([1.0, 0.0])
    else:  # y: towards +y
        if not y0 <= v <= y1:
            return
        l, r = (depth["left"] + GAP) * k, (depth["right"] + GAP) * k
        ends = [((x0 - l, v), (x0 - l - LENGTH * k, v)), ((x1 + r, v), (x1 + r + LENGTH * k, v))]
        look = np.array([0.0, 1.0])
    from castor.drawings.sheet import text_width

    # ISO 128's cutting plane: a thin long-dashed dotted line across the plan
    # joining the two heavy ends (as ArchiCAD's and Revit's section marks do)
    symbols.strokes.append(Stroke(np.array([ends[0][0], ends[1][0]]), pen=CHAIN_PEN, chain=True))
    for inner, outer in ends:
        outer = np.array(outer)
        symbols.strokes.append(Stroke(np.array([inner, outer]), pen=0.5))
        tip = outer + look * ARROW * 1.6 * k
        side = np.array([-look[1], look[0]]) * ARROW * 0.5 * k
        symbols.strokes.append(Stroke(np.array([outer, tip, tip - look * ARROW * k + side, tip,
                                                tip - look * ARROW * k - side]), pen=0.25))
        # the sheet number beyond the arrow's tip, clear of the cut line
        reach = (text_width(entry.number, LABEL) / 2 + 1.0) if look[0] else 2.5
        at = tip + look * reach * k
        symbols.labels.append(Label((float(at[0]), float(at[1])), (entry.number,), LABEL))
        label = _label_box(at, entry.number, k)
        points = np.concatenate([[inner, outer, tip, tip - look * ARROW * k + side,
                                  tip - look * ARROW * k - side], label])
        symbols.marks.append(np.array([points.min(axis=0), points.max(axis=0)]))


def _meets(box: np.ndarray, boxes: list) -> bool:
    return any(np.all(box[0] < other[1]) and np.all(other[0] < box[1]) for other in boxes)


def _elevation_mark(symbols, entry, box, k: float, depth: dict) -> None:
    x0, y0, x1, y1 = box
    side, look = ELEVATIONS[entry.view.name]
    middle = np.array({"bottom": ((x0 + x1) / 2, y0), "top": ((x0 + x1) / 2, y1),
                       "left": (x0, (y0 + y1) / 2), "right": (x1, (y0 + y1) / 2)}[side])
    look = np.array(look)
    across = np.array([-look[1], look[0]])
    tip0 = middle - look * (depth[side] + GAP + 3.0) * k
    from castor.drawings.sheet import text_width

    # the number beyond the triangle's base: below or above it, or beside it, clear of it
    beyond = 3.0 if look[1] else text_width(entry.number, LABEL) / 2 + 1.5
    for step in range(40):  # along the side, either way in turn, until clear of the others
        shift = (step + 1) // 2 * (1 if step % 2 else -1) * 2.0 * k
        tip = tip0 + across * shift
        base = tip - look * 4.0 * k
        at = base - look * beyond * k
        corners = np.array([tip, base + across * 3.0 * k, base - across * 3.0 * k])
        points = np.concatenate([corners, _label_box(at, entry.number, k)])
        extent = np.array([points.min(axis=0), points.max(axis=0)])
        if not _meets(extent, symbols.marks):
            break
    symbols.strokes.append(Stroke(corners, pen=0.25, closed=True))
    symbols.labels.append(Label((float(at[0]), float(at[1])), (entry.number,), LABEL))
    symbols.marks.append(extent)
