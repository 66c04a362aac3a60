"""What the classes and the project add to a sheet (castor.drawings.classes
gives them in page metres): the symbols on paper, the legend of the hatches
beside the scale bar, the project's rows over the title block."""

from __future__ import annotations

import math

import numpy as np

from castor.drawings.annotate import level_text
from castor.drawings.paper import (PROFILE_PEN, POCHE, SEEN_PEN, TEXT, THIN_PEN, TITLE_BLOCK,
                                   Arc, Group, Lines, Shape, Text, _fitted, text_width)

PROJECT_ROWS = 13.0  # mm the project's fields add on top of the title block


def _title_size(drawing) -> tuple[float, float]:
    """The title block's width and height: taller with the project's fields."""
    return TITLE_BLOCK[0], TITLE_BLOCK[1] + (PROJECT_ROWS if getattr(drawing, "fields", None) else 0.0)


LEGEND_ROWS, LEGEND_ROW, LEGEND_SWATCH = 4, 5.5, (8.0, 4.0)  # rows a column, mm


def _legend(drawing) -> list:
    return list(getattr(drawing.symbols, "legend", None) or [])


def _legend_width(drawing) -> float:
    """The legend's width: columns of LEGEND_ROWS swatches with their words."""
    entries = _legend(drawing)
    if not entries:
        return 0.0
    columns = [entries[k:k + LEGEND_ROWS] for k in range(0, len(entries), LEGEND_ROWS)]
    return sum(LEGEND_SWATCH[0] + 6.0 + max(text_width(w, TEXT) for _, w in c) for c in columns)


def _cut_lines(drawing, origin, mm: float) -> dict:
    """Where the set's cut lines (castor.drawings.marks) cross a plan, in paper
    mm (the page's ``origin`` there, ``mm`` a metre): "x" the paper x of those
    running up the page (crossing the bottom and top chains), "y" the paper y
    of those running across it. The chains' values keep clear of them."""
    cuts = {"x": [], "y": []}
    for stroke in getattr(drawing.symbols, "strokes", ()):
        if stroke.chain:
            (x0, y0), (x1, y1) = np.asarray(stroke.points, float)[[0, -1]]
            if abs(x1 - x0) < 1e-9:
                cuts["x"].append(origin[0] + x0 * mm)
            elif abs(y1 - y0) < 1e-9:
                cuts["y"].append(origin[1] - y0 * mm)
    return cuts


def _symbols(drawing, origin, mm: float) -> Group | None:
    """The classes' symbols (castor.drawings.classes) in paper mm: doors'
    leaves and swings, windows, stairs, what is overhead (dashed), room tags
    and a plan's floor level; None without classes."""
    symbols = drawing.symbols
    if symbols is None:
        return None

    def paper_of(points):
        points = np.asarray(points, float)
        return np.stack([points[..., 0] * mm + origin[0], origin[1] - points[..., 1] * mm], axis=-1)

    group = Group("symbols")
    by_pen: dict[tuple, list] = {}
    for stroke in symbols.strokes:
        points = paper_of(stroke.points)
        if stroke.closed:
            points = np.concatenate([points, points[:1]])
        by_pen.setdefault((stroke.pen, stroke.dashed, stroke.chain), []).extend(
            np.stack([points[:-1], points[1:]], axis=1).tolist())
    for (pen, dashed, chain), segments in sorted(by_pen.items()):
        kind = "overhead" if dashed else "cutline" if chain else "symbol"
        group.items.append(Lines(np.array(segments, float).reshape(-1, 2, 2), pen, kind, dashed,
                                 chain))
    for arc in symbols.arcs:
        (x, y), = paper_of([arc.centre]).tolist()
        group.items.append(Arc(x, y, arc.radius * mm, arc.start, arc.end, arc.pen))
    for label in symbols.labels:
        (x, y), = paper_of([label.at]).tolist()
        step = label.size * 1.3
        for k, line in enumerate(label.lines):
            size = label.size if k == 0 else TEXT
            # the line's middle at the label's point, further lines below it
            t = math.radians(label.angle)
            down = k * step + size * 0.35
            group.items.append(Text(x + math.sin(t) * down, y + math.cos(t) * down, line, size,
                                    label.angle, "middle"))
    if symbols.storey is not None and symbols.level_at is not None:
        (x, y), = paper_of([symbols.level_at]).tolist()
        y += 3.0 * 1.3 + 5.5  # below the first room's tag
        text = level_text(symbols.storey[1])
        group.items.append(Shape([np.array([(x - 5.5, y - 2.2), (x - 2.5, y - 2.2), (x - 4.0, y)])],
                                 THIN_PEN, None, True, "symbol"))
        group.items.append(Lines(np.array([[(x - 7.0, y), (x - 1.0, y)]]), THIN_PEN, "symbol"))
        group.items.append(Text(x - 0.5, y - 0.5, text, TEXT, 0.0, "start"))
    return group


def _legend_items(drawing, items, x: float, y: float) -> None:
    """The hatches the sheet uses, each a swatch and its words, in columns from
    (x, y), the lowest row's baseline."""
    w, h = LEGEND_SWATCH
    entries = _legend(drawing)
    for start in range(0, len(entries), LEGEND_ROWS):
        column = entries[start:start + LEGEND_ROWS]
        for k, (pattern, words) in enumerate(column):
            top = y - (len(column) - 1 - k) * LEGEND_ROW - h + 0.5
            box = np.array([(x, top), (x + w, top), (x + w, top + h), (x, top + h)])
            solid = pattern == "SOLID"
            items.append(Shape([box], THIN_PEN, POCHE if solid else "white", True, "legend",
                               None if solid else pattern, words))
            items.append(Text(x + w + 2.0, top + h - 0.5, words, TEXT))
        x += w + 6.0 + max(text_width(words, TEXT) for _, words in column)


def _project_rows(items, x, y, fields: dict) -> None:
    """The project's rows on top of the title block: its title and number; the
    sheet's number, the revision, who drew and who checked it."""
    w = TITLE_BLOCK[0]
    items.append(Shape([np.array([(x, y), (x + w, y), (x + w, y + PROJECT_ROWS),
                                  (x, y + PROJECT_ROWS)])], PROFILE_PEN, None, True, "sheet"))
    items.append(Lines(np.array([[(x, y + 6.5), (x + w, y + 6.5)],
                                 [(x + 40, y + 6.5), (x + 40, y + PROJECT_ROWS)],
                                 [(x + 62, y + 6.5), (x + 62, y + PROJECT_ROWS)],
                                 [(x + 86, y + 6.5), (x + 86, y + PROJECT_ROWS)]]),
                       SEEN_PEN, "sheet"))
    number = fields.get("number", "")
    room = w - 6 - (text_width(number, TEXT) + 3 if number else 0)
    text, size = _fitted(fields.get("project", ""), 3.5, room)
    items.append(Text(x + 3, y + 5.0, text, size))
    if number:
        items.append(Text(x + w - 3, y + 5.0, _fitted(number, TEXT, w / 2)[0], TEXT, 0.0, "end"))
    cells = ((x, 40, "Sheet", fields.get("sheet_number", "")), (x + 40, 22, "Rev", fields.get("revision", "")),
             (x + 62, 24, "Drawn", fields.get("drawn", "")), (x + 86, 24, "Checked", fields.get("checked", "")))
    for left, width, name, value in cells:
        text, size = _fitted(f"{name} {value}".strip(), TEXT, width - 3)
        items.append(Text(left + 1.5, y + 11.3, text, size))
