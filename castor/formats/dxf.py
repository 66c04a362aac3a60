"""DXF: a drawing for CAD, in metres, each object a layer named after it.

Written with ezdxf (imported only here, only when a DXF is asked for).
Cut regions are solid HATCH entities outlined by closed LWPOLYLINEs with a
heavy lineweight; seen edges are LINEs with a thin one. Coordinates are the
page's in scene units (metres), so the drawing has its true size in CAD;
the printed scale is the CAD program's plot setting.
"""

from __future__ import annotations

import io
import re

from castor.formats import Format

CUT_WEIGHT = 50  # hundredths of a millimetre
SEEN_WEIGHT = 18


def _layer_names(names: list[str]) -> list[str]:
    """Valid, distinct DXF layer names made from the objects' names."""
    seen: set[str] = set()
    out = []
    for name in names:
        base = re.sub(r'[<>/\\":;?*|=`,\x00-\x1f]', "_", name).strip() or "object"
        candidate, n = base, 2
        while candidate.lower() in seen or candidate == "0":
            candidate, n = f"{base}-{n}", n + 1
        seen.add(candidate.lower())
        out.append(candidate)
    return out


def _tidy(value: float) -> float:
    """A coordinate of the extents, rounded to 1e-9 m (-0.0 written as 0)."""
    return round(float(value), 9) + 0.0


def export_drawing(drawing) -> bytes:
    """The drawing as a DXF (R2010) document's bytes."""
    import ezdxf

    doc = ezdxf.new("R2010")
    doc.units = ezdxf.units.M
    doc.header["$MEASUREMENT"] = 1  # metric
    doc.header["$LWDISPLAY"] = 1  # show lineweights
    msp = doc.modelspace()
    for layer, name in zip(drawing.layers, _layer_names([l.name for l in drawing.layers])):
        doc.layers.add(name)
        if layer.cuts:
            hatch = msp.add_hatch(color=8, dxfattribs={"layer": name})
            hatch.set_solid_fill(color=8)
            for loop in layer.cuts:
                points = [tuple(p) for p in loop.tolist()]
                hatch.paths.add_polyline_path(points, is_closed=True)
                msp.add_lwpolyline(points, close=True,
                                   dxfattribs={"layer": name, "lineweight": CUT_WEIGHT})
        for (x0, y0), (x1, y1) in layer.lines.tolist():
            msp.add_line((x0, y0), (x1, y1), dxfattribs={"layer": name, "lineweight": SEEN_WEIGHT})
    low, high = drawing.box()
    if (high > low).any():
        # the header's extents from castor's own box, to the nanometre: the
        # coordinates' last bits of rounding (-6.999999999999999) are no size
        msp.reset_extents((_tidy(low[0]), _tidy(low[1]), 0.0), (_tidy(high[0]), _tidy(high[1]), 0.0))
    stream = io.StringIO()
    doc.write(stream)
    return stream.getvalue().encode("utf-8")


FORMATS = (Format("dxf", (".dxf",), "drawing", "a plan, section or elevation for CAD, in metres",
                  export_drawing, binary=False, listed=100),)
