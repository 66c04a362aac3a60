"""A quantity take-off: the figures of a frame's objects, for --stats and --summary.

Pure functions from a mesh frame (castor/mesh/frame.py) to numbers an architect
uses to price a facade or check a floor area: volume, surface area, bounding
box, shells (separate solids), polygons, and the area of each colour. Volumes
and areas are those of the written polygons, in scene units.
"""

from __future__ import annotations

import json
from typing import Callable, NamedTuple

import numpy as np

from castor.bim.solids import EMPTY, Copy, chain, footprint, section_area, shells
from castor.mesh.frame import Frame, FrameObject
from castor.mesh.arrays import components


class Figures(NamedTuple):
    name: str
    volume: float
    area: float
    bbox: tuple[tuple[float, float, float], tuple[float, float, float]] | None
    shells: int
    polygons: int
    vertices: int
    colours: list[tuple[tuple[float, float, float], float]]  # (rgb, area), largest first


def _triangle_figures(obj: FrameObject, centre: np.ndarray) -> tuple[np.ndarray, ...]:
    """Six times the signed volume of each fan triangle's tetrahedron from
    ``centre``, its area, and its polygon's origin: made a piece of polygons at
    a time, so that no (T, 3, 3) array of corners is held (72 bytes a triangle,
    and as much again for each temporary); each figure is the same number."""
    from castor.formats._mesh import CHUNK
    from castor.mesh.arrays import fan_triangles

    count = int(np.maximum(np.diff(obj.offsets) - 2, 0).sum())
    volumes, areas, origins = np.empty(count), np.empty(count), np.empty(count, np.int64)
    done = 0
    for first in range(0, obj.polygon_count, CHUNK):
        last = min(first + CHUNK, obj.polygon_count)
        start, end = obj.offsets[first], obj.offsets[last]
        tris, polygon = fan_triangles(obj.offsets[first:last + 1] - start, obj.indices[start:end])
        corners = obj.vertices[tris]
        a, b, c = corners[:, 0] - centre, corners[:, 1] - centre, corners[:, 2] - centre
        part = slice(done, done + len(tris))
        volumes[part] = np.einsum("ij,ij->i", a, np.cross(b, c))
        areas[part] = np.linalg.norm(np.cross(b - a, c - a), axis=1) / 2
        origins[part] = obj.origin_of[first + polygon]
        done += len(tris)
    return volumes, areas, origins


def shell_count(obj: FrameObject) -> int:
    """How many separate closed surfaces the object has (polygons joined by shared
    vertices), by label propagation with pointer jumping: no Python loop over
    vertices."""
    used = np.unique(obj.indices)
    if len(used) == 0:
        return 0
    following = np.arange(1, len(obj.indices) + 1)
    following[obj.offsets[1:] - 1] = obj.offsets[:-1]
    a, b = obj.indices, obj.indices[following]
    label = components(len(obj.vertices), a, b)
    return len(np.unique(label[used]))


def object_figures(obj: FrameObject, name: str) -> Figures:
    """The figures of one object."""
    if obj.polygon_count == 0:
        return Figures(name, 0.0, 0.0, None, 0, 0, 0, [])
    centre = (obj.vertices.min(axis=0) + obj.vertices.max(axis=0)) / 2
    volumes, areas, origin_of_triangle = _triangle_figures(obj, centre)
    volume = float(volumes.sum() / 6)
    origin_area = np.bincount(origin_of_triangle, weights=areas, minlength=len(obj.origins))
    by_colour: dict[tuple, float] = {}
    for origin, area in zip(obj.origins, origin_area.tolist()):
        key = tuple(float(x) for x in origin.colour)
        by_colour[key] = by_colour.get(key, 0.0) + area
    colours = sorted(by_colour.items(), key=lambda item: -item[1])
    low, high = obj.vertices.min(axis=0).tolist(), obj.vertices.max(axis=0).tolist()
    return Figures(name, volume, float(areas.sum()), (tuple(low), tuple(high)),
                   shell_count(obj), obj.polygon_count, len(obj.vertices), colours)


