"""DXF: a drawing for CAD, in metres, each object a layer named after it.

Written with ezdxf (imported only here, only when a DXF is asked for).
Cut regions are solid HATCH entities outlined by closed LWPOLYLINEs of the
cut lineweight (0.50 mm); seen edges are LINEs, profile 0.35 mm, the others
0.18 mm. Coordinates are the page's in scene units (metres), so the drawing
has its true size in CAD. The dimensions are real DIMENSION entities of a
dimension style ``CASTOR`` (metres, two decimals, oblique ticks, text as
high as the sheet's other text at the drawing's scale: capitals 1.8 mm),
measured between points on the cut regions' edges, so a CAD program keeps
them live. Levels, the scale bar,
north arrow and title block are drawn in model space where the sheet puts
them, at the sheet's scale: plotted at 1:N the model is the sheet.
"""

from __future__ import annotations

import io
import re
from contextlib import contextmanager
from typing import Iterator

import numpy as np

from castor.formats import WriteInfo


def _layer_names(names: list[str], taken: set[str]) -> list[str]:
    """Valid, distinct DXF layer names made from the objects' names."""
    seen = {t.lower() for t in taken}
    out = []
    for name in names:
        base = re.sub(r'[<>/\\":;?*|=`,\x00-\x1f]', "_", name).strip() or "object"
        candidate, n = base, 2
        while candidate.lower() in seen or candidate == "0":
            candidate, n = f"{base}-{n}", n + 1
        seen.add(candidate.lower())
        out.append(candidate)
    return out


# a DXF text's height is its capitals' height; the sheet's sizes (SVG's
# font-size, PDF's) are the em's, Helvetica's capitals 0.72 of it
CAP_HEIGHT = 0.72


def _weight(pen: float) -> int:
    """A pen (mm) as a DXF lineweight (hundredths of a millimetre)."""
    return int(round(pen * 100))


def _dimension_style(doc, mm: float, style: str = "CASTOR") -> str:
    """The style ``CASTOR`` (a set's: one per scale, ``CASTOR_50``), also made
    the header's current dimension variables (some CAD programs, LibreCAD among
    them, draw every dimension with the header's)."""
    if style in doc.dimstyles:
        return style
    from castor.drawings.paper import TEXT

    k = 1 / mm  # metres per paper millimetre
    values = {
        "dimtxt": TEXT * CAP_HEIGHT * k,  # as the other text: DXF's heights are capitals'
        "dimtsz": 1.25 * k, "dimasz": 1.25 * k, "dimexe": 1.5 * k,
        "dimexo": 2 * k, "dimdle": 1.5 * k, "dimgap": 0.6 * k, "dimdec": 2, "dimlunit": 2,
        "dimdsep": ord("."), "dimtad": 1, "dimtih": 0, "dimtoh": 0, "dimzin": 0, "dimtmove": 2,
        "dimlwd": 13, "dimlwe": 13, "dimscale": 1.0,
    }
    for name, value in values.items():
        doc.header[f"${name.upper()}"] = value
    doc.header["$DIMSTYLE"] = style
    doc.dimstyles.new(style, dxfattribs=values)
    return style


class _To:
    """Where a sheet's paper items go: model space in metres (shifted along x:
    the sheets of a set side by side) or a layout's paper space in mm."""

    def __init__(self, sheet, shift: float = 0.0, paper: bool = False, dashed: str = "CASTOR_DASHED",
                 style: str = "CASTOR"):
        self.sheet, self.shift, self.paper, self.dashed = sheet, shift, paper, dashed
        self.chain = CHAINED + dashed.removeprefix(DASHED)  # CASTOR_CHAIN_50 beside CASTOR_DASHED_50
        self.paper_style = style  # the dimension style of its scale
        self.unit = 1.0 if paper else 1.0 / sheet.mm  # drawing units per paper mm

    def points(self, points) -> np.ndarray:
        points = np.asarray(points, float)
        if self.paper:
            return np.stack([points[..., 0], self.sheet.height - points[..., 1]], axis=-1)
        return self.sheet.to_metres(points) + np.array([self.shift, 0.0])

    def model(self, points) -> np.ndarray:
        """Page metres (the drawing's own points) where they go in model space
        (unshifted: the very numbers, -0.0 and all)."""
        if not self.shift:
            return np.asarray(points, float)
        return np.asarray(points, float) + np.array([self.shift, 0.0])

    def point(self, p):
        """One page point where it goes in model space, as the tuple it was."""
        if not self.shift or p is None:
            return p
        return (float(p[0]) + self.shift, float(p[1]))


