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
from typing import NamedTuple

import numpy as np

from castor.drawings.annotate import (Chain, dimension_chains, length_text, level_heights,
                                      level_text, vertical_chain)
from castor.drawings.legend import (_cut_lines, _legend, _legend_items, _legend_width,
                                    _project_rows, _symbols, _title_size, PROJECT_ROWS)
# the sheet's items and pens (castor.drawings.paper), as the writers import them from here
from castor.drawings.paper import (ALONE_LINE, CHAIN_LINE, CUT_CLEAR, CUT_PEN, DASH,  # noqa: F401
                                   DEPTH,
                                   EXTENSION_GAP, GAP, GROUND_OVERHANG, LEVEL_WIDTH, MARGIN,
                                   OVERALL_LINE, OVERSHOOT, POCHE, PROFILE_PEN, READS, ROWS,
                                   SEEN_PEN, STANDARD_SCALES, TEXT, THIN_PEN, TITLE_BLOCK, Arc,
                                   Dimension, Group, Lines, Shape, Sheet, Text, _fitted,
                                   text_width)

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
    and its dimensions as CAD keeps them (added to ``dims``). ``push``: how
    much farther out (mm) its lines and values stand, beyond what the symbols
    draw past the box (a door swinging out); its extension lines still start
    EXTENSION_GAP from the box. ``cuts``: where the set's cut lines cross the
    side (paper, along it), which its values keep clear of."""

    def __init__(self, chain: Chain, box_mm, mm: float, origin, dims: list, push: float = 0.0,
                 cuts=()):
        self.chain = chain
        self.edge, self.out, self.horizontal = _side_frame(chain.side, box_mm)
        self.rows = ROWS[READS[chain.side]]
        self.mm, self.origin, self.dims = mm, origin, dims
        self.push, self.cuts = push, list(cuts)
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
        row = (row[0] + self.push, row[1] + self.push)
        top = min(self.edge + self.out * row[0], self.edge + self.out * row[1]) + 2.1
        return (s, top, 0.0) if self.horizontal else (top, s, 90.0)

    def clear(self, c: float, w: float, lo: float, hi: float) -> float | None:
        """Where a value ``w`` wide centred at ``c`` between ``lo`` and ``hi``
        stands clear of the cut lines (CUT_CLEAR mm from each): ``c`` itself
        when it is, else the nearest place along its dimension that is, 0.5 mm
        within its ends; None when there is none."""

        def free(m):
            return all(abs(s - m) >= w / 2 + CUT_CLEAR - 1e-9 for s in self.cuts)

        if free(c):
            return c
        places = [s + sign * (w / 2 + CUT_CLEAR) for s in self.cuts for sign in (-1, 1)]
        places = [m for m in places if lo + 0.5 + w / 2 <= m <= hi - 0.5 - w / 2 and free(m)]
        return min(places, key=lambda m: (abs(m - c), m)) if places else None

    def line(self, ends, d):
        d += self.push
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
        line_at = self.page(self.edge + self.out * (d + self.push))
        if self.horizontal:
            p1, p2, base, angle = (u1, chain.edge), (u2, chain.edge), (u1, line_at), 0.0
        else:
            p1, p2, base, angle = (chain.edge, u1), (chain.edge, u2), (line_at, u1), 90.0
        offset = abs(chain.edge - self.page(self.edge + self.out * EXTENSION_GAP))
        where = None
        if text_point is not None:
            where = ((text_point[0] - origin[0]) / mm, (origin[1] - text_point[1]) / mm)
        self.dims.append(Dimension(p1, p2, base, angle, where, offset, shown))


def _dimension_side(chain: Chain, box_mm, mm, origin, items, dims, push: float = 0.0, cuts=()):
    """Lines, ticks and texts of one side's chain and overall, ``push`` mm
    farther out, their values clear of the ``cuts`` (paper, along the side);
    returns how many of the chain's values had no room."""
    side = _Side(chain, box_mm, mm, origin, dims, push, cuts)
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
    middle = (o_lo + o_hi) / 2
    at = side.clear(middle, text_width(text, TEXT), o_lo, o_hi)
    x, y, angle = side.text_at(middle if at is None else at, row)
    side.texts.append(Text(x, y, text, TEXT, angle, "middle"))
    # moved along, clear of a cut line: CAD is told where
    side.dimension(overall[0], overall[1], d_overall, None if at in (None, middle) else (x, y))
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
        # along its dimension, clear of the set's cut lines
        m = side.clear(c, w, a, b) if w + 1.0 <= b - a else None
        # in the staggered row, clear of the overall's extension lines too
        s = side.clear(sum(_inside(c, w, o_lo, o_hi)) / 2, w, o_lo, o_hi) \
            if o_hi - o_lo >= w + 1.0 else None
        if m is not None and not _placed(main_row, m - w / 2, m + w / 2):
            main_row.append((m - w / 2, m + w / 2))
            x, y, angle = side.text_at(m, side.rows["chain"])
            side.texts.append(Text(x, y, text, TEXT, angle, "middle"))
            side.dimension(u1, u2, CHAIN_LINE, None if m == c else (x, y))
        elif s is not None and not _placed(stagger_row, *_inside(s, w, o_lo, o_hi)):
            stagger_row.append(_inside(s, w, o_lo, o_hi))
            x, y, angle = side.text_at(s, side.rows["stagger"])
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
    priority = {"ground": 0, "storey": 1, "top": 2, "opening": 3, "edge": 4}
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
    push: dict  # side -> mm its dimensions stand farther out, past the symbols (_pushes)


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
    chains = _chains(drawing, np.array([[x0, y0], [x1, y1]]), vertical)
    push = _pushes(drawing, np.array([[x0, y0], [x1, y1]]), mm)
    depth = _depths(chains, push)
    symbols = drawing.symbols
    levels = level_heights(drawing.layers, np.array([[x0, y0], [x1, y1]]),
                           symbols.storeys if symbols else (),
                           symbols.seen_openings + symbols.cut_openings if symbols else (),
                           symbols is not None,
                           [h for hs in symbols.sides.values() for h in hs] if symbols else (),
                           symbols.stairs if symbols else ()) if vertical else []
    level_x = box[1, 0] + depth["right"] + (4.0 if depth["right"] else 6.0)
    right = depth["right"] + (LEVEL_WIDTH + 6.0 if levels else 0.0)
    content = np.array([[box[0, 0] - depth["left"], box[0, 1] - depth["top"]],
                        [box[1, 0] + right, box[1, 1] + depth["bottom"]]])
    reach = _symbols_box(symbols, mm)  # the set's marks stand beyond the chains
    if reach is not None:
        content = np.array([np.minimum(content[0], reach[0]), np.maximum(content[1], reach[1])])
    return _Frame(box, ground, chains, levels, level_x, content, push)


