"""What a sheet is made of: its items in paper millimetres (x to the right, y
down) and the pens, text sizes and distances they are laid out with
(castor.drawings.sheet lays them out; castor.formats.svg, pdf and dxf write
them)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

CUT_PEN, PROFILE_PEN, SEEN_PEN, THIN_PEN = 0.5, 0.35, 0.18, 0.13  # mm
POCHE = "#8c8c8c"
TEXT = 2.5  # mm, the height of dimension, level and sheet text
MARGIN = 10.0  # mm round the sheet's content, and from the paper's edge to the border
STANDARD_SCALES = (20, 50, 100, 200, 500, 1000)
TITLE_BLOCK = (110.0, 30.0)  # mm
GROUND_OVERHANG = 5.0  # mm the ground line runs on beyond the drawing

# where the parts of a dimension stand, in mm out from the drawing's box
EXTENSION_GAP = 2.0  # extension lines start this far from the drawing
OVERSHOOT = 1.5  # and run on past the dimension line
CHAIN_LINE, OVERALL_LINE, ALONE_LINE = 10.0, 19.0, 10.0
CUT_CLEAR = 1.0  # mm a dimension's value keeps from a section's cut line across it
# text rows (from, to): the chain's own row, its staggered row, the overall's;
# text stands on the side of its line that reads as "above": towards the
# drawing at the bottom and right, away from it at the top and left
ROWS = {"inward": {"chain": (6.5, 9.0), "stagger": (12.0, 14.5), "overall": (15.5, 18.0),
                   "alone": (6.5, 9.0)},
        "outward": {"chain": (11.0, 13.5), "stagger": (14.5, 17.0), "overall": (20.0, 22.5),
                    "alone": (11.0, 13.5)}}
READS = {"bottom": "inward", "right": "inward", "top": "outward", "left": "outward"}
DEPTH = {"inward": 21.0, "outward": 23.5}  # mm a side's dimensions take
LEVEL_WIDTH = 22.0  # mm a column of levels takes


# Helvetica's advance widths (per em) for the characters drawings write most
_WIDTHS = {**{c: 0.556 for c in "0123456789+-±$#_?"}, ".": 0.278, ",": 0.278, " ": 0.278,
           ":": 0.278, "=": 0.584, "i": 0.222, "l": 0.222, "j": 0.222, "f": 0.278, "t": 0.278,
           "I": 0.278, "m": 0.833, "w": 0.722, "M": 0.833, "W": 0.944, "r": 0.333}


def text_width(text: str, size: float) -> float:
    """The width of ``text`` set in Helvetica at ``size`` mm, near enough to place it."""
    return size * sum(_WIDTHS.get(c, 0.667 if c.isupper() else 0.556) for c in text)


class Lines(NamedTuple):
    """Straight segments (L, 2, 2) in paper mm, drawn with one pen."""

    segments: np.ndarray
    pen: float
    kind: str  # "profile", "seen", "annotation", "sheet", "symbol", "overhead"
    dashed: bool = False  # ISO 128's dashed line: DASH mm dashes, GAP mm gaps
    chain: bool = False  # ISO 128's long-dashed dotted line: CHAIN's dash, gap, dot, gap


DASH, GAP = 3.0, 1.5  # mm
CHAIN = (12.0, 1.5, 0.5, 1.5)  # mm: a section's cut line across a plan


class Arc(NamedTuple):
    """A circular arc in paper mm, counter-clockwise as seen on the paper from
    ``start`` to ``end`` degrees (0 along paper x, 90 up the paper)."""

    x: float
    y: float
    radius: float
    start: float
    end: float
    pen: float
    kind: str = "symbol"


class Shape(NamedTuple):
    """Closed (or open) outlines in paper mm, filled or not."""

    loops: list
    pen: float
    fill: str | None = None
    closed: bool = True
    kind: str = "annotation"  # "cut", "annotation", "sheet"
    pattern: str | None = None  # a hatch (castor.drawings.classes.HATCHES) over the fill
    label: str = ""  # what it is (a cut region: its element's class)


class Text(NamedTuple):
    x: float
    y: float  # the baseline's anchor point, paper mm
    text: str
    size: float = TEXT
    angle: float = 0.0  # degrees, counter-clockwise as seen on the paper
    anchor: str = "start"  # "start", "middle", "end"


class Dimension(NamedTuple):
    """One dimension as CAD keeps it, in page metres: measured from p1 to p2
    along ``angle`` (0 or 90), its line through ``base``, its text at
    ``text_at`` (None: on the line's middle, where CAD puts it)."""

    p1: tuple
    p2: tuple
    base: tuple
    angle: float
    text_at: tuple | None
    offset: float  # metres from p1 and p2 to where the extension lines start
    shown: bool = True  # False: no room for its text, which is left out


@dataclass
class Group:
    name: str
    items: list = field(default_factory=list)


@dataclass
class Sheet:
    """A drawing laid on paper: the paper's size, the objects' groups, the
    annotation groups and what a CAD file needs to rebuild the dimensions."""

    width: float
    height: float
    title: str
    description: str
    origin: tuple[float, float]  # the paper point of the page's (0, 0) metres
    mm: float  # paper millimetres per metre
    layers: list[Group]  # one per object
    groups: list[Group]  # "dimensions", "levels", "sheet"
    dimensions: list[Dimension]
    drawing: object  # castor.drawings.model.Drawing

    def to_metres(self, points: np.ndarray) -> np.ndarray:
        """Paper mm back to page metres (where a CAD file puts the sheet's items)."""
        points = np.asarray(points, float)
        return np.column_stack([(points[..., 0].ravel() - self.origin[0]) / self.mm,
                                (self.origin[1] - points[..., 1].ravel()) / self.mm]
                               ).reshape(points.shape)


def _fitted(text: str, size: float, room: float, keep_end: bool = False) -> tuple[str, float]:
    """The text and size that fit ``room`` mm: smaller down to TEXT, then cut
    short (at its start for a path, whose end says most)."""
    while size > TEXT and text_width(text, size) > room:
        size = max(TEXT, size - 0.25)
    if text_width(text, size) > room:
        while text and text_width(text + "…", size) > room:
            text = text[1:] if keep_end else text[:-1]
        text = "…" + text if keep_end else text + "…"
    return text, size
