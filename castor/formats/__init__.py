"""Every file castor writes or reads: one table of formats, one writer signature.

As OpenSCAD's ``src/io/export.cc``: one table (``_DECLARED`` below) names
every format, its file endings, its kind and a line of description; every
format's module ``castor/formats/NAME.py`` has one writer with one signature,

    write(product, info: WriteInfo) -> iterable of bytes (the file, a piece at a time)

over its kind's product, and where castor reads the format back, ``read(path)``.
The kinds (castor.formats.kinds) make the products from a frame's evaluated
tree and its settings: the polygon stream and mesh files take a mesh frame
(castor.mesh.frame.Frame), pictures an (H, W, 3) uint8 image (an animation the
list of its frames' images), drawings a sheet (castor.drawings.sheet.Sheet),
building models a ``BuildingModel``. A format's own options (3MF's
``--scale``) reach its writer in ``info.options``, by the option's name
without dashes; the option is declared once, in castor.options.OUTPUT_OPTIONS,
and named in the format's record (``options=``). A kind's options (a
picture's ``--size``) are its own settings (castor.settings).

The table is plain records, read without importing any writer: the command
line knows every format's name, endings, kind and description (``-f``,
``--help``, ``-o x.glb``) without numpy, and a format's module is imported
when its writer is first called (``OnUse``).

Adding a format: its module here, with ``write`` (and ``read``); its record
in ``_DECLARED``; an option of its own in castor.options.OUTPUT_OPTIONS. The
command line's ``-f`` choices and messages, the frames' making (castor.jobs),
the output (castor.formats.output) and castor-view's readers read the table.
Adding an output kind: a ``Kind`` in castor.formats.kinds and its formats.
"""

from __future__ import annotations

import importlib
from typing import Callable, NamedTuple

from castor.formats.kinds import BIM, DRAWING, KINDS, MESH, PICTURE, STREAM, Kind


class OnUse:
    """A function of a format's module, named by its record and imported when first
    called (the module imports numpy, a writer's library: not at start-up)."""

    __slots__ = ("module", "name", "_function")

    def __init__(self, module: str, name: str):
        self.module, self.name, self._function = module, name, None

    def resolve(self) -> Callable:
        """The function itself (its module imported now, once)."""
        if self._function is None:
            self._function = getattr(importlib.import_module(self.module), self.name)
        return self._function

    def __call__(self, *args, **kwargs):
        return self.resolve()(*args, **kwargs)

    def __eq__(self, other):
        if isinstance(other, OnUse):
            return (self.module, self.name) == (other.module, other.name)
        return NotImplemented

    def __hash__(self):
        return hash((self.module, self.name))

    def __repr__(self):
        return f"{self.module}.{self.name}"

    def __getstate__(self):  # pickled by name: the function is found again where it is needed
        return (self.module, self.name)

    def __setstate__(self, state):
        self.module, self.name = state
        self._function = None


class WriteInfo(NamedTuple):
    """What a writer is told besides its product: where the file goes, and the
    format's own options (OpenSCAD's ExportInfo)."""

    path: str | None = None  # the file's path (a pattern filled in); None: standard output
    options: dict | None = None  # the format's own options by name ({"scale": 50.0} for 3MF)

    def option(self, name: str, default=None):
        """The value of the format's option ``name``, or ``default`` when not given."""
        return (self.options or {}).get(name, default)


class Format(NamedTuple):
    """One format: how castor names, writes and (perhaps) reads it. (A NamedTuple:
    castor --help and --version list the formats without importing dataclasses.)"""

    name: str  # what -f takes
    suffixes: tuple[str, ...]  # file name endings; the first is the one castor writes
    kind: Kind  # what its writer is given (castor.formats.kinds)
    description: str  # one line, for --help and the documentation
    write: Callable  # (product, WriteInfo) -> iterable of bytes: the file, a piece at a time
    read: Callable | None = None  # path -> iterator of castor.formats.cps.StreamFrame (z up)
    companions: Callable | None = None  # (product, WriteInfo) -> {path: bytes}: files beside it
    options: tuple[str, ...] = ()  # options of its own (castor.options.OUTPUT_OPTIONS)
    unavailable: Callable | None = None  # () -> why it cannot be written here (None: it can)
    binary: bool = True
    triangles_only: bool = False  # the format holds triangles: polygon merging is skipped
    one_frame: bool = True  # a file holds one frame (False: the stream, an animation)
    header: bytes = b""  # what a file of the stream begins with, once
    up: str = "z"  # the file's up axis ("y": glTF, OBJ); its reader turns it back to z
    reads_also: tuple[str, ...] = ()  # more endings its reader takes (.gltf), never written

    @property
    def suffix(self) -> str:
        """The ending of the files castor writes."""
        return self.suffixes[0]

    @property
    def gathers(self) -> bool:
        """Its file is made from every frame at once (an animation: one camera for all)."""
        return not self.one_frame and not self.kind.streamed


