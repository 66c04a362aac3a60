"""The Castor polygon stream (OUTPUT.md): text, one record a line.

Numbers are written in shortest round-trip form (Python's repr), so reading
them back gives the same double; whole numbers lose their '.0'.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Iterator

import numpy as np

from castor.formats import WriteInfo
from castor.mesh.frame import Frame

HEADER = "castor-polygons 1\n"


def _texts(values: list[float]) -> list[str]:
    out = list(map(repr, values))
    for i, text in enumerate(out):
        if text[-2:] == ".0":
            out[i] = text[:-2]
    return out


def number_strings(values: np.ndarray) -> list[str]:
    """Shortest round-trip text of each value; -0 is written 0. Where values
    repeat (walls on a grid, copies in rows), each is written once and looked up."""
    flat = np.asarray(values, dtype=np.float64).ravel() + 0.0
    if len(flat) < 4096:
        return _texts(flat.tolist())
    unique, index = np.unique(flat, return_inverse=True)
    if 2 * len(unique) > len(flat):
        return _texts(flat.tolist())
    return list(map(_texts(unique.tolist()).__getitem__, index.ravel().tolist()))


_UNSAFE = re.compile(r"[%\x00-\x20\x7f-\x9f\s]")


def where_field(where: str) -> str:
    """``FILE:LINE`` with a space, '%' or control character in FILE written %XX (its
    UTF-8 bytes), as in a URL, so that the record keeps its fields."""
    file, sep, line = where.rpartition(":")
    if not sep:
        file, line = where, ""
    file = _UNSAFE.sub(lambda m: "".join(f"%{b:02X}" for b in m.group().encode("utf-8")), file)
    return f"{file}{sep}{line}"


def frame_texts(frame: Frame, size: int | None = None) -> Iterator[str]:
    """The frame's records, from 'frame N WHERE' to 'endframe N COUNT', ``size``
    polygons at a time: each piece's texts are freed before the next is made."""
    from castor.formats._mesh import CHUNK

    size = size or CHUNK
    yield f"frame {frame.number} {where_field(frame.where)}\n"
    count = 0
    for obj in frame.objects:
        heads = []
        colours: dict[tuple, str] = {}
        for origin in obj.origins:
            colour = colours.get(origin.colour)
            if colour is None:
                colour = colours[origin.colour] = " ".join(_texts(
                    (np.array(origin.colour, dtype=np.float64) + 0.0).tolist()))
            heads.append(f"poly {origin.path} {colour} ")
        for first in range(0, obj.polygon_count, size):
            last = min(first + size, obj.polygon_count)
            start, end = obj.offsets[first], obj.offsets[last]
            # the texts of the vertices these polygons use, each written once
            used, local = np.unique(obj.indices[start:end], return_inverse=True)
            numbers = number_strings(obj.vertices[used])
            points = list(map(" ".join, zip(numbers[0::3], numbers[1::3], numbers[2::3])))
            del numbers
            offsets = obj.offsets[first:last + 1] - start
            # every polygon as its head, its size and its points, in one pass
            head_of = [heads[i] + str(n) + " " for i, n in
                       zip(obj.origin_of[first:last].tolist(), np.diff(offsets).tolist())]
            texts = list(map(points.__getitem__, local.ravel().tolist()))
            del points, used, local
            bounds = offsets.tolist()
            yield "\n".join([head_of[p] + " ".join(texts[bounds[p]:bounds[p + 1]])
                             for p in range(len(head_of))]) + "\n"
            count += len(head_of)
    yield f"endframe {frame.number} {count}\n"


def format_frame(frame: Frame) -> str:
    """The frame's records, from 'frame N WHERE' to 'endframe N COUNT', as one text."""
    return "".join(frame_texts(frame))


def export_chunks(frame: Frame, path: str | None = None, size: int | None = None) -> Iterator[bytes]:
    """The frame's records a piece at a time (the header, written once per
    stream, is ``HEADER``)."""
    for text in frame_texts(frame, size):
        yield text.encode("utf-8", "surrogateescape")