def _sheet_items(msp, to: _To, items, layer):
    """Lines, shapes and text of the sheet's paper, where ``to`` puts them."""
    from ezdxf.enums import TextEntityAlignment

    from castor.drawings.sheet import Arc, Lines, Shape

    for item in items:
        if isinstance(item, Lines):
            attributes = {"layer": layer, "lineweight": _weight(item.pen)}
            if item.dashed:
                attributes["linetype"] = to.dashed
            elif item.chain:
                attributes["linetype"] = to.chain
            for (a, b) in to.points(item.segments).tolist():
                msp.add_line(a, b, dxfattribs=attributes)
        elif isinstance(item, Arc):
            (x, y), = to.points(np.array([[item.x, item.y]])).tolist()
            msp.add_arc((x, y), item.radius * to.unit, item.start, item.end,
                        dxfattribs={"layer": layer, "lineweight": _weight(item.pen)})
        elif isinstance(item, Shape):
            loops = [to.points(loop) for loop in item.loops]
            if item.pattern is not None:
                _hatch(msp, to.unit, loops, item.pattern, layer)
            elif item.fill not in (None, "white"):
                hatch = msp.add_hatch(color=7, dxfattribs={"layer": layer})
                for loop in loops:
                    hatch.paths.add_polyline_path([tuple(p) for p in loop.tolist()], is_closed=True)
            for loop in loops:
                msp.add_lwpolyline([tuple(p) for p in loop.tolist()], close=item.closed,
                                   dxfattribs={"layer": layer, "lineweight": _weight(item.pen)})
        else:
            (x, y), = to.points(np.array([[item.x, item.y]])).tolist()
            text = msp.add_text(item.text, height=item.size * CAP_HEIGHT * to.unit,
                                rotation=item.angle, dxfattribs={"layer": layer})
            align = {"start": TextEntityAlignment.LEFT, "middle": TextEntityAlignment.CENTER,
                     "end": TextEntityAlignment.RIGHT}[item.anchor]
            text.set_placement((x, y), align=align)


DASHED, CHAINED = "CASTOR_DASHED", "CASTOR_CHAIN"


def _linetypes(doc, mm: float, name: str = DASHED) -> str:
    """ISO 128's dashed line at the printed size: DASH mm dashes, GAP mm gaps."""
    from castor.drawings.sheet import DASH, GAP

    k = 1 / mm
    if name not in doc.linetypes:
        doc.linetypes.add(name, pattern=[(DASH + GAP) * k, DASH * k, -GAP * k],
                          description="Dashed __ __ __")
    return name


def _chain_linetype(doc, mm: float, name: str) -> str:
    """ISO 128's long-dashed dotted line at the printed size (a section's cut line)."""
    from castor.drawings.paper import CHAIN

    k = 1 / mm
    if name not in doc.linetypes:
        dash, gap, dot, gap2 = CHAIN
        doc.linetypes.add(name, pattern=[sum(CHAIN) * k, dash * k, -gap * k, dot * k, -gap2 * k],
                          description="Chain __ . __ . __")
    return name


def _hatch(msp, unit: float, loops, pattern: str, layer: str) -> None:
    """A region hatched with its pattern (castor.drawings.classes.HATCHES): a
    real HATCH of that name, scaled so that its lines are as far apart on the
    printed sheet as in the SVG and PDF."""
    from castor.drawings.classes import HATCHES

    _, period, base = HATCHES[pattern]
    hatch = msp.add_hatch(color=7, dxfattribs={"layer": layer})
    hatch.set_pattern_fill(pattern, color=7, scale=period * unit / base)
    for loop in loops:
        hatch.paths.add_polyline_path([tuple(p) for p in np.asarray(loop).tolist()], is_closed=True)


def _tidy(value: float) -> float:
    """A coordinate of the extents, rounded to 1e-9 m (-0.0 written as 0)."""
    return round(float(value), 9) + 0.0


def _document():
    import ezdxf

    with _repeatable():
        doc = ezdxf.new("R2010")
    doc.units = ezdxf.units.M
    doc.header["$MEASUREMENT"] = 1  # metric
    doc.header["$LWDISPLAY"] = 1  # show lineweights
    doc.header["$INSUNITS"] = 6  # metres
    return doc


