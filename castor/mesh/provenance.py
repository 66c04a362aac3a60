"""Provenance: where each triangle of a solid comes from, through any depth
of booleans, and which face of its primitive it lies on.

**Origins.** manifold3d gives every template an ID and reports, for each run
of a result's triangles, the ID of the template it came from and the
transformation that placed it there; an ``Origins`` table holds one entry per
use of a primitive (that ID, that placement, and its ``frame.Origin``: path
and colour), so ``find`` names the use of every run. That is how colours and
paths survive booleans without guessing by geometry.

**Face numbers.** This module is the one place where face numbers are made:
a primitive's mesh numbers its flat faces (``primitives.Mesh.faces``); the
template keeps them (``Template.face_ids``), the engine carries them through
every boolean (``EngineMesh.face_ids``), and ``triangles`` gives each
triangle a face number unique in its batch::

    bits 0-31   the face of the template (primitives.Mesh.faces)
    bits 32-47  which use of a template: the copy in a run of placed copies,
                or the rank of the use's origin entry within an engine part
    bits 48-63  which piece of the batch

with ``Triangles.origin_ids`` (the entry of ``Origins``: its engine ID gives
the template, ``caches.PROCESS.engine_ids``). Regularization keeps both
arrays row for row with the triangles (flat.py, sheets.py, seams.py copy a
triangle's numbers to the pieces cut from it), and merging groups by face
number and gives each polygon a triangle it was made of (``Polygons.source``):
so a polygon's template face is ``face_ids[source] & 0xFFFFFFFF`` and its
use is ``origin_ids[source]`` — where a per-face attribute of the templates
(flat or curved, which smooth surface) is read after merging.
"""

from __future__ import annotations

import re
from typing import NamedTuple

import numpy as np

from castor.mesh import adapter
from castor.mesh.arrays import row_hash, unique
from castor.mesh.frame import Origin
from castor.mesh.caches import PROCESS
from castor.mesh.instances import Placed, moved_planes


class Origins:
    """Where a solid's triangles come from: one entry per use of a primitive,
    the engine's ID of its template, the matrix that places that template in
    the solid, and its Origin (path and colour).

    The engine reports each run of a result's triangles with the same pair
    (its ID and its accumulated transformation), so ``find`` names the use of
    every run. Two uses at one place give the same triangles, and either name
    is true of them."""

    __slots__ = ("_ids", "_matrices", "table", "_index", "_one", "_twins")

    def __init__(self, ids: np.ndarray | None, matrices: np.ndarray | None, table: tuple,
                 one: tuple | None = None):
        self._ids = ids  # (E,) int64
        self._matrices = matrices  # (E, 3, 4)
        self.table = table  # E Origins
        self._index = None  # for find: sorted keys, and sorted IDs, made once
        self._one = one  # (ID, matrix) of a single entry whose arrays are not made yet
        self._twins = None  # for twins: each entry's group of entries at one place, or -1

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
                       tuple(o._replace(steps=o.steps.under(prefix)) for o in self.table))

    def transformed(self, matrix: np.ndarray) -> "Origins":
        """The entries of a solid moved by a 3x4 ``matrix``."""
        moved = np.einsum("ij,ejk->eik", matrix[:, :3], self.matrices)
        moved[:, :, 3] += matrix[:, 3]
        return Origins(self.ids, moved, self.table)

    def keys(self) -> set:
        """(ID, placement rounded to 1e-9) of every entry."""
        return {(i, m) for i, m in zip(self.ids.tolist(), map(place_key, self.matrices))}

    def renamed(self, changes: dict) -> "Origins":
        """The entries whose (ID, rounded placement) is in ``changes``, under the new ID."""
        ids = self.ids.copy()
        for e, (i, m) in enumerate(zip(self.ids.tolist(), self.matrices)):
            new = changes.get((i, place_key(m)))
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


    def twins(self) -> np.ndarray | None:
        """For each entry, the number of its group of twins (entries of one
        ID at one placement, to 10⁻⁹: one primitive at one place, used in
        two operands), or -1 if it has none; None if no entry has a twin."""
        if self._twins is None:
            if len(self.table) < 2:
                self._twins = False
            else:
                key = row_hash(np.column_stack([self.ids, np.round(
                    self.matrices.reshape(-1, 12) * 1e9)]))
                _, group, count = np.unique(key, return_inverse=True, return_counts=True)
                group = group.ravel()
                self._twins = np.where(count[group] > 1, group, -1) if np.any(count > 1) else False
        return None if self._twins is False else self._twins


def cut_parity(origin: Origin) -> int:
    """How many times, odd or even, a use is cut away on its path: it is the
    second or a later operand of that many differences (``D2``, ``D3``, …),
    and each turns its faces inside out. What is left of the use's surface
    faces outward where the parity is even, inward where it is odd."""
    return sum(int(k) >= 2 for k in _CUT.findall(origin.path)) % 2


_CUT = re.compile(r"(?:^|[.)])D(\d+)")


