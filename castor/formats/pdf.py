"""PDF: a drawing's sheet for printing, its page the sheet's size.

Written with reportlab (imported only here, only when a PDF is asked for):
it comes as a wheel from PyPI and needs no system library, so ``pip install``
on a fresh machine is enough (cairosvg would need Debian's libcairo). The
page is vector: lines with the pens' widths at the printed size, poché as
filled paths, and text as text in Helvetica (one of PDF's standard fonts,
so a reader can search and copy the dimensions). ``invariant`` mode leaves
out the creation time and a random document id, so the same sheet gives the
same bytes.
"""

from __future__ import annotations

import io
from typing import Iterator

import numpy as np

from castor.formats import WriteInfo


MM = 72 / 25.4  # PDF points per millimetre


def _colour(canvas, name: str | None, fill: bool) -> None:
    from reportlab.lib import colors

    if name is None:
        return
    colour = colors.HexColor(name) if name.startswith("#") else getattr(colors, name)
    (canvas.setFillColor if fill else canvas.setStrokeColor)(colour)


def _outline(page, item):
    path = page.beginPath()
    for loop in item.loops:
        points = np.asarray(loop).tolist()
        path.moveTo(*points[0])
        for point in points[1:]:
            path.lineTo(*point)
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
    first = drawing_set.sheets[0]
    page = pdfcanvas.Canvas(out, pagesize=(first.width * MM, first.height * MM), invariant=1,
                            pageCompression=1)
    project = drawing_set.register.project.get("title", "") or first.title
    page.setTitle(f"{project}: drawing set")
    page.setCreator("castor")
    _index(page, drawing_set, first.width, first.height)
    for sheet in drawing_set.sheets:
        page.setPageSize((sheet.width * MM, sheet.height * MM))
        _page(page, sheet)
    page.save()
    return out.getvalue()


INDEX_COLUMNS = (("Sheet", 0), ("Title", 30), ("Drawing", 120), ("Scale", 175),
                 ("Paper", 195), ("Rev", 225))


def _index(page, drawing_set, width: float, height: float) -> None:
    """The set's first page: the project and every sheet's number, title,
    drawing, scale, paper and revision."""
    from castor.drawings.sheet import _fitted

    register = drawing_set.register
    page.saveState()
    page.translate(0, height * MM)
    page.scale(MM, -MM)
    x, y = 20.0, 25.0
    _text(page, x, y, register.project.get("title", "") or drawing_set.sheets[0].title, 7.0)
    extra = "   ".join(f"{name} {register.project[key]}" for key, name in (
        ("number", "No."), ("drawn", "Drawn"), ("checked", "Checked"),
        ("revision", "Rev")) if register.project.get(key))
    _text(page, x, y + 8, ("Drawing register   " + extra).strip(), 3.5)
    y += 20
    for name, at in INDEX_COLUMNS:
        _text(page, x + at, y, name, 3.0)
    page.setLineWidth(0.35)
    page.line(x, y + 2, width - 20, y + 2)
    for entry, sheet in zip(drawing_set.entries, drawing_set.sheets):
        y += 7
        paper = entry.paper.name if entry.paper is not None else "-"
        cells = (entry.number, entry.title or sheet.title, sheet.description,
                 f"1:{entry.scale:g}", paper, entry.revision)
        for (name, at), text in zip(INDEX_COLUMNS, cells):
            room = ([a for _, a in INDEX_COLUMNS if a > at] or [width - 40])[0] - at - 3
            _text(page, x + at, y, _fitted(text, 3.0, room)[0], 3.0)
        page.setLineWidth(0.13)
        page.line(x, y + 2, width - 20, y + 2)
    page.showPage()


def _text(page, x, y, text, size):
    page.saveState()
    page.translate(x, y)
    page.scale(1, -1)
    page.setFont("Helvetica", size)
    page.drawString(0, 0, text)
    page.restoreState()


def _page(page, sheet) -> None:
    """One sheet on the canvas's page, then the page ended."""
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
                if item.dashed:
                    page.setDash(DASH, GAP)
                    page.setLineCap(0)
                page.drawPath(path, stroke=1, fill=0)
                if item.dashed:
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
                path = page.beginPath()
                for loop in item.loops:
                    points = np.asarray(loop).tolist()
                    path.moveTo(*points[0])
                    for point in points[1:]:
                        path.lineTo(*point)
                    if item.closed:
                        path.close()
                page.setLineWidth(item.pen)
                _colour(page, item.fill, True)
                page.drawPath(path, stroke=1, fill=1 if item.fill else 0, fillMode=0)
                page.setFillColorRGB(0, 0, 0)
            else:
                page.saveState()
                page.translate(item.x, item.y)
                page.scale(1, -1)  # text upright again
                page.rotate(item.angle)
                page.setFont("Helvetica", item.size)
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
