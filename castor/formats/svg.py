"""SVG: a drawing at its printed size, each object a group named after it.

Lengths are millimetres on paper (at 1:100, 1 m of the scene is 10 mm);
the page is the drawing's extent plus a margin. Cut regions (poché) are
filled and outlined with a heavy line, seen edges drawn with a thin one, as
an architect's pens: 0.5 mm and 0.18 mm. Each group is also an Inkscape
layer labelled with the object's name.
"""

from __future__ import annotations

import re

import numpy as np

from castor.formats import Format

MARGIN = 10.0  # mm
CUT_PEN = 0.5  # mm
SEEN_PEN = 0.18  # mm
POCHE = "#8c8c8c"


def _ids(names: list[str]) -> list[str]:
    """Valid, distinct XML ids made from the objects' names."""
    seen: set[str] = set()
    ids = []
    for name in names:
        base = re.sub(r"[^A-Za-z0-9_.-]", "_", name) or "object"
        if not re.match(r"[A-Za-z_]", base):
            base = "_" + base
        candidate, n = base, 2
        while candidate in seen:
            candidate, n = f"{base}-{n}", n + 1
        seen.add(candidate)
        ids.append(candidate)
    return ids


def _number(x: float) -> str:
    text = f"{x:.3f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def export_drawing(drawing) -> bytes:
    """The drawing as SVG bytes, in millimetres at the drawing's scale."""
    # imported here: xml.sax.saxutils brings urllib, too slow for every start-up
    from xml.sax.saxutils import quoteattr

    mm = 1000.0 / drawing.scale  # millimetres on paper per metre
    (x0, y0), (x1, y1) = drawing.box()
    width = (x1 - x0) * mm + 2 * MARGIN
    height = (y1 - y0) * mm + 2 * MARGIN

    def page(points: np.ndarray) -> np.ndarray:
        return np.column_stack([(points[:, 0] - x0) * mm + MARGIN,
                                (y1 - points[:, 1]) * mm + MARGIN])

    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" '
        f'xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" '
        f'width="{_number(width)}mm" height="{_number(height)}mm" '
        f'viewBox="0 0 {_number(width)} {_number(height)}">',
        f'<title>{drawing.view.name} 1:{drawing.scale:g}</title>',
        '<rect width="100%" height="100%" fill="white"/>',
    ]
    for layer, ident in zip(drawing.layers, _ids([l.name for l in drawing.layers])):
        out.append(f'<g id="{ident}" inkscape:groupmode="layer" '
                   f'inkscape:label={quoteattr(layer.name)}>')
        if len(layer.lines):
            a = page(layer.lines[:, 0])
            b = page(layer.lines[:, 1])
            path = " ".join(f"M{_number(p[0])} {_number(p[1])}L{_number(q[0])} {_number(q[1])}"
                            for p, q in zip(a.tolist(), b.tolist()))
            out.append(f'<path d="{path}" fill="none" stroke="black" '
                       f'stroke-width="{SEEN_PEN}" stroke-linecap="round"/>')
        if layer.cuts:
            parts = []
            for loop in layer.cuts:
                points = page(loop).tolist()
                parts.append("M" + "L".join(f"{_number(x)} {_number(y)}" for x, y in points) + "Z")
            out.append(f'<path class="cut" d="{"".join(parts)}" fill="{POCHE}" '
                       f'fill-rule="evenodd" stroke="black" stroke-width="{CUT_PEN}" '
                       f'stroke-linejoin="round"/>')
        out.append("</g>")
    out.append("</svg>")
    return ("\n".join(out) + "\n").encode()


FORMATS = (Format("svg", (".svg",), "drawing", "a plan, section or elevation as a vector drawing",
                  export_drawing, binary=False, listed=90),)