def _model(doc, msp, to: _To, paper_items: bool) -> None:
    """One sheet's drawing in model space, in metres (shifted by ``to``): each
    object a layer, its dimensions, levels and symbols; its paper's items
    (border, title block, scale bar) too when ``paper_items``."""
    from castor.drawings.sheet import CUT_PEN, Lines

    sheet = to.sheet
    drawing = sheet.drawing
    annotation = {"dimensions", "levels", "sheet", "symbols"}
    names = _layer_names([l.name for l in drawing.layers], annotation | {"ground"})
    if drawing.symbols is not None:
        to.dashed = _linetypes(doc, sheet.mm, to.dashed)
        if any(item.chain for group in sheet.groups for item in group.items
               if isinstance(item, Lines)):
            to.chain = _chain_linetype(doc, sheet.mm, to.chain)

    def outline(loop, name):
        points = [tuple(p) for p in to.model(loop).tolist()]
        msp.add_lwpolyline(points, close=True,
                           dxfattribs={"layer": name, "lineweight": _weight(CUT_PEN)})
        return points

    for layer, name in zip(drawing.layers, names):
        if name not in doc.layers:
            doc.layers.add(name)
        if layer.regions is not None:
            for region in layer.regions:
                loops = [to.model(loop) for loop in region.loops]
                if region.pattern == "SOLID":
                    hatch = msp.add_hatch(color=8, dxfattribs={"layer": name})
                    hatch.set_solid_fill(color=8)
                    for loop in loops:
                        hatch.paths.add_polyline_path([tuple(p) for p in loop.tolist()],
                                                      is_closed=True)
                else:
                    _hatch(msp, 1 / sheet.mm, loops, region.pattern, name)
                for loop in region.loops:
                    outline(loop, name)
        elif layer.cuts:
            hatch = msp.add_hatch(color=8, dxfattribs={"layer": name})
            hatch.set_solid_fill(color=8)
            for loop in layer.cuts:
                hatch.paths.add_polyline_path(outline(loop, name), is_closed=True)
        pens = {item.kind: item.pen for group in sheet.layers for item in group.items
                if isinstance(item, Lines)}
        for kind, mask in (("seen", ~layer.profile), ("profile", layer.profile)):
            weight = _weight(pens.get(kind, 0.18 if kind == "seen" else 0.35))
            for a, b in to.model(layer.lines[mask]).tolist():
                msp.add_line(a, b, dxfattribs={"layer": name, "lineweight": weight})
    for group in sheet.layers[len(drawing.layers):]:  # the ground line
        if group.name not in doc.layers:
            doc.layers.add(group.name)
        _sheet_items(msp, to, group.items, group.name)
    if "dimensions" not in doc.layers:
        doc.layers.add("dimensions")
    style = None
    if sheet.dimensions:
        style = _dimension_style(doc, sheet.mm, to.paper_style)
    for d in sheet.dimensions:
        dim = msp.add_linear_dim(base=to.point(d.base), p1=to.point(d.p1), p2=to.point(d.p2),
                                 location=to.point(d.text_at), angle=d.angle,
                                 text="<>" if d.shown else " ",  # " ": no text (DXF's way)
                                 dimstyle=style, override={"dimexo": d.offset},
                                 dxfattribs={"layer": "dimensions"})
        dim.render()
        # the measurement itself (group code 42), as CAD programs write it
        dim.dimension.dxf.actual_measurement = dim.dimension.get_measurement()
    for group in sheet.groups:
        if group.name == "dimensions" or (group.name == "sheet" and not paper_items):
            continue  # the DIMENSION entities stand for them; the paper is a layout's
        if group.name not in doc.layers:
            doc.layers.add(group.name)
        _sheet_items(msp, to, group.items, group.name)


def _written(doc) -> bytes:
    """The document's bytes, the same at every run for the same drawing (as the
    PDF's): ezdxf's fixed dates and GUIDs in place of the time of writing and
    random ones, and the CLASSES section in the order of their names (ezdxf
    adds two of them in an order that varies from run to run)."""
    from collections import OrderedDict

    doc.classes.add_required_classes(doc.dxfversion)
    doc.classes.classes = OrderedDict(sorted(doc.classes.classes.items()))
    stream = io.StringIO()
    with _repeatable():
        doc.write(stream)
    return stream.getvalue().encode("utf-8")


