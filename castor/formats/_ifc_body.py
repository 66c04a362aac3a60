"""An element's body in IFC4: one closed ``IfcPolygonalFaceSet`` of castor's
polygons, coloured per face by an ``IfcIndexedColourMap`` and styled in its
largest colour for the readers that ignore colour maps (castor.formats.ifc).

A face is one ``IfcIndexedPolygonalFace`` (IFC4 has no bulk form for polygons,
only for triangles), made through the two calls ``create_entity`` ends in; its
vertices are turned so that the first three make a true corner.
"""

from __future__ import annotations

import numpy as np


class Styles:
    """One ``IfcSurfaceStyle`` per colour of the file, named as the mesh formats
    name their materials (``names``: {colour: name}, castor.bim.model's
    colour_names; a colour they lack by its values), both sides shaded so
    that a section box shows cut faces coloured. ``table``: the materials the
    elements' polygons are numbered into."""

    def __init__(self, f, table, create, names: dict | None = None):
        self.f, self.table, self.made, self.create = f, table, {}, create
        self.names = names or {}
        self.bodies: dict = {}  # (id of indices, of offsets) -> polygons (_polygons)

    def __call__(self, m: int):
        colour = tuple(float(c) for c in self.table[m].colour)
        if colour not in self.made:
            from castor.formats._mesh import colour_name

            create = self.create
            shading = create("IfcSurfaceStyleShading", create("IfcColourRgb", None, *colour), 0.0)
            name = self.names.get(colour) or colour_name(colour)
            self.made[colour] = create("IfcSurfaceStyle", name, "BOTH", [shading])
        return self.made[colour]


def face_set(f, solid, shift: float, material: np.ndarray | None = None, styles=None):
    """The solid's polygons as one closed face set (its vertices moved down by
    ``shift``, the storey's level); with ``material`` (each polygon's, into
    ``styles``' table) coloured per face and styled in the colour of the
    largest area."""
    create = styles.create if styles is not None else f.create_entity
    (rows, order), areas, kept = _polygons(solid, styles)
    vertices = solid.vertices if kept is None else solid.vertices[kept]
    coordinates = create("IfcCartesianPointList3D",
                         (vertices - np.array([0.0, 0.0, shift])).tolist())
    make = face_maker(f)
    faces = [None] * len(rows)
    for place in order:
        faces[place] = make(rows[place])
    item = create("IfcPolygonalFaceSet", coordinates, True, faces, None)
    if material is None:
        return item
    used, index = np.unique(material, return_inverse=True)
    areas = np.bincount(index, weights=areas(), minlength=len(used))
    colours = create("IfcColourRgbList", [list(map(float, styles.table[m].colour))
                                          for m in used.tolist()])
    create("IfcIndexedColourMap", item, None, colours, (index + 1).tolist())
    create("IfcStyledItem", item, [styles(int(used[int(np.argmax(areas))]))], None)
    return item


def _polygons(solid, styles) -> tuple[list, object, np.ndarray | None]:
    """Each polygon's vertex numbers from 1 (true corner first) among the
    vertices kept (``without_straight_points``: the third, None for all), and
    a function giving each polygon's area: the same as the last solid's when
    this one is it translated, sharing its polygons (castor.quantities moves
    one solid to each copy of a shared subtree: 1,024 houses' walls are
    measured once; ``styles`` keeps them for the file)."""
    from castor.bim.measures import polygon_areas
    from castor.mesh.merge import _translated

    known = getattr(styles, "bodies", {})
    key = (id(solid.indices), id(solid.offsets))
    last = known.get(key)
    if last is not None and _translated(last[2], solid.vertices):
        return last[3], last[4], last[5]
    offsets, indices, kept = without_straight_points(solid.vertices, solid.offsets,
                                                     solid.indices)
    vertices = solid.vertices if kept is None else solid.vertices[kept]
    ones = true_corner_first(vertices, offsets, indices) + 1  # from 1
    rows = _rows(ones, offsets)
    found: list = []

    def areas():
        if not found:
            found.append(polygon_areas(solid)[0])
        return found[0]
    if styles is not None:  # (the arrays kept: their ids stay theirs)
        known[key] = (solid.indices, solid.offsets, solid.vertices, rows, areas, kept)
    return rows, areas, kept


