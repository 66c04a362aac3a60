"""The language server's commands ``castor.snap``, ``castor.place`` and
``castor.move`` (and ``castor.measure``), as pure functions of one JSON
object (CLI.md, "Editing on screen"): what ``workspace/executeCommand``, the
live preview's page and any script call.

Each takes the command's arguments (a dict as JSON gives it) and a
``castor.editing.document.Cache`` that reads the scene's texts (an editor's
buffers, else the files) and keeps the last evaluations, and returns what
the command answers: a snap, or a ``WorkspaceEdit`` (``{"changes": {uri:
[TextEdit...]}}``) to send with ``workspace/applyEdit`` or to write with
``apply_workspace_edit``. Bad arguments, or a gesture the text does not
allow, raise ``CommandError`` with the message a JSON-RPC error carries;
nothing is changed then. An optional ``version`` (castor.editing.text.digest
of the text the gesture was made on) refuses an edit on a text that changed
since.
"""

from __future__ import annotations

import math
import re

from castor.editing.document import Cache, CommandError, path_to_uri, uri_to_path
from castor.editing.text import TextEdit, apply, digest, inverse

__all__ = ["COMMANDS", "Cache", "CommandError", "apply_workspace_edit", "execute",
           "inverse_workspace_edit", "measure", "move", "place", "snap", "text_version",
           "write_workspace_edit"]


def snap(arguments, cache: Cache) -> dict | None:
    """``castor.snap``: ``{"point", "feature", "source", "path"}`` or None."""
    from castor.editing.snap import snap as snapped

    arguments = _object(arguments)
    document = _document(arguments, cache)
    number = arguments.get("frame", 1)
    prepared = document.prepared(number)
    origin = _vector(arguments, "origin")
    direction = _vector(arguments, "direction")
    if math.hypot(*direction) == 0:
        raise CommandError("'direction' is a ray of zero length")
    pixel, pixel_size = arguments.get("pixel"), arguments.get("pixelSize")
    if pixel_size is not None:
        pixel_size = _positive(pixel_size, "pixelSize")
        pixel = None
    elif pixel is not None:
        pixel = _positive(pixel, "pixel")
    else:
        raise CommandError("give 'pixel' (the angle of one pixel, radians) or 'pixelSize' "
                           "(metres, for an orthographic view)")
    previous = _vector(arguments, "from") if arguments.get("from") is not None else None
    distance = arguments.get("distance")
    if distance is not None:
        distance = _number(distance, "distance")
        if previous is None:
            raise CommandError("a typed 'distance' needs the previous point ('from')")
    found = snapped(prepared, origin, direction, pixel, pixel_size, previous, distance)
    return None if found is None else found.as_json()


def place(arguments, cache: Cache) -> dict:
    """``castor.place``: the WorkspaceEdit that writes the new object."""
    from castor.editing.gestures import DEFAULT_COLOUR, place as placed

    arguments = _object(arguments)
    document = _document(arguments, cache)
    kind, extra = _primitive(arguments.get("primitive"))
    at = _vector(arguments, "at")
    size = _vector(arguments, "size")
    if any(s == 0 for s in size):
        raise CommandError("'size' has a zero: the box would be flat")
    colour = _vector(arguments, "colour") if arguments.get("colour") is not None \
        else DEFAULT_COLOUR
    if any(not 0 <= c <= 1 for c in colour):
        raise CommandError("'colour' takes three numbers between 0 and 1")
    name, into = arguments.get("name"), arguments.get("into")
    for key, value in (("name", name), ("into", into)):
        if value is not None and not isinstance(value, str):
            raise CommandError(f"'{key}' must be an object's name")
    edits = placed(document, arguments.get("frame", 1), kind, extra, at, size, colour, name,
                   into)
    return _workspace_edit(edits)


def move(arguments, cache: Cache) -> dict:
    """``castor.move``: the WorkspaceEdit that moves the use at ``source`` by ``by``."""
    from castor.editing.gestures import move as moved

    arguments = _object(arguments)
    document = _document(arguments, cache)
    source = arguments.get("source")
    if not isinstance(source, str) or not re.fullmatch(r".+:\d+:\d+", source):
        raise CommandError("'source' must be FILE:LINE:COL of a primitive or an object's use, "
                           "as castor.snap gives it")
    path = arguments.get("path")
    if path is not None and not isinstance(path, str):
        raise CommandError("'path' must be a path as castor.snap gives it")
    by = _vector(arguments, "by")
    return _workspace_edit(moved(document, arguments.get("frame", 1), source, by, path))


def measure(arguments, cache: Cache) -> dict:
    """``castor.measure``: between ``from`` and ``to``, the distance and its dx,
    dy, dz; of an ``object`` (a name), its volume, area and bounding box; of the
    face a ray (``origin``, ``direction``) meets, its area. Never an edit."""
    from castor.editing.gestures import distance, face_area, object_figures

    arguments = _object(arguments)
    if arguments.get("origin") is not None:
        document = _document(arguments, cache)
        origin, direction = _vector(arguments, "origin"), _vector(arguments, "direction")
        if math.hypot(*direction) == 0:
            raise CommandError("'direction' is a ray of zero length")
        return face_area(document, arguments.get("frame", 1), origin, direction)
    if arguments.get("object") is not None:
        document = _document(arguments, cache)
        name = arguments["object"]
        if not isinstance(name, str):
            raise CommandError("'object' must be an object's name")
        return object_figures(document, arguments.get("frame", 1), name)
    return distance(_vector(arguments, "from"), _vector(arguments, "to"))


