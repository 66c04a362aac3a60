"""Base quantities as buildingSMART's quantity sets name them (Qto_WallBaseQuantities
…), each only where castor's solids give it exactly; the volume and area of the
other elements in ``Castor_Quantities``.

A quantity that depends on what a wall or slab *is* (its length, its
thickness) is written only when the solid is that shape: a wall's Length and
Width when its plan's smallest rectangle times its height is its gross volume
(a straight wall of one thickness), a slab's Width when every vertex is on its
bottom or its top (a flat slab). A ring of four walls as one element gets its
volumes and height, not a length that no one could check.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from castor.mesh.frame import FrameObject


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
    from castor.quantities import footprint

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
    z = solid.vertices[:, 2]
    found = [Quantity("NetArea", "area", facing_area(solid, (0.0, 0.0, 1.0))),
             *_volumes(figures.volume, voids)]
    if np.all((np.abs(z - bottom) <= 1e-9) | (np.abs(z - top) <= 1e-9)):
        found.insert(0, Quantity("Width", "length", top - bottom))
    return tuple(found)


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
    elif ifc_class in ("IfcDoor", "IfcWindow"):
        if size is None:  # not in an opening: its own box
            from castor.quantities import footprint

            (_, _, bottom), (_, _, top) = figures.bbox
            size = (footprint(solid.vertices)[0], top - bottom)
        quantities = filler(*size)
    else:
        quantities = _volumes(figures.volume, voids)
    return (QuantitySet(name, quantities),)
