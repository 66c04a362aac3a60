"""What a drawing measures: the dimension chains of a plan or section and the
levels of an elevation or section, in metres on the page.

A chain runs along one side of the cut regions (the poché). Seen from that
side, the cut edges facing it and parallel to the page's axes form an
envelope: for each stretch along the side, the nearest facing edge. The
stretches whose edge lies within ``BAND`` of the outermost one are the outer
face (a wall, the door leaf in its opening); a stretch farther in is an
opening, seen through to the walls beyond. The chain's breaks are where the
envelope changes from one to another (wall, opening, wall ...); the overall
dimension spans the cut regions' whole extent.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

BAND = 1.0  # metres: how far in from the outermost face an edge still counts as outer
GRID = 1e-6  # metres: positions are rounded to this, so breaks meet bit for bit
MERGE = 1e-4  # metres: breaks closer than this are one
SIDES = ("bottom", "top", "left", "right")


class Chain(NamedTuple):
    """The dimensions along one side: ``breaks`` ascending along the side (page x
    for bottom and top, page y for left and right), empty when the chain would
    only repeat the overall; ``overall`` the extent; ``edge`` the page y (bottom,
    top) or x (left, right) of the outermost cut edge on that side."""

    side: str
    breaks: np.ndarray
    overall: tuple[float, float]
    edge: float


# the page (x, y) turned so that each side is the bottom: u along it, v outwards
# negative; and the way back from u and v to the page
_TURN = {"bottom": ((1, 0), (0, 1)), "top": ((-1, 0), (0, -1)),
         "left": ((0, -1), (1, 0)), "right": ((0, 1), (-1, 0))}


def _turned(points: np.ndarray, side: str) -> np.ndarray:
    (ux, uy), (vx, vy) = _TURN[side]
    return np.column_stack([ux * points[:, 0] + uy * points[:, 1],
                            vx * points[:, 0] + vy * points[:, 1]])


def _along(u: np.ndarray, side: str) -> np.ndarray:
    """Turned u back to the page coordinate along the side."""
    return -u if side in ("top", "left") else u


def _envelope(a: np.ndarray, b: np.ndarray):
    """The outermost facing edge along the side: edges a→b (turned) that run
    along u with the region above them; returns the stretch ends and, for each
    stretch, the v of its nearest edge (inf where there is none)."""
    du, dv = b[:, 0] - a[:, 0], b[:, 1] - a[:, 1]
    facing = (np.abs(dv) <= GRID) & (du > GRID)
    lo, hi, v = a[facing, 0], b[facing, 0], (a[facing, 1] + b[facing, 1]) / 2
    if not len(lo):
        return np.zeros(0), np.zeros(0)
    ends = np.unique(np.round(np.concatenate([lo, hi]) / GRID)) * GRID
    middles = (ends[:-1] + ends[1:]) / 2
    nearest = np.full(len(middles), np.inf)
    step = max(1, 4_000_000 // max(len(lo), 1))
    for s in range(0, len(middles), step):
        m = middles[s:s + step]
        cover = (lo[:, None] < m[None]) & (hi[:, None] > m[None])
        nearest[s:s + step] = np.where(cover, v[:, None], np.inf).min(axis=0)
    return ends, nearest


def dimension_chains(loops: list[np.ndarray], holes=(), classed: bool = False) -> list[Chain]:
    """The chains on each side of the cut regions (page metres). ``holes``:
    the page boxes ((x0, y0), (x1, y1)) of the openings the drawing cuts; a
    stretch of a side within one that reaches the outer face is an opening,
    whatever is seen through it. With classes (``classed``) the overall spans
    the chain it stands beside (the cut regions' extent when there is no chain)."""
    loops = [l for l in loops if len(l) >= 3]
    if not loops:
        return []
    every = np.concatenate(loops)
    chains = []
    for side in SIDES:
        turned = [_turned(l, side) for l in loops]
        a = np.concatenate(turned)
        b = np.concatenate([np.roll(t, -1, axis=0) for t in turned])
        ends, nearest = _envelope(a, b)
        finite = np.isfinite(nearest)
        if not finite.any():
            continue
        outermost = nearest[finite].min()
        outer = finite & (nearest <= outermost + BAND)
        state = np.where(outer, np.round(nearest / GRID), np.nan)
        middles = (ends[:-1] + ends[1:]) / 2
        for hole in holes:
            corners = _turned(np.asarray(hole, float), side)
            (u0, v0), (u1, v1) = corners.min(axis=0), corners.max(axis=0)
            if v0 <= outermost + 1e-3:  # it goes through the outer face
                state[(middles > u0) & (middles < u1)] = np.nan
        first, last = np.flatnonzero(outer)[[0, -1]]
        breaks = [ends[first]]
        for k in range(first + 1, last + 1):
            same = state[k] == state[k - 1] or (np.isnan(state[k]) and np.isnan(state[k - 1]))
            if not same:
                breaks.append(ends[k])
        breaks.append(ends[last + 1])
        breaks = np.array(breaks)
        # an edge's ends that float arithmetic put a hair apart are one break
        breaks = breaks[np.concatenate([[True], np.diff(breaks) > MERGE])]
        u = _turned(every, side)[:, 0]
        span = np.sort(_along(np.array([u.min(), u.max()]), side))
        along = np.sort(_along(breaks, side))
        if len(along) < 3:
            along = np.zeros(0)
        elif classed:  # the overall is the chain's extent
            span = along[[0, -1]]
        edge = outermost if side in ("bottom", "left") else -outermost
        chains.append(Chain(side, along, (float(span[0]), float(span[1])), float(edge)))
    return chains


def vertical_chain(side: str, edge: float, heights, top: float) -> Chain | None:
    """A vertical chain on the ``side`` ('left' or 'right') of a section or an
    elevation: its breaks the storeys' levels, the sills and heads of the
    openings on that side and the top (page y, metres), standing off the
    page x ``edge``; None when it would have a single dimension."""
    breaks = sorted({round(float(h), 6) for h in list(heights) + [top]})
    merged: list[float] = []
    for h in breaks:
        if not merged or h - merged[-1] > MERGE:
            merged.append(h)
    if len(merged) < 3:
        return None
    return Chain(side, np.array(merged), (merged[0], merged[-1]), float(edge))


class Level(NamedTuple):
    height: float  # metres, page y (z in an elevation or a vertical section)
    kind: str  # "ground", "storey", "top", "opening" (a sill or a head) or "edge"


def _through(seg: np.ndarray, holes) -> np.ndarray:
    """Which segments lie inside an opening's page box: seen through it."""
    inside = np.zeros(len(seg), bool)
    middle = seg.mean(axis=1)
    for (x0, y0), (x1, y1) in holes:
        inside |= ((middle[:, 0] > x0 + 1e-3) & (middle[:, 0] < x1 - 1e-3)
                   & (middle[:, 1] > y0 + 1e-3) & (middle[:, 1] < y1 - 1e-3))
    return inside


def _within(seg: np.ndarray, boxes) -> np.ndarray:
    """Which segments (L, 2, 2) lie wholly in one of the page ``boxes``: a
    stair's treads, cut or seen."""
    inside = np.zeros(len(seg), bool)
    for (x0, y0), (x1, y1) in boxes:
        inside |= np.all((seg[:, :, 0] >= x0 - 1e-3) & (seg[:, :, 0] <= x1 + 1e-3)
                         & (seg[:, :, 1] >= y0 - 1e-3) & (seg[:, :, 1] <= y1 + 1e-3), axis=1)
    return inside


def level_heights(layers, box: np.ndarray, storeys=(), holes=(), classed: bool = False,
                  openings=(), stairs=()) -> list[Level]:
    """The levels of an elevation or vertical section: the ground (z = 0), the
    storeys' floor levels, the top of what is drawn and every horizontal edge
    seen (profile or not: a sill or a head seen in front of the room behind it
    is not an outline) or of a cut region, each once (to the millimetre); an
    edge inside an opening seen face on (``holes``, page boxes) is seen
    through it, and never a level. With classes (``classed``), the seen edges
    are the profile's only, the sills and heads of the ``openings`` the
    drawing cuts or shows in its nearest façade are levels (kind "opening",
    shown before the edges), and no edge wholly inside a stair's page box
    (``stairs``: its treads, cut or seen) is a level."""
    heights = []
    for layer in layers:
        seg = layer.lines
        if len(seg):
            d = seg[:, 1] - seg[:, 0]
            flat = (np.abs(d[:, 1]) <= GRID) & (np.abs(d[:, 0]) > 1e-3)
            if classed:  # the outline only: the openings give their sills and heads
                flat &= layer.profile & ~_through(seg, holes) & ~_within(seg, stairs)
            heights.append(seg[flat, 0, 1])
        for loop in layer.cuts:
            nxt = np.roll(loop, -1, axis=0)
            flat = (np.abs(nxt[:, 1] - loop[:, 1]) <= GRID) & (np.abs(nxt[:, 0] - loop[:, 0]) > 1e-3)
            if stairs:
                flat &= ~_within(np.stack([loop, nxt], axis=1), stairs)
            heights.append(loop[flat, 1])
    found = {}
    for h in np.concatenate(heights).tolist() if heights else []:
        found.setdefault(round(h, 3), "edge")
    top = round(float(box[1, 1]), 3)
    found[top] = "top"
    for h in openings:
        if found.get(round(float(h), 3), "edge") == "edge":
            found[round(float(h), 3)] = "opening"
    for level in storeys:
        if box[0, 1] - 1e-3 <= level <= box[1, 1] + 1e-3:
            found[round(float(level), 3)] = "storey"
    found[0.0] = "ground"
    return [Level(h, kind) for h, kind in sorted(found.items())]


def level_text(height: float) -> str:
    """A level as drawings write it: ±0.00, +2.90, -0.25 (metres)."""
    text = f"{abs(height):.2f}"
    if text == "0.00":
        return "±0.00"
    return ("+" if height > 0 else "-") + text


def length_text(length: float) -> str:
    """A dimension as drawings write it: metres with two decimals, 2.40."""
    return f"{abs(length):.2f}"
