"""merge: the groups of more than two triangles are numbered all at once
(merge._groups_polygons) and give each the polygons it gives alone, on its
own vertices; a group met again (caches.PROCESS.groups) is not merged again."""

import numpy as np

from castor.mesh import merge
from castor.mesh.caches import Bounded


def _triangles():
    from castor.mesh import adapter, instances, primitives

    box = instances.template(primitives.build("cu", (), 0.01)).manifold
    solid = adapter.subtract(box.scale([4, 4, 1]), adapter.add(
        box.scale([1, 1, 3]).translate([0.5, 0.5, -1]), box.scale([0.5, 1.5, 3]).translate([2.5, 2, -1])))
    mesh = adapter.to_arrays(solid)
    return mesh.vertices, mesh.triangles, mesh.face_ids


def test_groups_at_once_are_each_group_alone():
    vertices, triangles, faces = _triangles()
    _, group = np.unique(faces, return_inverse=True)
    group = group.ravel()
    order = np.argsort(group, kind="stable")
    big = order[np.bincount(group)[group][order] > 2]
    starts = np.r_[0, np.flatnonzero(np.diff(group[big])) + 1]
    assert len(starts) >= 2  # the top and bottom faces, cut by both holes
    sizes, indices, owner = merge._groups_polygons(vertices, triangles, big, starts, None)
    offsets = np.r_[0, np.cumsum(sizes)]
    ends = np.r_[starts[1:], len(big)]
    for k, (start, end) in enumerate(zip(starts, ends)):
        alone = merge._groups_polygons(vertices, triangles, big[start:end], np.array([0]), None)
        mine = np.flatnonzero(owner == k)
        assert sizes[mine].tolist() == alone[0].tolist()
        assert np.concatenate([indices[offsets[p]:offsets[p + 1]] for p in mine]).tolist() \
            == alone[1].tolist()
        # every vertex number is one of the group's own triangles'
        assert set(alone[1].tolist()) <= set(triangles[big[start:end]].ravel().tolist())


def test_a_group_met_again_is_not_merged_again(monkeypatch):
    vertices, triangles, faces = _triangles()
    known = Bounded()
    first = merge.merge(vertices, triangles, np.arange(len(triangles)), faces, known)
    merged = []
    again = merge._merge_group
    monkeypatch.setattr(merge, "_merge_group", lambda *args: merged.append(1) or again(*args))
    # the same part again, with one more triangle of a face of its own: every
    # group of the part met again
    extra = np.vstack([vertices, [[9, 9, 9], [10, 9, 9], [9, 10, 9]]])
    more = np.vstack([triangles, [[len(vertices), len(vertices) + 1, len(vertices) + 2]]])
    second = merge.merge(extra, more, np.arange(len(more)), np.r_[faces, faces.max() + 1], known)
    assert merged == [] and known.hits >= 2
    assert len(np.diff(second.offsets)) \
        == len(np.diff(first.offsets)) + 1  # the new triangle, as it is
    fresh = merge.merge(vertices, triangles, np.arange(len(triangles)), faces, None)
    assert fresh.indices.tolist() == first.indices.tolist()
    assert fresh.source.tolist() == first.source.tolist()
