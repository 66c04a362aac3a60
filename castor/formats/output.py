"""Where frames go: standard output, one file, or one file per frame.

Every file is written beside its final name and renamed into place when
complete, so a reader never sees half a file and a failed run never clobbers
an old one. A destination that cannot be written is a usage error: it is
checked before any work, and a write that fails later (a full disk) stops the
run with the same kind of message.
"""

from __future__ import annotations

import importlib.util
import os
import re
import sys
import tempfile

from castor.diagnostics import CastorError, Location
from castor.mesh.frame import Frame
from castor.formats import FORMATS, module as writer

_PATTERN = re.compile(r"%0?\d*d")
_PERCENT = re.compile(r"%%|%0?\d*d|%")


class OutputError(CastorError):
    """The output cannot take this frame (a second frame for a one-frame file)."""


class Unwritable(Exception):
    """A destination that cannot be written: the run stops with a usage error (exit 2)."""


def has_pattern(path: str) -> bool:
    return bool(_PATTERN.search(path))


def frame_path(path: str, number: int) -> str:
    """``path`` with its frame-number pattern replaced by ``number`` (and '%%' by '%')."""
    def replace(match):
        text = match.group()
        return "%" if text == "%%" else text % number
    return _PERCENT.sub(replace, path)


def available(name: str) -> bool:
    """Whether the module that writes format ``name`` is part of this castor."""
    return importlib.util.find_spec(f"castor.formats.{FORMATS[name].module}") is not None


def suffix_message(path: str) -> str:
    """The usage error for an output whose extension names no format."""
    suffixes = []
    for f in FORMATS.values():
        if f.suffix not in suffixes and available(f.name):
            suffixes.append(f.suffix)
    hint = ""
    if path.lower().endswith(".gltf"):
        hint = " (castor writes glTF as one binary file, .glb)"
    return (f"cannot tell the format of '{path}' from its extension{hint}; use one of "
            f"{' '.join(suffixes)}, or give the format with -f NAME")


def destination_problem(path: str, option: str = "-o") -> str | None:
    """Why ``path`` cannot be written to, as a usage error says it, or None.

    Checked before any frame is made: a pattern is well formed (one %d, '%%'
    for a literal '%'), and the directory exists and takes new files.
    """
    if not path.strip():
        return f"{option} needs a file name, such as {option} house.stl"
    conversions = [m.group() for m in _PERCENT.finditer(path) if m.group() != "%%"]
    patterns = [c for c in conversions if c != "%"]
    if patterns and len(conversions) > len(patterns):
        return (f"{option} {path}: a '%' that is not the frame-number pattern; write '%%' "
                f"for a '%' in the name")
    if len(patterns) > 1:
        suffix = os.path.splitext(path)[1] or ".stl"
        return (f"{option} {path}: {len(patterns)} frame-number patterns; a path takes one, such as "
                f"house-%03d{suffix}")
    target = frame_path(path, 1) if patterns else path
    if target.endswith(os.sep) or os.path.isdir(target):
        return f"{option} {path}: is a directory; give a file name such as {os.path.join(path, 'scene.stl')}"
    directory = os.path.dirname(os.path.abspath(target))
    if not os.path.isdir(directory):
        shown = os.path.dirname(target) or "."
        return f"cannot write '{path}': the directory '{shown}' does not exist"
    if not os.access(directory, os.W_OK | os.X_OK):
        shown = os.path.dirname(target) or "."
        return f"cannot write '{path}': the directory '{shown}' is not writable"
    return None


def is_device(path: str) -> bool:
    """An existing path that is no regular file or directory (/dev/null, a pipe)."""
    import stat

    try:
        mode = os.stat(path).st_mode
    except (OSError, ValueError):  # no such path, a NUL in the name
        return False
    return not stat.S_ISREG(mode) and not stat.S_ISDIR(mode)


def _file_mode() -> int:
    """The mode a new file gets from open(): 0o666 less the umask."""
    mask = os.umask(0o022)
    os.umask(mask)
    return 0o666 & ~mask


