"""Regularization (LANGUAGE.md §4.3, §7): a boolean's result without what
has no volume.

The engine keeps results 2-manifold, not regular. Its solids lose their
shells of zero volume here (``regular``: sheets where solids only touch,
cavities kept); their triangles lose flat triangles, coincident twins and
the sheets the engine left inside a shell (``regular_triangles``, with
castor.mesh.flat and castor.mesh.sheets).
"""

from __future__ import annotations

import numpy as np

from castor.mesh import adapter
from castor.mesh.arrays import components, cross, digest, norm, paired, plane_sign, row_hash, shared_across
from castor.mesh.caches import PROCESS
from castor.mesh.checks import off_faces
from castor.mesh.flat import flat_triangles, without_flat_triangles
from castor.mesh.instances import moved_planes
from castor.mesh.provenance import Triangles
from castor.mesh.sheets import without_sheets

# A shell thinner than this (its volume over half its area), relative to the
# size of its coordinates, is a sheet: what solids that only touch leave.
SHEET = 1e-9


def regular(manifold: adapter.Manifold) -> adapter.Manifold:
    """A boolean's result without its shells of (about) zero volume.

    manifold3d keeps a result 2-manifold, not regular: solids that only touch
    intersect into a closed sheet of zero volume, a difference of coincident
    solids leaves one. Regularization (LANGUAGE.md §4.3, §7) removes them."""
    if manifold.is_empty() or (_many_shells(manifold) and not _may_have_sheets(manifold)):
        return manifold
    shells = adapter.decompose(manifold)
    kept = [shell for shell in shells if not _sheet(shell)]
    if len(kept) == len(shells):
        return manifold
    if not kept:
        return adapter.empty()
    outer = [shell for shell in kept if shell.volume() > 0]
    if len(outer) == len(kept):
        return kept[0] if len(kept) == 1 else adapter.compose(kept)
    # a cavity is a shell turned inside out, which compose drops: the sheets
    # are cut off instead, by the solid's own outer shells; if the engine's
    # intersection (every face coincident) leaves faces off their planes, the
    # sheet stays, to be cut out of the triangles at the end (regular_triangles)
    cut = adapter.intersect(manifold, outer[0] if len(outer) == 1 else adapter.compose(outer))
    return manifold if off_faces(cut) else cut


# The engine's decomposition costs about as much per shell as finding the
# shells and their volumes from the triangles costs per this many triangles.
TRIANGLES_PER_SHELL = 2000


def _many_shells(manifold: adapter.Manifold) -> bool:
    """Whether the solid has shells enough for ``_may_have_sheets`` to cost
    less than the engine's decomposition (a few shells of many triangles are
    decomposed, as always): its genus (1 - V/2 + E/2 - T/2, summed over its
    shells, each at most 0 if it has no handle) says at least how many."""
    at_least = 1 - manifold.genus()
    return at_least >= 4 and manifold.num_tri() <= TRIANGLES_PER_SHELL * at_least


def _may_have_sheets(manifold: adapter.Manifold) -> bool:
    """Whether a shell of the solid may be a sheet (``_sheet``), found
    without the engine's decomposition (the larger part of ``regular``): each
    shell's volume and area from its triangles (shells joined by their
    vertices, as the engine joins them). False only where every shell's volume
    is four times what a sheet's may be, with every shell's size taken as the
    whole solid's (at least its own): the engine's own figures, rounded
    otherwise, could not find a sheet either."""
    mesh = adapter.to_arrays(manifold)
    vertices, triangles = mesh.vertices, mesh.triangles
    if not len(triangles):
        return True
    label = components(len(vertices), np.concatenate([triangles.ravel(), mesh.merge_from]),
                       np.concatenate([triangles[:, [1, 2, 0]].ravel(), mesh.merge_to]))
    shell = np.unique(label[triangles[:, 0]], return_inverse=True)[1].ravel()
    corners = vertices[triangles] - vertices.mean(axis=0)
    normal = cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    area = np.bincount(shell, norm(normal) / 2)
    volume = np.bincount(shell, np.einsum("tj,tj->t", corners[:, 0], normal) / 6)
    size = max(1.0, float(np.abs(vertices).max()))
    return not bool(np.all(np.abs(volume) > 4 * SHEET * size * area / 2))


def _sheet(shell: adapter.Manifold) -> bool:
    box = shell.bounding_box()
    size = max(1.0, max(abs(c) for c in box))
    # a cavity is a shell of negative volume: as much a part of the solid
    return abs(shell.volume()) <= SHEET * size * shell.surface_area() / 2


# --- where no sheet can be


def mark_plain(manifold: adapter.Manifold) -> None:
    """Remember a result of a union of primitives no two of whose planes
    coincide: no sheet, no coincident twins can be in it, and the passes that
    look for them are skipped (caches.PROCESS.plain)."""
    PROCESS.plain.put(id(manifold), manifold)


def _is_plain(part) -> bool:
    return PROCESS.plain.get(id(part)) is part


