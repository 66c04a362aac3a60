"""What the mesh writers share: a frame's objects as vertex and face lists, triangles
that every reader takes, and names a person recognises for objects and materials."""

from __future__ import annotations

import re
from typing import Iterator, NamedTuple

import numpy as np

from castor.mesh.frame import Frame, FrameObject

# sin of the angle under which a polygon's corner counts as straight (a vertex in
# the middle of a straight edge, which a neighbouring polygon needs)
_STRAIGHT = 1e-9


# polygons formatted at a time by the writers that write in pieces: a piece's
# temporaries (texts, corners) are a few megabytes, freed before the next
CHUNK = 32768


class Piece(NamedTuple):
    """Polygons ``first`` to ``first + count`` of one object of a frame, numbered
    as in the object: its whole vertex list, offsets from 0, their indices."""

    number: int  # the object's place in the frame
    obj: FrameObject
    first: int
    offsets: np.ndarray
    indices: np.ndarray
    colour_table: np.ndarray  # (origins, 3) the colour of each of the object's origins

    @property
    def vertices(self) -> np.ndarray:
        return self.obj.vertices

    @property
    def polygon_count(self) -> int:
        return len(self.offsets) - 1

    def colours(self) -> np.ndarray:
        """(P, 3) the colour of each polygon of the piece."""
        origin_of = self.obj.origin_of[self.first:self.first + self.polygon_count]
        return self.colour_table[origin_of] if len(origin_of) else np.zeros((0, 3))


def object_pieces(obj: FrameObject,
                  size: int | None = None) -> Iterator[tuple[int, np.ndarray, np.ndarray]]:
    """The object's polygons ``size`` (``CHUNK``) at a time: the number of the
    first, offsets from 0, their vertex numbers (the object's)."""
    size = size or CHUNK
    for first in range(0, obj.polygon_count, size):
        last = min(first + size, obj.polygon_count)
        start, end = int(obj.offsets[first]), int(obj.offsets[last])
        yield first, obj.offsets[first:last + 1] - start, obj.indices[start:end]


def pieces(frame: Frame, size: int | None = None) -> Iterator[Piece]:
    """The frame's polygons, object after object, ``size`` (``CHUNK``) polygons at a time."""
    for number, obj in enumerate(frame.objects):
        table = np.array([o.colour for o in obj.origins], dtype=np.float64).reshape(-1, 3)
        for first, offsets, indices in object_pieces(obj, size):
            yield Piece(number, obj, first, offsets, indices, table)


def vertex_bases(frame: Frame) -> list[int]:
    """The number of each object's first vertex in the frame's combined vertex list."""
    return np.cumsum([0] + [len(o.vertices) for o in frame.objects]).tolist()


class Material(NamedTuple):
    name: str
    colour: tuple[float, float, float]


def byte_colours(colours: np.ndarray) -> np.ndarray:
    return np.clip(np.rint(colours * 255), 0, 255).astype(np.uint8)


def object_names(frame: Frame) -> list[str]:
    """The name of each object: the '>' command's object, else objectK; unique."""
    names, seen = [], set()
    for k, obj in enumerate(frame.objects, 1):
        name = obj.name or f"object{k}"
        base, n = name, 1
        while name in seen:
            n += 1
            name = f"{base}_{n}"
        seen.add(name)
        names.append(name)
    return names


_NAMED_STEP = re.compile(r"\(([^()]*)\)")
_OPERAND = re.compile(r"[UID](\d+)")


def colour_name(colour) -> str:
    """A colour by its own values, as a material name: ``rgb-0.9-0.9-0.85``."""
    def number(c: float) -> str:
        text = repr(float(c))
        return text[:-2] if text.endswith(".0") else text
    return "rgb-" + "-".join(number(c) for c in colour)


def _path_order(path: str) -> tuple[int, ...]:
    """The place of a primitive in the order the scene writes it: the operand
    numbers along its path (``U1.D2.U10`` before ``U2``), names left out."""
    return tuple(int(n) for n in _OPERAND.findall(_NAMED_STEP.sub("", path)))