def frame_figures(frame: Frame) -> list[Figures]:
    """The figures of each object of the frame, named as the mesh formats name them."""
    from castor.formats._mesh import object_names

    return [object_figures(obj, name) for obj, name in zip(frame.objects, object_names(frame))]


def _g(x: float) -> str:
    """A figure as a person reads it: 6 significant digits, no '-0'."""
    text = f"{x:.6g}"
    return "0" if text in ("-0", "0") else text


def stats_line(frame: Frame, primitives: int, booleans: int, seconds: float) -> str:
    """The --stats line of a frame (CLI.md)."""
    figures = frame_figures(frame)
    boxes = [f.bbox for f in figures if f.bbox is not None]
    if boxes:
        low = np.min([b[0] for b in boxes], axis=0)
        high = np.max([b[1] for b in boxes], axis=0)
        box = f"box {' '.join(map(_g, low))} to {' '.join(map(_g, high))}"
    else:
        box = "no box (empty)"
    return (f"castor: frame {frame.number} {frame.where}: {_count(primitives, 'primitive')}, "
            f"{_count(booleans, 'boolean operation')}, "
            f"{_count(sum(f.polygons for f in figures), 'polygon')}, "
            f"{_count(sum(f.vertices for f in figures), 'vertex', 'vertices')}, "
            f"volume {_g(sum(f.volume for f in figures))}, "
            f"area {_g(sum(f.area for f in figures))}, {box}, {seconds:.3f} s")


def _count(n: int, one: str, many: str | None = None) -> str:
    return f"{n} {one if n == 1 else (many or one + 's')}"


def _number(x: float) -> float | int:
    """JSON numbers without noise: 12 significant digits, whole numbers as integers."""
    x = float(f"{x:.12g}") + 0.0
    return int(x) if x.is_integer() and abs(x) < 1e15 else x


def summary_record(frame: Frame, frame_tree=None, facetizer=None,
                   warn: Callable[[str], None] = lambda message: None) -> dict:
    """One frame of the --summary document (OUTPUT.md, "Quantities"); with the
    frame's tree and the facetizer that made it, and classes in the scene, the
    totals per class and storey, the openings and the spaces too (``warn``
    hears of a door or window that cuts nothing, of storeys made one)."""
    objects = []
    for f in frame_figures(frame):
        objects.append({
            "name": f.name,
            "volume": _number(f.volume),
            "area": _number(f.area),
            "bbox": [[_number(x) for x in corner] for corner in f.bbox] if f.bbox else None,
            "shells": f.shells,
            "polygons": f.polygons,
            "colours": [{"rgb": [_number(c) for c in rgb], "area": _number(area)}
                        for rgb, area in f.colours],
        })
    record = {"number": frame.number, "where": frame.where, "objects": objects}
    if frame_tree is not None and facetizer is not None and frame_tree.classes is not None:
        record.update(Takeoff(frame_tree, facetizer, warn=warn).record(warn))
    return record


class Summary:
    """Collects each frame's record; ``text`` is the --summary document."""

    def __init__(self):
        self.frames: list[dict] = []

    def add(self, frame: Frame) -> None:
        self.frames.append(summary_record(frame))

    def text(self) -> str:
        frames = sorted(self.frames, key=lambda record: record["number"])
        # one line per object (per class total, opening, space): readable, and
        # still easy for grep
        parts = []
        for record in frames:
            head = json.dumps({k: v for k, v in record.items()
                               if not isinstance(v, list)})[:-1]
            for key, items in record.items():
                if not isinstance(items, list):
                    continue
                listed = ",\n   ".join(json.dumps(o) for o in items)
                head += (f', "{key}": [\n   {listed}]' if listed else f', "{key}": []')
            parts.append(f" {head}}}")
        return '{"frames": [\n' + ",\n".join(parts) + "]}\n"