COMMANDS = {"castor.snap": snap, "castor.place": place, "castor.move": move,
            "castor.measure": measure}


def execute(command: str, arguments, cache: Cache):
    """Run a command by its name (``workspace/executeCommand``)."""
    if command not in COMMANDS:
        raise CommandError(f"unknown command '{command}' (known: {', '.join(COMMANDS)})")
    return COMMANDS[command](arguments, cache)


# --- WorkspaceEdits

def _workspace_edit(edits) -> dict:
    changes: dict[str, list] = {}
    for path, edit in edits:
        changes.setdefault(path_to_uri(path), []).append(edit.as_json())
    return {"changes": changes}


def apply_workspace_edit(edit: dict, read) -> dict[str, str]:
    """The new text of each document a WorkspaceEdit changes (``read(uri)`` gives
    the current one): what ``castor --serve`` writes, atomically, file by file."""
    out = {}
    for uri, edits in edit.get("changes", {}).items():
        text = read(uri)
        if text is None:
            raise CommandError(f"cannot read '{uri}'")
        out[uri] = apply(text, [TextEdit.from_json(e) for e in edits])
    return out


def inverse_workspace_edit(edit: dict, read) -> dict:
    """The WorkspaceEdit that undoes ``edit``, given the texts before it: Undo."""
    changes = {}
    for uri, edits in edit.get("changes", {}).items():
        text = read(uri)
        if text is None:
            raise CommandError(f"cannot read '{uri}'")
        undo = inverse(text, [TextEdit.from_json(e) for e in edits])
        changes[uri] = [e.as_json() for e in undo]
    return {"changes": changes}


def write_workspace_edit(edit: dict, cache: Cache, uri: str) -> dict:
    """Write a WorkspaceEdit into the files, as ``castor --serve`` does: only the
    scene's own files (the main file ``uri`` and those it includes), each
    atomically; returns the WorkspaceEdit that undoes it."""
    from castor.formats.output import Unwritable, write_atomically

    document = cache.document(uri)
    allowed = {path_to_uri(path) for path in document.files}
    for target in edit.get("changes", {}):
        if target not in allowed:
            raise CommandError(f"'{uri_to_path(target)}' is not one of the scene's files: "
                               f"nothing was written")
    undo = inverse_workspace_edit(edit, cache.read)
    texts = apply_workspace_edit(edit, cache.read)
    for target, text in texts.items():
        try:
            write_atomically(uri_to_path(target), text.encode("utf-8"))
        except Unwritable as error:
            raise CommandError(str(error)) from None
    return undo


# --- arguments

def _object(arguments) -> dict:
    if isinstance(arguments, list) and len(arguments) == 1:
        arguments = arguments[0]  # executeCommand's arguments are a list
    if not isinstance(arguments, dict):
        raise CommandError("the arguments are one JSON object")
    return arguments


def _document(arguments: dict, cache: Cache):
    document = cache.document(arguments.get("uri"))
    version = arguments.get("version")
    if version is not None and version != document.version:
        raise CommandError(f"the text changed since this gesture began (it was version "
                           f"{version}, it is {document.version} now): nothing was changed; "
                           f"try again on the text as it is")
    if document.errors and not document.frames:
        raise CommandError(f"the scene has errors: {document.errors[0]}")
    return document


def _number(value, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise CommandError(f"'{name}' must be a number, not {value!r}")
    return float(value)


def _positive(value, name: str) -> float:
    value = _number(value, name)
    if value <= 0:
        raise CommandError(f"'{name}' must be more than 0")
    return value


# coordinates beyond this are refused: castor's own limit is 1e12
# (castor.csg.evaluate.MAX_COORDINATE), and an edit must stay within it
LARGEST = 1e9


def _vector(arguments: dict, name: str) -> tuple[float, float, float]:
    value = arguments.get(name)
    if not isinstance(value, (list, tuple)) or len(value) != 3:
        raise CommandError(f"'{name}' must be three numbers [x, y, z]")
    numbers = tuple(_number(v, name) for v in value)
    if any(abs(v) > LARGEST for v in numbers):
        raise CommandError(f"'{name}' reaches beyond {LARGEST:g}")
    return numbers


_PRIMITIVE = re.compile(r"\s*!([a-z]+)\s*(?:\((.*)\))?\s*\Z", re.DOTALL)
_NUMBER = re.compile(r"\s*-?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?\s*\Z")


def _primitive(value) -> tuple[str, tuple[float, ...]]:
    """``"!cu"``, ``"!pr(6)"``, ``"!ex(0, 0, 1, 0, 0, 1)"``: the kind and the
    arguments after the colour, numbers only (nothing from a page is evaluated)."""
    match = _PRIMITIVE.match(value) if isinstance(value, str) else None
    if match is None:
        raise CommandError(f"'primitive' must be written as the language does: \"!cu\", "
                           f"\"!pr(6)\", not {value!r}")
    kind, inside = match.groups()
    extra: list[float] = []
    if inside is not None and inside.strip():
        for piece in inside.split(","):
            if not _NUMBER.match(piece):
                raise CommandError(f"the arguments of '!{kind}' must be plain numbers, "
                                   f"not '{piece.strip()}'")
            extra.append(float(piece))
    return kind, tuple(extra)


def text_version(text: str) -> str:
    """The ``version`` of a text, for an edit made on it."""
    return digest(text)
