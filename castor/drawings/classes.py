"""What the classes of LANGUAGE.md §11 add to a drawing (OUTPUT.md, "What a
contractor builds from"), in page metres.

- Each element's cut is hatched by its class (``PATTERNS``), unclassed solid
  grey; a legend lists the patterns used.
- Plans: a door cut by the plan gets its leaf and swing from its hinge and
  swing settings, a window its frame and glass in the wall's thickness, a
  stair its break line at the cut, its treads beyond it dashed and an arrow
  up with its number of risers; what lies above the cut within the storey
  (eaves, a canopy, the well of the floor above) is dashed; each space cut by
  the plan gets a tag with its name and its area at the plan's height.

Everything is read from the frame's take-off (castor.quantities.Takeoff):
the elements' own solids, the openings' blocks, the rooms and the storeys.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from castor.csg.elements import cuts_nothing
from castor.drawings.cut import cut_loops

# pattern name (as DXF names it) -> (line families (angle in degrees, offset as
# a fraction of the period), period in paper mm, its period in the DXF
# pattern's own units)
HATCHES = {
    "ANSI31": (((45.0, 0.0),), 2.0, 3.175),
    "ANSI37": (((45.0, 0.0), (135.0, 0.0)), 2.5, 3.175),
    "NET": (((0.0, 0.0), (90.0, 0.0)), 1.5, 3.175),
    "ANSI32": (((45.0, 0.0), (45.0, 1 / 3)), 4.5, 9.525),
    "ANSI34": (((45.0, 0.0), (45.0, 1 / 6), (45.0, 1 / 3), (45.0, 1 / 2)), 7.0, 19.05),
}
SOLID = "SOLID"
# a class's pattern and its legend's words
PATTERNS = {
    "IfcWall": ("ANSI31", "Walls"), "IfcWallStandardCase": ("ANSI31", "Walls"),
    "IfcCurtainWall": ("ANSI31", "Walls"),
    "IfcSlab": ("ANSI37", "Slabs and roofs"), "IfcRoof": ("ANSI37", "Slabs and roofs"),
    "IfcFooting": ("ANSI37", "Slabs and roofs"), "IfcRamp": ("ANSI37", "Slabs and roofs"),
    "IfcColumn": ("NET", "Columns and beams"), "IfcBeam": ("NET", "Columns and beams"),
    "IfcMember": ("NET", "Columns and beams"), "IfcPile": ("NET", "Columns and beams"),
    "IfcStair": ("ANSI32", "Stairs"), "IfcStairFlight": ("ANSI32", "Stairs"),
}
OTHER = ("ANSI34", "Other elements")
UNCLASSED = (SOLID, "Unclassed")

WALLS = ("IfcWall", "IfcWallStandardCase", "IfcCurtainWall")
SLABS = ("IfcSlab", "IfcRoof")
SEEN_PEN = 0.18  # mm: symbols are seen edges (OUTPUT.md)
DOOR, WINDOW, STAIR = "IfcDoor", "IfcWindow", "IfcStair"


def pattern_of(element) -> tuple[str, str]:
    """The hatch pattern and legend words of an element's class."""
    if element.classification is None or element.ifc_class == "IfcBuildingElementProxy":
        return UNCLASSED
    return PATTERNS.get(element.ifc_class, OTHER)


class Region(NamedTuple):
    """One element's cut regions: loops in page metres, hatched with ``pattern``."""

    name: str  # the element's object name
    ifc_class: str
    pattern: str
    loops: list


class Stroke(NamedTuple):
    """A polyline of page points (n, 2), drawn with ``pen`` mm, dashed or not."""

    points: np.ndarray
    pen: float = SEEN_PEN
    dashed: bool = False
    closed: bool = False
    chain: bool = False  # ISO 128's long-dashed dotted line (a section's cut line)


