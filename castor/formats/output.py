"""Where frames go: standard output, one file, or one file per frame.

Every file is written beside its final name and renamed into place when
complete, so a reader never sees half a file and a failed run never clobbers
an old one. A destination that cannot be written is a usage error: it is
checked before any work, and a write that fails later (a full disk) stops the
run with the same kind of message.
"""

from __future__ import annotations

import codecs
import itertools
import os
import re
import sys
from typing import Iterable, Iterator, NamedTuple, Union

from castor.diagnostics import CastorError, Location
from castor.formats import WriteInfo, registry

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


def suffix_message(path: str) -> str:
    """The usage error for an output whose extension names no format."""
    suffixes = []
    for f in registry().values():
        if f.suffix not in suffixes:
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


def same_file(output: str, scene: str) -> bool:
    """Whether writing ``output`` would write over the scene file ``scene`` (as
    cpp and compilers refuse to; a '-o' of a device such as /dev/null never does)."""
    try:
        return os.path.samefile(output, scene) and not is_device(output)
    except (OSError, ValueError):  # either absent, unreadable, or a name with a NUL
        return False


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


class Spooled(NamedTuple):
    """A frame's bytes in a file a worker process wrote (beside the output, or in
    the temporary directory): moved into place or copied, then removed."""

    path: str


# what a writer hands on: the bytes, the bytes a piece at a time, or a spooled file
Data = Union[bytes, Iterable[bytes], Spooled]

_BLOCK = 1 << 20  # bytes copied at a time from a spooled file


def pieces_of(data: Data) -> Iterator[bytes]:
    """The bytes of ``data`` a piece at a time (a spooled file's blocks; its
    owner removes it)."""
    if isinstance(data, (bytes, bytearray)):
        yield data
    elif isinstance(data, Spooled):
        with open(data.path, "rb") as handle:
            while True:
                block = handle.read(_BLOCK)
                if not block:
                    break
                yield block
    else:
        yield from data


# files being written beside their final names, and spooled frames not yet
# written: what an interrupted run removes (castor.cli, on Ctrl-C)
_temporaries: set[str] = set()
# where their names are told as well (castor.supervisor: the process that waits
# for this one removes them when it kills it); empty: nowhere
_told: list[int] = []


def tell_temporaries(fd: int) -> None:
    """Tell the name of every temporary file, before it is made, through ``fd``
    (``+NAME\\0``), and again when it is renamed into place or removed (``-NAME\\0``)."""
    _told[:] = [fd]


def _own(path: str) -> None:
    _temporaries.add(path)
    _tell(b"+", path)


def _disown(path: str) -> None:
    _temporaries.discard(path)
    _tell(b"-", path)


def _tell(sign: bytes, path: str) -> None:
    for fd in _told:
        try:
            os.write(fd, sign + os.fsencode(path) + b"\0")  # the same working directory
        except OSError:  # the process that waits has gone: this one goes with it
            pass


def track(data: Data | None) -> None:
    """Count a spooled file among the temporaries until it is written."""
    if isinstance(data, Spooled):
        _own(data.path)


def remove_temporaries() -> None:
    """Remove every file being written: an interrupted run leaves no half file."""
    for path in list(_temporaries):
        try:
            os.unlink(path)
        except OSError:
            pass
    _temporaries.clear()


def discard(data: Data | None) -> None:
    """Remove a spooled file that will not be written anywhere."""
    if isinstance(data, Spooled):
        try:
            os.unlink(data.path)
        except OSError:
            pass
        _disown(data.path)


def _temporary_in(directory: str) -> tuple[int, str]:
    """A new private file in ``directory`` (.castor-RANDOM.tmp), open: as
    tempfile.mkstemp makes it, without importing tempfile (with shutil, random,
    bz2 and lzma, some 8 ms of a run that writes a file)."""
    flags = os.O_RDWR | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0) \
        | getattr(os, "O_CLOEXEC", 0)
    for _ in range(100):
        path = os.path.join(directory, f".castor-{os.urandom(6).hex()}.tmp")
        _own(path)  # counted before it exists: removed if the run is stopped meanwhile
        try:
            return os.open(path, flags, 0o600), path
        except FileExistsError:
            _disown(path)  # another's
            continue
        except OSError:
            _disown(path)
            raise
    raise FileExistsError(f"no new temporary file name in {directory}")


