"""Output formats: one module per format, chosen from one table of named fields.

Modules are imported only when their format is used, so that the default path
(the polygon stream) stays light. ``kind`` says what a format is made from:
``mesh`` formats from a frame's polygons, ``picture`` formats from its
evaluated CSG tree (ray traced), ``drawing`` formats from its solids cut and
seen from a side.
"""

from __future__ import annotations

import importlib
from typing import NamedTuple


class Format(NamedTuple):
    name: str
    module: str  # castor.formats.<module>
    suffix: str
    description: str
    kind: str  # "mesh", "picture" or "drawing"
    binary: bool
    triangles_only: bool  # the format holds triangles: polygon merging is skipped
    all_frames: bool = False  # one file holds every frame (the stream, a GIF)
    # the module's function: (frame, path=None) -> bytes; the same name with
    # '_chunks', where the module has it, gives the bytes a piece at a time
    exporter: str = "export"


FORMATS: dict[str, Format] = {f.name: f for f in (
    Format("cps", "cps", ".cps", "the Castor polygon stream", "mesh", False, False, True),
    Format("off", "off", ".off", "Geomview OFF with a colour per face", "mesh", False, False),
    Format("obj", "obj", ".obj", "Wavefront OBJ with a material per colour", "mesh", False, False),
    Format("stl", "stl", ".stl", "binary STL, geometry only", "mesh", True, True),
    Format("stl-ascii", "stl", ".stl", "ASCII STL, geometry only", "mesh", False, True,
           exporter="export_ascii"),
    Format("ply", "ply", ".ply", "binary PLY with vertex colours", "mesh", True, True),
    Format("glb", "glb", ".glb", "binary glTF 2.0, one node per object", "mesh", True, True),
    Format("3mf", "threemf", ".3mf", "3D Manufacturing Format, coloured, in millimetres",
           "mesh", True, True),
    # IFC: its options (--title, --ifc-class) come from the Spec (castor.jobs)
    Format("ifc", "ifc", ".ifc", "IFC4 for BIM programs, one element per object", "mesh",
           False, False),
    Format("png", "png", ".png", "a ray-traced picture of the exact solids", "picture", True,
           False),
    Format("gif", "gif", ".gif", "every frame ray traced, as an animation", "picture", True,
           False, True),
    Format("svg", "svg", ".svg", "a plan, section or elevation as a vector drawing", "drawing",
           False, False),
    Format("dxf", "dxf", ".dxf", "a plan, section or elevation for CAD, in metres", "drawing",
           False, False),
)}


def format_for_suffix(path: str) -> str | None:
    """The format whose suffix ``path`` ends with (the binary one where two share it)."""
    lowered = path.lower()
    for f in FORMATS.values():
        if f.name != "stl-ascii" and lowered.endswith(f.suffix):
            return f.name
    return None


def module(name: str):
    """The module that writes format ``name``."""
    return importlib.import_module(f"castor.formats.{FORMATS[name].module}")