def _declare(module: str, name: str, suffixes: tuple[str, ...], kind: Kind, description: str,
             *, writer: str = "write", reads: bool = False, companions: bool = False,
             unavailable: str | None = None, **fields) -> Format:
    """The record of a format whose module ``castor.formats.MODULE`` has its
    ``writer`` (and ``read``, ``companions``, the function ``unavailable`` names,
    where given)."""
    path = f"{__name__}.{module}"
    return Format(name, suffixes, kind, description, OnUse(path, writer),
                  read=OnUse(path, "read") if reads else None,
                  companions=OnUse(path, "companions") if companions else None,
                  unavailable=OnUse(path, unavailable) if unavailable else None, **fields)


# The table of formats, in the order they are listed (-f choices, messages).
_DECLARED = (
    _declare("cps", "cps", (".cps",), STREAM, "the Castor polygon stream", reads=True,
             binary=False, one_frame=False, header=b"castor-polygons 1\n"),
    _declare("off", "off", (".off",), MESH, "Geomview OFF with a colour per face", reads=True,
             binary=False),
    _declare("obj", "obj", (".obj",), MESH, "Wavefront OBJ with a material per colour",
             reads=True, companions=True, binary=False, up="y"),
    _declare("stl", "stl", (".stl",), MESH, "binary STL, geometry only", reads=True,
             triangles_only=True),
    _declare("stl", "stl-ascii", (".stl",), MESH, "ASCII STL, geometry only",
             writer="write_ascii", reads=True, binary=False, triangles_only=True),
    _declare("ply", "ply", (".ply",), MESH, "binary PLY with vertex colours", reads=True,
             triangles_only=True),
    _declare("glb", "glb", (".glb",), MESH, "binary glTF 2.0, one node per object", reads=True,
             triangles_only=True, up="y", reads_also=(".gltf",)),
    _declare("threemf", "3mf", (".3mf",), MESH, "3D Manufacturing Format, coloured, in millimetres",
             reads=True, triangles_only=True, options=("--scale",)),
    _declare("ifc", "ifc", (".ifc",), BIM, "IFC4 for BIM programs, one element per object",
             unavailable="unavailable", binary=False),
    _declare("png", "png", (".png",), PICTURE, "a ray-traced picture of the exact solids"),
    _declare("gif", "gif", (".gif",), PICTURE, "every frame ray traced, as an animation",
             one_frame=False),
    _declare("svg", "svg", (".svg",), DRAWING, "a plan, section or elevation as a vector drawing",
             binary=False, companions=True),  # companions: a drawing set's other sheets
    _declare("dxf", "dxf", (".dxf",), DRAWING, "a plan, section or elevation for CAD, in metres",
             binary=False, companions=True),
    _declare("pdf", "pdf", (".pdf",), DRAWING,
             "a plan, section or elevation on its sheet, for printing", companions=True),
)

_registry: dict[str, Format] | None = None


def registry() -> dict[str, Format]:
    """Every format, by name, in the order they are listed."""
    global _registry
    if _registry is None:
        _registry = {f.name: f for f in _DECLARED}
    return _registry


def __getattr__(name: str):
    if name == "FORMATS":  # the registry
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


def of_kind(*kinds: Kind | str) -> list[Format]:
    """The formats of these kinds (or kinds' names), in the order they are listed."""
    return [f for f in registry().values() if f.kind in kinds or f.kind.name in kinds]


def acts_on(option: str, chosen: Format) -> bool:
    """Whether the output option ``option`` (castor.options.OUTPUT_OPTIONS) has an
    effect on the format ``chosen``: its kind's option, or the format's own."""
    return option in chosen.kind.options or option in chosen.options


def without_effect(given: list[str], chosen: Format,
                   brings: dict[str, tuple[str, ...]] | None = None) -> list[str]:
    """A warning for each output option of ``given`` that has no effect on the
    format ``chosen``, naming the outputs it acts on (CLI.md): neither its own
    nor brought by another option given that acts on it (``brings``: the
    options each option brings, from castor.options.OUTPUT_OPTIONS; --pixel-error
    brings the camera's options)."""
    brings = brings or {}
    brought = {flag for option in given
               if acts_on(option, chosen) for flag in brings.get(option, ())}
    return [f"{option} has no effect on {chosen.name} output (it acts on "
            f"{' and '.join(outputs_of(option))}); it is ignored"
            for option in given if not acts_on(option, chosen) and option not in brought]


def outputs_of(option: str) -> list[str]:
    """What ``option`` acts on, in words: the kinds that take it, then the formats."""
    return ([kind.plural for kind in KINDS if option in kind.options]
            + [f.name for f in registry().values() if option in f.options])
