"""The Castor polygon stream (OUTPUT.md): text, one record a line.

Numbers are written in shortest round-trip form (Python's repr), so reading
them back gives the same double; whole numbers lose their '.0'.
"""

from __future__ import annotations

import numpy as np

from ..frame import Frame

HEADER = "castor-polygons 1\n"


def number_strings(values: np.ndarray) -> list[str]:
    """Shortest round-trip text of each value; -0 is written 0."""
    out = []
    for x in (values.ravel() + 0.0).tolist():
        s = repr(x)
        out.append(s[:-2] if s.endswith(".0") else s)
    return out


def format_frame(frame: Frame) -> str:
    """The frame's records, from 'frame N WHERE' to 'endframe N COUNT'."""
    parts = [f"frame {frame.number} {frame.where}\n"]
    count = 0
    for obj in frame.objects:
        numbers = number_strings(obj.vertices)
        points = [" ".join(numbers[i:i + 3]) for i in range(0, len(numbers), 3)]
        heads = []
        for origin in obj.origins:
            colour = " ".join(number_strings(np.array(origin.colour, dtype=np.float64)))
            heads.append(f"poly {origin.path} {colour} ")
        offsets = obj.offsets.tolist()
        indices = obj.indices.tolist()
        origin_of = obj.origin_of.tolist()
        lines = []
        for p in range(len(origin_of)):
            start, end = offsets[p], offsets[p + 1]
            lines.append(heads[origin_of[p]] + str(end - start) + " "
                         + " ".join([points[i] for i in indices[start:end]]))
        if lines:
            parts.append("\n".join(lines))
            parts.append("\n")
        count += len(lines)
    parts.append(f"endframe {frame.number} {count}\n")
    return "".join(parts)


def write(frame: Frame, stream) -> None:
    stream.write(format_frame(frame))
