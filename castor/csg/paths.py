"""Paths (LANGUAGE.md §8): where a polygon comes from, `(voiture).U3(roue)!cy`.

Paths are built as linked segments and turned into text only when written:
a scene nested ten thousand levels deep then costs memory in proportion to its
depth, not to its square (each level would otherwise copy the whole string).
"""

from __future__ import annotations


def join(segments) -> str:
    """Segments from the root down, as text: a boolean step after anything gets a dot."""
    out = []
    for segment in segments:
        if not segment:
            continue
        if out and segment[0] in "UID":
            out.append(".")
        out.append(segment)
    return "".join(out)


class Path:
    """A path from some node down to a primitive: a segment, then the rest."""

    __slots__ = ("segment", "rest", "_text")

    def __init__(self, segment: str, rest: "Path | None" = None):
        self.segment = segment
        self.rest = rest
        self._text = None

    def under(self, segment: str) -> "Path":
        """This path seen from one level up: ``segment`` in front."""
        return Path(segment, self)

    def __str__(self) -> str:
        if self._text is None:
            segments = []
            node = self
            while node is not None:
                segments.append(node.segment)
                node = node.rest
            self._text = join(segments)
        return self._text


class Trail:
    """The way down from the root of a '>' object to the node being evaluated,
    for messages that name a primitive's path."""

    __slots__ = ("parent", "segment")

    def __init__(self, parent: "Trail | None" = None, segment: str = ""):
        self.parent = parent
        self.segment = segment

    def down(self, segment: str) -> "Trail":
        return Trail(self, segment)

    def steps(self) -> str:
        """The way down as path text ('' at the root)."""
        segments = []
        node = self
        while node is not None and node.segment:
            segments.append(node.segment)
            node = node.parent
        return join(reversed(segments))

    def __str__(self) -> str:
        return self.steps() or "the object"


ROOT = Trail()