def facing_twins(origins: Origins, vertices: np.ndarray, triangles: np.ndarray,
                 origin_ids: np.ndarray, face_ids: np.ndarray) -> np.ndarray:
    """Each triangle's entry, chosen among twins by the way it faces.

    The engine names a triangle by its template's ID and placement; where two
    uses of a primitive stand at one place in two operands (twins) and their
    runs could not be renamed apart (booleans._renamed_runs), both have that
    ID and placement, and ``find`` gave either. What is left of a use's face
    faces as the face does (outward) if the use is cut away an even number of
    times on its path, and inward if odd (``cut_parity``): a triangle facing
    against its face comes from a twin of odd parity, one facing with it from
    one of even parity. Twins of one parity give the same triangles on a
    shared face, turned the same way, and either name is true of them; so the
    engine's choice stays unless it faces the wrong way, and a triangle too
    thin to face either way (rounding) keeps it too."""
    twins = origins.twins()
    if twins is None:
        return origin_ids
    rows = np.flatnonzero(twins[origin_ids] >= 0)
    if not len(rows):
        return origin_ids
    entries = origin_ids[rows]
    p = vertices[triangles[rows]]
    normal = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    length = np.linalg.norm(normal, axis=1)
    facing = np.zeros(len(rows))
    for entry in np.unique(entries).tolist():
        template = PROCESS.engine_ids.get(int(origins.ids[entry]))
        if template is None:
            continue
        mine = np.flatnonzero(entries == entry)
        planes = template.planes
        try:
            face_normal, _, _ = moved_planes(planes[np.minimum(face_ids[rows[mine]],
                                                               len(planes) - 1)],
                                             origins.matrices[entry])
        except np.linalg.LinAlgError:
            continue
        facing[mine] = np.einsum("ij,ij->i", normal[mine], face_normal)
    # turned with its face or against it, beyond rounding (half the angle's cosine)
    want = np.where(facing > 0.5 * length, 0, np.where(facing < -0.5 * length, 1, -1))
    parity = {}
    groups: dict[int, list[int]] = {}
    for e in np.flatnonzero(twins >= 0).tolist():
        groups.setdefault(int(twins[e]), []).append(e)
    out = origin_ids.copy()
    for k, (entry, wanted) in enumerate(zip(entries.tolist(), want.tolist())):
        if wanted < 0:
            continue
        if entry not in parity:
            parity[entry] = cut_parity(origins[entry])
        if parity[entry] == wanted:
            continue
        for other in groups[int(twins[entry])]:
            if other not in parity:
                parity[other] = cut_parity(origins[other])
            if parity[other] == wanted:
                out[rows[k]] = other
                break
    return out


def _coarse_keys(ids: np.ndarray, flat: np.ndarray) -> np.ndarray:
    """One number per (ID, placement rounded to 10⁻⁶)."""
    return row_hash(np.column_stack([ids, np.round(flat * 1e6)]))


def place_key(matrix: np.ndarray) -> bytes:
    return np.round(matrix.ravel() * 1e9).tobytes()


NO_ORIGINS = Origins(np.zeros(0, np.int64), np.zeros((0, 3, 4)), ())


def merged_origins(solids) -> Origins:
    """The origins of solids taken together (the operands of a boolean)."""
    return Origins.merged([s.origins for s in solids])


# --- face numbers: from the templates to the triangles that are merged


class Triangles(NamedTuple):
    """Triangles of a solid, each with its origin and its face number (see the
    module's docstring)."""

    vertices: np.ndarray  # (V, 3) float64
    triangles: np.ndarray  # (T, 3) int64
    origin_ids: np.ndarray  # (T,) int64: the entry of the solid's Origins
    face_ids: np.ndarray  # (T,) int64: the flat face (of one primitive) each lies on


def batches(parts, triangles: int = 20_000, count: int = 256):
    """Parts in batches of about ``triangles`` triangles, so that the work after
    the engine is done in large array operations, not once for each of many
    small parts. (Not composed by the engine: that would renumber them, and
    copies of one object would no longer look alike.)"""
    batch: list = []
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
    vertex list for all (as the engine leaves them: castor.mesh.regularize
    takes out flat triangles and sheets)."""
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
        return pieces[0]
    base = np.cumsum([0] + [len(p.vertices) for p in pieces[:-1]])
    # faces of different parts must not share a number: the part in the top bits
    return Triangles(
        np.concatenate([p.vertices for p in pieces]),
        np.concatenate([p.triangles + b for p, b in zip(pieces, base)]),
        np.concatenate([p.origin_ids for p in pieces]),
        np.concatenate([p.face_ids + (k << 48) for k, p in enumerate(pieces)]))


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


def _part_triangles(part, origins: Origins) -> Triangles:
    """A part's triangles in double precision, with each one's origin and face."""
    mesh = adapter.to_arrays(part)
    vertices, tris = mesh.vertices, mesh.triangles
    # identify vertices that manifold3d split only for properties
    if len(mesh.merge_from):
        remap = np.arange(len(vertices))
        remap[mesh.merge_from] = mesh.merge_to
        tris = remap[tris]
    entries = origins.find(mesh.run_ids, mesh.placements)
    counts = np.diff(mesh.run_index)
    origin_ids = facing_twins(origins, vertices, tris, np.repeat(entries, counts), mesh.face_ids)
    # one number for each flat face of each use of a primitive: the rank of its
    # entry in this part, then its face. Copies of one object (whose entries
    # keep their order) number their faces alike, so their polygons can be reused.
    rank = np.searchsorted(unique(origin_ids), origin_ids)
    faces = (rank << 32) | mesh.face_ids
    return Triangles(vertices, tris, origin_ids, faces)
