"""Every file castor writes or reads: one registry of formats, merged from their modules.

As trimesh's ``exchange/``: each format is one module of this package that
declares its ``FORMATS``, a tuple of ``Format`` records naming the functions
that write it and, where castor reads it back, the one that reads it.

The records are read from the modules' source without running them, as
setuptools reads a ``version = attr: ...`` (a record is plain data: literals,
and the names of its module's functions), and a format's module is imported
when one of its functions is first called. So the command line knows every
format's name, endings and description (``-f``, ``--help``, ``-o x.glb``)
without importing numpy or any writer: ``castor --check`` and the stream of a
cube import only what they use. A record written otherwise (a computed field)
still works: its module is then imported to read it, as before, and
tests/formats/test_registry.py says which one slows start-up. A module whose
own dependencies are missing is left out in that case; a format read from the
source whose module then fails to import says so when it is used.

Adding a format is one module here: ``castor/formats/NAME.py`` with its
functions and ``FORMATS = (Format(...),)`` at its end. Nothing else lists it:
the command line's ``-f`` choices and messages, the writers' dispatch
(castor.jobs), the output (castor.formats.output) and castor-view's readers
all read the registry.
"""

from __future__ import annotations

import ast
import importlib
import os
from typing import Callable, NamedTuple

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


class Format(NamedTuple):
    """One format: how castor names, writes and (perhaps) reads it. (A NamedTuple:
    castor --help and --version list the formats without importing dataclasses.)"""

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


class OnUse:
    """A function of a format's module, named by its record and imported when first
    called: what a record read from the source holds in place of the function."""

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


_FIELDS = Format._fields
_FUNCTIONS = {"write", "write_pieces", "read", "companions"}  # the fields that name functions
_MARK = "\nFORMATS = "  # where a module's records begin


def declared(module: str, source: str) -> list[Format] | None:
    """The records at the end of a format module's ``source``, read without running
    it; None where one is not plain data (then the module is imported to read them)."""
    start = source.rfind(_MARK)
    if start < 0:
        return None
    try:
        statement = ast.parse(source[start + 1:]).body
    except SyntaxError:
        return None
    if len(statement) != 1 or not isinstance(statement[0], ast.Assign):
        return None
    value = statement[0].value
    if not isinstance(value, (ast.Tuple, ast.List)):
        return None
    records = []
    for call in value.elts:
        if not (isinstance(call, ast.Call) and isinstance(call.func, ast.Name)
                and call.func.id == "Format" and len(call.args) <= len(_FIELDS)):
            return None
        named = list(zip(_FIELDS, call.args)) + [(k.arg, k.value) for k in call.keywords]
        given = {}
        for field, node in named:
            if field in _FUNCTIONS and isinstance(node, ast.Name):
                given[field] = OnUse(module, node.id)
                continue
            try:
                given[field] = ast.literal_eval(node)
            except (ValueError, TypeError, SyntaxError, MemoryError, RecursionError):
                return None
        try:
            records.append(Format(**given))
        except TypeError:  # an unknown or missing field: Python says which on import
            return None
    return records


def source_modules(path) -> list[tuple[str, str]]:
    """(directory, name) of each module of a package whose ``__path__`` is ``path``,
    by name: its ``NAME.py`` files (pkgutil's listing, without importing pkgutil)."""
    found = {}
    for directory in path:
        try:
            entries = os.listdir(directory)
        except OSError:
            continue
        for entry in entries:
            name, dot, suffix = entry.partition(".")
            if suffix == "py" and name.isidentifier():
                found.setdefault(name, directory)
    return sorted((directory, name) for name, directory in found.items())


_registry: dict[str, Format] | None = None
_SKIPPED = {"output"}  # modules of this package that declare no format


def _imported(module: str) -> list[Format]:
    """The records of a module that cannot be read without running it."""
    try:
        return list(getattr(importlib.import_module(module), "FORMATS", ()))
    except ImportError as exc:
        if (exc.name or "").split(".")[0] == "castor":
            raise  # castor's own module is broken: say so, never hide a format
        return []  # its own dependency is missing: not part of this castor


def registry() -> dict[str, Format]:
    """Every format, by name, in the order they are listed; built once, from the
    modules' records (read from their source; a module imported only where its
    records are not plain data)."""
    global _registry
    if _registry is None:
        found: list[Format] = []
        for directory, name in source_modules(__path__):
            if name.startswith("_") or name in _SKIPPED:
                continue
            module = f"{__name__}.{name}"
            records = None
            path = os.path.join(directory, f"{name}.py")
            try:
                with open(path, encoding="utf-8") as handle:
                    records = declared(module, handle.read())
            except (OSError, UnicodeDecodeError):
                pass  # no source here (a package of compiled files only): imported instead
            found.extend(_imported(module) if records is None else records)
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