class Arc(NamedTuple):
    """A circular arc in page metres, counter-clockwise from ``start`` to ``end`` degrees."""

    centre: tuple[float, float]
    radius: float
    start: float
    end: float
    pen: float = SEEN_PEN


class Label(NamedTuple):
    """Text at a page point (the centre of its first line), ``size`` mm high."""

    at: tuple[float, float]
    lines: tuple[str, ...]
    size: float = 2.5
    angle: float = 0.0


@dataclass
class Symbols:
    """What the classes add to a drawing, besides each layer's regions."""

    strokes: list = field(default_factory=list)
    arcs: list = field(default_factory=list)
    labels: list = field(default_factory=list)
    legend: list = field(default_factory=list)  # (pattern, words), in the order first used
    storey: tuple | None = None  # a plan's storey: (name, floor level)
    level_at: tuple | None = None  # where a plan marks its floor level (page metres)
    walls: list = field(default_factory=list)  # the cut walls' loops: the chains follow them
    cut_openings: list = field(default_factory=list)  # page boxes of the openings cut
    seen_openings: list = field(default_factory=list)  # page boxes of openings seen face on
    storeys: list = field(default_factory=list)  # the storeys' floor levels
    # a section's or elevation's vertical chains: side -> heights of its
    # openings' sills and heads
    sides: dict = field(default_factory=dict)
    # a vertical section's cut slabs and roofs: the heights of their undersides
    # and tops, on both vertical chains (the structure's thicknesses)
    slabs: list = field(default_factory=list)
    # the page boxes ((x0, y0), (x1, y1)) the set's marks take (castor.drawings.marks),
    # beyond the chains: the sheet makes room for them
    marks: list = field(default_factory=list)
    # a section's or elevation's stairs, cut or seen: their page boxes; their
    # treads are no levels (castor.drawings.annotate.level_heights)
    stairs: list = field(default_factory=list)
    # the page box of the plan's own strokes and arcs (a door swinging out: its
    # leaf and swing; the eaves overhead), the set's marks left out: the
    # dimension chains stand beyond it (castor.drawings.sheet)
    reach: np.ndarray | None = None


def classify(drawing, takeoff, warn=None) -> None:
    """Give ``drawing`` (castor.drawings.model.Drawing) its layers' regions and
    its symbols from the frame's take-off; ``warn(message)`` hears of what
    cannot be drawn."""
    warn = warn or (lambda message: None)
    symbols = Symbols()
    drawing.symbols = symbols
    plan = drawing.section is not None and drawing.section.axis == "z"
    blocks = takeoff.blocks()  # measured once: each call measures them again
    if drawing.section is not None:
        z = float(drawing.section.value)
        doors = [b for b in blocks if plan and b.opening.classification.ifc_class == DOOR
                 and b.sill < z < b.head]
        _regions(drawing, takeoff, symbols, plan, doors)
    symbols.storeys = [level for _, level in takeoff.storeys()]
    _openings(drawing, blocks, symbols, takeoff)
    if not plan:
        symbols.stairs = _stairs(drawing, takeoff)
        return
    z = float(drawing.section.value)
    storeys = takeoff.storeys()
    name = takeoff.storey_at(z)
    level = dict(storeys)[name]
    above = [lv for _, lv in storeys if lv > level + 0.01]
    ceiling = min(above) if above else math.inf
    symbols.storey = (name, level)
    centre = _centre(takeoff)
    loops = [loop for layer in drawing.layers for loop in layer.cuts]
    for block in blocks:
        cls = block.opening.classification.ifc_class
        if not block.sill < z < block.head:
            continue
        if cls == DOOR:
            _door(block, centre, loops, symbols)
        elif cls == WINDOW:
            _window(block, loops, symbols)
    for opening in takeoff.idle(blocks):
        warn(cuts_nothing(opening, "no symbol is drawn"))
    for p in takeoff.placed():
        box = p.figures.bbox
        if p.element.ifc_class == STAIR and box[0][2] < z < box[1][2] + 1e-9:
            _stair(p, takeoff, z, drawing.view, symbols, warn)
        elif box[0][2] > z and box[0][2] < ceiling - 1e-9 and p.element.ifc_class != STAIR:
            _overhead(takeoff.solid(p.element), drawing.view, symbols)
    from castor.drawings.rooms import room_tags

    for at, lines in room_tags(takeoff, drawing.view, z, drawing.scale, warn):
        symbols.labels.append(Label(at, lines, 3.0))
        if symbols.level_at is None:
            symbols.level_at = (at[0], at[1])
    symbols.reach = _reach(symbols)


