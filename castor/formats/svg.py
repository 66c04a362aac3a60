"""SVG: a drawing's sheet at its printed size, each object a group named after it.

Lengths are millimetres on paper (at 1:100, 1 m of the scene is 10 mm). The
objects' groups sit in one group ``drawing`` whose ``data-origin`` is the
paper point of the page's (0, 0) metres and ``data-mm-per-metre`` the scale,
so a reader can take any point back to metres. Pens are stroke widths at the
printed size (castor.drawings.sheet); each object's group is also an Inkscape
layer labelled with its name. Text is text, escaped, in Helvetica.
"""

from __future__ import annotations

import re
from typing import Iterator

import numpy as np

from castor.formats import WriteInfo


FONT = "Helvetica, Arial, sans-serif"


def _ids(names: list[str], taken: set[str]) -> list[str]:
    """Valid, distinct XML ids made from the objects' names."""
    seen = set(taken)
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


def _item(item) -> str:
    """One item of the sheet as an SVG element."""
    # imported here: xml.sax.saxutils brings urllib, too slow for every start-up
    from xml.sax.saxutils import escape

    from castor.drawings.paper import CHAIN
    from castor.drawings.sheet import DASH, GAP, Arc, Lines, Shape

    if isinstance(item, Lines):
        a, b = item.segments[:, 0].tolist(), item.segments[:, 1].tolist()
        path = " ".join(f"M{_number(p[0])} {_number(p[1])}L{_number(q[0])} {_number(q[1])}"
                        for p, q in zip(a, b))
        dashes = f' stroke-dasharray="{DASH:g} {GAP:g}"' if item.dashed else ""
        if item.chain:
            dashes = f' stroke-dasharray="{" ".join(f"{v:g}" for v in CHAIN)}"'
        cap = "butt" if item.dashed or item.chain else "round"
        return (f'<path class="{item.kind}" d="{path}" fill="none" stroke="black" '
                f'stroke-width="{item.pen}" stroke-linecap="{cap}"{dashes}/>')
    if isinstance(item, Arc):
        ends = []
        for angle in (item.start, item.end):
            t = np.radians(angle)
            ends.append((item.x + item.radius * np.cos(t), item.y - item.radius * np.sin(t)))
        sweep = (item.end - item.start) % 360
        large = 1 if sweep > 180 else 0
        r = _number(item.radius)
        return (f'<path class="{item.kind}" d="M{_number(ends[0][0])} {_number(ends[0][1])}'
                f'A{r} {r} 0 {large} 0 {_number(ends[1][0])} {_number(ends[1][1])}" '
                f'fill="none" stroke="black" stroke-width="{item.pen}" '
                f'data-centre="{_number(item.x)} {_number(item.y)}"/>')
    if isinstance(item, Shape):
        parts = []
        for loop in item.loops:
            points = np.asarray(loop).tolist()
            parts.append("M" + "L".join(f"{_number(x)} {_number(y)}" for x, y in points)
                         + ("Z" if item.closed else ""))
        fill = item.fill or "none"
        rule = ' fill-rule="evenodd"' if item.fill else ""
        shape = (f'<path class="{item.kind}" d="{"".join(parts)}" fill="{fill}"{rule} '
                 f'stroke="black" stroke-width="{item.pen}" stroke-linejoin="round"/>')
        if item.pattern is None:
            return shape
        # its white ground, the hatch, then the outline
        d = "".join(parts)
        return "\n".join([
            f'<path class="ground" d="{d}" fill="white"{rule} stroke="none" stroke-width="0"/>',
            f'<path class="hatch" d="{d}" fill="url(#hatch-{item.pattern})"{rule} stroke="none" '
            'stroke-width="0" '
            f'data-pattern="{item.pattern}" data-class="{item.label}"/>',
            f'<path class="{item.kind}" d="{d}" fill="none" stroke="black" '
            f'stroke-width="{item.pen}" stroke-linejoin="round"/>'])
    anchor = f' text-anchor="{item.anchor}"' if item.anchor != "start" else ""
    turn = (f' transform="rotate({_number(-item.angle)} {_number(item.x)} {_number(item.y)})"'
            if item.angle else "")
    return (f'<text x="{_number(item.x)}" y="{_number(item.y)}" '
            f'font-size="{_number(item.size)}"{anchor}{turn}>{escape(item.text)}</text>')


