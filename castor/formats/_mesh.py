"""What the mesh writers share: all objects of a frame as one vertex and face list."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from castor.mesh.frame import Frame


class Combined(NamedTuple):
    vertices: np.ndarray  # (V, 3) float64
    offsets: np.ndarray  # (P + 1,)
    indices: np.ndarray  # vertex numbers of the polygons, counter-clockwise from outside
    colours: np.ndarray  # (P, 3) float64 in 0..1
    objects: np.ndarray  # (P,) object number of each polygon


def combine(frame: Frame) -> Combined:
    vertices, offsets, indices, colours, objects = [], [np.zeros(1, np.int64)], [], [], []
    base_vertex = 0
    base_index = 0
    for number, obj in enumerate(frame.objects):
        vertices.append(obj.vertices)
        indices.append(obj.indices + base_vertex)
        offsets.append(obj.offsets[1:] + base_index)
        table = np.array([o.colour for o in obj.origins], dtype=np.float64).reshape(-1, 3)
        colours.append(table[obj.origin_of] if len(obj.origin_of) else np.zeros((0, 3)))
        objects.append(np.full(obj.polygon_count, number, np.int64))
        base_vertex += len(obj.vertices)
        base_index += len(obj.indices)
    if not frame.objects:
        return Combined(np.zeros((0, 3)), np.zeros(1, np.int64), np.zeros(0, np.int64),
                        np.zeros((0, 3)), np.zeros(0, np.int64))
    return Combined(np.concatenate(vertices), np.concatenate(offsets), np.concatenate(indices),
                    np.concatenate(colours), np.concatenate(objects))


def byte_colours(colours: np.ndarray) -> np.ndarray:
    return np.clip(np.rint(colours * 255), 0, 255).astype(np.uint8)


def split_large(offsets: np.ndarray, indices: np.ndarray, colours: np.ndarray,
                largest: int = 4) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Cut polygons of more than ``largest`` (4) vertices into a fan of quads.

    The pieces of a convex polygon are convex and share its plane; some readers
    (trimesh's OFF loader among them) take nothing larger than a quad.
    """
    sizes = np.diff(offsets)
    if np.all(sizes <= largest):
        return offsets, indices, colours
    new_sizes, new_indices, new_colours = [], [], []
    index_list = indices.tolist()
    starts = offsets[:-1].tolist()
    for p, n in enumerate(sizes.tolist()):
        face = index_list[starts[p]:starts[p] + n]
        if n <= largest:
            pieces = [face]
        else:
            pieces = []
            k = 1
            while k < n - 1:
                piece = [face[0]] + face[k:k + 3] if k + 2 < n else [face[0]] + face[k:k + 2]
                pieces.append(piece)
                k += len(piece) - 2
        for piece in pieces:
            new_sizes.append(len(piece))
            new_indices.extend(piece)
            new_colours.append(p)
    new_offsets = np.zeros(len(new_sizes) + 1, np.int64)
    np.cumsum(new_sizes, out=new_offsets[1:])
    return new_offsets, np.array(new_indices, np.int64), colours[np.array(new_colours, np.int64)]