def _part_name(path: str) -> tuple[int, str] | None:
    """What a primitive's path names it part of: its innermost named sub-object
    (rank 0), else its object's own name (rank 1), else None."""
    named = _NAMED_STEP.findall(path)
    if path.startswith("(") and named:
        own, below = named[0], named[1:]
        return (0, below[-1]) if below else (1, own)
    return (0, named[-1]) if named else None


def materials(frame: Frame) -> tuple[list[Material], list[np.ndarray]]:
    """The frame's materials, and for each object the material of each of its polygons.

    Within each object, a colour is one material, named (OUTPUT.md) after the
    named sub-object whose primitives carry that colour there: the innermost
    named object on their path (``poteau``, ``fenetres_sud``), or the object's
    own name where its primitives are named by nothing else, or else the colour's
    values (``rgb-0.9-0.9-0.85``); never after another object. Where several named
    sub-objects of one object share a colour, the first of them in the order the
    scene writes them names it (the house's blue is ``fenetres_sud``, though
    the north windows and the door are cut by it too): the part a reader meets
    first in the file, and one short name that a Blender user finds in the
    material list, rather than a list of every part. Objects that name a colour
    alike share the material; one name for two colours gets a number
    (``fenetre``, ``fenetre_2``).
    """
    table: list[Material] = []
    index: dict[tuple[str, tuple], int] = {}  # (base name, colour) -> material
    taken: set[str] = set()
    per_object = []
    for obj in frame.objects:
        chosen: dict[tuple, tuple] = {}  # colour -> (rank, path order, name)
        colour_of = []
        for origin in obj.origins:
            key = tuple(float(c) for c in origin.colour)
            colour_of.append(key)
            part = _part_name(origin.path)
            candidate = ((2, (), colour_name(key)) if part is None
                         else (part[0], _path_order(origin.path), part[1]))
            if key not in chosen or candidate < chosen[key]:
                chosen[key] = candidate
        origin_material = np.zeros(len(obj.origins), np.int64)
        for i, key in enumerate(colour_of):
            base = chosen[key][2]
            if (base, key) not in index:
                name, n = base, 1
                while name in taken:
                    n += 1
                    name = f"{base}_{n}"
                taken.add(name)
                index[(base, key)] = len(table)
                table.append(Material(name, key))
            origin_material[i] = index[(base, key)]
        per_object.append(origin_material[obj.origin_of] if len(obj.origin_of)
                          else np.zeros(0, np.int64))
    return table, per_object


def corner_turns(vertices: np.ndarray, offsets: np.ndarray, indices: np.ndarray):
    """For each corner of each polygon: the position of the vertex after it in
    ``indices``, how much the boundary turns there (|incoming × outgoing|), and
    the product of the two edges' lengths, to which a caller compares the turn."""
    starts = offsets[:-1]
    following = np.arange(1, len(indices) + 1)
    following[offsets[1:] - 1] = starts
    previous = np.arange(-1, len(indices) - 1)
    previous[starts] = offsets[1:] - 1
    p = vertices[indices]
    incoming, outgoing = p - p[previous], p[following] - p
    turn = np.linalg.norm(np.cross(incoming, outgoing), axis=1)
    return following, turn, np.linalg.norm(incoming, axis=1) * np.linalg.norm(outgoing, axis=1)


def straight_corners(vertices: np.ndarray, offsets: np.ndarray,
                     indices: np.ndarray) -> np.ndarray:
    """(P,) which polygons have a straight corner: a vertex in the middle of a
    straight edge, there because a neighbouring polygon ends at it."""
    sizes = np.diff(offsets)
    if len(indices) == 0 or np.all(sizes == 3):
        return np.zeros(len(offsets) - 1, bool)
    starts = offsets[:-1]
    _, turn, lengths = corner_turns(vertices, offsets, indices)
    straight = turn <= _STRAIGHT * lengths
    # a triangle keeps even a flat corner: cutting it would leave a hole
    return np.logical_or.reduceat(straight, starts) & (sizes > 3)


def triangle_counts(vertices: np.ndarray, offsets: np.ndarray,
                    indices: np.ndarray) -> np.ndarray:
    """(P,) how many triangles ``triangles`` cuts each polygon into, without
    making them: what a header that gives the count needs before the first."""
    counts = np.maximum(np.diff(offsets) - 2, 0)
    for p in np.flatnonzero(straight_corners(vertices, offsets, indices)).tolist():
        counts[p] = len(_clip_ears(vertices, indices[offsets[p]:offsets[p + 1]].tolist()))
    return counts