def _reach(symbols: Symbols) -> np.ndarray | None:
    """The page box ((x0, y0), (x1, y1)) of the symbols' strokes and arcs, or None."""
    points = [np.asarray(stroke.points, float).reshape(-1, 2) for stroke in symbols.strokes]
    for arc in symbols.arcs:
        # its ends, and where it passes an axis: its extremes
        sweep = (arc.end - arc.start) % 360.0
        turns = [a for a in (0.0, 90.0, 180.0, 270.0) if (a - arc.start) % 360.0 < sweep]
        t = np.radians([arc.start, arc.start + sweep] + turns)
        points.append(np.column_stack([arc.centre[0] + arc.radius * np.cos(t),
                                       arc.centre[1] + arc.radius * np.sin(t)]))
    if not points:
        return None
    every = np.concatenate(points)
    return np.array([every.min(axis=0), every.max(axis=0)])


def _regions(drawing, takeoff, symbols: Symbols, plan: bool, doors=()) -> None:
    """Each layer's cut regions, element by element, with their patterns. An
    unclassed solid's cut wholly inside the block of a door the plan cuts
    (``doors``) is that door's leaf, closed: the plan draws the door's symbol
    (its leaf open and its swing) instead."""
    depth = drawing.view.plane_depth(drawing.section)
    by_object: dict[int, list] = {}
    dropped: dict[int, list] = {}  # object -> the closed leaves' loops left out
    for p in takeoff.placed():
        if plan and p.element.ifc_class == STAIR:
            continue  # a plan draws the stair's symbol, not its cut
        loops = cut_loops(takeoff.solid(p.element), drawing.view, depth)
        pattern, words = pattern_of(p.element)
        if doors and pattern == SOLID:
            leaves = [loop for loop in loops if any(_within(loop, b) for b in doors)]
            dropped.setdefault(p.element.object, []).extend(leaves)
            loops = [loop for loop in loops if not any(loop is leaf for leaf in leaves)]
        if not loops:
            continue
        if p.element.ifc_class in WALLS:
            symbols.walls.extend(loops)
        elif p.element.ifc_class in SLABS and drawing.view.basis()[1][2] > 0.99:
            symbols.slabs.extend(y for loop in loops for y in (np.min(np.asarray(loop)[:, 1]),
                                                               np.max(np.asarray(loop)[:, 1])))
        by_object.setdefault(p.element.object, []).append(
            Region(p.element.name, p.element.ifc_class, pattern, loops))
        if (pattern, words) not in symbols.legend:
            symbols.legend.append((pattern, words))
    for layer in drawing.layers:
        layer.regions = by_object.get(layer.source, [])
        if dropped.get(layer.source) and len(layer.lines):
            # and the leaf's seen edges below the cut, along its outline
            keep = ~_along(layer.lines, dropped[layer.source])
            layer.lines, layer.profile = layer.lines[keep], layer.profile[keep]


def _within(loop, block, tolerance: float = 1e-6) -> bool:
    """Whether a plan loop lies wholly inside the opening block's footprint (a
    rectangle of its width along its direction and its thickness across)."""
    (x0, y0, _), (x1, y1, _) = block.figures.bbox
    along = np.array(block.direction, float)
    along /= np.linalg.norm(along)
    across = np.array([-along[1], along[0]])
    offsets = np.asarray(loop, float) - np.array([(x0 + x1) / 2, (y0 + y1) / 2])
    return bool(np.all(np.abs(offsets @ along) <= block.width / 2 + tolerance)
                and np.all(np.abs(offsets @ across) <= block.thickness / 2 + tolerance))