def _depths(chains, push: dict | None = None) -> dict:
    """How far out (mm) each side's dimensions reach from the drawing's box
    (``push``: side -> mm they stand farther out, _pushes)."""
    depth = {side: 0.0 for side in ("bottom", "top", "left", "right")}
    for chain in chains:
        depth[chain.side] = DEPTH[READS[chain.side]] - (0 if len(chain.breaks) else 9)
        if push and push.get(chain.side):
            depth[chain.side] += push[chain.side]
    return depth


def _pushes(drawing, box: np.ndarray, mm: float) -> dict:
    """Side -> how far (paper mm) the symbols draw past the drawing's ``box``
    (page metres) on that side: a door swinging out, its leaf and swing; the
    eaves overhead. The side's dimensions stand that much farther out, as a
    draughtsman moves a chain out past a door's swing."""
    reach = getattr(drawing.symbols, "reach", None)
    if reach is None:
        return {}
    (x0, y0), (x1, y1) = box
    (a0, b0), (a1, b1) = reach
    past = {"bottom": y0 - b0, "top": b1 - y1, "left": x0 - a0, "right": a1 - x1}
    return {side: float(d) * mm for side, d in past.items() if d > 1e-6}


def annotation_depths(drawing) -> dict:
    """Side -> how far out (paper mm) a drawing's dimension chains reach from
    what is drawn: where the set's marks may stand (castor.drawings.marks)."""
    box = drawing.box()
    return _depths(_chains(drawing, box, tuple(drawing.view.up) == (0, 0, 1)),
                   _pushes(drawing, box, 1000.0 / drawing.scale))


def _symbols_box(symbols, mm: float):
    """The paper box (page origin at 0, y down) of the set's marks, or None."""
    if symbols is None or not symbols.marks:
        return None
    allp = np.concatenate([np.asarray(box, float) for box in symbols.marks])
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    return np.array([[lo[0] * mm, -hi[1] * mm], [hi[0] * mm, -lo[1] * mm]])


