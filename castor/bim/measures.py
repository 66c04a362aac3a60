"""Base quantities as buildingSMART's quantity sets name them (Qto_WallBaseQuantities
…), each only where castor's solids give it exactly; the volume and area of the
other elements (and of roofs) in ``Castor_Quantities``; a stair's risers and
treads, as its common property set has them, where exact.

A quantity that depends on what a wall or slab *is* (its length, its
thickness) is written only when the solid is that shape: a wall's Length and
Width when its plan's smallest rectangle times its height is its gross volume
(a straight wall of one thickness), a slab's Width when its faces are its top,
its bottom and upright sides (a flat slab). A ring of four walls as one
element gets its volumes and height, not a length that no one could check.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from castor.mesh.frame import FrameObject, faces_up


class Quantity(NamedTuple):
    name: str
    kind: str  # "length", "area", "volume"
    value: float


class QuantitySet(NamedTuple):
    name: str  # Qto_WallBaseQuantities, Castor_Quantities
    quantities: tuple[Quantity, ...]


CASTOR = "Castor_Quantities"

# the base quantity set of each class that castor fills (the rest: CASTOR)
BASE_SETS = {
    "IfcWall": "Qto_WallBaseQuantities",
    "IfcSlab": "Qto_SlabBaseQuantities",
    "IfcDoor": "Qto_DoorBaseQuantities",
    "IfcWindow": "Qto_WindowBaseQuantities",
    "IfcSpace": "Qto_SpaceBaseQuantities",
    "IfcColumn": "Qto_ColumnBaseQuantities",
    "IfcBeam": "Qto_BeamBaseQuantities",
    "IfcMember": "Qto_MemberBaseQuantities",
    "IfcPlate": "Qto_PlateBaseQuantities",
    "IfcFooting": "Qto_FootingBaseQuantities",
    "IfcRoof": "Qto_RoofBaseQuantities",
    "IfcStairFlight": "Qto_StairFlightBaseQuantities",
}

EXACT = 1e-9  # relative: a solid is "a box" when its volume says so to this


def polygon_areas(solid: FrameObject) -> tuple[np.ndarray, np.ndarray]:
    """Each polygon's area and unit normal (convex polygons: a fan's sum)."""
    from castor.mesh.arrays import fan_triangles

    tris, polygon = fan_triangles(solid.offsets, solid.indices)
    corners = solid.vertices[tris]
    cross = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    summed = np.zeros((solid.polygon_count, 3))
    np.add.at(summed, polygon, cross)
    length = np.linalg.norm(summed, axis=1)
    normals = summed / np.where(length > 0, length, 1.0)[:, None]
    return length / 2, normals


def facing_area(solid: FrameObject, direction) -> float:
    """The area of the faces that face exactly ``direction`` (a unit vector)."""
    if solid.polygon_count == 0:
        return 0.0
    areas, normals = polygon_areas(solid)
    return float(areas[normals @ np.asarray(direction, float) > 1 - 1e-9].sum())


def _volumes(volume: float, voids: float) -> tuple[Quantity, ...]:
    return (Quantity("GrossVolume", "volume", volume + voids),
            Quantity("NetVolume", "volume", volume))


def wall(solid: FrameObject, figures, voids: float) -> tuple[Quantity, ...]:
    """Height, volumes; Length, Width and NetSideArea when the wall is straight
    and of one thickness (``voids``: the volume its openings took)."""
    from castor.bim.solids import footprint

    (_, _, bottom), (_, _, top) = figures.bbox
    height = top - bottom
    found = [Quantity("Height", "length", height), *_volumes(figures.volume, voids)]
    length, width, (dx, dy) = footprint(solid.vertices)
    gross = figures.volume + voids
    if gross > 0 and abs(length * width * height - gross) <= EXACT * gross:
        side = facing_area(solid, (-dy, dx, 0.0))  # one side: across the length
        found = [Quantity("Length", "length", length), Quantity("Width", "length", width),
                 *found, Quantity("NetSideArea", "area", side)]
    return tuple(found)


def slab(solid: FrameObject, figures, voids: float) -> tuple[Quantity, ...]:
    """NetArea (its upper faces), volumes; Width (its thickness) when flat."""
    (_, _, bottom), (_, _, top) = figures.bbox
    found = [Quantity("NetArea", "area", facing_area(solid, (0.0, 0.0, 1.0))),
             *_volumes(figures.volume, voids)]
    if flat(solid, bottom, top):
        found.insert(0, Quantity("Width", "length", top - bottom))
    return tuple(found)


def flat(solid: FrameObject, bottom: float, top: float) -> bool:
    """Whether the solid is ``top - bottom`` thick wherever it is: its faces
    that look up all on its top, those that look down all on its bottom, the
    others upright (a vertical line through it then meets it at its bottom
    and its top only). A face of no area to speak of (the sliver a difference
    leaves where two planes are a rounding apart) has no direction to count."""
    if solid.polygon_count == 0:
        return False
    areas, normals = polygon_areas(solid)
    counted = areas > EXACT * areas.sum()
    up, down = normals[:, 2] > 1 - 1e-9, normals[:, 2] < -1 + 1e-9
    if np.any(counted & ~up & ~down & (np.abs(normals[:, 2]) > 1e-9)):
        return False
    z = solid.vertices[solid.indices, 2]
    polygon = np.repeat(np.arange(solid.polygon_count), np.diff(solid.offsets))
    off = (counted & up)[polygon] & (np.abs(z - top) > 1e-9)
    off |= (counted & down)[polygon] & (np.abs(z - bottom) > 1e-9)
    return not off.any()


def roof(solid: FrameObject, voids: float) -> tuple[Quantity, ...]:
    """NetArea: its outer surface, the faces that look up (a pitched roof's
    slopes, a flat roof's top); GrossArea (the same) and ProjectedArea (their
    plan) when no opening cut it, the area an opening took from a slope not
    being known exactly."""
    if solid.polygon_count == 0:
        return ()
    areas, normals = polygon_areas(solid)
    up = normals[:, 2] > 1e-9
    net = float(areas[up].sum())
    if voids > 0:
        return (Quantity("NetArea", "area", net),)
    return (Quantity("GrossArea", "area", net), Quantity("NetArea", "area", net),
            Quantity("ProjectedArea", "area", float((areas * normals[:, 2])[up].sum())))


class Property(NamedTuple):
    """A property of an element's common set besides its Reference."""

    name: str  # as Pset_StairCommon names it: NumberOfRiser
    type: str  # its IFC measure: IfcCountMeasure, IfcPositiveLengthMeasure
    value: float | int


