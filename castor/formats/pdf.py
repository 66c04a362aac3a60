"""PDF: a drawing's sheet for printing, its page the sheet's size.

Written with reportlab (imported only here, only when a PDF is asked for):
it comes as a wheel from PyPI and needs no system library, so ``pip install``
on a fresh machine is enough (cairosvg would need Debian's libcairo). The
page is vector: lines with the pens' widths at the printed size, poché as
filled paths, and text as text in Helvetica (one of PDF's standard fonts,
so a reader can search and copy the dimensions), or, for a text with
characters its encoding lacks (ĉ), in an embedded TrueType font that has
them (castor.formats._pdf_fonts). ``invariant`` mode leaves out the creation
time and a random document id, so the same sheet gives the same bytes.
"""

from __future__ import annotations

import io
from typing import Iterator

import numpy as np

from castor.formats import WriteInfo
from castor.formats._pdf_fonts import font_for


MM = 72 / 25.4  # PDF points per millimetre


def _colour(canvas, name: str | None, fill: bool) -> None:
    from reportlab.lib import colors

    if name is None:
        return
    colour = colors.HexColor(name) if name.startswith("#") else getattr(colors, name)
    (canvas.setFillColor if fill else canvas.setStrokeColor)(colour)


def _outline(page, item, closed: bool = True):
    """The item's loops as a path, each loop closed unless ``closed`` is false."""
    path = page.beginPath()
    for loop in item.loops:
        points = np.asarray(loop).tolist()
        path.moveTo(*points[0])
        for point in points[1:]:
            path.lineTo(*point)
        if closed:
            path.close()
    return path


def _hatched(page, item) -> None:
    """A region hatched with its pattern (castor.drawings.classes.HATCHES) at the
    printed size: white, the pattern's lines clipped to the region, its outline."""
    from reportlab.pdfgen.canvas import FILL_EVEN_ODD

    from castor.drawings.classes import HATCHES
    from castor.drawings.sheet import THIN_PEN

    page.setFillColorRGB(1, 1, 1)
    page.drawPath(_outline(page, item), stroke=0, fill=1, fillMode=FILL_EVEN_ODD)
    page.setFillColorRGB(0, 0, 0)
    points = np.concatenate([np.asarray(loop, float) for loop in item.loops])
    low, high = points.min(axis=0), points.max(axis=0)
    page.saveState()
    page.clipPath(_outline(page, item), stroke=0, fill=0, fillMode=FILL_EVEN_ODD)
    families, period, _ = HATCHES[item.pattern]
    reach = float(np.linalg.norm(high - low)) / 2 + period
    centre = (low + high) / 2
    lines = page.beginPath()
    for angle, offset in families:
        t = np.radians(angle)
        d = np.array([np.cos(t), -np.sin(t)])  # along the line, on paper (y down)
        n = np.array([-d[1], d[0]])
        first = np.floor((centre @ n - reach) / period)
        for k in range(int(2 * reach / period) + 3):
            c = ((first + k + offset) * period)
            base = n * c + d * (centre @ d)
            a, b = base - d * reach, base + d * reach
            lines.moveTo(*a.tolist())
            lines.lineTo(*b.tolist())
    page.setLineWidth(THIN_PEN)
    page.drawPath(lines, stroke=1, fill=0)
    page.restoreState()
    page.setLineWidth(item.pen)
    page.drawPath(_outline(page, item), stroke=1, fill=0)


def export_drawing(sheet) -> bytes:
    """The sheet as PDF bytes, one page of the sheet's size."""
    from reportlab.pdfgen import canvas as pdfcanvas

    out = io.BytesIO()
    page = pdfcanvas.Canvas(out, pagesize=(sheet.width * MM, sheet.height * MM), invariant=1,
                            pageCompression=1)
    page.setTitle(f"{sheet.title}: {sheet.description}")
    page.setCreator("castor")
    _page(page, sheet)
    page.save()
    return out.getvalue()


def export_set(drawing_set) -> bytes:
    """A drawing set as one PDF: its index, then a page per sheet, each page its
    sheet's size."""
    from reportlab.pdfgen import canvas as pdfcanvas

    out = io.BytesIO()
    width, height = index_paper(drawing_set.sheets)
    page = pdfcanvas.Canvas(out, pagesize=(width * MM, height * MM), invariant=1,
                            pageCompression=1)
    project = drawing_set.project.get("project", "") or drawing_set.title
    page.setTitle(f"{project}: drawing set")
    page.setCreator("castor")
    _index(page, drawing_set, width, height)
    for sheet in drawing_set.sheets:
        page.setPageSize((sheet.width * MM, sheet.height * MM))
        _page(page, sheet)
    page.save()
    return out.getvalue()


INDEX_COLUMNS = (("Sheet", 0), ("Title", 30), ("Drawing", 120), ("Scale", 175),
                 ("Paper", 195), ("Rev", 225))
INDEX_MARGIN, INDEX_TOP, INDEX_ROW = 20.0, 45.0, 7.0  # mm: the table's margins, first row, rows
INDEX_WIDTH = INDEX_COLUMNS[-1][1] + 15.0  # mm: the table, its last column 15 mm wide
INDEX_A4 = (297.0, 210.0)  # A4 landscape


def index_paper(sheets) -> tuple[float, float]:
    """The index page's paper (mm): the largest sheet's (the set's cover, as
    large as its largest drawing) when the table's width fits on it and it is
    at least as tall as A4; else A4 landscape. Rows that do not fit go on
    to another index page of the same size."""
    largest = max(sheets, key=lambda s: s.width * s.height)
    if largest.width >= INDEX_WIDTH + 2 * INDEX_MARGIN and largest.height >= INDEX_A4[1]:
        return float(largest.width), float(largest.height)
    return INDEX_A4


