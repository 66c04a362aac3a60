"""The sheet: a drawing laid out on paper with its dimensions, levels, scale
bar, north arrow and title block, as plain items in paper millimetres (x to
the right, y down) that castor.formats.svg, pdf and dxf write out.

Pens (ISO 128-20, as an office's standard sets them): the outline of cut
regions 0.5 mm, the profile 0.35 mm, other seen edges 0.18 mm, dimensions
and text 0.13 mm. Text is 2.5 mm high (ISO 3098), upright and readable from
the bottom or the right. Dimension lines end in oblique ticks, the
architect's terminator of ISO 129-1; levels are marked as ISO 7519 draws
them, a triangle on the level's line with its height above.
"""

from __future__ import annotations

import datetime
import os
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from castor.drawings.annotate import (Chain, dimension_chains, length_text, level_heights,
                                      level_text)

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
    kind: str  # "profile", "seen", "annotation", "sheet"


class Shape(NamedTuple):
    """Closed (or open) outlines in paper mm, filled or not."""

    loops: list
    pen: float
    fill: str | None = None
    closed: bool = True
    kind: str = "annotation"  # "cut", "annotation", "sheet"


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


class DoesNotFit(Exception):
    """The drawing is larger than the sheet at the asked scale."""


def sheet_date() -> str:
    """Today, or the day SOURCE_DATE_EPOCH fixes (the reproducible-builds
    convention), as ISO 8601 writes it."""
    stamp = os.environ.get("SOURCE_DATE_EPOCH")
    when = None
    if stamp is not None:
        try:
            when = datetime.datetime.fromtimestamp(int(stamp), datetime.timezone.utc)
        except (ValueError, OverflowError, OSError):
            when = None
    if when is None:
        when = datetime.datetime.now(datetime.timezone.utc)
    return when.strftime("%Y-%m-%d")


def scale_bar_length(scale: float) -> tuple[float, float]:
    """The scale bar's length and division, metres: 0 to 5 m at 1:50 and 1:100."""
    for most, length, step in ((25, 2, 0.5), (100, 5, 1), (200, 10, 2), (500, 20, 5),
                               (1000, 50, 10)):
        if scale <= most:
            return length, step
    return 100, 20


def _inside(c: float, w: float, lo: float, hi: float) -> tuple[float, float]:
    """A text w wide centred as near c as it can be between lo and hi (0.5 mm in)."""
    c = min(max(c, lo + 0.5 + w / 2), hi - 0.5 - w / 2)
    return c - w / 2, c + w / 2


def _placed(intervals: list, lo: float, hi: float, gap: float = 0.8) -> bool:
    return any(lo < b + gap and a - gap < hi for a, b in intervals)


def _side_frame(side: str, box_mm: np.ndarray):
    """For a side: the box edge's paper coordinate across the side, the sign
    of 'outwards', and whether the side runs along paper x."""
    (x0, y0), (x1, y1) = box_mm  # paper: y0 the top, y1 the bottom
    return {"bottom": (y1, 1, True), "top": (y0, -1, True),
            "left": (x0, -1, False), "right": (x1, 1, False)}[side]