class AtomicFile:
    """A file written a piece at a time beside ``path`` and renamed into place by
    ``commit``: never half a file. A device or a pipe (/dev/null) is written into.

    Raises ``Unwritable`` with a message in the user's words when the file
    cannot be written (missing directory, no permission, full disk)."""

    def __init__(self, path: str):
        self.path = path
        self.temporary = None
        try:
            if is_device(path):
                # /dev/null, a named pipe, a terminal: written into, never renamed over
                self.handle = open(path, "wb")
                return
            directory = os.path.dirname(os.path.abspath(path))
            fd, self.temporary = _temporary_in(directory)
            self.handle = os.fdopen(fd, "wb")
        except OSError as exc:
            raise Unwritable(f"cannot write '{path}': {_reason(exc)}") from None

    def write(self, data: bytes) -> None:
        try:
            self.handle.write(data)
        except OSError as exc:
            self.discard()
            raise Unwritable(f"cannot write '{self.path}': {_reason(exc)}") from None

    def commit(self) -> None:
        try:
            self.handle.close()
            if self.temporary is not None:
                os.chmod(self.temporary, _file_mode())  # mkstemp makes it private
                os.replace(self.temporary, self.path)
                _disown(self.temporary)
                self.temporary = None
        except OSError as exc:
            self.discard()
            raise Unwritable(f"cannot write '{self.path}': {_reason(exc)}") from None

    def discard(self) -> None:
        """Leave the old file as it was (nothing written in place)."""
        try:
            self.handle.close()
        except OSError:
            pass
        if self.temporary is not None:
            try:
                os.unlink(self.temporary)
            except OSError:
                pass
            _disown(self.temporary)
            self.temporary = None


def write_atomically(path: str, data: Data) -> None:
    """Write beside ``path`` and rename into place: never half a file. ``data``
    is bytes, the bytes a piece at a time, or a spooled file (renamed into
    place when it is beside ``path``, else copied and removed).

    Raises ``Unwritable`` with a message in the user's words when the file
    cannot be written (missing directory, no permission, full disk)."""
    if isinstance(data, Spooled) and not is_device(path) and (
            os.path.dirname(os.path.abspath(data.path)) == os.path.dirname(os.path.abspath(path))):
        try:
            os.chmod(data.path, _file_mode())
            os.replace(data.path, path)
            _disown(data.path)
            return
        except OSError:
            pass  # copied below
    destination = AtomicFile(path)
    try:
        for piece in pieces_of(data):
            destination.write(piece)
        destination.commit()
    except BaseException:
        destination.discard()
        raise
    finally:
        discard(data)


def _reason(exc: OSError) -> str:
    text = (exc.strerror or str(exc)).lower()
    return text[0].lower() + text[1:] if text else "failed"


def encode(product, name: str, target: str | None = None, *, number: int | None = None,
           options: dict | None = None) -> tuple[bytes, dict[str, bytes]]:
    """The product in format ``name``, and the files that go beside it (by path).
    ``target`` is -o's path (a pattern is filled in with the frame's ``number``,
    by default the product's own); ``options``: the format's own (WriteInfo)."""
    pieces, companions = encode_pieces(product, name, target, number=number, options=options)
    return b"".join(pieces), companions


def encode_pieces(product, name: str, target: str | None = None, *, number: int | None = None,
                  options: dict | None = None) -> tuple[Iterator[bytes], dict[str, bytes]]:
    """As ``encode``, the bytes made a piece at a time as they are read (by the
    format's writer; a format made whole is one piece): the writer's memory is a
    piece's."""
    chosen = registry()[name]
    patterned = target is not None and has_pattern(target)
    if patterned:
        target = frame_path(target, getattr(product, "number", 1) if number is None else number)
    info = WriteInfo(target, options)
    written = chosen.write(product, info)  # its pieces (bytes, or nothing, taken as such)
    data = iter([written]) if isinstance(written, (bytes, bytearray)) else iter(written or ())
    if chosen.header and patterned:  # a file of its own: it begins with the header
        data = itertools.chain([chosen.header], data)
    companions = chosen.companions
    return data, (companions(product, info) if companions is not None and target else {})


def render(product, name: str, path: str | None = None) -> bytes:
    """The bytes of ``product`` in format ``name`` (``path``: where it is going, for
    formats that name a companion file)."""
    return b"".join(registry()[name].write(product, WriteInfo(path)))


def _with_bytes(data: Data) -> Data | None:
    """``data``, or None where it holds no byte (its pieces read up to the first byte)."""
    if isinstance(data, Spooled):
        return data
    if isinstance(data, (bytes, bytearray)):
        return data if data else None
    pieces = iter(data)
    for piece in pieces:
        if piece:
            return itertools.chain([piece], pieces)
    return None


