"""The boolean engine, manifold3d, behind one small adapter.

A ``Solid`` is a manifold plus the table of its origins. manifold3d gives
every primitive's mesh an ID and records, for each run of output triangles,
the ID of the mesh it came from and the transformation that placed it there;
castor maps that pair to the use of the primitive, its path and colour. That
is how colours and paths survive any depth of booleans without guessing by
geometry, and why an object used many times is the engine's one solid moved,
never a copy rebuilt from its mesh (which the engine may rebuild differently).
Everything that touches manifold3d is in this file.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass
from typing import NamedTuple

import manifold3d
import numpy as np

from castor.mesh import polygons
from castor.mesh.frame import Origin
from castor.mesh.primitives import Mesh

_Add = manifold3d.OpType.Add
_Intersect = manifold3d.OpType.Intersect


class Template:
    """A primitive's shape in the engine, built once, with its own triangles
    kept as arrays: a copy placed somewhere is written from them directly."""

    __slots__ = ("manifold", "id", "vertices", "triangles", "face_ids", "turned", "box", "_planes",
                 "__weakref__")

    def __init__(self, manifold: manifold3d.Manifold):
        self.manifold = manifold
        gl = manifold.to_mesh64()
        # every copy enters the engine as this manifold moved, under its ID
        # (that of its run: original_id() says -1 for a manifold built from a mesh)
        self.id = int(np.asarray(gl.run_original_id)[0])
        self.vertices = np.array(np.asarray(gl.vert_properties)[:, :3], dtype=np.float64)
        self.triangles = np.asarray(gl.tri_verts, dtype=np.int64)
        self.face_ids = np.asarray(gl.face_id, dtype=np.int64) & 0xFFFFFFFF
        self.turned = self.triangles[:, ::-1].copy()  # for mirrored copies
        self.box = (self.vertices.min(axis=0), self.vertices.max(axis=0))
        self._planes = None
        _TEMPLATES[self.id] = self

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
    first = polygons.largest_of_each(area, face_ids)
    faces = np.flatnonzero(first >= 0)
    first = first[faces]
    planes = np.zeros((int(face_ids.max()) + 1, 4))
    unit = n[first] / np.maximum(area[first], 1e-300)[:, None]
    planes[faces, :3] = unit
    planes[faces, 3] = np.einsum("ij,ij->i", unit, p[first].mean(axis=1))
    return planes


def _moved_planes(planes: np.ndarray, placement: np.ndarray):
    """Planes (P, 4: unit normal, offset) of a template where ``placement``
    (3x4) puts them: the normal goes by the inverse transpose. Raises
    LinAlgError for a flat placement. Returns unit normals, offsets, and
    which planes had a normal (a face number no triangle has gives none)."""
    m = planes[:, :3] @ np.linalg.inv(placement[:, :3])  # rows: A^-T n
    length = np.linalg.norm(m, axis=1)
    has = length > 0
    safe = np.where(has, length, 1.0)
    return m / safe[:, None], (planes[:, 3] + m @ placement[:, 3]) / safe, has


# Results larger than this are not checked (off_faces): the check costs a
# quarter of a boolean, and large results are mostly of curved primitives,
# whose faces seldom coincide exactly.
CHECKED_TRIANGLES = 200_000

# the templates by their engine ID, for the check of a boolean's result
_TEMPLATES: "weakref.WeakValueDictionary[int, Template]" = weakref.WeakValueDictionary()


def off_faces(manifold: manifold3d.Manifold) -> int:
    """How many of a result's triangles have a corner off the plane of the
    primitive's face it comes from (beyond rounding): none, in a right result.

    The engine's union of solids whose faces coincide exactly was seen to go
    wrong (tests/test_regularize.py): a few vertices moved off their faces
    and volume lost. The engine reports each run's template and placement,
    so each triangle's plane is known without trusting its vertices."""
    if manifold.is_empty() or manifold.num_tri() > CHECKED_TRIANGLES:
        return 0
    gl = manifold.to_mesh64()
    vertices = np.asarray(gl.vert_properties, dtype=np.float64)[:, :3]
    tris = np.asarray(gl.tri_verts, dtype=np.int64)
    faces = np.asarray(gl.face_id, dtype=np.int64) & 0xFFFFFFFF
    run_index = np.asarray(gl.run_index, dtype=np.int64) // 3
    run_ids = np.asarray(gl.run_original_id, dtype=np.int64)
    placements = np.asarray(gl.run_transform, dtype=np.float64).transpose(0, 2, 1)
    tolerance = 1e-9 * max(1.0, float(np.abs(vertices).max()))
    bad = 0
    for r in range(len(run_ids)):
        template = _TEMPLATES.get(int(run_ids[r]))
        if template is None:
            continue
        low, high = run_index[r], run_index[r + 1]
        if high == low:
            continue
        try:
            normal, offset, _ = _moved_planes(
                template.planes[np.minimum(faces[low:high], len(template.planes) - 1)],
                placements[r])
        except np.linalg.LinAlgError:
            continue
        corners = vertices[tris[low:high]]
        distance = np.abs(np.einsum("tkj,tj->tk", corners, normal) - offset[:, None])
        bad += int(np.count_nonzero(distance.max(axis=1) > tolerance))
    return bad


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

    def in_engine(self) -> manifold3d.Manifold:
        """The engine's copy: the template moved (its runs keep the template's
        ID, or this use's own, with this matrix as their transformation)."""
        manifold = self.template.manifold if self.own is None else self.own[0]
        return manifold.transform(np.ascontiguousarray(self.matrix))

    def distinguished(self) -> "Placed":
        """The same use with a copy of the template of its own, under a new ID."""
        copy = self.template.manifold.as_original()
        id = copy.original_id()
        _TEMPLATES[id] = self.template
        return Placed(self.template, self.matrix, (copy, id))