class _Side:
    """One side of the drawing's box, where a chain of dimensions stands: where
    its lines, ticks and texts go on paper (the segments and texts it gathers),
    and its dimensions as CAD keeps them (added to ``dims``)."""

    def __init__(self, chain: Chain, box_mm, mm: float, origin, dims: list):
        self.chain = chain
        self.edge, self.out, self.horizontal = _side_frame(chain.side, box_mm)
        self.rows = ROWS[READS[chain.side]]
        self.mm, self.origin, self.dims = mm, origin, dims
        self.segments: list = []
        self.texts: list = []

    def at(self, s, d):
        """The paper point s along the side (paper), d out from the box."""
        return (s, self.edge + self.out * d) if self.horizontal else (self.edge + self.out * d, s)

    def along(self, v):
        """Page metres along the side, to paper."""
        return self.origin[0] + v * self.mm if self.horizontal else self.origin[1] - v * self.mm

    def text_at(self, s, row):
        """The baseline point of a text centred at s in a row (mm out from the
        box): its reading top is the row's paper end nearer the paper's top
        (or left, for text turned to read from the right)."""
        top = min(self.edge + self.out * row[0], self.edge + self.out * row[1]) + 2.1
        return (s, top, 0.0) if self.horizontal else (top, s, 90.0)

    def line(self, ends, d):
        a, b = min(ends), max(ends)
        self.segments.append([self.at(a - OVERSHOOT, d), self.at(b + OVERSHOOT, d)])
        for s in ends:
            self.segments.append([self.at(s, EXTENSION_GAP), self.at(s, d + OVERSHOOT)])
            t = 1.25  # the tick: an oblique stroke, 45 degrees, 2.5 mm long
            (px, py) = self.at(s, d)
            self.segments.append([(px - t, py + t), (px + t, py - t)])

    def page(self, c):
        """A paper coordinate across the side, back to page metres."""
        return (self.origin[1] - c) / self.mm if self.horizontal else (c - self.origin[0]) / self.mm

    def dimension(self, u1, u2, d, text_point, shown=True):
        """The CAD dimension from u1 to u2 (page metres along the side)."""
        chain, origin, mm = self.chain, self.origin, self.mm
        line_at = self.page(self.edge + self.out * d)
        if self.horizontal:
            p1, p2, base, angle = (u1, chain.edge), (u2, chain.edge), (u1, line_at), 0.0
        else:
            p1, p2, base, angle = (chain.edge, u1), (chain.edge, u2), (line_at, u1), 90.0
        offset = abs(chain.edge - self.page(self.edge + self.out * EXTENSION_GAP))
        where = None
        if text_point is not None:
            where = ((text_point[0] - origin[0]) / mm, (origin[1] - text_point[1]) / mm)
        self.dims.append(Dimension(p1, p2, base, angle, where, offset, shown))


def _dimension_side(chain: Chain, box_mm, mm, origin, items, dims):
    """Lines, ticks and texts of one side's chain and overall; returns how many
    of the chain's values had no room."""
    side = _Side(chain, box_mm, mm, origin, dims)
    left_out = 0
    overall = chain.overall
    o_lo, o_hi = sorted((side.along(overall[0]), side.along(overall[1])))
    if len(chain.breaks):
        left_out = _chain_values(side, o_lo, o_hi)
        d_overall, row = OVERALL_LINE, side.rows["overall"]
    else:
        d_overall, row = ALONE_LINE, side.rows["alone"]
    side.line([o_lo, o_hi], d_overall)
    text = length_text(overall[1] - overall[0])
    x, y, angle = side.text_at((o_lo + o_hi) / 2, row)
    side.texts.append(Text(x, y, text, TEXT, angle, "middle"))
    side.dimension(overall[0], overall[1], d_overall, None)
    items.append(Lines(np.array(side.segments, float).reshape(-1, 2, 2), THIN_PEN, "annotation"))
    items.extend(side.texts)
    return left_out


