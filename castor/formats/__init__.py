"""Every file castor writes or reads: one registry of formats, merged from their modules.

As trimesh's ``exchange/``: each format is one module of this package that
declares its ``FORMATS``, a tuple of ``Format`` records naming the functions
that write it and, where castor reads it back, the one that reads it. The
registry imports the modules the first time it is asked (``FORMATS``,
``format_for_suffix``), so that ``import castor.formats`` stays light; a
module whose own dependencies are missing is left out, and its format is then
not part of this castor.

Adding a format is one module here: ``castor/formats/NAME.py`` with its
functions and ``FORMATS = (Format(...),)`` at its end. Nothing else lists it:
the command line's ``-f`` choices and messages, the writers' dispatch
(castor.jobs), the output (castor.formats.output) and castor-view's readers
all read the registry.
"""

from __future__ import annotations

import importlib
import pkgutil
from dataclasses import dataclass
from typing import Callable

# What a format is made from, and so what its ``write`` is given:
KINDS = {
    "stream": "the polygon stream: write(frame, path) -> bytes, frame after frame in one file",
    "mesh": "a frame's polygons: write(frame, path) -> bytes (castor.mesh.frame.Frame)",
    "picture": "a ray-traced picture: write(image) -> bytes, the (H, W, 3) uint8 array; "
               "a format of every frame is given the list of them",
    "drawing": "a plan, section or elevation laid on its sheet: write(sheet) -> bytes "
               "(castor.drawings.sheet.Sheet; its drawing, castor.drawings.Drawing)",
    "bim": "a building model: write(scene, frame, settings) -> bytes, the evaluated CSG "
           "tree (castor.csg.tree.FrameTree), its mesh frame and the FrameSettings",
}


@dataclass(frozen=True)
class Format:
    """One format: how castor names, writes and (perhaps) reads it."""

    name: str  # what -f takes
    suffixes: tuple[str, ...]  # file name endings; the first is the one castor writes
    kind: str  # one of KINDS
    description: str  # one line, for --help and the documentation
    write: Callable  # the whole file at once (its argument by kind: see KINDS)
    # the same bytes a piece at a time, (frame, path) -> Iterator[bytes], where the
    # module can: a frame's bytes need not be held whole
    write_pieces: Callable | None = None
    # path -> iterator of castor.formats.cps.StreamFrame (z up, scene units):
    # what castor-view draws; None where castor does not read the format
    read: Callable | None = None
    companions: Callable | None = None  # (frame, path) -> {path: bytes}: files beside it (.mtl)
    binary: bool = True
    triangles_only: bool = False  # the format holds triangles: polygon merging is skipped
    one_frame: bool = True  # a file holds one frame (False: the stream, an animation)
    header: bytes = b""  # what a file of the stream begins with, once
    up: str = "z"  # the file's up axis ("y": glTF, OBJ); its reader turns it back to z
    reads_also: tuple[str, ...] = ()  # more endings its reader takes (.gltf), never written
    listed: int = 1000  # place in lists of formats (-f choices, messages): lowest first

    @property
    def suffix(self) -> str:
        """The ending of the files castor writes."""
        return self.suffixes[0]


_registry: dict[str, Format] | None = None
_SKIPPED = {"output"}  # modules of this package that declare no format


def registry() -> dict[str, Format]:
    """Every format, by name, in the order they are listed; built once, from the modules."""
    global _registry
    if _registry is None:
        found: list[Format] = []
        for info in pkgutil.iter_modules(__path__):
            if info.name.startswith("_") or info.name in _SKIPPED:
                continue
            try:
                module = importlib.import_module(f"{__name__}.{info.name}")
            except ImportError as exc:
                if (exc.name or "").split(".")[0] == "castor":
                    raise  # castor's own module is broken: say so, never hide a format
                continue  # its own dependency is missing: not part of this castor
            found.extend(getattr(module, "FORMATS", ()))
        for record in found:
            if record.kind not in KINDS:
                raise ValueError(f"format {record.name}: unknown kind {record.kind!r}")
        found.sort(key=lambda f: (f.listed, f.name))
        _registry = {f.name: f for f in found}
    return _registry


def __getattr__(name: str):
    if name == "FORMATS":  # the registry, made on first use
        return registry()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def format_for_suffix(path: str) -> str | None:
    """The format castor writes for ``path``'s ending (the first listed where two share it)."""
    lowered = path.lower()
    for f in registry().values():
        if lowered.endswith(f.suffixes):
            return f.name
    return None


def reader_for(path: str) -> Format | None:
    """The format whose reader takes ``path`` (by its ending), or None."""
    lowered = path.lower()
    for f in registry().values():
        if f.read is not None and lowered.endswith(f.suffixes + f.reads_also):
            return f
    return None


def of_kind(*kinds: str) -> list[Format]:
    """The formats of these kinds, in the order they are listed."""
    return [f for f in registry().values() if f.kind in kinds]
