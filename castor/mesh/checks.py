"""The check of every boolean's result, and the retry when it fails.

The engine's booleans of solids whose faces coincide exactly were seen to go
wrong: a few vertices moved off their faces, and volume lost. A triangle's
face is known from provenance (its run's template and placement), so the
check needs no trust in the vertices; a result that fails it is computed
again another way (``checked``).
"""

from __future__ import annotations

import numpy as np

from castor.mesh import adapter
from castor.mesh.caches import PROCESS
from castor.mesh.instances import moved_planes

# Results larger than this are not checked (off_faces): the check costs a
# quarter of a boolean, and large results are mostly of curved primitives,
# whose faces seldom coincide exactly.
CHECKED_TRIANGLES = 200_000


def off_faces(manifold: adapter.Manifold) -> int:
    """How many of a result's triangles have a corner off the plane of the
    primitive's face it comes from (beyond rounding): none, in a right result.

    The engine's union of solids whose faces coincide exactly was seen to go
    wrong (tests/geometry/test_regular_booleans.py): a few vertices moved off their faces
    and volume lost. The engine reports each run's template and placement,
    so each triangle's plane is known without trusting its vertices."""
    if manifold.is_empty() or manifold.num_tri() > CHECKED_TRIANGLES:
        return 0
    mesh = adapter.to_arrays(manifold)
    vertices, tris, faces = mesh.vertices, mesh.triangles, mesh.face_ids
    run_index, run_ids, placements = mesh.run_index, mesh.run_ids, mesh.placements
    tolerance = 1e-9 * max(1.0, float(np.abs(vertices).max()))
    templates = [PROCESS.engine_ids.get(r) for r in run_ids.tolist()]
    suspects = _suspects(mesh, templates, tolerance)
    bad = 0
    for r in range(len(run_ids)) if suspects is None else suspects:
        template = templates[r]
        if template is None:
            continue
        low, high = run_index[r], run_index[r + 1]
        if high == low:
            continue
        try:
            normal, offset, _ = moved_planes(
                template.planes[np.minimum(faces[low:high], len(template.planes) - 1)],
                placements[r])
        except np.linalg.LinAlgError:
            continue
        corners = vertices[tris[low:high]]
        distance = np.abs(np.einsum("tkj,tj->tk", corners, normal) - offset[:, None])
        bad += int(np.count_nonzero(distance.max(axis=1) > tolerance))
    return bad


def _suspects(mesh: adapter.EngineMesh, templates: list, tolerance: float):
    """The runs that may have a triangle off its face: the distances of every
    run at once, and the runs with one beyond half the tolerance (the count
    itself is made run by run, as ``off_faces`` always made it, so that it
    does not change by a rounding). None if a placement is flat."""
    counts = np.diff(mesh.run_index)
    known = np.array([t is not None for t in templates], dtype=bool) & (counts > 0)
    runs = np.flatnonzero(known)
    if not len(runs):
        return []
    base = np.zeros(len(templates), dtype=np.int64)
    size = np.ones(len(templates), dtype=np.int64)
    tables, planes, filled = {}, [], 0
    for r in runs.tolist():
        template = templates[r]
        at = tables.get(id(template))
        if at is None:
            at = tables[id(template)] = filled
            planes.append(template.planes)
            filled += len(template.planes)
        base[r], size[r] = at, len(template.planes)
    try:
        inverse = np.zeros((len(templates), 3, 3))
        inverse[runs] = np.linalg.inv(mesh.placements[runs, :, :3])
    except np.linalg.LinAlgError:
        return None
    run = np.repeat(np.arange(len(templates)), counts)
    triangle = np.arange(mesh.run_index[0], mesh.run_index[-1])[known[run]]
    run = run[known[run]]
    plane = np.concatenate(planes)[np.minimum(mesh.face_ids[triangle], size[run] - 1) + base[run]]
    m = np.einsum("tj,tjk->tk", plane[:, :3], inverse[run])  # rows: A^-T n
    length = np.linalg.norm(m, axis=1)
    safe = np.where(length > 0, length, 1.0)
    offset = (plane[:, 3] + np.einsum("tj,tj->t", m, mesh.placements[run, :, 3])) / safe
    corners = mesh.vertices[mesh.triangles[triangle]]
    distance = np.abs(np.einsum("tkj,tj->tk", corners, m / safe[:, None]) - offset[:, None])
    return np.unique(run[~(distance.max(axis=1) <= tolerance / 2)]).tolist()


def checked(result: adapter.Manifold, *others) -> adapter.Manifold:
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