def _chain_values(side: _Side, o_lo: float, o_hi: float) -> int:
    """The chain's line and its values: each in its row where it has room, else
    in the staggered row within the overall's extension lines, else left out
    (its ticks stay; in CAD, a dimension with no text). Returns how many were."""
    chain = side.chain
    ends = [side.along(b) for b in chain.breaks]
    side.line(ends, CHAIN_LINE)
    order = np.argsort(ends)
    ends_sorted = [ends[i] for i in order]
    main_row, stagger_row = [], []
    left_out = 0
    for i in range(len(ends_sorted) - 1):
        a, b = ends_sorted[i], ends_sorted[i + 1]
        u1, u2 = sorted((chain.breaks[order[i]], chain.breaks[order[i + 1]]))
        text = length_text(u2 - u1)
        w = text_width(text, TEXT)
        c = (a + b) / 2
        if w + 1.0 <= b - a and not _placed(main_row, c - w / 2, c + w / 2):
            main_row.append((c - w / 2, c + w / 2))
            x, y, angle = side.text_at(c, side.rows["chain"])
            side.texts.append(Text(x, y, text, TEXT, angle, "middle"))
            side.dimension(u1, u2, CHAIN_LINE, None)
        elif (o_hi - o_lo >= w + 1.0
              and not _placed(stagger_row, *_inside(c, w, o_lo, o_hi))):
            c = sum(_inside(c, w, o_lo, o_hi)) / 2  # clear of the overall's extension lines
            stagger_row.append(_inside(c, w, o_lo, o_hi))
            x, y, angle = side.text_at(c, side.rows["stagger"])
            side.texts.append(Text(x, y, text, TEXT, angle, "middle"))
            side.dimension(u1, u2, CHAIN_LINE, (x, y))
        else:
            left_out += 1
            side.dimension(u1, u2, CHAIN_LINE, None, shown=False)
    return left_out


def _level_symbols(levels, box_mm, x, items):
    """The level symbols in a column at paper x. A level closer to one already
    shown than its text's height and gap is merged into it; the ground and the
    top are shown first, then the others from the bottom up. Returns the
    levels shown."""
    priority = {"ground": 0, "top": 1, "edge": 2}
    shown: list = []
    for level, y in sorted(levels, key=lambda item: (priority[item[0].kind], -item[1])):
        if all(abs(y - other) >= TEXT + 1.0 for _, other in shown):
            shown.append((level, y))
    shown.sort(key=lambda item: -item[1])
    segments = []
    for level, y in shown:
        segments.append([(x, y), (x + LEVEL_WIDTH - 4, y)])
        items.append(Shape([np.array([(x + 1.0, y - 2.6), (x + 4.0, y - 2.6), (x + 2.5, y)])],
                           THIN_PEN, None))
        items.append(Text(x + 5.0, y - 0.8, level_text(level.height)))
    items.insert(0, Lines(np.array(segments, float).reshape(-1, 2, 2), THIN_PEN, "annotation"))
    return [level for level, _ in shown]


class _Frame(NamedTuple):
    """What stands round a drawing at a scale, before it is placed on paper (paper
    mm, the page's origin at (0, 0), y down)."""

    box: np.ndarray  # the box of what is drawn (with the ground line's overhang)
    ground: bool  # a ground line under an elevation or a vertical section
    chains: list  # the dimension chains (castor.drawings.annotate.Chain)
    levels: list  # the level heights of an elevation or a vertical section
    level_x: float  # where the column of levels stands
    content: np.ndarray  # the box of the drawing and everything round it


def _framed(drawing, mm: float) -> _Frame:
    (x0, y0), (x1, y1) = drawing.box()
    vertical = tuple(drawing.view.up) == (0, 0, 1)  # an elevation or a vertical section
    ground = vertical
    if ground:
        y0, y1 = min(y0, 0.0), max(y1, 0.0)
    box = np.array([[x0 * mm, -y1 * mm], [x1 * mm, -y0 * mm]])
    if ground:
        box[0, 0] -= GROUND_OVERHANG
        box[1, 0] += GROUND_OVERHANG
    loops = [c for layer in drawing.layers for c in layer.cuts]
    chains = dimension_chains(loops) if drawing.section is not None else []
    depth = {side: 0.0 for side in ("bottom", "top", "left", "right")}
    for chain in chains:
        depth[chain.side] = DEPTH[READS[chain.side]] if len(chain.breaks) else DEPTH[READS[chain.side]] - 9
    levels = level_heights(drawing.layers, np.array([[x0, y0], [x1, y1]])) if vertical else []
    level_x = box[1, 0] + depth["right"] + (4.0 if depth["right"] else 6.0)
    right = depth["right"] + (LEVEL_WIDTH + 6.0 if levels else 0.0)
    content = np.array([[box[0, 0] - depth["left"], box[0, 1] - depth["top"]],
                        [box[1, 0] + right, box[1, 1] + depth["bottom"]]])
    return _Frame(box, ground, chains, levels, level_x, content)