# --- the take-off by class and storey (LANGUAGE.md §11)

LEVEL_SLACK = 0.01  # levels this close are one; an element this far below a level is on it


def one_per_level(storeys: list[tuple[str, float]]) -> tuple[list, list]:
    """LANGUAGE.md §11's storeys at one level: ``storeys`` ((name, level)) from
    the lowest (of those at the same level, in the order given), each within
    LEVEL_SLACK of the storey kept below it made one with that storey, which
    keeps its name and level. (the storeys kept, the (kept, dropped) pairs)."""
    kept: list[tuple[str, float]] = []
    merged: list[tuple[tuple[str, float], tuple[str, float]]] = []
    for storey in sorted(storeys, key=lambda s: s[1]):
        if kept and storey[1] - kept[-1][1] <= LEVEL_SLACK:
            merged.append((kept[-1], storey))
        else:
            kept.append(storey)
    return kept, merged


def storeys_made_one(kept: tuple[str, float], dropped: tuple[str, float]) -> str:
    """The warning for two declared storeys one_per_level made one: both
    levels, unless they read the same."""
    (name, level), (other, other_level) = kept, dropped
    if _g(level) == _g(other_level):
        where = f"'{name}' and '{other}' are both at level {_g(level)}"
    else:
        where = (f"'{name}' (level {_g(level)}) and '{other}' (level {_g(other_level)}) are "
                 f"within {_g(LEVEL_SLACK)} of each other")
    return f"storeys {where}: the model has one storey there, '{name}'"


class Placed(NamedTuple):
    """An element measured and put on its storey."""

    element: object  # castor.csg.elements.Element
    figures: Figures
    storey: str


class Block(NamedTuple):
    """One opening: a separate block a door or window cut out of its element."""

    opening: object  # castor.csg.elements.Opening
    piece: int  # which of the opening's blocks, from 0
    solid: FrameObject
    figures: Figures
    host: object  # the Element it was cut from (by the boxes), or None
    storey: str
    width: float  # along the wall (the long side of its plan)
    thickness: float  # across it: the wall's
    height: float
    sill: float
    head: float
    direction: tuple[float, float]  # of the width, in plan


class Room(NamedTuple):
    """A space measured: its name, storey, floor area and volume."""

    space: object  # castor.csg.elements.SpaceUse
    name: str  # the annotation's room name, else the object's
    storey: str
    floor_area: float
    volume: float
    solid: FrameObject


