"""The Castor polygon stream (OUTPUT.md): text, one record a line.

Numbers are written in shortest round-trip form (Python's repr), so reading
them back gives the same double; whole numbers lose their '.0'.
"""

from __future__ import annotations

import re

import numpy as np

from castor.mesh.frame import Frame

HEADER = "castor-polygons 1\n"


def number_strings(values: np.ndarray) -> list[str]:
    """Shortest round-trip text of each value; -0 is written 0."""
    out = list(map(repr, (np.asarray(values, dtype=np.float64).ravel() + 0.0).tolist()))
    for i, text in enumerate(out):
        if text[-2:] == ".0":
            out[i] = text[:-2]
    return out


_UNSAFE = re.compile(r"[%\x00-\x20\x7f-\x9f\s]")


def where_field(where: str) -> str:
    """``FILE:LINE`` with a space, '%' or control character in FILE written %XX (its
    UTF-8 bytes), as in a URL, so that the record keeps its fields."""
    file, sep, line = where.rpartition(":")
    if not sep:
        file, line = where, ""
    file = _UNSAFE.sub(lambda m: "".join(f"%{b:02X}" for b in m.group().encode("utf-8")), file)
    return f"{file}{sep}{line}"


def format_frame(frame: Frame) -> str:
    """The frame's records, from 'frame N WHERE' to 'endframe N COUNT'."""
    parts = [f"frame {frame.number} {where_field(frame.where)}\n"]
    count = 0
    for obj in frame.objects:
        numbers = number_strings(obj.vertices)
        points = list(map(" ".join, zip(numbers[0::3], numbers[1::3], numbers[2::3])))
        heads = []
        for origin in obj.origins:
            colour = " ".join(number_strings(np.array(origin.colour, dtype=np.float64)))
            heads.append(f"poly {origin.path} {colour} ")
        sizes = np.diff(obj.offsets)
        # every polygon as its head, its size and its points, in one pass
        head_of = [heads[i] + str(n) + " " for i, n in zip(obj.origin_of.tolist(), sizes.tolist())]
        texts = list(map(points.__getitem__, obj.indices.tolist()))
        bounds = obj.offsets.tolist()
        lines = [head_of[p] + " ".join(texts[bounds[p]:bounds[p + 1]]) for p in range(len(head_of))]
        if lines:
            parts.append("\n".join(lines))
            parts.append("\n")
        count += len(lines)
    parts.append(f"endframe {frame.number} {count}\n")
    return "".join(parts)


def export(frame: Frame, path: str | None = None) -> bytes:
    """The frame's records (the header, written once per stream, is ``HEADER``)."""
    return format_frame(frame).encode("utf-8", "surrogateescape")
