"""Where frames go: standard output, one file, or one file per frame.

Every file is written beside its final name and renamed into place when
complete, so a reader never sees half a file and a failed run never clobbers
an old one.
"""

from __future__ import annotations

import io
import os
import re
import sys
import tempfile

from castor.diagnostics import CastorError, Location
from castor.mesh.frame import Frame
from castor.formats import FORMATS, module as writer

_PATTERN = re.compile(r"%0?\d*d")


class OutputError(CastorError):
    """The output cannot take this frame (a second frame for a one-frame file)."""


def has_pattern(path: str) -> bool:
    return bool(_PATTERN.search(path))


def _file_mode() -> int:
    """The mode a new file gets from open(): 0o666 less the umask."""
    mask = os.umask(0o022)
    os.umask(mask)
    return 0o666 & ~mask


def write_atomically(path: str, data: bytes) -> None:
    """Write beside ``path`` and rename into place: never half a file."""
    directory = os.path.dirname(os.path.abspath(path))
    fd, temporary = tempfile.mkstemp(prefix=".castor-", suffix=".tmp", dir=directory)
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
        os.chmod(temporary, _file_mode())  # mkstemp makes it private; open() would not
        os.replace(temporary, path)
    except BaseException:
        try:
            os.unlink(temporary)
        except OSError:
            pass
        raise


def encode(frame: Frame, name: str, target: str | None = None) -> tuple[bytes, dict[str, bytes]]:
    """The frame in format ``name``, and the files that go beside it (by path)."""
    patterned = target is not None and has_pattern(target)
    if name == "cps" and not patterned:  # a part of one stream, not a file of its own
        from castor.formats.cps import format_frame

        return format_frame(frame).encode("utf-8"), {}
    if patterned:
        target = target % frame.number
    data = _render(frame, name, target)
    companions = getattr(writer(name), "companions", None)
    return data, (companions(frame, target) if companions and target else {})


def _render(frame: Frame, name: str, path: str | None = None) -> bytes:
    module = writer(name)
    binary = FORMATS[name].binary
    if binary:
        buffer = io.BytesIO()
        module.write(frame, buffer)
        return buffer.getvalue()
    text = io.StringIO()
    if name == "cps":
        from castor.formats.cps import HEADER

        text.write(HEADER)
        module.write(frame, text)
    elif name == "stl-ascii":
        module.write_ascii(frame, text)
    elif name == "obj":
        module.write(frame, text, path)
    else:
        module.write(frame, text)
    return text.getvalue().encode("utf-8")


class Output:
    """Sends each finished frame to its destination in the chosen format."""

    def __init__(self, path: str | None, format_name: str):
        self.path = path
        self.format = format_name
        self.frames = 0
        self.stream_parts: list[str] = []  # the cps stream, for a single -o file

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
            text = data.decode("utf-8")
            if self.path is None:
                sys.stdout.write(text)
                sys.stdout.flush()
            else:
                self.stream_parts.append(text)
            return
        if self.frames > 1 and not patterned:
            where = self.path or "standard output"
            stem, suffix = os.path.splitext(self.path or f"scene{FORMATS[self.format].suffix}")
            raise OutputError(
                f"{self.format} output holds one frame, and this is frame {number} for "
                f"{where}; give a pattern such as -o {stem}-%03d{suffix} for one file per frame",
                location)
        if self.path is None:
            sys.stdout.buffer.write(data)
            sys.stdout.buffer.flush()
            return
        for companion, content in companions.items():
            write_atomically(companion, content)
        write_atomically(self.target(number), data)

    def target(self, number: int) -> str | None:
        if self.path is None:
            return None
        return self.path % number if has_pattern(self.path) else self.path

    def finish(self, had_errors: bool) -> bool:
        """Put a single cps file in place; False when it was left out."""
        if self.path is None or self.format != "cps" or has_pattern(self.path):
            return True
        if had_errors and not self.stream_parts:
            return False
        from castor.formats.cps import HEADER

        write_atomically(self.path, (HEADER + "".join(self.stream_parts)).encode("utf-8"))
        return True
