"""Instancing: a primitive's template built once in the engine, and its uses
as placed copies that enter the engine only when a boolean needs them.

A template keeps its triangles as arrays, so a copy that meets nothing is
written from them directly (a forest of 400 trees holds one mesh per kind of
primitive); a copy's transformation is deferred, held as a 3x4 matrix, and
composed with every transformation above it without touching the engine.
"""

from __future__ import annotations

import numpy as np

from castor.mesh import adapter
from castor.mesh.arrays import largest_of_each
from castor.mesh.caches import PROCESS
from castor.mesh.primitives import Mesh


def template(mesh: Mesh) -> "Template":
    """A primitive's mesh in the engine, built once and instanced many times;
    adapter.EngineError if the engine refuses it."""
    return Template(adapter.from_mesh(mesh.vertices, mesh.triangles, mesh.faces))


class Template:
    """A primitive's shape in the engine, built once, with its own triangles
    kept as arrays: a copy placed somewhere is written from them directly."""

    __slots__ = ("manifold", "id", "vertices", "triangles", "face_ids", "turned", "box", "_planes",
                 "__weakref__")

    def __init__(self, manifold: adapter.Manifold):
        self.manifold = manifold
        mesh = adapter.to_arrays(manifold)
        # every copy enters the engine as this manifold moved, under its ID
        # (that of its run: original_id() says -1 for a manifold built from a mesh)
        self.id = int(mesh.run_ids[0])
        self.vertices = np.array(mesh.vertices, dtype=np.float64)
        self.triangles = mesh.triangles
        self.face_ids = mesh.face_ids
        self.turned = self.triangles[:, ::-1].copy()  # for mirrored copies
        self.box = (self.vertices.min(axis=0), self.vertices.max(axis=0))
        self._planes = None
        PROCESS.engine_ids[self.id] = self

    @property
    def planes(self) -> np.ndarray:
        """(faces, 4): each flat face's unit normal and offset (made when first asked for)."""
        if self._planes is None:
            self._planes = _face_planes(self.vertices, self.triangles, self.face_ids)
        return self._planes

    def num_tri(self) -> int:
        return len(self.triangles)


def _face_planes(vertices, triangles, face_ids) -> np.ndarray:
    """(faces, 4): each flat face's unit normal and offset, from its largest triangle."""
    p = vertices[triangles]
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    area = np.linalg.norm(n, axis=1)
    first = largest_of_each(area, face_ids)
    faces = np.flatnonzero(first >= 0)
    first = first[faces]
    planes = np.zeros((int(face_ids.max()) + 1, 4))
    unit = n[first] / np.maximum(area[first], 1e-300)[:, None]
    planes[faces, :3] = unit
    planes[faces, 3] = np.einsum("ij,ij->i", unit, p[first].mean(axis=1))
    return planes


def moved_planes(planes: np.ndarray, placement: np.ndarray):
    """Planes (P, 4: unit normal, offset) of a template where ``placement``
    (3x4) puts them: the normal goes by the inverse transpose. Raises
    LinAlgError for a flat placement. Returns unit normals, offsets, and
    which planes had a normal (a face number no triangle has gives none)."""
    m = planes[:, :3] @ np.linalg.inv(placement[:, :3])  # rows: A^-T n
    length = np.linalg.norm(m, axis=1)
    has = length > 0
    safe = np.where(has, length, 1.0)
    return m / safe[:, None], (planes[:, 3] + m @ placement[:, 3]) / safe, has


class Placed:
    """One use of a primitive: its template and where it stands, not yet in
    the engine. A copy costs a few hundred bytes, not the engine's mesh; it
    goes to the engine (the template moved) only when a boolean needs it,
    so that a union of 200,000 cubes that do not meet, or a forest, holds one
    mesh per kind of primitive. A use that stands exactly where another use
    of its template stands, in one boolean, has a copy of its own with an ID
    of its own (``distinguished``), or the two could not be told apart."""

    __slots__ = ("template", "matrix", "own", "_box")

    def __init__(self, template: Template, matrix: np.ndarray, own=None):
        self.template = template
        self.matrix = matrix  # (3, 4)
        self.own = own  # None, or (the engine's copy of the template, its ID)
        self._box = None

    @property
    def id(self) -> int:
        return self.template.id if self.own is None else self.own[1]

    def num_tri(self) -> int:
        return len(self.template.triangles)

    def is_empty(self) -> bool:
        return False

    def vertices(self) -> np.ndarray:
        m = self.matrix
        return self.template.vertices @ m[:, :3].T + m[:, 3]

    def bounding_box(self) -> tuple:
        if self._box is None:
            linear = self.matrix[:, :3]
            if np.count_nonzero(linear - np.diag(np.diagonal(linear))) == 0:
                # moved and scaled along the axes: the template's box, moved
                low, high = self.template.box
                corners = np.array([low, high]) * np.diagonal(linear) + self.matrix[:, 3]
                self._box = (*corners.min(axis=0).tolist(), *corners.max(axis=0).tolist())
            else:
                v = self.vertices()
                self._box = (*v.min(axis=0).tolist(), *v.max(axis=0).tolist())
        return self._box

    def moved(self, matrix: np.ndarray) -> "Placed":
        m = matrix[:3, :3] @ self.matrix
        m[:, 3] += matrix[:3, 3]
        return Placed(self.template, m, self.own)

    def in_engine(self) -> adapter.Manifold:
        """The engine's copy: the template moved (its runs keep the template's
        ID, or this use's own, with this matrix as their transformation)."""
        manifold = self.template.manifold if self.own is None else self.own[0]
        return adapter.transform(manifold, np.ascontiguousarray(self.matrix))

    def distinguished(self) -> "Placed":
        """The same use with a copy of the template of its own, under a new ID
        and with the template's face numbers (the engine's ``as_original``
        numbers the faces afresh: the checks then found the copy's triangles
        off the planes of the faces they named, and computed its booleans
        another, worse, way)."""
        id = adapter.reserve_ids(1)
        copy = adapter.with_run_ids(self.template.manifold, np.array([id], np.int64))
        if copy is None:  # (the engine keeps a primitive's mesh as it is given)
            copy, id = adapter.as_original(self.template.manifold)
        PROCESS.engine_ids[id] = self.template
        return Placed(self.template, self.matrix, (copy, id))


def in_engine(part) -> adapter.Manifold:
    """A part as the engine's manifold (a composition made now)."""
    return part.in_engine() if type(part) is Placed else adapter.engine(part)


def fill_boxes(parts) -> None:
    """The boxes of many placed copies at once (one array operation for the
    copies of each template, not a small one for each)."""
    waiting: dict[int, list] = {}
    for part in parts:
        if type(part) is Placed and part._box is None:
            waiting.setdefault(id(part.template), []).append(part)
    for group in waiting.values():
        if len(group) < 8:
            continue  # one at a time is as quick
        corners = group[0].template.vertices
        step = max(1, 4_000_000 // max(1, len(corners)))
        for k in range(0, len(group), step):
            chunk = group[k:k + step]
            m = np.stack([part.matrix for part in chunk])
            points = np.einsum("nij,kj->nki", m[:, :, :3], corners) + m[:, None, :, 3]
            low, high = points.min(axis=1).tolist(), points.max(axis=1).tolist()
            for part, lo, hi in zip(chunk, low, high):
                part._box = (*lo, *hi)