class Takeoff:
    """The elements, openings, storeys and spaces of one frame, their solids made
    when first asked for, with the facetizer that made the frame (its caches
    hold the frame's shared subtrees, so only the booleans that part the
    solids out are new work). What the take-off, the drawings and the IFC
    handover read of a frame's classes."""

    def __init__(self, frame_tree, facetizer, polygons: bool = False,
                 warn: Callable[[str], None] | None = None):
        from castor.csg.elements import Boxes, find

        self.boxes = Boxes()
        # hears of what the take-off decides for the scene (storeys made one)
        self.warn = warn or (lambda message: None)
        self.frame_tree = frame_tree
        self.facetizer = facetizer
        # the solids as polygons (the BIM model's bodies), else as triangles
        self.polygons = polygons
        self.elements, self.openings = find(frame_tree)
        self._solids: dict = {}
        self._copies: dict = {}  # key -> Copy: a solid that is a unit moved
        self._units: dict = {}  # shared key -> the solid of a subtree copies move
        self._unit_figures: dict = {}
        self._unit_pieces: dict = {}
        self._storeys: list[tuple[str, float]] | None = None
        self._placed: list[Placed] | None = None

    def _made(self, key, node) -> FrameObject:
        self._make_all([(key, node)])
        return self._get(key)

    def _make_all(self, wanted: list) -> None:
        """The solids of ``wanted`` ((key, CSG tree or None) pairs), those not
        made yet, as the objects of one frame: the facetizer's patterns serve
        every copy of a part, and a frame's fixed costs are paid once. A tree
        that is a shared subtree moved (the chain of uses down to it), whose
        subtree other wanted trees move too, is made once at the identity and
        each copy moved (castor.bim.solids.Copy): 1,024 houses' walls are one
        wall's solid and 1,024 placements."""
        from castor.csg import tree

        alone: list = []  # (key, tree)
        copies: dict[str, list] = {}  # the shared key of a unit -> its copies
        for key, node in wanted:
            if key in self._solids or key in self._copies:
                continue
            if node is None:
                self._solids[key] = EMPTY
                continue
            uses = chain(node)
            if uses:
                copies.setdefault(uses[-1].shared.key, []).append((key, node, uses))
            else:
                alone.append((key, node))
        units = []
        for unit_key, found in copies.items():
            if unit_key not in self._units:
                if len(found) == 1:  # made as it stands: the bytes of a lone element kept
                    alone.append(found[0][:2])
                    continue
                inner = found[0][2][-1]
                alone.append((("unit", unit_key), tree.Use(tree.IDENTITY, "", inner.shared)))
            units.append((unit_key, found))
        self._frame(alone)
        for unit_key, found in units:
            if unit_key not in self._units:
                self._units[unit_key] = self._solids.pop(("unit", unit_key))
            for key, _, uses in found:
                self._copies[key] = Copy(unit_key, uses)

    def _frame(self, wanted: list) -> None:
        """The solids of ``wanted`` ((key, tree) pairs) as the objects of one
        frame, each checked against the polygon limit as before (the limit
        times the objects, for the frame)."""
        from castor.csg import tree

        if not wanted:
            return
        whole = self.frame_tree
        frame_tree = tree.FrameTree(whole.number, whole.where, whole.location,
                                    tuple(tree.Object(str(key), node) for key, node in wanted))
        # triangles: the figures are the same, and no polygons are written
        facetizer = self.facetizer
        merging, limit = facetizer.merge_polygons, facetizer.max_polygons
        facetizer.merge_polygons = self.polygons
        facetizer.max_polygons = limit * len(wanted)
        try:
            made = facetizer.frame(frame_tree).objects
        finally:
            facetizer.merge_polygons, facetizer.max_polygons = merging, limit
        self._solids.update(zip((key for key, _ in wanted), made))

    def _get(self, key) -> FrameObject:
        """A solid made by _make_all: its own, or its unit's moved."""
        found = self._solids.get(key)
        if found is None:
            copy = self._copies[key]
            found = self._solids[key] = copy.moved(self._units[copy.unit])
        return found

    def _figures(self, key, name: str) -> Figures:
        """The figures of a solid made by _make_all: a rigid copy's are its
        unit's (volume, area, colours, shells are the same), with its own box."""
        copy = self._copies.get(key)
        if copy is None or not copy.rigid:
            return object_figures(self._get(key), name)
        if copy.unit not in self._unit_figures:
            self._unit_figures[copy.unit] = object_figures(self._units[copy.unit], name)
        unit = self._unit_figures[copy.unit]
        if unit.bbox is None:
            return unit._replace(name=name)
        solid = self._get(key)
        low, high = solid.vertices.min(axis=0).tolist(), solid.vertices.max(axis=0).tolist()
        return unit._replace(name=name, bbox=(tuple(low), tuple(high)))

    def known(self, element, solid: FrameObject) -> None:
        """Take ``solid`` as the element's own (made already: a whole '>' object's)."""
        self._solids[("element", element.number)] = solid

    def solid(self, element) -> FrameObject:
        """The element's own solid, as polygons."""
        from castor.csg.elements import element_tree

        key = ("element", element.number)
        if key in self._solids or key in self._copies:
            return self._get(key)
        return self._made(key, element_tree(self.frame_tree, element, self.boxes))

    def _all_elements(self) -> None:
        """Every element's solid, made in one frame."""
        from castor.csg.elements import element_tree

        self._make_all([(("element", e.number), element_tree(self.frame_tree, e, self.boxes))
                        for e in self.elements if ("element", e.number) not in self._solids
                        and ("element", e.number) not in self._copies])

    def figures(self, element) -> Figures:
        self.solid(element)
        return self._figures(("element", element.number), element.name)

    def space_solid(self, index: int) -> FrameObject:
        from castor.csg import tree

        space = self.frame_tree.spaces[index]
        return self._made(("space", index), tree.Use(space.matrix, "", space.shared))

    def storeys(self) -> list[tuple[str, float]]:
        """(name, floor level) from the lowest: LANGUAGE.md §11's rule, storeys
        within LEVEL_SLACK of one another made one (one_per_level). What the
        take-off, the drawings and the IFC all read: none keeps its own."""
        if self._storeys is None:
            self._storeys = self._find_storeys()
        return self._storeys

    def _find_storeys(self) -> list[tuple[str, float]]:
        declared = self.frame_tree.classes.storeys if self.frame_tree.classes is not None else ()
        values = dict(self.frame_tree.parameters)
        found = [(m.name, float(values[m.parameter])) for m in declared if m.parameter in values]
        if found:
            kept, merged = one_per_level(found)
            for below, above in merged:
                self.warn(storeys_made_one(below, above))
            return kept
        self._all_elements()
        tops = [f.bbox[1][2] for f in (self.figures(e) for e in self.elements
                                       if _is_floor(e)) if f.bbox is not None]
        levels, _ = one_per_level([("", top) for top in tops])
        if not levels:
            return [("Level 0", 0.0)]
        return [(f"Level {k}", level) for k, (_, level) in enumerate(levels)]

    def storey_at(self, height: float) -> str:
        """The highest storey whose level is at most ``height`` (+ the slack), or
        the lowest."""
        storeys = self.storeys()
        chosen = storeys[0][0]
        for name, level in storeys:
            if level <= height + LEVEL_SLACK:
                chosen = name
        return chosen

    def placed(self) -> list[Placed]:
        """Every element with a solid, measured, on its storey (by its bottom; a
        floor slab by its top)."""
        if self._placed is None:
            self._all_elements()
            self._placed = []
            for element in self.elements:
                f = self.figures(element)
                if f.bbox is None:
                    continue  # the rest of an object wholly made of classed parts
                height = f.bbox[1][2] if _is_floor(element) else f.bbox[0][2]
                self._placed.append(Placed(element, f, self.storey_at(height)))
        return self._placed

    def blocks(self) -> list[Block]:
        """Every opening's blocks, in the order of the openings."""
        from castor.csg.elements import opening_tree

        out = []
        # an opening's host is an element of its own '>' object: looked for there
        # only (1,024 houses, 13,000 openings: not each against every element)
        of_object: dict[int, list[Placed]] = {}
        for p in self.placed():
            of_object.setdefault(p.element.object, []).append(p)
        self._make_all([(("opening", o.number), opening_tree(self.frame_tree, o))
                        for o in self.openings])
        for opening in self.openings:
            for k, (piece, f, (width, thickness, direction)) in enumerate(
                    self._pieces(("opening", opening.number), opening.name)):
                (_, _, z0), (_, _, z1) = f.bbox
                out.append(Block(opening, k, piece, f,
                                 _host(of_object.get(opening.object, []), f.bbox),
                                 self.storey_at(z0), width, thickness, z1 - z0, z0, z1,
                                 direction))
        return out

    def idle(self, blocks: list[Block] | None = None) -> list:
        """The openings that cut nothing from the element they are subtracted
        from (no block: a door moved off its wall), each said by
        castor.csg.elements.cuts_nothing where an output leaves it out;
        ``blocks``: those measured already (each call of ``blocks`` measures again)."""
        cut = {id(b.opening) for b in (self.blocks() if blocks is None else blocks)}
        return [o for o in self.openings if id(o) not in cut]

    def _pieces(self, key, name: str) -> list:
        """The separate blocks of an opening's solid, each with its figures and
        footprint: a rigid copy's are its unit's moved (the footprint measured
        again where the copy is turned)."""
        copy = self._copies.get(key)
        if copy is None or not copy.rigid:
            return [(piece, object_figures(piece, name), footprint(piece.vertices))
                    for piece in shells(self._get(key))]
        if copy.unit not in self._unit_pieces:
            self._unit_pieces[copy.unit] = [
                (piece, object_figures(piece, name), footprint(piece.vertices))
                for piece in shells(self._units[copy.unit])]
        out = []
        for piece, f, plan in self._unit_pieces[copy.unit]:
            moved = copy.moved(piece)
            low, high = moved.vertices.min(axis=0).tolist(), moved.vertices.max(axis=0).tolist()
            out.append((moved, f._replace(name=name, bbox=(tuple(low), tuple(high))),
                        plan if copy.translation else footprint(moved.vertices)))
        return out

    def rooms(self) -> list[Room]:
        out = []
        for index, space in enumerate(self.frame_tree.spaces):
            solid = self.space_solid(index)
            f = object_figures(solid, space.name)
            if f.bbox is None:
                continue
            bottom = f.bbox[0][2]
            out.append(Room(space, space.classification.long_name or space.name,
                            self.storey_at(bottom), section_area(solid, bottom + 1e-3),
                            f.volume, solid))
        return out

    def record(self, warn: Callable[[str], None] = lambda message: None) -> dict:
        """What --summary adds to a frame: storeys, totals per class and storey,
        openings, spaces; ``warn`` hears of each opening that cuts nothing."""
        from castor.csg.elements import cuts_nothing

        totals: dict[tuple[str, str], list] = {}
        for p in self.placed():
            total = totals.setdefault((p.element.ifc_class, p.storey), [0, 0.0, 0.0])
            total[0] += 1
            total[1] += p.figures.volume
            total[2] += p.figures.area
        order = {name: k for k, (name, _) in enumerate(self.storeys())}
        classes = [{"class": c, "storey": s, "count": n, "volume": _number(v), "area": _number(a)}
                   for (c, s), (n, v, a) in sorted(totals.items(),
                                                   key=lambda i: (order[i[0][1]], i[0][0]))]
        openings = []
        blocks = self.blocks()
        for b in blocks:
            openings.append({
                "class": b.opening.classification.ifc_class, "name": b.opening.name,
                "host": b.host.name if b.host is not None else None, "storey": b.storey,
                "width": _number(b.width), "height": _number(b.height), "sill": _number(b.sill),
                "head": _number(b.head), "volume": _number(b.figures.volume),
                **dict(b.opening.classification.settings)})
        for opening in self.idle(blocks):
            warn(cuts_nothing(opening))
        spaces = [{"name": r.name, "object": r.space.name, "storey": r.storey,
                   "floor_area": _number(r.floor_area), "volume": _number(r.volume)}
                  for r in self.rooms()]
        return {"storeys": [{"name": n, "level": _number(level)} for n, level in self.storeys()],
                "classes": classes, "openings": openings, "spaces": spaces}


def _is_floor(element) -> bool:
    c = element.classification
    return c is not None and c.ifc_class == "IfcSlab" and c.predefined == "floor"


def _host(placed: list[Placed], box):
    """The element whose box holds most of the opening's box; of those that
    hold as much, the one whose box is smallest (a wall rather than the house)."""
    best, rank = None, None
    low, high = np.asarray(box[0]), np.asarray(box[1])
    for p in placed:
        a, b = p.figures.bbox
        overlap = float(np.clip(np.minimum(high, b) - np.maximum(low, a), 0, None).prod())
        if overlap <= 0:
            continue
        key = (-round(overlap, 9), float(np.prod(np.subtract(b, a))))
        if rank is None or key < rank:
            best, rank = p.element, key
    return best
