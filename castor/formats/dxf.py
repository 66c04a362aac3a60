"""DXF: a drawing for CAD, in metres, each object a layer named after it.

Written with ezdxf (imported only here, only when a DXF is asked for).
Cut regions are solid HATCH entities outlined by closed LWPOLYLINEs of the
cut lineweight (0.50 mm); seen edges are LINEs, profile 0.35 mm, the others
0.18 mm. Coordinates are the page's in scene units (metres), so the drawing
has its true size in CAD. The dimensions are real DIMENSION entities of a
dimension style ``CASTOR`` (metres, two decimals, oblique ticks, text
2.5 mm high at the drawing's scale), measured between points on the cut
regions' edges, so a CAD program keeps them live. Levels, the scale bar,
north arrow and title block are drawn in model space where the sheet puts
them, at the sheet's scale: plotted at 1:N the model is the sheet.
"""

from __future__ import annotations

import io
import re
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


def _weight(pen: float) -> int:
    """A pen (mm) as a DXF lineweight (hundredths of a millimetre)."""
    return int(round(pen * 100))


def _dimension_style(doc, mm: float):
    """The style ``CASTOR``, also made the header's current dimension
    variables (some CAD programs, LibreCAD among them, draw every dimension
    with the header's)."""
    k = 1 / mm  # metres per paper millimetre
    values = {
        "dimtxt": 2.5 * k, "dimtsz": 1.25 * k, "dimasz": 1.25 * k, "dimexe": 1.5 * k,
        "dimexo": 2 * k, "dimdle": 1.5 * k, "dimgap": 0.6 * k, "dimdec": 2, "dimlunit": 2,
        "dimdsep": ord("."), "dimtad": 1, "dimtih": 0, "dimtoh": 0, "dimzin": 0, "dimtmove": 2,
        "dimlwd": 13, "dimlwe": 13, "dimscale": 1.0,
    }
    for name, value in values.items():
        doc.header[f"${name.upper()}"] = value
    doc.header["$DIMSTYLE"] = "CASTOR"
    return doc.dimstyles.new("CASTOR", dxfattribs=values)


def _sheet_items(msp, sheet, items, layer):
    """Lines, shapes and text of the sheet's paper, in model-space metres."""
    from ezdxf.enums import TextEntityAlignment

    from castor.drawings.sheet import Arc, Lines, Shape

    for item in items:
        if isinstance(item, Lines):
            attributes = {"layer": layer, "lineweight": _weight(item.pen)}
            if item.dashed:
                attributes["linetype"] = DASHED
            for (a, b) in sheet.to_metres(item.segments).tolist():
                msp.add_line(a, b, dxfattribs=attributes)
        elif isinstance(item, Arc):
            (x, y), = sheet.to_metres(np.array([[item.x, item.y]])).tolist()
            msp.add_arc((x, y), item.radius / sheet.mm, item.start, item.end,
                        dxfattribs={"layer": layer, "lineweight": _weight(item.pen)})
        elif isinstance(item, Shape):
            loops = [sheet.to_metres(loop) for loop in item.loops]
            if item.pattern is not None:
                _hatch(msp, sheet, loops, item.pattern, layer)
            elif item.fill not in (None, "white"):
                hatch = msp.add_hatch(color=7, dxfattribs={"layer": layer})
                for loop in loops:
                    hatch.paths.add_polyline_path([tuple(p) for p in loop.tolist()], is_closed=True)
            for loop in loops:
                msp.add_lwpolyline([tuple(p) for p in loop.tolist()], close=item.closed,
                                   dxfattribs={"layer": layer, "lineweight": _weight(item.pen)})
        else:
            (x, y), = sheet.to_metres(np.array([[item.x, item.y]])).tolist()
            text = msp.add_text(item.text, height=item.size * 0.72 / sheet.mm,
                                rotation=item.angle, dxfattribs={"layer": layer})
            align = {"start": TextEntityAlignment.LEFT, "middle": TextEntityAlignment.CENTER,
                     "end": TextEntityAlignment.RIGHT}[item.anchor]
            text.set_placement((x, y), align=align)


DASHED = "CASTOR_DASHED"


def _linetypes(doc, mm: float) -> None:
    """ISO 128's dashed line at the printed size: DASH mm dashes, GAP mm gaps."""
    from castor.drawings.sheet import DASH, GAP

    k = 1 / mm
    doc.linetypes.add(DASHED, pattern=[(DASH + GAP) * k, DASH * k, -GAP * k],
                      description="Dashed __ __ __")