def _chains(drawing, box: np.ndarray, vertical: bool) -> list:
    """The dimension chains of a drawing: along the cut regions of a plan or
    section; with classes, along the cut walls only (the others when none is
    cut), breaking at every opening cut, and on a section or an elevation
    vertical chains of the storeys, the openings' sills and heads, the cut slabs'
    undersides and tops, and the top."""
    symbols = drawing.symbols
    loops = [c for layer in drawing.layers for c in layer.cuts]
    if symbols is None:
        return dimension_chains(loops) if drawing.section is not None else []
    chains = []
    if drawing.section is not None:
        chains = dimension_chains(symbols.walls or loops, symbols.cut_openings, classed=True)
    if vertical:
        levels = [h for h in symbols.storeys if box[0, 1] - 1e-3 <= h <= box[1, 1] + 1e-3]
        sides = {"left": box[0, 0], "right": box[1, 0]}
        made = {}
        for side, edge in sides.items():
            heights = levels + symbols.slabs + symbols.sides.get(side, [])
            chain = vertical_chain(side, edge, heights, float(box[1, 1]))
            if chain is not None:
                made[side] = chain
        if made:  # they stand for the cut regions' own chains on those sides
            chains = [c for c in chains if c.side not in ("left", "right")] + list(made.values())
    return chains


# the scale bar and north arrow above the title block, when the two do not
# fit side by side (an upright A4): the band is this much taller
STACKED = 25.0


def _bar_width(drawing, scale: float) -> float:
    """The scale bar's width with its label, the north arrow's beside it for a
    plan, and the legend of the hatches beside them."""
    bar_m, _ = scale_bar_length(scale)
    return bar_m * 1000.0 / scale + 10.0 + (20.0 if drawing.is_plan else 0.0) + _legend_width(drawing)


def _band(drawing, scale: float, room: float | None) -> tuple[float, bool]:
    """The band below the content (scale bar, north arrow, title block): its
    height, and whether the scale bar stands above the title block, which it
    does when the two do not fit side by side in ``room`` mm (None: no paper)."""
    side_by_side = room is None or TITLE_BLOCK[0] + _bar_width(drawing, scale) + 10.0 <= room
    return _title_size(drawing)[1] + 8.0 + (0.0 if side_by_side else STACKED), not side_by_side


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
    is larger than the paper at its scale. A register's sheet title (the field
    ``sheet_title``) replaces ``title``: the title block's, the SVG's and PDF's."""
    title = drawing.fields.get("sheet_title") or title
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
    symbols = _symbols(drawing, origin, mm)
    dimensions, levels, cad = _annotated(drawing, frame, box_mm, origin, mm,
                                         frame.level_x + shift[0], warn)
    band = _sheet_band(drawing, paper, width, height, stacked, mm, title, where)
    groups = [dimensions, levels, band] if symbols is None else [symbols, dimensions, levels, band]
    return Sheet(width, height, title, drawing.description(), origin, mm, layers,
                 groups, cad, drawing)


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
        if layer.regions is not None:
            for region in layer.regions:  # element by element, hatched by class
                solid = region.pattern == "SOLID"
                group.items.append(Shape([paper_of(loop) for loop in region.loops], CUT_PEN,
                                         POCHE if solid else "white", True, "cut",
                                         None if solid else region.pattern, region.ifc_class))
        elif layer.cuts:
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
    cuts = _cut_lines(drawing, origin, mm)
    for chain in frame.chains:
        missing = _dimension_side(chain, box_mm, mm, origin, dimensions_group.items, cad,
                                  frame.push.get(chain.side, 0.0),
                                  cuts["x" if chain.side in ("bottom", "top") else "y"])
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
    title_w, title_h = _title_size(drawing)
    tx, ty = width - MARGIN - title_w, height - MARGIN - title_h
    if paper is not None:
        group.items.append(Shape([np.array([(MARGIN, MARGIN), (width - MARGIN, MARGIN),
                                            (width - MARGIN, height - MARGIN),
                                            (MARGIN, height - MARGIN)])], PROFILE_PEN,
                                 None, True, "sheet"))
        bx, by = MARGIN + 5.0, (ty - 6.0 if stacked else height - MARGIN - 8.0)
    else:
        bx, by = MARGIN, height - MARGIN - 8.0
    if drawing.fields:
        _project_rows(group.items, tx, ty, drawing.fields)
        ty += PROJECT_ROWS
    _title_block(group.items, tx, ty, title, drawing.description(),
                 f"1:{drawing.scale:g}", sheet_date(), where)
    bar_m, bar_step = scale_bar_length(drawing.scale)
    _scale_bar(group.items, bx, by, bar_m, bar_step, mm)
    if drawing.is_plan:
        _north_arrow(group.items, bx + bar_m * mm + 18.0, by - 9.0)
    if _legend(drawing):
        _legend_items(drawing, group.items,
                      bx + bar_m * mm + 10.0 + (20.0 if drawing.is_plan else 0.0), by + 4.0)
    return group


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