class Origins:
    """Where a solid's triangles come from: one entry per use of a primitive,
    the engine's ID of its template, the matrix that places that template in
    the solid, and its Origin (path and colour).

    The engine reports each run of a result's triangles with the same pair
    (its ID and its accumulated transformation), so ``find`` names the use of
    every run. Two uses at one place give the same triangles, and either name
    is true of them."""

    __slots__ = ("_ids", "_matrices", "table", "_index", "_one")

    def __init__(self, ids: np.ndarray | None, matrices: np.ndarray | None, table: tuple,
                 one: tuple | None = None):
        self._ids = ids  # (E,) int64
        self._matrices = matrices  # (E, 3, 4)
        self.table = table  # E Origins
        self._index = None  # for find: sorted keys, and sorted IDs, made once
        self._one = one  # (ID, matrix) of a single entry whose arrays are not made yet

    @property
    def ids(self) -> np.ndarray:
        if self._ids is None:
            self._ids = np.full(1, self._one[0], np.int64)
        return self._ids

    @property
    def matrices(self) -> np.ndarray:
        if self._matrices is None:
            self._matrices = self._one[1][None]
        return self._matrices

    @staticmethod
    def one(id: int, matrix: np.ndarray, origin: Origin) -> "Origins":
        """One entry (its arrays made when first asked for: a union of 200,000
        primitives gathers theirs in one operation)."""
        return Origins(None, None, (origin,), (id, matrix))

    @staticmethod
    def merged(all_origins) -> "Origins":
        all_origins = [o for o in all_origins if len(o.table)]
        if len(all_origins) == 1:
            return all_origins[0]
        if not all_origins:
            return NO_ORIGINS
        if all(o._one is not None and o._ids is None for o in all_origins):
            return Origins(np.array([o._one[0] for o in all_origins], np.int64),
                           np.stack([o._one[1] for o in all_origins]),
                           tuple(o.table[0] for o in all_origins))
        return Origins(np.concatenate([o.ids for o in all_origins]),
                       np.concatenate([o.matrices for o in all_origins]),
                       tuple(t for o in all_origins for t in o.table))

    def __len__(self) -> int:
        return len(self.table)

    def __getitem__(self, entry: int) -> Origin:
        return self.table[entry]

    def prefixed(self, prefix: str) -> "Origins":
        return Origins(self.ids, self.matrices,
                       tuple(Origin(o.steps.under(prefix), o.colour) for o in self.table))

    def transformed(self, matrix: np.ndarray) -> "Origins":
        """The entries of a solid moved by a 3x4 ``matrix``."""
        moved = np.einsum("ij,ejk->eik", matrix[:, :3], self.matrices)
        moved[:, :, 3] += matrix[:, 3]
        return Origins(self.ids, moved, self.table)

    def keys(self) -> set:
        """(ID, placement rounded to 1e-9) of every entry."""
        return {(i, m) for i, m in zip(self.ids.tolist(), map(_place_key, self.matrices))}

    def renamed(self, changes: dict) -> "Origins":
        """The entries whose (ID, rounded placement) is in ``changes``, under the new ID."""
        ids = self.ids.copy()
        for e, (i, m) in enumerate(zip(self.ids.tolist(), self.matrices)):
            new = changes.get((i, _place_key(m)))
            if new is not None:
                ids[e] = new
        return Origins(ids, self.matrices, self.table)

    def find(self, ids: np.ndarray, matrices: np.ndarray) -> np.ndarray:
        """The entry of each run (its engine ID, its (R, 3, 4) placement): the
        entry of that ID whose matrix is nearest (the engine composes
        transformations in its own order, so they agree to rounding).

        Runs and entries are first matched on their ID and placement rounded
        to 10⁻⁶ (one sort, for 200,000 copies of one cube); a run whose
        rounding fell the other way is matched among all entries of its ID."""
        wanted = matrices.reshape(-1, 12)
        flat = self.matrices.reshape(-1, 12)
        if self._index is None:
            entry_keys = _coarse_keys(self.ids, flat)
            order = np.argsort(entry_keys, kind="stable")
            by_id = np.argsort(self.ids, kind="stable")
            self._index = (order, entry_keys[order], by_id, self.ids[by_id])
        order, sorted_keys, by_id, sorted_ids = self._index
        at = np.minimum(np.searchsorted(sorted_keys, _coarse_keys(ids, wanted)), len(order) - 1)
        found = order[at]
        close = (self.ids[found] == ids) & (np.abs(flat[found] - wanted).max(axis=1)
                                            <= 1e-6 * np.maximum(1.0, np.abs(wanted).max(axis=1)))
        rest = np.flatnonzero(~close)
        if len(rest):
            low = np.searchsorted(sorted_ids, ids[rest], "left")
            high = np.searchsorted(sorted_ids, ids[rest], "right")
            if np.any(high == low):
                raise KeyError(f"no origin for the engine's ID {int(ids[rest][high == low][0])}")
            for start in np.unique(low).tolist():
                runs = rest[low == start]
                candidates = by_id[start:high[low == start][0]]
                step = max(1, 4_000_000 // (12 * len(candidates)))
                for k in range(0, len(runs), step):
                    chunk = runs[k:k + step]
                    distance = np.abs(wanted[chunk][:, None, :] - flat[candidates][None]).max(axis=2)
                    found[chunk] = candidates[np.argmin(distance, axis=1)]
        return found


def _coarse_keys(ids: np.ndarray, flat: np.ndarray) -> np.ndarray:
    """One number per (ID, placement rounded to 10⁻⁶)."""
    return polygons.row_hash(np.column_stack([ids, np.round(flat * 1e6)]))


def _place_key(matrix: np.ndarray) -> bytes:
    return np.round(matrix.ravel() * 1e9).tobytes()


def _distinguished(solids: list) -> list:
    """The operands of one boolean, with every use of a primitive that stands
    where a use in an earlier operand stands given an ID of its own (its
    triangles would otherwise be told apart by neither ID nor placement: a
    cube cut away and the same cube added back have different paths and
    colours). Uses inside a result of the engine keep theirs."""
    if len(solids) < 2 or not _may_clash(solids):
        return solids
    keys = [s.origins.keys() for s in solids]
    placed = [{(p.id, _place_key(p.matrix)) for p in s.parts if type(p) is Placed} for s in solids]
    owners: dict = {}
    for k, operand_keys in enumerate(keys):
        for key in operand_keys:
            owners.setdefault(key, []).append(k)
    renew: list[set] = [set() for _ in solids]
    for key, where in owners.items():
        if len(where) < 2:
            continue
        # the use inside a result of the engine keeps the ID (it cannot change);
        # uses not yet in the engine take new ones
        fixed = [k for k in where if key not in placed[k]]
        keep = fixed[0] if fixed else where[0]
        for k in where:
            if k != keep and key in placed[k]:
                renew[k].add(key)
    out = []
    for solid, wanted in zip(solids, renew):
        if wanted:
            parts, changes = [], {}
            for part in solid.parts:
                if type(part) is Placed and (key := (part.id, _place_key(part.matrix))) in wanted:
                    part = part.distinguished()
                    changes[key] = part.id
                parts.append(part)
            solid = Solid(tuple(parts), solid.origins.renamed(changes))
        out.append(solid)
    return out


def _may_clash(solids: list) -> bool:
    """Whether two operands may have a use of one template at one place: one
    number per entry (its ID and rounded placement, hashed), sorted."""
    every = Origins.merged([s.origins for s in solids])
    key = polygons.row_hash(np.column_stack([every.ids,
                                             np.round(every.matrices.reshape(-1, 12) * 1e9)]))
    owner = np.repeat(np.arange(len(solids)), [len(s.origins) for s in solids])
    return polygons.shared_across(key, owner)


NO_ORIGINS = Origins(np.zeros(0, np.int64), np.zeros((0, 3, 4)), ())


@dataclass(frozen=True, slots=True)
class Solid:
    """A solid as parts whose bounding boxes do not meet, and its origins.

    A union of operands that do not meet never goes to the engine and is
    never composed into one mesh: it stays a list of parts, so that a forest
    of copies of one tree, or a union of 100,000 operands, costs no more
    than its parts. The engine sees one part, or the composition of all,
    only when a boolean needs it.
    """

    parts: tuple  # never empty: manifolds, and primitives not yet in the engine (Placed)
    origins: Origins

    @property
    def empty(self) -> bool:
        return not self.parts

    def triangle_count(self) -> int:
        return sum(part.num_tri() for part in self.parts)  # at most MAX_PARTS calls

    def part_boxes(self) -> np.ndarray:
        """(parts, 2, 3): each part's (min xyz, max xyz)."""
        _fill_boxes(self.parts)
        return np.array([part.bounding_box() for part in self.parts],
                        dtype=np.float64).reshape(-1, 2, 3)

    def box(self) -> np.ndarray:
        """(min xyz, max xyz) as a (2, 3) array."""
        if len(self.parts) == 1:
            return np.array(self.parts[0].bounding_box(), dtype=np.float64).reshape(2, 3)
        boxes = self.part_boxes()
        return np.array([boxes[:, 0].min(axis=0), boxes[:, 1].max(axis=0)])

    def whole(self) -> manifold3d.Manifold:
        """All parts as one manifold, for a boolean that needs them together
        (of a solid whose parts are all in the engine: see ``in_engine``)."""
        if len(self.parts) == 1:
            return self.parts[0]
        return manifold3d.Manifold.compose(list(self.parts))

    def in_engine(self, which=None) -> "Solid":
        """The same solid with its parts (or those numbered in ``which``) in the engine."""
        if not any(type(p) is Placed for p in self.parts):
            return self
        parts = list(self.parts)
        for i in range(len(parts)) if which is None else which:
            parts[i] = _in_engine(parts[i])
        return Solid(tuple(parts), self.origins)

    def prefixed(self, prefix: str) -> "Solid":
        """The same solid with ``prefix`` put in front of every path."""
        return Solid(self.parts, self.origins.prefixed(prefix))

    def transformed(self, matrix) -> "Solid":
        """Moved by an affine map: a 3x4 or 4x4 matrix, or its 12 numbers row by row."""
        rows = np.asarray(matrix, dtype=np.float64).reshape(-1, 4)[:3]
        full = np.eye(4)
        full[:3] = rows
        m = np.ascontiguousarray(rows)
        return Solid(tuple(part.moved(full) if type(part) is Placed else part.transform(m)
                           for part in self.parts), self.origins.transformed(m))


def _solid(manifolds, origins: Origins) -> Solid:
    return Solid(tuple(m for m in manifolds if not m.is_empty()), origins)


# A shell thinner than this (its volume over half its area), relative to the
# size of its coordinates, is a sheet: what solids that only touch leave.
SHEET = 1e-9


def regular(manifold: manifold3d.Manifold) -> manifold3d.Manifold:
    """A boolean's result without its shells of (about) zero volume.

    manifold3d keeps a result 2-manifold, not regular: solids that only touch
    intersect into a closed sheet of zero volume, a difference of coincident
    solids leaves one. Regularization (LANGUAGE.md §4.3, §7) removes them."""
    if manifold.is_empty():
        return manifold
    shells = manifold.decompose()
    kept = [shell for shell in shells if not _sheet(shell)]
    if len(kept) == len(shells):
        return manifold
    if not kept:
        return manifold3d.Manifold()
    outer = [shell for shell in kept if shell.volume() > 0]
    if len(outer) == len(kept):
        return kept[0] if len(kept) == 1 else manifold3d.Manifold.compose(kept)
    # a cavity is a shell turned inside out, which compose drops: the sheets
    # are cut off instead, by the solid's own outer shells; if the engine's
    # intersection (every face coincident) leaves faces off their planes, the
    # sheet stays, to be cut out of the triangles at the end (polygons)
    cut = manifold ^ (outer[0] if len(outer) == 1 else manifold3d.Manifold.compose(outer))
    return manifold if off_faces(cut) else cut


def _sheet(shell: manifold3d.Manifold) -> bool:
    box = shell.bounding_box()
    size = max(1.0, max(abs(c) for c in box))
    # a cavity is a shell of negative volume: as much a part of the solid
    return abs(shell.volume()) <= SHEET * size * shell.surface_area() / 2


EMPTY = Solid((), NO_ORIGINS)


class EngineError(Exception):
    """manifold3d refused a mesh (not an oriented 2-manifold)."""


def template(mesh: Mesh) -> Template:
    """A primitive's mesh in the engine, built once and instanced many times."""
    gl = manifold3d.Mesh64(
        vert_properties=mesh.vertices,
        tri_verts=mesh.triangles.astype(np.uint64),
        face_id=mesh.faces.astype(np.uint64),
    )
    manifold = manifold3d.Manifold(gl)
    if manifold.status() != manifold3d.Error.NoError:
        raise EngineError(str(manifold.status()))
    return Template(manifold)


_IDENTITY = np.eye(4)[:3]


def instance(shape: Template, origin: Origin, matrix=None) -> Solid:
    """One use of a primitive, placed by ``matrix`` (its 12 numbers row by row, or
    None); it enters the engine only if a boolean needs it."""
    rows = (_IDENTITY.copy() if matrix is None
            else np.array(matrix, dtype=np.float64).reshape(3, 4))
    return Solid((Placed(shape, rows),), Origins.one(shape.id, rows, origin))  # neither changes it


def _fill_boxes(parts) -> None:
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


def _merged_origins(solids) -> Origins:
    return Origins.merged([s.origins for s in solids])


def _overlap_groups(boxes: np.ndarray) -> list[list[int]]:
    """Groups of operands whose boxes meet (touching counts).

    Boxes go into the cells of a grid twice as large as a typical box; only boxes
    sharing a cell can meet, so a union of 200,000 cubes that do not meet is a
    few array operations, not a sweep in Python. A box over very many cells is
    compared with all the others at once."""
    n = len(boxes)
    lo, hi = boxes[:, 0, :], boxes[:, 1, :]
    extent = hi - lo
    cell = np.maximum(2 * np.median(extent, axis=0), 1e-300)
    cell = np.where(cell > 0, cell, np.maximum(extent.max(axis=0), 1.0))
    first = np.floor(lo / cell).astype(np.int64)
    last = np.floor(hi / cell).astype(np.int64)
    span = last - first + 1
    cells = np.prod(span, axis=1)
    big = cells > 64
    pairs = []
    small = np.flatnonzero(~big)
    if len(small):
        # one entry per (box, cell it covers)
        counts = cells[small]
        owner = np.repeat(small, counts)
        k = np.arange(len(owner)) - np.repeat(np.cumsum(counts) - counts, counts)
        sx, sy = span[owner, 0], span[owner, 1]
        cx = first[owner, 0] + k % sx
        cy = first[owner, 1] + (k // sx) % sy
        cz = first[owner, 2] + k // (sx * sy)
        cx, cy, cz = cx - cx.min(), cy - cy.min(), cz - cz.min()
        key = (cx * (int(cy.max()) + 1) + cy) * (int(cz.max()) + 1) + cz
        order = np.argsort(key, kind="stable")
        key, owner = key[order], owner[order]
        starts = np.flatnonzero(np.r_[True, key[1:] != key[:-1]])
        sizes = np.diff(np.r_[starts, len(key)])
        for size in np.unique(sizes[sizes > 1]).tolist():
            members = owner[starts[sizes == size][:, None] + np.arange(size)]
            a, b = np.triu_indices(size, 1)
            pairs.append(np.stack([members[:, a].ravel(), members[:, b].ravel()], axis=1))
    for i in np.flatnonzero(big).tolist():
        others = np.arange(n)
        pairs.append(np.stack([np.full(n, i), others], axis=1)[others != i])
    label = np.arange(n)
    if pairs:
        pairs = np.unique(np.sort(np.concatenate(pairs), axis=1), axis=0)
        a, b = pairs[:, 0], pairs[:, 1]
        meet = np.all((lo[a] <= hi[b]) & (lo[b] <= hi[a]), axis=1)
        a, b = a[meet], b[meet]
        label = polygons.components(n, a, b)
    order = np.argsort(label, kind="stable")
    bounds = np.flatnonzero(np.diff(label[order])) + 1
    return [group.tolist() for group in np.split(order, bounds)]


class Counter:
    """Counts the calls made to the engine, for --stats."""

    def __init__(self):
        self.booleans = 0


def union(solids: list[Solid], counter: Counter) -> Solid:
    """Regularized union; parts whose boxes do not meet stay separate parts."""
    solids = [s for s in solids if not s.empty]
    if not solids:
        return EMPTY
    if len(solids) == 1:
        return solids[0]
    solids = _distinguished(solids)
    parts = [part for s in solids for part in s.parts]
    _fill_boxes(parts)
    boxes = np.array([part.bounding_box() for part in parts], dtype=np.float64).reshape(-1, 2, 3)
    origins = _merged_origins(solids)
    result, result_boxes = [], []
    for group in _overlap_groups(boxes):
        if len(group) == 1:
            result.append(parts[group[0]])
            result_boxes.append(boxes[group[0]])
        else:
            counter.booleans += 1
            operands = _distinct([_in_engine(parts[i]) for i in group])
            united = regular(_united(operands))
            if all(type(parts[i]) is Placed for i in group) and not _planes_meet(
                    [parts[i] for i in group]):
                _plain(united)
            result.append(united)
            result_boxes.append(np.array([boxes[group, 0].min(axis=0), boxes[group, 1].max(axis=0)]))
    return _solid(_fewer_parts(result, np.array(result_boxes)), origins)


def _distinct(manifolds: list) -> list:
    """The manifolds without exact copies: A with A is A, and the engine,
    asked to unite a solid with a copy of itself (every face coincident), was
    seen to lose volume. Copies are found by their counts, box, volume and
    area, then confirmed vertex for vertex."""
    kept, seen = [], {}
    for m in manifolds:
        key = (m.num_tri(), m.num_vert(), m.bounding_box(), m.volume(), m.surface_area())
        twins = seen.setdefault(key, [])
        if any(_same_mesh(m, other) for other in twins):
            continue
        twins.append(m)
        kept.append(m)
    return kept


def _same_mesh(a: manifold3d.Manifold, b: manifold3d.Manifold) -> bool:
    ga, gb = a.to_mesh64(), b.to_mesh64()
    va = np.asarray(ga.vert_properties)[:, :3]
    vb = np.asarray(gb.vert_properties)[:, :3]
    ta = np.sort(np.sort(va[np.asarray(ga.tri_verts, dtype=np.int64)].reshape(-1, 9).view(
        [("", np.float64)] * 9), axis=0), axis=0)
    tb = np.sort(np.sort(vb[np.asarray(gb.tri_verts, dtype=np.int64)].reshape(-1, 9).view(
        [("", np.float64)] * 9), axis=0), axis=0)
    return ta.shape == tb.shape and bool(np.all(ta == tb))


def _united(operands: list) -> manifold3d.Manifold:
    """The union of manifolds, two at a time in a balanced tree. (manifold3d's
    batch_boolean unites them all at once; on operands whose faces coincide,
    copies of one object side by side, it was seen to lose volume where
    unions two at a time do not: tests/test_regularize.py.)"""
    united = _balanced(operands)
    if not off_faces(united):
        return united
    # some union went wrong (off_faces): again, two at a time, each checked and
    # computed the other way round if need be
    while len(operands) > 1:
        operands = [_checked_union(operands[k], operands[k + 1]) if k + 1 < len(operands)
                    else operands[k] for k in range(0, len(operands), 2)]
    return operands[0]


def _checked_union(a: manifold3d.Manifold, b: manifold3d.Manifold) -> manifold3d.Manifold:
    """a + b, or the same union computed another way if the engine's is off
    its faces: b + a, then (a - b) + b and (b - a) + a."""
    return _checked(a + b, lambda: b + a, lambda: _checked(a - b) + b, lambda: _checked(b - a) + a)


def _balanced(operands: list) -> manifold3d.Manifold:
    while len(operands) > 1:
        operands = [operands[k] + operands[k + 1] if k + 1 < len(operands) else operands[k]
                    for k in range(0, len(operands), 2)]
    return operands[0]


def _checked(result: manifold3d.Manifold, *others) -> manifold3d.Manifold:
    """``result``, unless it has triangles off their faces (off_faces): then
    the first of the same boolean computed otherwise (the operands the other
    way round) that has none, or of all the one with fewest."""
    wrong = off_faces(result)
    if not wrong:
        return result
    best = (wrong, result)
    for other in others:
        candidate = other()
        wrong = off_faces(candidate)
        if not wrong:
            return candidate
        best = min(best, (wrong, candidate), key=lambda pair: pair[0])
    return best[1]


def _in_engine(part) -> manifold3d.Manifold:
    """A part as the engine's manifold."""
    return part.in_engine() if type(part) is Placed else part


# More parts than this are composed into fewer: each part costs the engine a
# few kilobytes and castor a Python call, whatever its size.
MAX_PARTS = 1024


def _fewer_parts(parts: list, boxes: np.ndarray) -> list:
    """Many parts of the engine composed into at most MAX_PARTS, neighbours
    together (by x). Placed primitives stay as they are: they cost little."""
    engine_parts = [i for i, p in enumerate(parts) if type(p) is not Placed]
    if len(engine_parts) <= MAX_PARTS:
        return parts
    placed = [p for p in parts if type(p) is Placed]
    parts = [parts[i] for i in engine_parts]
    boxes = boxes[engine_parts]
    order = np.argsort(boxes[:, 0, 0], kind="stable")
    size = -(-len(parts) // MAX_PARTS)
    return placed + [manifold3d.Manifold.compose([parts[i] for i in order[k:k + size]])
                     for k in range(0, len(parts), size)]


def _apart(a: np.ndarray, b: np.ndarray) -> bool:
    """Boxes with no common interior (touching counts as apart)."""
    return bool(np.any(np.maximum(a[0], b[0]) >= np.minimum(a[1], b[1])))


def intersection(solids: list[Solid], counter: Counter) -> Solid:
    """Regularized intersection; empty at once if the boxes have no common interior."""
    if not solids or any(s.empty for s in solids):
        return EMPTY
    if len(solids) == 1:
        return solids[0]
    boxes = np.stack([s.box() for s in solids])
    lo, hi = boxes[:, 0, :].max(axis=0), boxes[:, 1, :].min(axis=0)
    if np.any(lo >= hi):
        return EMPTY
    counter.booleans += 1
    solids = [s.in_engine() for s in _distinguished(solids)]
    wholes = [s.whole() for s in solids]
    manifold = regular(_checked(manifold3d.Manifold.batch_boolean(wholes, _Intersect),
                                lambda: manifold3d.Manifold.batch_boolean(wholes[::-1], _Intersect)))
    return _solid([manifold], _merged_origins(solids))


def difference(a: Solid, b: Solid, counter: Counter) -> Solid:
    """Regularized a - b, part by part; a part whose box does not meet b's stays."""
    if a.empty or b.empty:
        return a
    box_b = b.box()
    boxes = a.part_boxes()
    touched = [i for i in range(len(a.parts)) if not _apart(boxes[i], box_b)]
    if not touched:
        return a
    counter.booleans += 1
    a, b = _distinguished([a, b])
    a = a.in_engine(touched)
    b = b.in_engine()
    cutter = b.whole()
    parts = list(a.parts)
    for i in touched:
        part = parts[i]
        # (A + B) - B is A - B, computed otherwise
        parts[i] = regular(_checked(part - cutter, lambda part=part: (part + cutter) - cutter))
    return _solid(parts, _merged_origins((a, b)))


class Triangles(NamedTuple):
    vertices: np.ndarray  # (V, 3) float64
    triangles: np.ndarray  # (T, 3) int64
    origin_ids: np.ndarray  # (T,) int64: the entry of the solid's Origins
    face_ids: np.ndarray  # (T,) int64: the flat face (of one primitive) each lies on


def batches(parts, triangles: int = 20_000, count: int = 256):
    """Parts in batches of about ``triangles`` triangles, so that the work after
    the engine is done in large array operations, not once for each of many
    small parts. (Not composed by the engine: that would renumber them, and
    copies of one object would no longer look alike.)"""
    batch: list[manifold3d.Manifold] = []
    size = 0
    for part in parts:
        size_of_part = part.num_tri()
        if size_of_part >= 256:
            # big enough to go alone: copies of one object are then recognized
            if batch:
                yield batch
                batch, size = [], 0
            yield [part]
            continue
        batch.append(part)
        size += size_of_part
        if size >= triangles or len(batch) >= count:
            yield batch
            batch, size = [], 0
    if batch:
        yield batch


def triangles(parts, origins: Origins) -> Triangles:
    """The triangles of the parts of a solid whose origins are ``origins``, one
    vertex list for all, none of them flat."""
    pieces = []
    run: list[Placed] = []
    for part in parts:  # copies of one primitive side by side are placed at once
        if type(part) is Placed:
            if run and run[-1].template is not part.template:
                pieces.append(_placed_triangles(run, origins))
                run = []
            run.append(part)
            continue
        if run:
            pieces.append(_placed_triangles(run, origins))
            run = []
        pieces.append(_part_triangles(part, origins))
    if run:
        pieces.append(_placed_triangles(run, origins))
    if len(pieces) == 1:
        plain = len(parts) == 1 and _PLAIN.get(id(parts[0])) is parts[0]
        return _without_flat(pieces[0], sheets=not plain)
    base = np.cumsum([0] + [len(p.vertices) for p in pieces[:-1]])
    # faces of different parts must not share a number: the part in the top bits
    return _without_flat(Triangles(
        np.concatenate([p.vertices for p in pieces]),
        np.concatenate([p.triangles + b for p, b in zip(pieces, base)]),
        np.concatenate([p.origin_ids for p in pieces]),
        np.concatenate([p.face_ids + (k << 48) for k, p in enumerate(pieces)])))


def _placed_triangles(run: list[Placed], origins: Origins) -> Triangles:
    """The triangles of copies of one primitive, placed with one array operation;
    a mirrored copy's triangles turn the other way."""
    template = run[0].template
    matrices = np.stack([p.matrix for p in run])  # (k, 3, 4)
    v = template.vertices
    vertices = (np.einsum("kij,vj->kvi", matrices[:, :, :3], v)
                + matrices[:, None, :, 3]).reshape(-1, 3)
    mirrored = np.linalg.det(matrices[:, :, :3]) < 0
    count = len(template.triangles)
    tris = np.where(mirrored[:, None, None], template.turned[None], template.triangles[None])
    tris = (tris + (np.arange(len(run)) * len(v))[:, None, None]).reshape(-1, 3)
    entries = origins.find(np.array([p.id for p in run], np.int64), matrices)
    origin_ids = np.repeat(entries, count)
    faces = ((np.arange(len(run), dtype=np.int64) << 32)[:, None] | template.face_ids[None]).ravel()
    return Triangles(vertices, tris, origin_ids, faces)


# Results of unions of primitives no two of whose planes coincide: no sheet,
# no coincident twins can be in them, and the passes that look for them are
# skipped (by id; the manifold is held, so that its id is not reused).
_PLAIN: dict[int, manifold3d.Manifold] = {}


def _plain(manifold: manifold3d.Manifold) -> None:
    if len(_PLAIN) > 1000:
        _PLAIN.clear()
    _PLAIN[id(manifold)] = manifold


def _planes_meet(placed: list) -> bool:
    """Whether a plane of a face of one primitive coincides (to 10⁻⁷, either
    side) with a plane of another's: its planes moved by its matrix, keyed on
    two grids half a cell apart, so that planes that close never miss."""
    keys, owners = [], []
    for k, part in enumerate(placed):
        try:
            normal, offset, has = _moved_planes(part.template.planes, part.matrix)
        except np.linalg.LinAlgError:
            return True
        normal, offset = normal[has], offset[has]
        sign = polygons.plane_sign(normal)
        keys.append(np.column_stack([normal * sign[:, None], offset * sign]))
        owners.append(np.full(len(normal), k))
    rows, owner = np.concatenate(keys), np.concatenate(owners)
    # offsets relative to the size of the scene's coordinates, as the sheets' test has them
    rows[:, 3] /= max(1.0, max(abs(c) for part in placed for c in part.bounding_box()))
    return any(polygons.shared_across(polygons.row_hash(np.floor(rows * 1e7 + half)), owner)
               for half in (0.0, 0.5))


# Parts already found clean, by their triangles and faces: a copy of one
# object moved by an affine map has no sheet or flat triangle if the first had none.
_CLEAN: dict[int, bool] = {}


def _without_flat(tri: Triangles, sheets: bool = True) -> Triangles:
    """The engine leaves sheets where faces only touch, and its rounding a few
    triangles of zero area: both gone (polygons)."""
    key = None
    if len(tri.triangles) <= 200_000:
        key = hash((tri.triangles.tobytes(), tri.face_ids.tobytes()))
        if key in _CLEAN:
            return tri
    cleaned = _cleaned(tri) if sheets else _unflattened(tri)
    if key is not None and cleaned is tri:
        if len(_CLEAN) > 10_000:
            _CLEAN.clear()
        _CLEAN[key] = True
    return cleaned


def _unflattened(tri: Triangles) -> Triangles:
    """Only the flat triangles taken out (where no sheet can be)."""
    triangles, origin_ids, face_ids = polygons.without_flat_triangles(
        tri.vertices, tri.triangles, tri.origin_ids, tri.face_ids, twins=False)
    if triangles is tri.triangles:
        return tri
    return Triangles(tri.vertices, triangles, origin_ids, face_ids)


def _cleaned(tri: Triangles) -> Triangles:
    vertices = tri.vertices
    triangles, origin_ids, face_ids = polygons.without_flat_triangles(
        vertices, tri.triangles, tri.origin_ids, tri.face_ids)
    cut_vertices, cut, origin_cut, face_cut = polygons.without_sheets(
        vertices, triangles, origin_ids, face_ids)
    if cut is not triangles:  # cutting can leave slivers of its own
        cut, origin_cut, face_cut = polygons.without_flat_triangles(
            cut_vertices, cut, origin_cut, face_cut)
        # kept only if every edge is still paired and nothing is flat: a
        # sheet left in place is better than a surface that is not closed
        if polygons.paired(cut) and not polygons.flat_triangles(cut_vertices, cut).any():
            return Triangles(cut_vertices, cut, origin_cut, face_cut)
    if triangles is tri.triangles:
        return tri  # nothing to do: the same object, so that it is known clean
    return Triangles(vertices, triangles, origin_ids, face_ids)


def _part_triangles(part: manifold3d.Manifold, origins: Origins) -> Triangles:
    """A part's triangles in double precision, with each one's origin and face."""
    gl = part.to_mesh64()
    vertices = np.asarray(gl.vert_properties, dtype=np.float64)[:, :3]
    tris = np.asarray(gl.tri_verts, dtype=np.int64)
    # identify vertices that manifold3d split only for properties
    merge_from = np.asarray(gl.merge_from_vert, dtype=np.int64)
    if len(merge_from):
        remap = np.arange(len(vertices))
        remap[merge_from] = np.asarray(gl.merge_to_vert, dtype=np.int64)
        tris = remap[tris]
    run_index = np.asarray(gl.run_index, dtype=np.int64) // 3
    run_ids = np.asarray(gl.run_original_id, dtype=np.int64)
    # the engine's transformations are (R, 4, 3), the columns of our 3x4 rows
    placements = np.asarray(gl.run_transform, dtype=np.float64).transpose(0, 2, 1)
    entries = origins.find(run_ids, placements)
    counts = np.diff(run_index)
    origin_ids = np.repeat(entries, counts)
    # one number for each flat face of each use of a primitive: the rank of its
    # entry in this part, then its face. Copies of one object (whose entries
    # keep their order) number their faces alike, so their polygons can be reused.
    rank = np.searchsorted(np.unique(entries), entries)
    faces = (np.repeat(rank, counts) << 32) | (np.asarray(gl.face_id, dtype=np.int64) & 0xFFFFFFFF)
    return Triangles(vertices, tris, origin_ids, faces)


def triangulate(outline: np.ndarray) -> np.ndarray:
    """Triangles (T, 3) of a simple polygon (N, 2), counter-clockwise."""
    return np.asarray(manifold3d.triangulate([outline]), dtype=np.int64)


def refined(vertices: np.ndarray, triangles: np.ndarray, entries: np.ndarray,
            faces: np.ndarray, table: tuple) -> Solid:
    """A solid from a closed triangle mesh castor made itself (a smooth
    solid's refined facets), each triangle with its entry in ``table`` (its
    Origin) and the face it belongs to: one engine ID per entry, so that the
    triangles of each keep their origin through any boolean."""
    order = np.lexsort((faces, entries))
    entries, faces, triangles = entries[order], faces[order], triangles[order]
    starts = np.flatnonzero(np.r_[True, entries[1:] != entries[:-1]])
    used = entries[starts]
    first = manifold3d.Manifold.reserve_ids(len(used))
    ids = np.arange(first, first + len(used), dtype=np.int64)
    gl = manifold3d.Mesh64(
        vert_properties=np.ascontiguousarray(vertices, dtype=np.float64),
        tri_verts=np.ascontiguousarray(triangles, dtype=np.uint64),
        run_index=(np.r_[starts, len(triangles)] * 3).astype(np.uint64),
        run_original_id=ids.astype(np.uint32),
        face_id=faces.astype(np.uint64))
    manifold = manifold3d.Manifold(gl)
    if manifold.status() != manifold3d.Error.NoError:
        raise EngineError(str(manifold.status()))
    origins = Origins(ids, np.repeat(_IDENTITY[None], len(ids), axis=0),
                      tuple(table[int(e)] for e in used))
    return _solid([manifold], origins)