def without_straight_points(vertices: np.ndarray, offsets: np.ndarray, indices: np.ndarray):
    """The polygons without the points that are a corner of none of them: a
    point in the middle of an edge in every polygon around it (where the
    engine met a plane a rounding away, a point on a slab's upright edge
    between its top and its bottom), taken out of each, which keeps every
    edge used once each way; none that would leave a polygon fewer than
    three corners. (offsets, indices, kept): the vertices still used, numbered
    among themselves, ``kept`` None when none is taken out."""
    if len(indices) == 0:
        return offsets, indices, None
    from castor.formats._mesh import corner_turns

    _, turn, lengths = corner_turns(vertices, offsets, indices)
    straight = turn <= 1e-9 * lengths
    count = len(vertices)
    gone = np.bincount(indices, weights=straight, minlength=count) == np.bincount(
        indices, minlength=count)
    if not gone[indices].any():
        return offsets, indices, None
    sizes = np.diff(offsets)
    polygon = np.repeat(np.arange(len(sizes)), sizes)
    left = sizes - np.bincount(polygon, weights=gone[indices], minlength=len(sizes))
    if np.any(left < 3):  # (a polygon of no area: its points stay)
        gone[indices[(left < 3)[polygon]]] = False
        if not gone[indices].any():
            return offsets, indices, None
    keep = ~gone[indices]
    new_offsets = np.zeros(len(offsets), offsets.dtype)
    np.cumsum(np.bincount(polygon[keep], minlength=len(sizes)), out=new_offsets[1:])
    number = np.cumsum(~gone) - 1
    return new_offsets, number[indices[keep]].astype(indices.dtype), ~gone


def true_corner_first(vertices: np.ndarray, offsets: np.ndarray,
                      indices: np.ndarray) -> np.ndarray:
    """The polygons' vertex numbers, each polygon turned (same vertices, same
    order) so that its first three vertices make a true corner.

    A castor polygon may have a straight corner, a vertex in the middle of an
    edge that a neighbour ends at. A reader that takes a face's plane from its
    first three vertices (a common shortcut) finds one this way."""
    if len(indices) == 0:
        return indices
    from castor.formats._mesh import corner_turns

    sizes = np.diff(offsets)
    starts = offsets[:-1]
    following, turn, lengths = corner_turns(vertices, offsets, indices)
    true = turn > 1e-9 * lengths
    position = np.arange(len(indices))
    ready = true[following[starts]]  # the second vertex is a true corner already
    if ready.all():
        return indices
    # the first true corner of each polygon (its second vertex if none is)
    first = np.minimum.reduceat(np.where(true, position, len(indices)), starts)
    first = np.where((first < offsets[1:]) & ~ready, first, starts + 1)
    shift = np.repeat((first - starts - 1) % sizes, sizes)
    local = position - np.repeat(starts, sizes)
    return indices[np.repeat(starts, sizes) + (local + shift) % np.repeat(sizes, sizes)]


def _rows(ones: np.ndarray, offsets: np.ndarray) -> tuple[list, list]:
    """Each polygon's vertex numbers as a list, and the order the faces are made
    in (by size, as the lists are cut): one array cut a size at a time, so
    that Python makes no slice per polygon."""
    sizes = np.diff(offsets)
    rows, order = [None] * len(sizes), []
    for size in np.unique(sizes).tolist():
        which = np.flatnonzero(sizes == size)
        starts = offsets[which]
        places = which.tolist()
        order.extend(places)
        for place, row in zip(places, ones[starts[:, None] + np.arange(size)].tolist()):
            rows[place] = row
    return rows, order


def face_maker(f):
    """A function from a polygon's vertex numbers to a new IfcIndexedPolygonalFace."""
    make = entity_maker(f)  # (looked up here: a test swaps it for create_entity)
    quick = getattr(make, "create", None)
    if quick is None:
        return lambda row: make("IfcIndexedPolygonalFace", row)

    def face(row):
        entity = quick("IfcIndexedPolygonalFace", -1)
        entity.set_attribute_value_py(0, row)
        return entity
    return face


def entity_maker(f):
    """``f.create_entity``, made quicker: ``make(cls, *args, **named)``.

    ``create_entity`` spends most of its time in Python (argument checks, the
    undo journal, an attribute's index looked up by name at each call); here
    an entity is made through the two calls it ends in (the same entity, the
    same file), each attribute's index looked up once per class, and an
    attribute left unset (``$``) rather than set to None: about three times as
    fast. Where an ifcopenshell lacks those calls, or records an undo journal,
    ``create_entity`` itself is used."""
    import ifcopenshell

    create = getattr(f, "create", None)
    if (create is None or getattr(f, "transaction", None) is not None
            or not hasattr(ifcopenshell.entity_instance, "set_attribute_value_py")):
        return f.create_entity
    indices: dict[tuple[str, str], int] = {}

    def make(cls, *args, **named):
        entity = create(cls, -1)
        for index, value in enumerate(args):
            if value is not None:
                entity.set_attribute_value_py(index, value)
        for name, value in named.items():
            index = indices.get((cls, name))
            if index is None:
                index = indices[(cls, name)] = entity.get_argument_index(name)
            if value is not None:
                entity.set_attribute_value_py(index, value)
        return entity
    make.create = create  # (face_maker's: one attribute, by its index)
    return make