def _index(page, drawing_set, width: float, height: float) -> None:
    """The set's first page(s): the project and every sheet's number, title,
    drawing, scale, paper and revision, as their title blocks give them."""
    project = drawing_set.project
    x, right = INDEX_MARGIN, width - INDEX_MARGIN
    title = project.get("project", "") or drawing_set.title
    extra = "   ".join(f"{name} {project[key]}" for key, name in (
        ("number", "No."), ("drawn", "Drawn"), ("checked", "Checked"),
        ("revision", "Rev")) if project.get(key))
    rows = []
    for entry, sheet in zip(drawing_set.entries, drawing_set.sheets):
        paper = entry.paper.name if entry.paper is not None else "-"
        rows.append((entry.number, entry.title or sheet.title, sheet.description,
                     f"1:{entry.scale:g}", paper, sheet.drawing.fields.get("revision", "") or "-"))
    per_page = max(1, int((height - INDEX_TOP - INDEX_MARGIN) // INDEX_ROW))
    for first in range(0, len(rows), per_page):
        page.setPageSize((width * MM, height * MM))
        page.saveState()
        page.translate(0, height * MM)
        page.scale(MM, -MM)
        _fitted_text(page, x, 25.0, title, 7.0, right - x)
        heading = ("Drawing register   " + extra).strip()
        if first:
            heading += f"   (continued, {first + 1}–{min(first + per_page, len(rows))})"
        _fitted_text(page, x, 33.0, heading, 3.5, right - x)
        y = INDEX_TOP
        for name, at in INDEX_COLUMNS:
            _text(page, x + at, y, name, 3.0)
        page.setLineWidth(0.35)
        page.line(x, y + 2, right, y + 2)
        for cells in rows[first:first + per_page]:
            y += INDEX_ROW
            for (name, at), text in zip(INDEX_COLUMNS, cells):
                room = ([a for _, a in INDEX_COLUMNS if a > at] or [INDEX_WIDTH])[0] - at - 3
                _fitted_text(page, x + at, y, text, 3.0, room)
            page.setLineWidth(0.13)
            page.line(x, y + 2, right, y + 2)
        page.restoreState()
        page.showPage()


def _fitted_text(page, x, y, text, size, room):
    """Text made smaller, or cut short, to fit ``room`` mm."""
    from castor.drawings.paper import _fitted

    _text(page, x, y, *_fitted(text, size, room))


def _text(page, x, y, text, size):
    page.saveState()
    page.translate(x, y)
    page.scale(1, -1)
    page.setFont(font_for(text), size)
    page.drawString(0, 0, text)
    page.restoreState()


def _page(page, sheet) -> None:
    """One sheet on the canvas's page, then the page ended."""
    from castor.drawings.paper import CHAIN
    from castor.drawings.sheet import DASH, GAP, Arc, Lines, Shape

    # millimetres, y down, as the sheet is laid out
    page.translate(0, sheet.height * MM)
    page.scale(MM, -MM)
    page.setLineCap(1)
    page.setLineJoin(1)
    for group in [*sheet.layers, *sheet.groups]:
        for item in group.items:
            if isinstance(item, Lines):
                path = page.beginPath()
                for (x0, y0), (x1, y1) in item.segments.tolist():
                    path.moveTo(x0, y0)
                    path.lineTo(x1, y1)
                page.setLineWidth(item.pen)
                if item.dashed or item.chain:
                    page.setDash(list(CHAIN) if item.chain else [DASH, GAP])
                    page.setLineCap(0)
                page.drawPath(path, stroke=1, fill=0)
                if item.dashed or item.chain:
                    page.setDash()
                    page.setLineCap(1)
            elif isinstance(item, Arc):
                # y runs down the page here: an angle on paper is its negative
                path = page.beginPath()
                r = item.radius
                path.arc(item.x - r, item.y - r, item.x + r, item.y + r, -item.end,
                         (item.end - item.start) % 360)
                page.setLineWidth(item.pen)
                page.drawPath(path, stroke=1, fill=0)
            elif isinstance(item, Shape) and item.pattern is not None:
                _hatched(page, item)
            elif isinstance(item, Shape):
                path = _outline(page, item, item.closed)
                page.setLineWidth(item.pen)
                _colour(page, item.fill, True)
                page.drawPath(path, stroke=1, fill=1 if item.fill else 0, fillMode=0)
                page.setFillColorRGB(0, 0, 0)
            else:
                page.saveState()
                page.translate(item.x, item.y)
                page.scale(1, -1)  # text upright again
                page.rotate(item.angle)
                page.setFont(font_for(item.text), item.size)
                if item.anchor == "middle":
                    page.drawCentredString(0, 0, item.text)
                elif item.anchor == "end":
                    page.drawRightString(0, 0, item.text)
                else:
                    page.drawString(0, 0, item.text)
                page.restoreState()
    page.showPage()


def write(sheet, info: WriteInfo) -> Iterator[bytes]:
    """The registry's writer (castor.formats): the sheet as one piece; a drawing
    set (--sheets) as one document, or its first sheet for a %d pattern."""
    from castor.formats.svg import written

    return written(sheet, export_drawing, export_set)


def companions(product, info: WriteInfo) -> dict:
    """A drawing set written to a %d pattern: the files of its other sheets."""
    from castor.formats.svg import sheet_files

    return sheet_files(product, export_drawing)