def export(frame: Frame, path: str | None = None) -> bytes:
    """The frame's records (the header, written once per stream, is ``HEADER``)."""
    return b"".join(export_chunks(frame, path))


# --- reading the stream back


class StreamError(ValueError):
    """A polygon stream that cannot be read; the message says where and why."""


@dataclass
class StreamFrame:
    """One frame: polygons as a flat vertex list with offsets, and a colour each."""

    number: int
    where: str
    points: np.ndarray  # (N, 3) float64, polygon after polygon
    offsets: np.ndarray  # (P + 1,)
    colours: np.ndarray  # (P, 3) in 0..1
    # each polygon's path (an index into paths), where the file gives one
    path_of: np.ndarray | None = None
    paths: list[str] | None = None

    @property
    def polygon_count(self) -> int:
        return len(self.offsets) - 1

    def triangles(self) -> tuple[np.ndarray, np.ndarray]:
        """Fan triangles as point numbers, and the polygon of each."""
        from castor.mesh.arrays import fan_triangles

        return fan_triangles(self.offsets, np.arange(len(self.points)))


def load(lines: Iterator[str], name: str = "<stdin>") -> Iterator[StreamFrame]:
    """Frames of a castor polygon stream, each as soon as its 'endframe' is read."""
    header_seen = False
    current = None
    for number, line in enumerate(lines, 1):
        line = line.rstrip("\n")
        if not line:
            continue
        if not header_seen:
            if not line.startswith("castor-polygons "):
                raise StreamError(f"{name}:{number}: not a castor polygon stream (first line is "
                                  f"'{shown(line)}'); give a mesh file, or pipe castor's output")
            header_seen = True
            continue
        fields = line.split(" ")
        kind = fields[0]
        try:
            if kind == "frame":
                current = (int(fields[1]), fields[2] if len(fields) > 2 else "", [], [], [0], {},
                           [])
            elif kind == "poly":
                _, _, points, colours, offsets, paths, path_of = current
                path_of.append(paths.setdefault(fields[1], len(paths)))
                n = int(fields[5])
                values = np.array(fields[6:6 + 3 * n], dtype=np.float64)
                if len(values) != 3 * n:
                    raise ValueError("vertex count")
                colours.append([float(x) for x in fields[2:5]])
                points.append(values.reshape(n, 3))
                offsets.append(offsets[-1] + n)
            elif kind == "endframe":
                frame_number, where, points, colours, offsets, paths, path_of = current
                yield StreamFrame(frame_number, where,
                              np.concatenate(points) if points else np.zeros((0, 3)),
                              np.array(offsets, np.int64),
                              np.array(colours, dtype=np.float64).reshape(-1, 3),
                              np.array(path_of, np.int64), list(paths))
                current = None
        except (ValueError, IndexError, TypeError):
            raise StreamError(f"{name}:{number}: malformed '{kind}' record") from None


def shown(text: str, limit: int = 40) -> str:
    """Text read from a stream as a message shows it: printable ASCII, every other
    character escaped (a byte that is not UTF-8 as \\xcd, as castor says it), at
    most about ``limit`` characters, '...' after."""
    out, length = [], 0
    for c in text:
        if length >= limit:
            return "".join(out) + "..."
        if " " <= c <= "~" and c != "\\":
            piece = c
        elif "\udc80" <= c <= "\udcff":  # a byte kept by 'surrogateescape'
            piece = f"\\x{ord(c) - 0xdc00:02x}"
        else:
            piece = c.encode("unicode_escape").decode("ascii")
        out.append(piece)
        length += len(piece)
    return "".join(out)


def read(path: str) -> Iterator[StreamFrame]:
    """A polygon stream file's frames, each as soon as it is read."""
    try:
        handle = open(path, encoding="utf-8", errors="surrogateescape")
    except OSError as exc:
        raise StreamError(f"cannot read '{path}': {exc.strerror}") from None
    with handle:
        yield from load(handle, path)


# header: HEADER as bytes, written out (the registry reads records without running this module)


def write(frame: Frame, info: WriteInfo) -> Iterator[bytes]:
    """The registry's writer (castor.formats): the frame a piece at a time."""
    return export_chunks(frame, info.path)