def _along(segments: np.ndarray, loops: list, tolerance: float = 1e-6) -> np.ndarray:
    """Which segments (L, 2, 2) lie along the loops' outlines (their ends and
    points between each on an edge of a loop, which may run on in pieces)."""
    a, b = segments[:, 0], segments[:, 1]
    samples = [a + (b - a) * t for t in np.linspace(0.0, 1.0, 9)]
    near = [np.full(len(segments), np.inf) for _ in samples]
    for loop in loops:
        p = np.asarray(loop, float)
        for start, end in zip(p, np.roll(p, -1, axis=0)):
            e = end - start
            square = float(e @ e)
            for k, q in enumerate(samples):
                t = np.clip((q - start) @ e / square, 0, 1) if square > 1e-24 else np.zeros(len(q))
                near[k] = np.minimum(near[k], np.linalg.norm(q - start - t[:, None] * e, axis=1))
    return np.all([d < tolerance for d in near], axis=0)


def _openings(drawing, blocks, symbols: Symbols, takeoff=None) -> None:
    """The page boxes of the openings the drawing cuts (the chains break at
    them) and of those it sees face on (what is seen through them is no
    level); for a section or an elevation, the sills and heads of the
    openings on each side, for its vertical chains."""
    basis = drawing.view.basis()
    towards = basis[2]
    depth = drawing.view.plane_depth(drawing.section)
    if not blocks:
        return
    seen = []
    for block in blocks:
        low, high = np.array(block.figures.bbox)
        corners = np.array([[x, y, z] for x in (low[0], high[0]) for y in (low[1], high[1])
                            for z in (low[2], high[2])]) @ basis.T
        box = (tuple(corners[:, :2].min(axis=0)), tuple(corners[:, :2].max(axis=0)))
        d0, d1 = corners[:, 2].min(), corners[:, 2].max()
        across = np.array([-block.direction[1], block.direction[0], 0.0])
        face_on = abs(float(across @ towards)) > 0.99
        if depth is not None and d0 < depth < d1:
            symbols.cut_openings.append(box)
            seen.append((block, box, True))
        elif face_on and (depth is None or d1 <= depth + 1e-9):
            symbols.seen_openings.append(box)
            seen.append((block, box, False))
    vertical = abs(basis[1][2]) > 0.99
    if not vertical:
        return
    # the vertical chains: the openings cut, else (an elevation) those seen in
    # the façade nearest the viewer
    chosen = [(b, box) for b, box, cut in seen if cut]
    if not chosen and drawing.section is None:
        nearest = max(float(np.max(np.array(b.figures.bbox) @ towards)) for b, _, _ in seen) \
            if seen else None
        walls = [p for p in takeoff.placed() if p.element.ifc_class in WALLS] \
            if takeoff is not None and seen else []
        if walls:  # the façade is the outer walls' face, not a wall inside behind it
            nearest = max(float(np.max(_corners(p.figures.bbox) @ towards)) for p in walls)
        chosen = [(b, box) for b, box, _ in seen
                  if float(np.max(np.array(b.figures.bbox) @ towards)) > nearest - 1.0]
    if not chosen:
        return
    extent = drawing.box()
    middle = (extent[0, 0] + extent[1, 0]) / 2
    for block, box in chosen:
        side = "left" if (box[0][0] + box[1][0]) / 2 < middle else "right"
        symbols.sides.setdefault(side, []).extend([box[0][1], box[1][1]])