def write_atomically(path: str, data: bytes) -> None:
    """Write beside ``path`` and rename into place: never half a file.

    Raises ``Unwritable`` with a message in the user's words when the file
    cannot be written (missing directory, no permission, full disk)."""
    if is_device(path):
        # /dev/null, a named pipe, a terminal: written into, never renamed over
        try:
            with open(path, "wb") as handle:
                handle.write(data)
        except OSError as exc:
            raise Unwritable(f"cannot write '{path}': {_reason(exc)}") from None
        return
    directory = os.path.dirname(os.path.abspath(path))
    try:
        fd, temporary = tempfile.mkstemp(prefix=".castor-", suffix=".tmp", dir=directory)
    except OSError as exc:
        raise Unwritable(f"cannot write '{path}': {_reason(exc)}") from None
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
        os.chmod(temporary, _file_mode())  # mkstemp makes it private; open() would not
        os.replace(temporary, path)
    except BaseException as exc:
        try:
            os.unlink(temporary)
        except OSError:
            pass
        if isinstance(exc, OSError):
            raise Unwritable(f"cannot write '{path}': {_reason(exc)}") from None
        raise


def _reason(exc: OSError) -> str:
    text = (exc.strerror or str(exc)).lower()
    return text[0].lower() + text[1:] if text else "failed"


def encode(frame: Frame, name: str, target: str | None = None) -> tuple[bytes, dict[str, bytes]]:
    """The frame in format ``name``, and the files that go beside it (by path).
    ``target`` is -o's path (a pattern is filled in with the frame's number)."""
    patterned = target is not None and has_pattern(target)
    if patterned:
        target = frame_path(target, frame.number)
    data = render(frame, name, target)
    if name == "cps" and patterned:  # a file of its own: it begins with the header
        from castor.formats.cps import HEADER

        data = HEADER.encode("utf-8") + data
    companions = getattr(writer(name), "companions", None)
    return data, (companions(frame, target) if companions is not None and target else {})


def render(frame: Frame, name: str, path: str | None = None) -> bytes:
    """The bytes of ``frame`` in format ``name`` (``path``: where it is going, for
    formats that name a companion file)."""
    return getattr(writer(name), FORMATS[name].exporter)(frame, path)


def to_stdout(data: bytes) -> None:
    """Bytes to standard output (through its text layer when it has no bytes one,
    as under a test's redirection)."""
    buffer = getattr(sys.stdout, "buffer", None)
    if buffer is None:
        sys.stdout.write(data.decode("utf-8", "surrogateescape"))
        sys.stdout.flush()
        return
    sys.stdout.flush()
    buffer.write(data)
    buffer.flush()


class Output:
    """Sends each finished frame to its destination in the chosen format."""

    def __init__(self, path: str | None, format_name: str):
        self.path = path
        self.format = format_name
        self.frames = 0
        self.stream_parts: list[bytes] = []  # the cps stream, for a single -o file

    def start(self) -> None:
        if self.path is None and self.format == "cps":
            from castor.formats.cps import HEADER

            sys.stdout.write(HEADER)
            sys.stdout.flush()

    def put(self, number: int, data: bytes, companions: dict[str, bytes],
            location: Location) -> None:
        """Write one frame's encoded bytes where they go."""
        self.frames += 1
        patterned = bool(self.path and has_pattern(self.path))
        if self.format == "cps" and not patterned:
            if self.path is None:
                to_stdout(data)
            else:
                self.stream_parts.append(data)
            return
        refusal = self.refusal(self.frames, number, location)
        if refusal is not None:
            raise refusal
        if self.path is None:
            to_stdout(data)
            return
        for companion, content in companions.items():
            write_atomically(companion, content)
        write_atomically(frame_path(self.path, number) if patterned else self.path, data)

    def refusal(self, count: int, number: int, location: Location) -> OutputError | None:
        """Why this output cannot take its ``count``-th frame (frame ``number``), or None."""
        if count <= 1 or FORMATS[self.format].all_frames or (self.path and has_pattern(self.path)):
            return None
        where = self.path or "standard output"
        stem, suffix = os.path.splitext(self.path or f"scene{FORMATS[self.format].suffix}")
        return OutputError(
            f"{self.format} output holds one frame, and this is frame {number} for {where}; "
            f"give a pattern such as -o {stem}-%03d{suffix} for one file per frame (the frames "
            f"after it are not made)", location)

    def finish(self, had_errors: bool) -> bool:
        """Put a single cps file in place; False when it was left out."""
        if self.path is None or self.format != "cps" or has_pattern(self.path):
            return True
        if had_errors and not self.stream_parts:
            return False
        from castor.formats.cps import HEADER

        write_atomically(self.path, HEADER.encode("utf-8") + b"".join(self.stream_parts))
        return True