def triangles(vertices: np.ndarray, offsets: np.ndarray,
              indices: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each convex polygon as triangles, none of them flat; also the polygon of
    each triangle.

    A fan would give a flat triangle wherever a polygon has a straight corner
    (three of its vertices on one line); CGAL's exact booleans in OpenSCAD stop
    with an assertion on such faces, and slicers flag them. Those polygons are
    cut by clipping ears at true corners instead.
    """
    from castor.mesh.arrays import fan_triangles

    straight = straight_corners(vertices, offsets, indices)
    if not straight.any():
        return fan_triangles(offsets, indices)
    keep = ~straight
    sizes = np.diff(offsets)
    fan_offsets = np.zeros(int(keep.sum()) + 1, np.int64)
    np.cumsum(sizes[keep], out=fan_offsets[1:])
    fan_indices = indices[np.repeat(keep, sizes)]
    tris, polygon = fan_triangles(fan_offsets, fan_indices)
    pieces, owners = [tris], [np.flatnonzero(keep)[polygon]]
    for p in np.flatnonzero(straight).tolist():
        clipped = _clip_ears(vertices, indices[offsets[p]:offsets[p + 1]].tolist())
        pieces.append(np.array(clipped, np.int64).reshape(-1, 3))
        owners.append(np.full(len(clipped), p, np.int64))
    tris = np.concatenate(pieces)
    polygon = np.concatenate(owners)
    order = np.argsort(polygon, kind="stable")
    return tris[order], polygon[order]


def _clip_ears(vertices: np.ndarray, ring: list[int]) -> list[tuple[int, int, int]]:
    """Triangles of a convex polygon with straight corners, none of them flat.

    An ear is clipped at a true corner, choosing one that leaves a polygon that
    is not flat (all on one line) until three vertices remain.
    """
    points = vertices.tolist()

    def flat(a, b, c) -> bool:
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = points[a], points[b], points[c]
        ux, uy, uz, wx, wy, wz = bx - ax, by - ay, bz - az, cx - bx, cy - by, cz - bz
        cross = ((uy * wz - uz * wy) ** 2 + (uz * wx - ux * wz) ** 2
                 + (ux * wy - uy * wx) ** 2)
        return cross <= _STRAIGHT ** 2 * (ux * ux + uy * uy + uz * uz) * (wx * wx + wy * wy + wz * wz)

    ring = list(ring)
    out = []
    while len(ring) > 3:
        n = len(ring)
        corner_flat = [flat(ring[i - 1], ring[i], ring[(i + 1) % n]) for i in range(n)]
        true_corners = n - sum(corner_flat)
        chosen = None
        for i in range(n):
            if corner_flat[i]:
                continue
            before, after = ring[i - 1], ring[(i + 1) % n]
            # what is left keeps a true corner: one far from i, or one of i's
            # neighbours, which turn when i goes
            others = true_corners - 1 - (not corner_flat[i - 1]) - (not corner_flat[(i + 1) % n])
            if (others > 0 or not flat(ring[i - 2], before, after)
                    or not flat(before, after, ring[(i + 2) % n])):
                chosen = i
                break
        if chosen is None:  # nothing left but a line: no area to cover
            return out
        out.append((ring[chosen - 1], ring[chosen], ring[(chosen + 1) % n]))
        del ring[chosen]
    if not flat(*ring):
        out.append(tuple(ring))
    return out


def split_large(offsets: np.ndarray, indices: np.ndarray, colours: np.ndarray,
                largest: int = 4) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Cut polygons of more than ``largest`` (4) vertices into a fan of quads.

    The pieces of a convex polygon without straight corners are convex and share
    its plane; some readers (trimesh's OFF loader among them) take nothing
    larger than a quad.
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


def y_up(vertices: np.ndarray) -> np.ndarray:
    """Scene coordinates (z up) as +Y-up ones (glTF, OBJ): (x, y, z) -> (x, z, -y)."""
    out = np.empty_like(vertices)
    out[:, 0] = vertices[:, 0]
    out[:, 1] = vertices[:, 2]
    out[:, 2] = -vertices[:, 1]
    return out + 0.0  # no -0