def _stairs(drawing, takeoff) -> list:
    """The page boxes of the stairs a section or an elevation cuts or sees."""
    basis = drawing.view.basis()
    depth = drawing.view.plane_depth(drawing.section)
    boxes = []
    for p in takeoff.placed():
        if p.element.ifc_class != STAIR:
            continue
        corners = _corners(p.figures.bbox) @ basis.T
        if depth is None or corners[:, 2].min() < depth:
            boxes.append((tuple(corners[:, :2].min(axis=0)), tuple(corners[:, :2].max(axis=0))))
    return boxes


def _corners(bbox) -> np.ndarray:
    low, high = np.array(bbox)
    return np.array([[x, y, z] for x in (low[0], high[0]) for y in (low[1], high[1])
                     for z in (low[2], high[2])])


def _centre(takeoff) -> np.ndarray:
    """The plan middle of what the frame builds: doors swing in towards it."""
    boxes = [p.figures.bbox for p in takeoff.placed()]
    low = np.min([b[0] for b in boxes], axis=0)
    high = np.max([b[1] for b in boxes], axis=0)
    return (low[:2] + high[:2]) / 2


def _frame_of(block, loops):
    """The block's plan middle, the unit vector along its width and across it,
    and the wall's thickness: read from the cut regions (``loops``) just beyond
    its jambs, as the block a cutter took can be deeper than the wall where
    another cutter (the room's inside) took the rest."""
    (x0, y0, _), (x1, y1, _) = block.figures.bbox
    middle = np.array([(x0 + x1) / 2, (y0 + y1) / 2])
    along = np.array(block.direction, float)
    along /= np.linalg.norm(along)
    across = np.array([-along[1], along[0]])
    for sign in (1, -1):
        probe = middle + along * sign * (block.width / 2 + 0.02)
        span = _span(loops, probe, across, block.thickness / 2)
        if span is not None:
            return middle + across * (span[0] + span[1]) / 2, along, across, span[1] - span[0]
    return middle, along, across, block.thickness


def _span(loops, point, direction, reach: float):
    """The stretch (s0, s1) of the line point + s * direction inside the loops
    that holds a point within ``reach`` of s = 0, or None."""
    hits = []
    for loop in loops:
        p, q = loop, np.roll(loop, -1, axis=0)
        e = q - p
        # point + s d = p + t e
        det = direction[0] * (-e[:, 1]) - direction[1] * (-e[:, 0])
        ok = np.abs(det) > 1e-12
        r = p - point
        s = np.where(ok, (r[:, 0] * (-e[:, 1]) - r[:, 1] * (-e[:, 0])) / np.where(ok, det, 1), 0)
        t = np.where(ok, (direction[0] * r[:, 1] - direction[1] * r[:, 0]) / np.where(ok, det, 1), -1)
        hits.extend(s[ok & (t >= 0) & (t < 1)].tolist())
    hits.sort()
    for a, b in zip(hits[0::2], hits[1::2]):
        if a - 1e-9 <= reach and b + 1e-9 >= -reach and b - a > 1e-6:
            if a <= 0 <= b or abs(a) <= reach or abs(b) <= reach:
                return a, b
    return None


def _door(block, centre, loops, symbols: Symbols) -> None:
    """The leaf, square to the wall at its hinge, open, and its swing: a quarter
    circle of the door's width from the leaf's end to the other jamb. ``hinge``
    is seen from the side the door opens towards; ``swing=in`` opens towards
    the building's middle."""
    settings = dict(block.opening.classification.settings)
    middle, along, across, t = _frame_of(block, loops)
    inwards = across if float(np.dot(centre - middle, across)) >= 0 else -across
    towards = inwards if settings.get("swing", "in") == "in" else -inwards
    left = np.array([towards[1], -towards[0]])  # the left hand of one facing the door
    side = left if settings.get("hinge", "left") == "left" else -left
    w = block.width
    hinge = middle + towards * t / 2 + side * w / 2
    symbols.strokes.append(Stroke(np.array([hinge, hinge + towards * w])))
    a = math.degrees(math.atan2(towards[1], towards[0]))
    b = math.degrees(math.atan2(-side[1], -side[0]))
    start, end = (a, b) if abs((b - a) % 360 - 90.0) < 1e-6 else (b, a)
    symbols.arcs.append(Arc((float(hinge[0]), float(hinge[1])), w, start % 360, end % 360))