def planes_meet(placed: list) -> bool:
    """Whether a plane of a face of one primitive coincides (to 10⁻⁷, either
    side) with a plane of another's: its planes moved by its matrix, keyed on
    two grids half a cell apart, so that planes that close never miss."""
    keys, owners = [], []
    for k, part in enumerate(placed):
        try:
            normal, offset, has = moved_planes(part.template.planes, part.matrix)
        except np.linalg.LinAlgError:
            return True
        normal, offset = normal[has], offset[has]
        sign = plane_sign(normal)
        keys.append(np.column_stack([normal * sign[:, None], offset * sign]))
        owners.append(np.full(len(normal), k))
    rows, owner = np.concatenate(keys), np.concatenate(owners)
    # offsets relative to the size of the scene's coordinates, as the sheets' test has them
    rows[:, 3] /= max(1.0, max(abs(c) for part in placed for c in part.bounding_box()))
    return any(shared_across(row_hash(np.floor(rows * 1e7 + half)), owner)
               for half in (0.0, 0.5))


# --- the triangles of a solid


def regular_triangles(tri: Triangles, parts) -> Triangles:
    """The triangles of ``parts`` (provenance.triangles) without what the
    engine leaves: sheets where faces only touch, and triangles of zero area
    from its rounding. Parts already found clean are remembered by their
    triangles and faces (caches.PROCESS.clean): a copy of one object moved by
    an affine map has no sheet or flat triangle if the first had none."""
    sheets = not (len(parts) == 1 and _is_plain(parts[0]))
    key = None
    if len(tri.triangles) <= 200_000:
        key = hash((tri.triangles.tobytes(), tri.face_ids.tobytes()))
        if PROCESS.clean.get(key):  # (counted: caches.Bounded.hits)
            return tri
    if sheets:
        return _remembered(tri, key)
    cleaned = _unflattened(tri)
    if key is not None and cleaned is tri:
        PROCESS.clean.put(key, True)
    return cleaned


def _remembered(tri: Triangles, clean_key) -> Triangles:
    """``_cleaned(tri)``, or the same regularization of the same triangles made
    before (caches.PROCESS.regular: a part whose operands did not change since
    the last frame). Every pass carries a triangle's origin to the triangles
    made of it, and decides nothing by it: the regularization is computed
    with each triangle's row for its origin, and remembered as the rows each
    triangle comes from, which give the origins of the triangles of any frame."""
    key = digest(tri.vertices, tri.triangles, tri.face_ids)
    known = PROCESS.regular.get(key)
    if known is not None:
        vertices, triangles, rows, face_ids = known
        if rows is None:
            return tri
        return Triangles(tri.vertices if vertices is None else vertices, triangles,
                         tri.origin_ids[rows], face_ids)
    rows = np.arange(len(tri.triangles), dtype=np.int64)
    cleaned = _cleaned(Triangles(tri.vertices, tri.triangles, rows, tri.face_ids))
    if cleaned.triangles is tri.triangles:  # nothing to do: the same object, known clean
        if clean_key is not None:
            PROCESS.clean.put(clean_key, True)
        PROCESS.regular.put(key, (None, None, None, None), 1)
        return tri
    PROCESS.regular.put(key, (None if cleaned.vertices is tri.vertices else cleaned.vertices,
                              cleaned.triangles, cleaned.origin_ids, cleaned.face_ids),
                        len(cleaned.triangles))
    return Triangles(cleaned.vertices, cleaned.triangles, tri.origin_ids[cleaned.origin_ids],
                     cleaned.face_ids)


def _unflattened(tri: Triangles) -> Triangles:
    """Only the flat triangles taken out (where no sheet can be)."""
    triangles, origin_ids, face_ids = without_flat_triangles(
        tri.vertices, tri.triangles, tri.origin_ids, tri.face_ids, twins=False)
    if triangles is tri.triangles:
        return tri
    return Triangles(tri.vertices, triangles, origin_ids, face_ids)


def _cleaned(tri: Triangles) -> Triangles:
    vertices = tri.vertices
    triangles, origin_ids, face_ids = without_flat_triangles(
        vertices, tri.triangles, tri.origin_ids, tri.face_ids)
    cut_vertices, cut, origin_cut, face_cut = without_sheets(
        vertices, triangles, origin_ids, face_ids)
    if cut is not triangles:  # cutting can leave slivers of its own
        cut, origin_cut, face_cut = without_flat_triangles(
            cut_vertices, cut, origin_cut, face_cut)
        # kept only if every edge is still paired and no triangle is flat
        # that was not flat without the cut: a sheet left in place is better
        # than a surface that is not closed, but a flat triangle the engine
        # left elsewhere (one its flip could not take out) is no reason to
        # keep the sheet (wide oracle, seed 22: 3.3 m² of inner faces kept
        # for a needle of 9e-11 on the outside)
        if paired(cut):
            left = int(flat_triangles(cut_vertices, cut).sum())
            if not left or left <= int(flat_triangles(vertices, triangles).sum()):
                return Triangles(cut_vertices, cut, origin_cut, face_cut)
    if triangles is tri.triangles:
        return tri  # nothing to do: the same object, so that it is known clean
    return Triangles(vertices, triangles, origin_ids, face_ids)
