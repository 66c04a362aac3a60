"""What one '>' command produces: the polygons of each object, ready to write."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from castor.csg.paths import Path


class FaceSurfaces:
    """For each face number of a primitive's mesh, the curved surface it is a
    facet of, or -1 (castor.primitives.base.Mesh.surfaces). Equal only to
    itself: one table is shared by every use of one mesh."""

    __slots__ = ("of_face",)

    def __init__(self, of_face: np.ndarray):
        self.of_face = of_face


class Origin(NamedTuple):
    """Where a polygon comes from: the path of its primitive, its colour, the
    primitive's kind, and which of its faces are facets of a curved surface
    (None: every face is flat)."""

    steps: Path
    colour: tuple[float, float, float]
    kind: str = ""
    surfaces: FaceSurfaces | None = None

    @property
    def path(self) -> str:
        return str(self.steps)


@dataclass
class FrameObject:
    """One object of a '>' command: a closed surface of convex polygons."""

    vertices: np.ndarray  # (V, 3) float64, every vertex used
    offsets: np.ndarray  # (P + 1,) start of each polygon in indices
    indices: np.ndarray  # vertex numbers, counter-clockwise seen from outside
    origin_of: np.ndarray  # (P,) index into origins
    origins: list[Origin]
    name: str = ""  # the '>' command's object: its name, or objectK
    # (P,) the curved surface of its primitive each polygon is a facet of, -1
    # for a flat face (castor.mesh.creases); None where not known
    surface_of: np.ndarray | None = None

    @property
    def polygon_count(self) -> int:
        return len(self.offsets) - 1

    def edge_count(self) -> int:
        start = self.indices
        following = np.arange(1, len(start) + 1)
        following[self.offsets[1:] - 1] = self.offsets[:-1]
        a, b = start, start[following]
        return len(np.unique(np.minimum(a, b) * (len(self.vertices) + 1) + np.maximum(a, b)))


@dataclass
class Frame:
    number: int
    where: str  # FILE:LINE of the '>' command
    objects: list[FrameObject] = field(default_factory=list)

    @property
    def polygon_count(self) -> int:
        return sum(o.polygon_count for o in self.objects)


def curved_origins(origin_table) -> np.ndarray:
    """For each entry of ``origin_table``, whether its primitive has curved faces
    (made once per object: a union of 200,000 cubes has as many entries)."""
    return np.array([origin_table[e].surfaces is not None for e in range(len(origin_table))],
                    bool)


def polygon_surfaces(origin_table, curved: np.ndarray, origin_ids: np.ndarray,
                     face_ids: np.ndarray) -> np.ndarray:
    """For polygons of the origins ``origin_ids`` (entries of ``origin_table``,
    ``curved`` where its primitive has curved faces) on their primitive's
    faces ``face_ids`` (the face number in the low 32 bits), the curved
    surface each is a facet of, or -1: looked up per use of a primitive with
    curved faces, none for the others."""
    surfaces = np.full(len(origin_ids), -1, np.int64)
    if not len(origin_ids) or not curved.any():
        return surfaces
    rows = np.flatnonzero(curved[origin_ids])
    if not len(rows):
        return surfaces
    rows = rows[np.argsort(origin_ids[rows], kind="stable")]
    entries = origin_ids[rows]
    bounds = np.flatnonzero(np.diff(entries)) + 1
    for group in np.split(rows, bounds):
        table = origin_table[int(origin_ids[group[0]])].surfaces.of_face
        face = face_ids[group] & 0xFFFFFFFF
        known = face < len(table)
        surfaces[group] = np.where(known, table[np.minimum(face, len(table) - 1)], -1)
    return surfaces


def compact(pieces, origin_table, name: str = "") -> FrameObject:
    """One object from its parts' polygons, each piece (vertices, polygons) or
    (vertices, polygons, their surfaces): vertices and origins compacted to
    those the polygons use."""
    if not pieces:
        return FrameObject(np.zeros((0, 3)), np.zeros(1, np.int64), np.zeros(0, np.int64),
                           np.zeros(0, np.int64), [], name, np.zeros(0, np.int64))
    known = all(len(piece) > 2 for piece in pieces)
    surface_of = np.concatenate([piece[2] for piece in pieces]) if known else None
    pieces = [piece[:2] for piece in pieces]
    if len(pieces) == 1:
        vertices, merged = pieces[0]
        offsets, indices, origin_ids = merged.offsets, merged.indices, merged.origin_ids
    else:
        vertex_base = np.cumsum([0] + [len(v) for v, _ in pieces[:-1]])
        index_base = np.cumsum([0] + [len(m.indices) for _, m in pieces[:-1]])
        vertices = np.concatenate([v for v, _ in pieces])
        indices = np.concatenate([m.indices + b for (_, m), b in zip(pieces, vertex_base)])
        offsets = np.concatenate([np.zeros(1, np.int64)]
                                 + [m.offsets[1:] + b for (_, m), b in zip(pieces, index_base)])
        origin_ids = np.concatenate([m.origin_ids for _, m in pieces])
    used = np.zeros(len(vertices), bool)
    used[indices] = True
    if not used.all():  # vertices left inside merged polygons
        renumber = np.cumsum(used) - 1
        indices = renumber[indices]
        vertices = vertices[used]
    ids, origin_of = np.unique(origin_ids, return_inverse=True)
    origins = [origin_table[int(i)] for i in ids]
    return FrameObject(np.ascontiguousarray(vertices), offsets, indices.astype(np.int64),
                       origin_of.ravel().astype(np.int64), origins, name, surface_of)


def faces_up(solid: FrameObject, cosine: float, decimals: int) -> list[tuple[float, np.ndarray]]:
    """The faces of ``solid`` that look up (their normal's z at least ``cosine`` of
    its length), by height rounded to ``decimals`` places, from the lowest:
    (height, the plan points of their triangles). A stair's treads, for its IFC
    properties (castor.bim.measures) and its plan symbol (castor.drawings.classes)."""
    from castor.mesh.arrays import fan_triangles

    if solid.polygon_count == 0:
        return []
    tris, _ = fan_triangles(solid.offsets, solid.indices)
    corners = solid.vertices[tris]
    normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    length = np.linalg.norm(normal, axis=1)
    up = (length > 1e-12) & (normal[:, 2] > cosine * np.maximum(length, 1e-300))
    heights = np.round(corners[up, 0, 2], decimals)
    return [(float(h), corners[up][heights == h][:, :, :2].reshape(-1, 2))
            for h in np.unique(heights)]