def _window(block, loops, symbols: Symbols) -> None:
    """The frame (a band in the middle of the wall's thickness) and the glass
    (a line along its middle), between the jambs."""
    middle, along, across, t = _frame_of(block, loops)
    w = block.width
    f = min(0.07, t / 3) / 2
    ends = [middle - along * w / 2, middle + along * w / 2]
    corners = np.array([ends[0] - across * f, ends[1] - across * f,
                        ends[1] + across * f, ends[0] + across * f])
    symbols.strokes.append(Stroke(corners, closed=True))
    symbols.strokes.append(Stroke(np.array(ends), pen=0.13))


def _stair(placed, takeoff, z: float, view, symbols: Symbols, warn) -> None:
    """The flight cut by the plan: its treads' nosings (those beyond the cut
    dashed), the break line where the plan cuts it, the arrow up from its foot
    with the number of risers."""
    element = placed.element
    from castor.mesh.frame import faces_up

    treads = faces_up(takeoff.solid(element), 0.999, 6)  # (a step's top, tilted by up to 2.6°)
    bottom = placed.figures.bbox[0][2]
    treads = [(h, pts) for h, pts in treads if h > bottom + 1e-6]
    if len(treads) < 2:
        warn(f"stair '{element.name}' ({element.where}) has {len(treads)} riser"
             f"{'' if len(treads) == 1 else 's'}: it is drawn as it is cut, with no arrow")
        return
    # the middles of the lowest and highest treads (of their boxes: a tread's
    # triangles say nothing of its middle)
    first = (treads[0][1].min(axis=0) + treads[0][1].max(axis=0)) / 2
    last = (treads[-1][1].min(axis=0) + treads[-1][1].max(axis=0)) / 2
    up = last - first
    if np.linalg.norm(up) < 1e-9:
        warn(f"stair '{element.name}' ({element.where}) rises in place: no flight to draw")
        return
    up /= np.linalg.norm(up)
    side = np.array([-up[1], up[0]])
    every = np.concatenate([pts for _, pts in treads])
    b0, b1 = float((every @ side).min()), float((every @ side).max())
    nosings = [float((pts @ up).min()) for _, pts in treads]
    end = float((treads[-1][1] @ up).max())
    cut = next((k for k, (h, _) in enumerate(treads) if h > z), None)

    def point(a, b):
        return up * a + side * b

    for k, (h, _) in enumerate(treads):
        if cut is not None and k >= cut:
            symbols.strokes.append(Stroke(np.array([point(nosings[k], b0), point(nosings[k], b1)]),
                                          dashed=True))
    if cut is not None:
        a = nosings[cut]
        symbols.strokes.append(Stroke(np.array([point(nosings[cut], b0), point(end, b0)]),
                                      dashed=True))
        symbols.strokes.append(Stroke(np.array([point(nosings[cut], b1), point(end, b1)]),
                                      dashed=True))
        # the break line: across the flight, slanting, with a zigzag in its middle
        mid, width = (b0 + b1) / 2, b1 - b0
        g = min(0.12, width / 8)
        zig = [(a - 0.25, b0 - 0.1), (a - g / 2, mid - g), (a + g, mid - g / 3),
               (a - g, mid + g / 3), (a + g / 2, mid + g), (a + 0.25, b1 + 0.1)]
        # past the flight on each side, but not into a wall it runs along
        for end, inner, edge in ((0, 1, b0), (5, 4, b1)):
            if _in_walls(point(*zig[end]), symbols.walls):
                (u0, v0), (u1, v1) = zig[end], zig[inner]
                zig[end] = (u0 + (u1 - u0) * (edge - v0) / (v1 - v0), edge)
        symbols.strokes.append(Stroke(np.array([point(u, v) for u, v in zig])))
        top = a - 0.1
    else:
        top = end - 0.1
    foot = nosings[0] - (nosings[1] - nosings[0]) * 0.5
    mid = (b0 + b1) / 2
    symbols.strokes.append(Stroke(np.array([point(foot, mid), point(top, mid)]), pen=0.13))
    head = 0.15
    symbols.strokes.append(Stroke(np.array([point(top - head, mid - head / 2), point(top, mid),
                                            point(top - head, mid + head / 2)]), pen=0.13))
    angle = math.degrees(math.atan2(up[1], up[0]))
    if angle <= -90 or angle > 90:
        angle -= 180 if angle > 90 else -180
    risers = len(treads)
    # beside the arrow, along the flight, a quarter of its width off the middle
    at = point((foot + top) / 2, mid - (b1 - b0) / 4)
    symbols.labels.append(Label((float(at[0]), float(at[1])), (f"{risers} R",), 2.5, angle))