def _hatch(msp, sheet, loops, pattern: str, layer: str) -> None:
    """A region hatched with its pattern (castor.drawings.classes.HATCHES): a
    real HATCH of that name, scaled so that its lines are as far apart on the
    printed sheet as in the SVG and PDF."""
    from castor.drawings.classes import HATCHES

    _, period, unit = HATCHES[pattern]
    hatch = msp.add_hatch(color=7, dxfattribs={"layer": layer})
    hatch.set_pattern_fill(pattern, color=7, scale=period / sheet.mm / unit)
    for loop in loops:
        hatch.paths.add_polyline_path([tuple(p) for p in np.asarray(loop).tolist()], is_closed=True)


def _tidy(value: float) -> float:
    """A coordinate of the extents, rounded to 1e-9 m (-0.0 written as 0)."""
    return round(float(value), 9) + 0.0


def export_drawing(sheet) -> bytes:
    """The sheet as a DXF (R2010) document's bytes."""
    import ezdxf

    from castor.drawings.sheet import CUT_PEN, Lines

    doc = ezdxf.new("R2010")
    doc.units = ezdxf.units.M
    doc.header["$MEASUREMENT"] = 1  # metric
    doc.header["$LWDISPLAY"] = 1  # show lineweights
    doc.header["$INSUNITS"] = 6  # metres
    msp = doc.modelspace()
    drawing = sheet.drawing
    annotation = {"dimensions", "levels", "sheet"}
    names = _layer_names([l.name for l in drawing.layers], annotation | {"ground"})
    if drawing.symbols is not None:
        _linetypes(doc, sheet.mm)
    for layer, name in zip(drawing.layers, names):
        doc.layers.add(name)
        if layer.regions is not None:
            for region in layer.regions:
                if region.pattern == "SOLID":
                    hatch = msp.add_hatch(color=8, dxfattribs={"layer": name})
                    hatch.set_solid_fill(color=8)
                    for loop in region.loops:
                        hatch.paths.add_polyline_path([tuple(p) for p in loop.tolist()],
                                                      is_closed=True)
                else:
                    _hatch(msp, sheet, region.loops, region.pattern, name)
                for loop in region.loops:
                    msp.add_lwpolyline([tuple(p) for p in loop.tolist()], close=True,
                                       dxfattribs={"layer": name, "lineweight": _weight(CUT_PEN)})
        elif layer.cuts:
            hatch = msp.add_hatch(color=8, dxfattribs={"layer": name})
            hatch.set_solid_fill(color=8)
            for loop in layer.cuts:
                points = [tuple(p) for p in loop.tolist()]
                hatch.paths.add_polyline_path(points, is_closed=True)
                msp.add_lwpolyline(points, close=True,
                                   dxfattribs={"layer": name, "lineweight": _weight(CUT_PEN)})
        pens = {item.kind: item.pen for group in sheet.layers for item in group.items
                if isinstance(item, Lines)}
        for kind, mask in (("seen", ~layer.profile), ("profile", layer.profile)):
            weight = _weight(pens.get(kind, 0.18 if kind == "seen" else 0.35))
            for (x0, y0), (x1, y1) in layer.lines[mask].tolist():
                msp.add_line((x0, y0), (x1, y1), dxfattribs={"layer": name, "lineweight": weight})
    for group in sheet.layers[len(drawing.layers):]:  # the ground line
        doc.layers.add(group.name)
        _sheet_items(msp, sheet, group.items, group.name)
    doc.layers.add("dimensions")
    if sheet.dimensions:
        _dimension_style(doc, sheet.mm)
    for d in sheet.dimensions:
        dim = msp.add_linear_dim(base=d.base, p1=d.p1, p2=d.p2, location=d.text_at, angle=d.angle,
                                 text="<>" if d.shown else " ",  # " ": no text (DXF's way)
                                 dimstyle="CASTOR", override={"dimexo": d.offset},
                                 dxfattribs={"layer": "dimensions"})
        dim.render()
        # the measurement itself (group code 42), as CAD programs write it
        dim.dimension.dxf.actual_measurement = dim.dimension.get_measurement()
    for group in sheet.groups:
        if group.name == "dimensions":
            continue  # the DIMENSION entities stand for them
        doc.layers.add(group.name)
        _sheet_items(msp, sheet, group.items, group.name)
    # the header's extents: the sheet's paper, in metres, to the nanometre (the
    # coordinates' last bits of rounding, -6.999999999999999, are no size)
    (x0, y0), (x1, y1) = sheet.to_metres(np.array([[0.0, 0.0], [sheet.width, sheet.height]])).tolist()
    msp.reset_extents((_tidy(min(x0, x1)), _tidy(min(y0, y1)), 0.0),
                      (_tidy(max(x0, x1)), _tidy(max(y0, y1)), 0.0))
    stream = io.StringIO()
    doc.write(stream)
    return stream.getvalue().encode("utf-8")


def write(sheet, info: WriteInfo) -> Iterator[bytes]:
    """The registry's writer (castor.formats): the sheet as one piece."""
    return iter([export_drawing(sheet)])