def to_stdout(data: Data) -> None:
    """Bytes to standard output, a piece at a time (through its text layer when
    it has no bytes one, as under a test's redirection)."""
    buffer = getattr(sys.stdout, "buffer", None)
    if buffer is None:
        decoder = codecs.getincrementaldecoder("utf-8")("surrogateescape")
        for piece in pieces_of(data):
            sys.stdout.write(decoder.decode(piece))
        sys.stdout.write(decoder.decode(b"", final=True))
        sys.stdout.flush()
        return
    sys.stdout.flush()
    for piece in pieces_of(data):
        buffer.write(piece)
    buffer.flush()


class Output:
    """Sends each finished frame to its destination in the chosen format."""

    def __init__(self, path: str | None, format_name: str):
        self.path = path
        self.format = format_name
        self.frames = 0
        self.stream: AtomicFile | None = None  # the stream, for a single -o file
        chosen = registry()[format_name]
        self.streamed = chosen.kind.streamed  # frame after frame into one file
        self.header = chosen.header
        self.one_frame = chosen.one_frame
        self.suffix = chosen.suffix

    def start(self) -> None:
        """Standard output's stream begins with its first frame (or at the end of a
        run that made frames and wrote none): a scene that cannot be read, or that
        has no '>' command, writes nothing at all."""
        self.header_due = self.path is None and self.streamed

    def _begin(self) -> None:
        if getattr(self, "header_due", False):
            self.header_due = False
            sys.stdout.write(self.header.decode("utf-8"))
            sys.stdout.flush()

    def put(self, number: int, data: Data, companions: dict[str, bytes],
            location: Location) -> None:
        """Write one frame's encoded bytes where they go, a piece at a time."""
        try:
            self._put(number, data, companions, location)
        finally:
            discard(data)

    def _put(self, number: int, data: Data, companions: dict[str, bytes],
             location: Location) -> None:
        self.frames += 1
        self._begin()
        patterned = bool(self.path and has_pattern(self.path))
        if self.streamed and not patterned:
            if self.path is None:
                to_stdout(data)
                return
            # a single file: frames go into it as they come, renamed into place
            # at the end
            if self.stream is None:
                self.stream = AtomicFile(self.path)
                self.stream.write(self.header)
            try:
                for piece in pieces_of(data):
                    self.stream.write(piece)
            except BaseException:
                self.abandon()
                raise
            return
        refusal = self.refusal(self.frames, number, location)
        if refusal is not None:
            raise refusal
        data = _with_bytes(data)
        if data is None:  # a file of nothing would pass for the frame: the old one stays
            raise self.unmade(number, location)
        if self.path is None:
            to_stdout(data)
            return
        for companion, content in companions.items():
            write_atomically(companion, content)
        write_atomically(frame_path(self.path, number) if patterned else self.path, data)

    def unmade(self, number: int, location: Location) -> OutputError:
        """The error of a frame its format's writer gave no bytes for: nothing is written."""
        patterned = bool(self.path and has_pattern(self.path))
        where = (frame_path(self.path, number) if patterned else self.path) or "standard output"
        return OutputError(f"{where} not written: the {self.format} writer gave no bytes for "
                           f"frame {number}", location)

    def refusal(self, count: int, number: int, location: Location) -> OutputError | None:
        """Why this output cannot take its ``count``-th frame (frame ``number``), or None."""
        if count <= 1 or not self.one_frame or (self.path and has_pattern(self.path)):
            return None
        where = self.path or "standard output"
        stem, suffix = os.path.splitext(self.path or f"scene{self.suffix}")
        return OutputError(
            f"{self.format} output holds one frame, and this is frame {number} for {where}; "
            f"give a pattern such as -o {stem}-%03d{suffix} for one file per frame (the frames "
            f"after it are not made)", location)

    def finish(self, had_errors: bool, frames_made: int = 1) -> bool:
        """Put a single stream file in place; False when it was left out.
        ``frames_made``: the '>' commands met (none: standard output stays empty)."""
        if frames_made:
            self._begin()  # frames that all failed: still a stream, with no frame
        if self.path is None or not self.streamed or has_pattern(self.path):
            return True
        if self.stream is None:
            if had_errors and not is_device(self.path):
                return False  # a device (-o /dev/null) has no old file to keep: as stdout
            write_atomically(self.path, self.header)
            return True
        stream, self.stream = self.stream, None
        stream.commit()
        return True

    def abandon(self) -> None:
        """A run that stops on an exception: a single stream file being written is
        left out (the old file stays)."""
        if self.stream is not None:
            self.stream.discard()
            self.stream = None