# the scale bar and north arrow above the title block, when the two do not
# fit side by side (an upright A4): the band is this much taller
STACKED = 25.0


def _bar_width(drawing, scale: float) -> float:
    """The scale bar's width with its label, and the north arrow's beside it for a plan."""
    bar_m, _ = scale_bar_length(scale)
    return bar_m * 1000.0 / scale + 10.0 + (20.0 if drawing.is_plan else 0.0)


def _band(drawing, scale: float, room: float | None) -> tuple[float, bool]:
    """The band below the content (scale bar, north arrow, title block): its
    height, and whether the scale bar stands above the title block, which it
    does when the two do not fit side by side in ``room`` mm (None: no paper)."""
    side_by_side = room is None or TITLE_BLOCK[0] + _bar_width(drawing, scale) + 10.0 <= room
    return TITLE_BLOCK[1] + 8.0 + (0.0 if side_by_side else STACKED), not side_by_side


class _Room(NamedTuple):
    """A drawing at one scale on one paper: what it needs and what the paper holds."""

    frame: _Frame
    band: float
    stacked: bool
    area: tuple[float, float]  # the paper's room for the content, mm

    @property
    def need(self) -> tuple[float, float]:
        return tuple(self.frame.content[1] - self.frame.content[0])

    def fits(self, paper, drawing, scale: float) -> bool:
        room = paper.width - 2 * MARGIN
        return (self.need[0] <= self.area[0] and self.need[1] <= self.area[1]
                and max(TITLE_BLOCK[0], _bar_width(drawing, scale)) + 10.0 <= room)


def _room(drawing, paper, scale: float) -> _Room:
    band, stacked = _band(drawing, scale, float(paper.width) - 2 * MARGIN)
    area = (float(paper.width) - 2 * MARGIN - 10.0, float(paper.height) - 2 * MARGIN - 10.0 - band)
    return _Room(_framed(drawing, 1000.0 / scale), band, stacked, area)


def _refusal(drawing, paper, room: _Room) -> DoesNotFit:
    """Why the drawing does not fit its paper at its scale, and the largest
    standard scale at which it does (laid out as it would then be)."""
    cw, ch = room.need
    if cw <= room.area[0] and ch <= room.area[1]:
        need = (f"its scale bar needs {_bar_width(drawing, drawing.scale):.0f} mm; "
                f"the sheet holds {paper.width - 2 * MARGIN - 10.0:.0f} mm")
    else:
        need = (f"{cw:.0f} x {ch:.0f} mm; the sheet holds {room.area[0]:.0f} x "
                f"{room.area[1]:.0f} mm")
    fits = [n for n in STANDARD_SCALES if _room(drawing, paper, n).fits(paper, drawing, n)]
    if fits:
        return DoesNotFit(f"the drawing does not fit on {paper.name} at 1:{drawing.scale:g} "
                          f"({need}); the largest scale that fits is 1:{min(fits)}: "
                          f"--scale 1:{min(fits)}, or a larger --sheet")
    return DoesNotFit(f"the drawing does not fit on {paper.name} at 1:{drawing.scale:g} "
                      f"({need}), nor at 1:{STANDARD_SCALES[-1]}; use a larger --sheet")