def treads(solid: FrameObject) -> list[tuple[float, np.ndarray]]:
    """A stair's treads: (height, plan points of the faces that look up there),
    from the lowest, above its bottom."""
    found = faces_up(solid, 1 - 1e-9, 9)
    if not found:
        return []
    bottom = float(solid.vertices[:, 2].min())
    return [(h, points) for h, points in found if h > bottom + 1e-9]


def _equal(values: np.ndarray, scale: float) -> float | None:
    """The value of ``values`` when they are all one (to 1e-9 of ``scale``)."""
    if len(values) == 0 or np.ptp(values) > 1e-9 * max(1.0, scale):
        return None
    return float(values.mean())


def stair(solid: FrameObject) -> tuple[Property, ...]:
    """A stair's or flight's risers and treads, as its common property set has
    them, each where the solid gives it exactly: one tread per level of faces
    that look up above its bottom (the top step's included), one riser below
    each; RiserHeight when every rise is the same; TreadLength (nosing to
    nosing, along the line from the lowest tread to the highest) when every
    going is the same."""
    found = treads(solid)
    if not found:
        return ()
    bottom = float(solid.vertices[:, 2].min())
    levels = np.array([bottom] + [h for h, _ in found])
    out = [Property("NumberOfRiser", "IfcCountMeasure", len(found)),
           Property("NumberOfTreads", "IfcCountMeasure", len(found))]
    rise = _equal(np.diff(levels), float(levels[-1]))
    if rise is not None:
        out.append(Property("RiserHeight", "IfcPositiveLengthMeasure", rise))
    if len(found) >= 2:
        middle = [(pts.min(axis=0) + pts.max(axis=0)) / 2 for _, pts in found]
        up = middle[-1] - middle[0]
        if np.linalg.norm(up) > 1e-9:
            up = up / np.linalg.norm(up)
            nosings = np.array([float((pts @ up).min()) for _, pts in found])
            going = _equal(np.diff(nosings), float(np.abs(nosings).max()))
            if going is not None and going > 0:
                out.append(Property("TreadLength", "IfcPositiveLengthMeasure", going))
    return tuple(out)


def common_properties(ifc_class: str, solid: FrameObject) -> tuple[Property, ...]:
    """What an element's common property set holds besides its Reference."""
    if ifc_class in ("IfcStair", "IfcStairFlight"):
        return stair(solid)
    return ()


def filler(width: float, height: float) -> tuple[Quantity, ...]:
    """A door's or window's: its opening's width and height, and their area."""
    return (Quantity("Width", "length", width), Quantity("Height", "length", height),
            Quantity("Area", "area", width * height))


def space(floor_area: float, volume: float, height: float) -> tuple[Quantity, ...]:
    return (Quantity("Height", "length", height), Quantity("NetFloorArea", "area", floor_area),
            Quantity("NetVolume", "volume", volume))


def castor(figures) -> QuantitySet:
    """Volume and area as --summary gives them."""
    return QuantitySet(CASTOR, (Quantity("Volume", "volume", max(figures.volume, 0.0)),
                                Quantity("SurfaceArea", "area", figures.area)))


def element_sets(ifc_class: str, solid: FrameObject, figures, voids: float = 0.0,
                 size: tuple[float, float] | None = None) -> tuple[QuantitySet, ...]:
    """The quantity sets of an element of ``ifc_class``."""
    name = BASE_SETS.get(ifc_class)
    if name is None or figures.bbox is None:
        return (castor(figures),)
    if ifc_class == "IfcWall":
        quantities = wall(solid, figures, voids)
    elif ifc_class == "IfcSlab":
        quantities = slab(solid, figures, voids)
    elif ifc_class == "IfcRoof":
        quantities = roof(solid, voids)
        return ((QuantitySet(name, quantities),) if quantities else ()) + (castor(figures),)
    elif ifc_class in ("IfcDoor", "IfcWindow"):
        if size is None:  # not in an opening: its own box
            from castor.bim.solids import footprint

            (_, _, bottom), (_, _, top) = figures.bbox
            size = (footprint(solid.vertices)[0], top - bottom)
        quantities = filler(*size)
    else:
        quantities = _volumes(figures.volume, voids)
    return (QuantitySet(name, quantities),)
