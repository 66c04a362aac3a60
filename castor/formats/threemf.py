"""3D Manufacturing Format (3MF): what a slicer prints, in colour.

One named object per '>' object, a base material per colour (named after what
it colours), triangles counter-clockwise seen from outside. Units are
millimetres with one scene unit = one metre, so a 9 m house is 9000 mm: a
slicer shows it at its true size and scales it to the model's scale (1:100)
in one step, or `--scale 1:N` writes it at that scale (1 unit = 1000/N mm,
castor.jobs scales the frame). The package is written with fixed dates, so that the same frame
gives the same bytes.
"""

from __future__ import annotations

import io
from typing import Iterator

import numpy as np

from castor.formats import WriteInfo
from castor.mesh.frame import Frame
from castor.formats._mesh import CHUNK, materials, object_names, object_pieces, triangles
from castor.formats.cps import number_strings

MILLIMETRES_PER_UNIT = 1000.0

_CONTENT_TYPES = """<?xml version="1.0" encoding="UTF-8"?>
<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">
 <Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>
 <Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>
</Types>
"""
_RELATIONSHIPS = """<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">
 <Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>
</Relationships>
"""


def model(frame: Frame) -> str:
    """The 3D/3dmodel.model document of the package."""
    return b"".join(model_pieces(frame)).decode("utf-8")


def model_pieces(frame: Frame) -> Iterator[bytes]:
    """The 3D/3dmodel.model document, encoded, an object's part at a time: the
    text is held once, as bytes, not as a line per triangle."""
    # imported here: xml.sax.saxutils brings urllib, too slow for every start-up
    from xml.sax.saxutils import quoteattr

    table, material_of = materials(frame)
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           '<model unit="millimeter" xml:lang="en-US" '
           'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">',
           ' <metadata name="Application">castor</metadata>',
           ' <resources>']
    if table:
        out.append('  <basematerials id="1">')
        for material in table:
            rgb = "".join(f"{int(round(c * 255)):02X}" for c in material.colour)
            out.append(f'   <base name={quoteattr(material.name)} displaycolor="#{rgb}FF"/>')
        out.append('  </basematerials>')
    items = []
    for obj, name, material in zip(frame.objects, object_names(frame), material_of):
        colour = None  # of the first triangle; none: the object is left out
        for first, offsets, indices in object_pieces(obj):
            tris, polygon = triangles(obj.vertices, offsets, indices)
            if len(tris):
                colour = int(material[first + polygon[0]])
                break
        if colour is None:
            continue
        number = len(items) + 2
        items.append(number)
        out.append(f'  <object id="{number}" name={quoteattr(name)} type="model" pid="1" '
                   f'pindex="{colour}">')
        out.append('   <mesh>')
        out.append('    <vertices>')
        yield ("\n".join(out) + "\n").encode("utf-8")
        for first in range(0, len(obj.vertices), CHUNK):
            numbers = number_strings(np.round(obj.vertices[first:first + CHUNK]
                                              * MILLIMETRES_PER_UNIT, 6))
            yield ("\n".join(f'     <vertex x="{x}" y="{y}" z="{z}"/>'
                             for x, y, z in zip(numbers[0::3], numbers[1::3], numbers[2::3]))
                   + "\n").encode("utf-8")
        out = ['    </vertices>', '    <triangles>']
        yield ("\n".join(out) + "\n").encode("utf-8")
        for first, offsets, indices in object_pieces(obj):
            tris, polygon = triangles(obj.vertices, offsets, indices)
            if len(tris):
                yield ("\n".join(f'     <triangle v1="{a}" v2="{b}" v3="{c}" pid="1" p1="{m}"/>'
                                 for (a, b, c), m in zip(tris.tolist(),
                                                         material[first + polygon].tolist()))
                       + "\n").encode("utf-8")
        out = ['    </triangles>']
        out.append('   </mesh>')
        out.append('  </object>')
    out.append(' </resources>')
    out.append(' <build>')
    out.extend(f'  <item objectid="{number}"/>' for number in items)
    out.append(' </build>')
    out.append('</model>')
    yield ("\n".join(out) + "\n").encode("utf-8")