def layout(drawing, paper=None, title: str = "", where: str = "", warn=None) -> Sheet:
    """The drawing on its sheet (``paper``: castor.settings.Paper, or None for a
    sheet as large as the drawing needs). Raises DoesNotFit when the drawing
    is larger than the paper at its scale."""
    mm = 1000.0 / drawing.scale
    stacked = False
    if paper is None:
        frame = _framed(drawing, mm)
        band, _ = _band(drawing, drawing.scale, None)
        cw, ch = frame.content[1] - frame.content[0]
        width = max(cw, TITLE_BLOCK[0] + _bar_width(drawing, drawing.scale) + 10.0) + 2 * MARGIN
        height = ch + band + 2 * MARGIN
        shift = np.array([MARGIN + (width - 2 * MARGIN - cw) / 2, MARGIN]) - frame.content[0]
    else:
        room = _room(drawing, paper, drawing.scale)
        if not room.fits(paper, drawing, drawing.scale):
            raise _refusal(drawing, paper, room)
        frame, stacked = room.frame, room.stacked
        (cw, ch), (area_w, area_h) = room.need, room.area
        width, height = float(paper.width), float(paper.height)
        top_left = np.array([MARGIN + 5.0 + (area_w - cw) / 2, MARGIN + 5.0 + (area_h - ch) / 2])
        shift = top_left - frame.content[0]
    origin = (float(shift[0]), float(shift[1]))
    box_mm = frame.box + shift
    layers = _drawn(drawing, frame.ground, box_mm, origin, mm)
    dimensions, levels, cad = _annotated(drawing, frame, box_mm, origin, mm,
                                         frame.level_x + shift[0], warn)
    band = _sheet_band(drawing, paper, width, height, stacked, mm, title, where)
    return Sheet(width, height, title, drawing.description(), origin, mm, layers,
                 [dimensions, levels, band], cad, drawing)


def _drawn(drawing, ground: bool, box_mm, origin, mm: float) -> list[Group]:
    """One group per object of the drawing (and the ground line), in paper mm."""

    def paper_of(points):
        points = np.asarray(points, float)
        return np.stack([points[..., 0] * mm + origin[0], origin[1] - points[..., 1] * mm], axis=-1)

    layers = []
    for layer in drawing.layers:
        group = Group(layer.name)
        if len(layer.lines):
            seen = paper_of(layer.lines[~layer.profile])
            profile = paper_of(layer.lines[layer.profile])
            if len(seen):
                group.items.append(Lines(seen, SEEN_PEN, "seen"))
            if len(profile):
                group.items.append(Lines(profile, PROFILE_PEN, "profile"))
        if layer.cuts:
            group.items.append(Shape([paper_of(loop) for loop in layer.cuts], CUT_PEN, POCHE,
                                     True, "cut"))
        layers.append(group)
    if ground:
        layers.append(Group("ground", [Lines(np.array([[[box_mm[0, 0], origin[1]],
                                                        [box_mm[1, 0], origin[1]]]]),
                                             PROFILE_PEN, "profile")]))
    return layers


def _annotated(drawing, frame: _Frame, box_mm, origin, mm: float, level_x: float,
               warn) -> tuple[Group, Group, list]:
    """The dimensions' and the levels' groups, and the dimensions as CAD keeps them."""
    dimensions_group, levels_group = Group("dimensions"), Group("levels")
    cad: list[Dimension] = []
    left_out = {}
    for chain in frame.chains:
        missing = _dimension_side(chain, box_mm, mm, origin, dimensions_group.items, cad)
        if missing:
            left_out[chain.side] = missing
    if left_out and warn is not None:
        sides = ", ".join(f"{n} on the {side}" for side, n in left_out.items())
        warn(f"{sum(left_out.values())} dimension(s) left out, too narrow for their text at "
             f"1:{drawing.scale:g} ({sides}); a larger scale shows them")
    if frame.levels:
        placed = [(level, origin[1] - level.height * mm) for level in frame.levels]
        _level_symbols(placed, box_mm, level_x, levels_group.items)
    return dimensions_group, levels_group, cad


