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
    bad = 0
    for r in range(len(run_ids)):
        template = PROCESS.engine_ids.get(int(run_ids[r]))
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