def _in_walls(at: np.ndarray, walls) -> bool:
    """Whether a plan point lies inside one of the cut walls' loops."""
    from castor.drawings.rooms import inside

    return any(inside(np.array([at]), [np.asarray(loop, float)])[0] for loop in walls)


def _overhead(solid, view, symbols: Symbols) -> None:
    """The outline of an element above the cut seen from below the roof: the
    edges between a face turned up and one that is not, dashed."""
    from castor.mesh.arrays import fan_triangles

    if solid.polygon_count == 0:
        return
    tris, _ = fan_triangles(solid.offsets, solid.indices)
    corners = solid.vertices[tris]
    normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    length = np.linalg.norm(normal, axis=1)
    keep = length > 1e-15
    corners, normal, length = corners[keep], normal[keep], length[keep]
    facing_up = normal[:, 2] > 1e-6 * length
    faces: dict[tuple, list[bool]] = {}
    ends: dict[tuple, tuple] = {}
    keys = np.round(corners / 1e-7).astype(np.int64)
    for t in range(len(corners)):
        for i, j in ((0, 1), (1, 2), (2, 0)):
            a, b = tuple(keys[t, i]), tuple(keys[t, j])
            key = (a, b) if a <= b else (b, a)
            faces.setdefault(key, []).append(bool(facing_up[t]))
            ends.setdefault(key, (corners[t, i], corners[t, j]))
    basis = view.basis()
    segments = []
    for key, ups in faces.items():
        if any(ups) and not all(ups):
            p, q = ends[key]
            segments.append([(basis @ p)[:2], (basis @ q)[:2]])
    for segment in _joined(segments):
        symbols.strokes.append(Stroke(np.array(segment), dashed=True))


def _joined(segments: list) -> list:
    """Collinear segments that meet end to end joined, so that dashes run on."""
    out: list = []
    rest = [np.asarray(s, float) for s in segments
            if np.linalg.norm(np.subtract(s[1], s[0])) > 1e-9]
    while rest:
        a, b = rest.pop()
        d = (b - a) / np.linalg.norm(b - a)
        grown = True
        while grown:
            grown = False
            for k, (p, q) in enumerate(rest):
                e = q - p
                if abs(d[0] * e[1] - d[1] * e[0]) > 1e-9 * np.linalg.norm(e):
                    continue
                for u, v in ((p, q), (q, p)):
                    if np.linalg.norm(u - b) < 1e-7 and abs(np.cross(d, v - a)) < 1e-7:
                        b = v
                    elif np.linalg.norm(v - a) < 1e-7 and abs(np.cross(d, u - a)) < 1e-7:
                        a = u
                    else:
                        continue
                    rest.pop(k)
                    grown = True
                    break
                if grown:
                    break
        out.append([a, b])
    return out