def _sheet_band(drawing, paper, width: float, height: float, stacked: bool, mm: float,
                title: str, where: str) -> Group:
    """The border (on paper), the title block at the lower right, the scale bar
    and the north arrow at the left of it, or above it when ``stacked``."""
    group = Group("sheet")
    title_w, title_h = TITLE_BLOCK
    tx, ty = width - MARGIN - title_w, height - MARGIN - title_h
    if paper is not None:
        group.items.append(Shape([np.array([(MARGIN, MARGIN), (width - MARGIN, MARGIN),
                                            (width - MARGIN, height - MARGIN),
                                            (MARGIN, height - MARGIN)])], PROFILE_PEN,
                                 None, True, "sheet"))
        bx, by = MARGIN + 5.0, (ty - 6.0 if stacked else height - MARGIN - 8.0)
    else:
        bx, by = MARGIN, height - MARGIN - 8.0
    _title_block(group.items, tx, ty, title, drawing.description(),
                 f"1:{drawing.scale:g}", sheet_date(), where)
    bar_m, bar_step = scale_bar_length(drawing.scale)
    _scale_bar(group.items, bx, by, bar_m, bar_step, mm)
    if drawing.is_plan:
        _north_arrow(group.items, bx + bar_m * mm + 18.0, by - 9.0)
    return group


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


def _title_block(items, x, y, title, what, scale, date, where):
    w, h = TITLE_BLOCK
    items.append(Shape([np.array([(x, y), (x + w, y), (x + w, y + h), (x, y + h)])],
                       PROFILE_PEN, None, True, "sheet"))
    items.append(Lines(np.array([[(x, y + 11), (x + w, y + 11)],
                                 [(x, y + 18.5), (x + w, y + 18.5)],
                                 [(x, y + 24.5), (x + w, y + 24.5)],
                                 [(x + 45, y + 18.5), (x + 45, y + 24.5)]]), SEEN_PEN, "sheet"))
    text, size = _fitted(title, 5.0, w - 6)
    items.append(Text(x + 3, y + 8.0, text, size))
    text, size = _fitted(what, 3.5, w - 6)
    items.append(Text(x + 3, y + 16.5, text, size))
    items.append(Text(x + 3, y + 22.5, f"Scale {scale}"))
    items.append(Text(x + 48, y + 22.5, f"Date {date}"))
    text, size = _fitted(where, TEXT, w - 6, keep_end=True)
    items.append(Text(x + 3, y + 28.5, text, size))


def _scale_bar(items, x, y, length, step, mm):
    """Blocks of ``step`` metres, black and white in turn, numbered in metres."""
    count = int(round(length / step))
    blocks = [np.array([(x + k * step * mm, y - 2), (x + (k + 1) * step * mm, y - 2),
                        (x + (k + 1) * step * mm, y), (x + k * step * mm, y)])
              for k in range(count)]
    items.append(Shape(blocks[0::2], THIN_PEN, "black", True, "sheet"))
    items.append(Shape(blocks[1::2], THIN_PEN, "white", True, "sheet"))
    for k in range(count + 1):
        label = f"{k * step:g}" + (" m" if k == count else "")
        items.append(Text(x + k * step * mm, y + 4.0, label, TEXT, 0.0,
                          "start" if k == count else "middle"))


def _north_arrow(items, x, y):
    """A circle with an arrow pointing up the page (north, +y) and an N."""
    angles = np.linspace(0, 2 * np.pi, 49)[:-1]
    items.append(Shape([np.column_stack([x + 6 * np.cos(angles), y + 6 * np.sin(angles)])],
                       THIN_PEN, None, True, "sheet"))
    items.append(Shape([np.array([(x, y - 6), (x + 2.5, y + 4), (x, y + 2), (x - 2.5, y + 4)])],
                       THIN_PEN, "black", True, "sheet"))
    items.append(Text(x, y - 7.5, "N", 3.5, 0.0, "middle"))