def _patterns(sheet) -> list[str]:
    """The <pattern>s of the hatches the sheet uses, at their printed size: a
    tile turned by the pattern's first angle, holding its lines (castor.drawings.classes)."""
    from castor.drawings.classes import HATCHES
    from castor.drawings.sheet import THIN_PEN, Shape

    used = sorted({item.pattern for group in [*sheet.layers, *sheet.groups]
                   for item in group.items if isinstance(item, Shape) and item.pattern})
    if not used:
        return []
    out = ["<defs>"]
    for name in used:
        families, period, _ = HATCHES[name]
        first = families[0][0]
        p = _number(period)
        lines = []
        for angle, offset in families:
            at = _number(((offset + 0.5) % 1.0) * period)  # whole, not halved by the tile's edge
            if (angle - first) % 180 == 0:
                lines.append(f"M0 {at}H{p}")
            else:
                lines.append(f"M{at} 0V{p}")
        out.append(f'<pattern id="hatch-{name}" patternUnits="userSpaceOnUse" width="{p}" '
                   f'height="{p}" patternTransform="rotate({_number(-first)})">'
                   f'<path d="{"".join(lines)}" stroke="black" stroke-width="{THIN_PEN}"/>'
                   "</pattern>")
    out.append("</defs>")
    return out


def export_drawing(sheet) -> bytes:
    """The sheet as SVG bytes, in millimetres at the drawing's scale."""
    from xml.sax.saxutils import escape, quoteattr

    width, height = _number(sheet.width), _number(sheet.height)
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" '
        f'xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" '
        f'width="{width}mm" height="{height}mm" viewBox="0 0 {width} {height}">',
        f'<title>{escape(sheet.title)}: {escape(sheet.description)}, '
        f'1:{sheet.drawing.scale:g}</title>',
        '<rect width="100%" height="100%" fill="white"/>',
        f'<g id="drawing" data-origin="{_number(sheet.origin[0])} {_number(sheet.origin[1])}" '
        f'data-mm-per-metre="{sheet.mm:.12g}">',
    ]
    out[4:4] = _patterns(sheet)  # before the drawing's group
    reserved = {"drawing"} | {g.name for g in sheet.groups}
    for group, ident in zip(sheet.layers, _ids([g.name for g in sheet.layers], reserved)):
        out.append(f'<g id="{ident}" inkscape:groupmode="layer" '
                   f'inkscape:label={quoteattr(group.name)}>')
        out.extend(_item(item) for item in group.items)
        out.append("</g>")
    out.append("</g>")
    for group in sheet.groups:
        out.append(f'<g id="{group.name}" font-family="{FONT}" fill="black">')
        out.extend(_item(item) for item in group.items)
        out.append("</g>")
    out.append("</svg>")
    return ("\n".join(out) + "\n").encode()


def write(sheet, info: WriteInfo) -> Iterator[bytes]:
    """The registry's writer (castor.formats): the sheet as one piece; of a
    drawing set (--sheets, a file per sheet), its first sheet."""
    return written(sheet, export_drawing)


def companions(product, info: WriteInfo) -> dict:
    """A drawing set written to a %d pattern: the files of its other sheets."""
    return sheet_files(product, export_drawing)


def written(product, export, export_set=None) -> Iterator[bytes]:
    """A drawing format's file: a sheet by ``export(sheet)``; a drawing set
    (--sheets) as one document by ``export_set(set)``, or its first sheet where
    it goes to a %d pattern or the format holds one sheet a file (no
    ``export_set``)."""
    if hasattr(product, "sheets"):
        if export_set is None or patterned(product):
            return iter([export(product.sheets[0])])
        return iter([export_set(product)])
    return iter([export(product)])


def sheet_files(product, export) -> dict:
    """For a drawing set written to a %d pattern, the files of the sheets after
    the first (the pattern filled with the frame's number + 1, + 2, ...), made by
    ``export(sheet)``; a single sheet, or a set in one file: none."""
    from castor.formats.output import frame_path

    if not patterned(product):
        return {}
    return {frame_path(product.target, product.number + k): export(sheet)
            for k, sheet in enumerate(product.sheets[1:], 1)}


def patterned(product) -> bool:
    """Whether a drawing set goes to a %d pattern: a file per sheet."""
    from castor.formats.output import has_pattern

    target = getattr(product, "target", None) if hasattr(product, "sheets") else None
    return target is not None and has_pattern(target)
