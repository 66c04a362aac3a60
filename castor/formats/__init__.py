"""Output formats: one module per format, each a ``write(frame, stream)`` function.

``FORMATS`` maps a format name to (module name, file suffix, description, binary,
triangles only);
modules are imported only when their format is used, so that the default path
(the polygon stream) stays light.
"""

from __future__ import annotations

import importlib

FORMATS: dict[str, tuple[str, str, str, bool, bool]] = {
    "cps": ("cps", ".cps", "the Castor polygon stream", False, False),
    "off": ("off", ".off", "Geomview OFF with a colour per face", False, False),
    "obj": ("obj", ".obj", "Wavefront OBJ with a material per colour", False, False),
    "stl": ("stl", ".stl", "binary STL, geometry only", True, True),
    "stl-ascii": ("stl", ".stl", "ASCII STL, geometry only", False, True),
    "ply": ("ply", ".ply", "binary PLY with face colours", True, True),
    "glb": ("glb", ".glb", "binary glTF 2.0, one mesh per object", True, True),
}


def format_for_suffix(path: str) -> str | None:
    lowered = path.lower()
    for name, (_, suffix, _, _, _) in FORMATS.items():
        if name != "stl-ascii" and lowered.endswith(suffix):
            return name
    return None


def writer(name: str):
    """The module that writes format ``name``."""
    return importlib.import_module(f"castor.formats.{FORMATS[name][0]}")
