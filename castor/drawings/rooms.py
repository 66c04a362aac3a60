"""Room tags (OUTPUT.md, what a contractor builds from): each space a plan
cuts (LANGUAGE.md §11) gets its name and its area at the plan's height, at
its middle, or where the tag fits inside it nearest its middle; a space that
gets no tag, or whose tag does not fit in it at the drawing's scale, is
reported with its FILE:LINE, never left out in silence."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from castor.drawings.cut import cut_loops, loops_area

NAME, AREA = 3.0, 2.5  # mm: the name's height, the area's below it
STEP = NAME * 1.3  # mm from the name's middle to the area's (castor.drawings.legend)


class _Cut(NamedTuple):
    value: float
    axis: str = "z"


def room_tags(takeoff, view, z: float, scale: float, warn) -> list:
    """A tag in each space the plan at height z cuts: (where its name's middle
    is, page metres; its lines); ``warn(message)`` hears of a space cut with no
    area, or too small at 1:scale for its tag, or empty."""
    tags = []
    depth = view.plane_depth(_Cut(z))
    k = scale / 1000.0  # metres per paper mm
    rooms = takeoff.rooms()
    measured = {id(room.space) for room in rooms}
    for space in takeoff.frame_tree.spaces:
        if id(space) not in measured:
            warn(f"space '{space.name}' ({space.where}) is empty: it has no room tag")
    for room in rooms:
        low, high = room.solid.vertices[:, 2].min(), room.solid.vertices[:, 2].max()
        if not low < z < high:
            continue
        loops = cut_loops(room.solid, view, depth)
        area = loops_area(loops)
        where = f"space '{room.space.name}' ({room.space.where})"
        if area <= 0:
            warn(f"{where} crosses the plan z = {z:.2f} but its cut has no area: "
                 "it has no room tag")
            continue
        lines = (room.name, f"{area:.2f} m²")
        at = _placed(loops, lines, k)
        if at is None:
            at = _middle(loops)
            warn(f"{where} is too small at 1:{scale:g} for its room tag: the tag is drawn "
                 "over its outline")
        tags.append((at, lines))
    return tags


def _tag_box(at, lines, k: float) -> np.ndarray:
    """The page box of a tag whose name's middle is at ``at`` (castor.drawings
    .legend sets its lines), half a millimetre clear all round."""
    from castor.drawings.paper import text_width

    w = max(text_width(lines[0], NAME), text_width(lines[1], AREA)) / 2 + 0.5
    return np.array([(at[0] - w * k, at[1] - (STEP + AREA * 0.5 + 0.8) * k),
                     (at[0] + w * k, at[1] + (NAME * 0.5 + 0.5) * k)])


def inside(points: np.ndarray, loops) -> np.ndarray:
    """Whether each point lies inside the loops (even-odd)."""
    within = np.zeros(len(points), bool)
    x, y = points[:, 0:1], points[:, 1:2]
    for loop in loops:
        p, q = loop, np.roll(loop, -1, axis=0)
        crosses = (p[:, 1] > y) != (q[:, 1] > y)
        with np.errstate(divide="ignore", invalid="ignore"):
            at = p[:, 0] + (y - p[:, 1]) / (q[:, 1] - p[:, 1]) * (q[:, 0] - p[:, 0])
        within ^= (np.sum(crosses & (x < at), axis=1) % 2).astype(bool)
    return within


def _fits(box: np.ndarray, loops) -> bool:
    """Whether the box lies inside the loops: its edges' points inside, and no
    corner of a loop within it."""
    (x0, y0), (x1, y1) = box
    t = np.linspace(0.0, 1.0, 9)
    edges = np.concatenate([np.column_stack([x0 + (x1 - x0) * t, np.full(9, y)]) for y in (y0, y1)]
                           + [np.column_stack([np.full(9, x), y0 + (y1 - y0) * t]) for x in (x0, x1)])
    if not inside(edges, loops).all():
        return False
    corners = np.concatenate(loops)
    return not np.any((corners[:, 0] > x0) & (corners[:, 0] < x1)
                      & (corners[:, 1] > y0) & (corners[:, 1] < y1))


def _placed(loops, lines, k: float):
    """Where the tag goes: the space's middle when it fits there, else the
    point nearest it on a grid over the space where it fits; None where it
    fits nowhere."""
    at = _middle(loops)
    if _fits(_tag_box(at, lines, k), loops):
        return at
    points = np.concatenate(loops)
    (x0, y0), (x1, y1) = points.min(axis=0), points.max(axis=0)
    xs, ys = np.meshgrid(np.linspace(x0, x1, 25), np.linspace(y0, y1, 25))
    grid = np.column_stack([xs.ravel(), ys.ravel()])
    for g in grid[np.argsort(np.hypot(grid[:, 0] - at[0], grid[:, 1] - at[1]))]:
        if _fits(_tag_box(g, lines, k), loops):
            return float(g[0]), float(g[1])
    return None


def _middle(loops) -> tuple[float, float]:
    """The area centroid of the loops, or, when it falls outside them (an L),
    the middle of the longest stretch inside along the horizontal through it."""
    total, cx, cy = 0.0, 0.0, 0.0
    for loop in loops:
        x, y = loop[:, 0], loop[:, 1]
        xn, yn = np.roll(x, -1), np.roll(y, -1)
        cross = x * yn - xn * y
        total += cross.sum() / 2
        cx += ((x + xn) * cross).sum() / 6
        cy += ((y + yn) * cross).sum() / 6
    cx, cy = cx / total, cy / total
    crossings = []
    for loop in loops:
        p, q = loop, np.roll(loop, -1, axis=0)
        hit = (p[:, 1] > cy) != (q[:, 1] > cy)
        t = (cy - p[hit, 1]) / (q[hit, 1] - p[hit, 1])
        crossings.extend((p[hit, 0] + t * (q[hit, 0] - p[hit, 0])).tolist())
    crossings.sort()
    spans = [(crossings[k], crossings[k + 1]) for k in range(0, len(crossings) - 1, 2)]
    if any(a <= cx <= b for a, b in spans) or not spans:
        return float(cx), float(cy)
    a, b = max(spans, key=lambda s: s[1] - s[0])
    return float((a + b) / 2), float(cy)