def export(frame: Frame, path: str | None = None) -> bytes:
    import zipfile

    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as package:
        for name, data in (("[Content_Types].xml", _CONTENT_TYPES.encode("utf-8")),
                           ("_rels/.rels", _RELATIONSHIPS.encode("utf-8")),
                           ("3D/3dmodel.model", None)):
            if data is None:
                data = b"".join(model_pieces(frame))
            info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            package.writestr(info, data)
            del data
    return buffer.getvalue()


# --- reading a package back (castor-view): the core specification's mesh
# objects, their base materials and the build's items

_CORE = "{http://schemas.microsoft.com/3dmanufacturing/core/2015/02}"
# the model's unit in scene units (metres)
_UNITS = {"micron": 1e-6, "millimeter": 1e-3, "centimeter": 1e-2, "inch": 0.0254,
          "foot": 0.3048, "meter": 1.0}


def read(path: str):
    """A 3MF package as one frame of coloured triangles, in scene units (metres)."""
    import zipfile
    from xml.etree import ElementTree

    from castor.formats.cps import StreamError, StreamFrame

    try:
        with zipfile.ZipFile(path) as package:
            names = [n for n in package.namelist() if n.lower().endswith(".model")]
            if not names:
                raise StreamError(f"{path}: not a 3MF package (no 3D model in it)")
            root = ElementTree.fromstring(package.read(names[0]))
    except (OSError, zipfile.BadZipFile, ElementTree.ParseError, KeyError) as exc:
        raise StreamError(f"{path}: cannot read this 3MF file ({exc})") from None
    scale = _UNITS.get(root.get("unit", "millimeter"), 1e-3)
    colours: dict[str, list[tuple[float, float, float]]] = {}
    for group in root.iter(f"{_CORE}basematerials"):
        colours[group.get("id")] = [_colour(base.get("displaycolor", "#CCCCCC"))
                                    for base in group.findall(f"{_CORE}base")]
    points, face_colours = [], []
    try:
        for obj in root.iter(f"{_CORE}object"):
            mesh = obj.find(f"{_CORE}mesh")
            if mesh is None:
                continue
            vertices = np.array([[float(v.get(a)) for a in "xyz"]
                                 for v in mesh.iter(f"{_CORE}vertex")]).reshape(-1, 3) * scale
            default_group, default_index = obj.get("pid"), int(obj.get("pindex", 0))
            tris, rgb = [], []
            for t in mesh.iter(f"{_CORE}triangle"):
                tris.append((int(t.get("v1")), int(t.get("v2")), int(t.get("v3"))))
                table = colours.get(t.get("pid", default_group), [])
                index = int(t.get("p1", default_index))
                rgb.append(table[index] if index < len(table) else (0.8, 0.8, 0.8))
            if tris:
                points.append(vertices[np.array(tris, np.int64)].reshape(-1, 3))
                face_colours.append(np.array(rgb, np.float64))
    except (TypeError, ValueError, IndexError) as exc:
        raise StreamError(f"{path}: malformed 3MF mesh ({exc})") from None
    if not points:
        raise StreamError(f"{path}: the file holds no faces")
    count = sum(len(c) for c in face_colours)
    yield StreamFrame(1, path, np.concatenate(points), np.arange(count + 1) * 3,
                      np.concatenate(face_colours))


def _colour(text: str) -> tuple[float, float, float]:
    """'#RRGGBB' or '#RRGGBBAA' as 0..1 numbers (grey when unreadable)."""
    digits = text.lstrip("#")
    try:
        return tuple(int(digits[i:i + 2], 16) / 255.0 for i in (0, 2, 4))
    except ValueError:
        return (0.8, 0.8, 0.8)


def write(frame: Frame, info: WriteInfo) -> Iterator[bytes]:
    """The registry's writer (castor.formats): the package, made whole, of the
    frame at its scale (``--scale 1:N``: 1 scene unit = 1000/N mm)."""
    scale = info.option("scale")
    return iter([export(frame if scale is None else scaled(frame, 1 / scale), info.path)])


def scaled(frame: Frame, factor: float) -> Frame:
    """The frame's polygons times ``factor``: a model at its scale."""
    from dataclasses import replace

    return replace(frame, objects=[replace(obj, vertices=obj.vertices * factor)
                                   for obj in frame.objects])