@contextmanager
def _repeatable():
    """While in the block, ezdxf writes fixed metadata (its option made for
    comparing files: dates of 2000-01-01, constant GUIDs) instead of the time."""
    import ezdxf

    before = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        yield
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = before


def export_drawing(sheet) -> bytes:
    """The sheet as a DXF (R2010) document's bytes: drawn in model space as it is
    printed at its scale."""
    doc = _document()
    msp = doc.modelspace()
    to = _To(sheet)
    to.paper_style = "CASTOR"
    _model(doc, msp, to, True)
    # the header's extents: the sheet's paper, in metres, to the nanometre (the
    # coordinates' last bits of rounding, -6.999999999999999, are no size)
    (x0, y0), (x1, y1) = sheet.to_metres(np.array([[0.0, 0.0], [sheet.width, sheet.height]])).tolist()
    msp.reset_extents((_tidy(min(x0, x1)), _tidy(min(y0, y1)), 0.0),
                      (_tidy(max(x0, x1)), _tidy(max(y0, y1)), 0.0))
    return _written(doc)


SPACING = 20.0  # paper mm between the sheets' drawings side by side in model space


def export_set(drawing_set) -> bytes:
    """A drawing set as one DXF: each sheet's drawing in model space, in metres,
    side by side; each sheet a paper-space layout named after its number, its
    border, title block, scale bar and legend in paper millimetres, and a
    viewport that shows its drawing at the sheet's scale (so that a CAD program
    plots the layout at 1:1 with the pens' true widths)."""
    doc = _document()
    # a viewport shows the model's linetypes in model units at its scale: each
    # scale's CASTOR_DASHED_N is 3 mm dashes on paper (1 would read them as paper mm)
    doc.header["$PSLTSCALE"] = 0
    msp = doc.modelspace()
    shift = 0.0
    used: set[str] = set()
    for entry, sheet in zip(drawing_set.entries, drawing_set.sheets):
        scale = sheet.drawing.scale
        # the sheet's paper, in model metres, starts where the last one ended
        (x0, _), (x1, _) = sheet.to_metres(np.array([[0.0, 0.0], [sheet.width, sheet.height]]))
        left = min(x0, x1)
        to = _To(sheet, shift - left, dashed=f"{DASHED}_{scale:g}")
        to.paper_style = f"CASTOR_{scale:g}"
        _model(doc, msp, to, False)
        name = _layout_name(entry.number, used)
        layout = doc.layouts.new(name)
        layout.page_setup(size=(sheet.width, sheet.height), margins=(0, 0, 0, 0), units="mm")
        paper = _To(sheet, paper=True, dashed=to.dashed)
        for group in sheet.groups:
            if group.name == "sheet":
                if group.name not in doc.layers:
                    doc.layers.add(group.name)
                _sheet_items(layout, paper, group.items, group.name)
        # the viewport: the whole paper inside the border, looking at the sheet's
        # paper in model space at 1:N
        centre_paper = (sheet.width / 2, sheet.height / 2)
        (cx, cy), = to.points(np.array([[sheet.width / 2, sheet.height / 2]]))
        viewport = layout.add_viewport(center=centre_paper, size=(sheet.width, sheet.height),
                                       view_center_point=(float(cx), float(cy)),
                                       view_height=sheet.height / sheet.mm)
        viewport.dxf.status = 2
        shift += (x1 - x0 if x1 > x0 else x0 - x1) + SPACING / sheet.mm
    if "Layout1" in doc.layouts and len(drawing_set.sheets):
        doc.layouts.delete("Layout1")  # ezdxf's own empty layout
    return _written(doc)


def _layout_name(number: str, used: set) -> str:
    base = re.sub(r'[<>/\\":;?*|=`,\x00-\x1f]', "_", number).strip() or "Sheet"
    name, n = base, 2
    while name.lower() in used or name.lower() == "model":
        name, n = f"{base}-{n}", n + 1
    used.add(name.lower())
    return name


def write(sheet, info: WriteInfo) -> Iterator[bytes]:
    """The registry's writer (castor.formats): the sheet as one piece; a drawing
    set (--sheets) as one document, or its first sheet for a %d pattern."""
    from castor.formats.svg import written

    return written(sheet, export_drawing, export_set)


def companions(product, info: WriteInfo) -> dict:
    """A drawing set written to a %d pattern: the files of its other sheets."""
    from castor.formats.svg import sheet_files

    return sheet_files(product, export_drawing)
