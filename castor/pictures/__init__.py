"""Pictures of the exact solids: rays cast against a frame's evaluated CSG tree.

``picture(tree, spec)`` gives an (H, W, 3) uint8 image (OUTPUT.md, "Pictures").
One ray through each pixel's centre finds the visible surface, its normal, its
colour and whether the sun reaches it; pixels that differ from a neighbour (an
outline, a crease, a change of colour or of shadow) are traced again with
``--samples`` rays each and averaged, so edges are anti-aliased at the cost of
the edges only. Rays go in square tiles, so that each tile's rays meet only
the subtrees whose boxes they cross.
"""

from __future__ import annotations

import numpy as np

from castor.pictures import shade
from castor.pictures.camera import Camera, make_camera
from castor.pictures.trace import Projection, TracedTree, compile_frame

TILE = 64  # pixels on a side of a tile of rays
CHUNK = 16384  # rays traced at once

__all__ = ["draw", "draw_tree", "framing", "picture", "probe", "render_traced", "sample_offsets"]


def picture(tree, spec) -> np.ndarray:
    """The frame drawn with the picture settings ``spec`` (castor.settings.PictureSettings)."""
    return draw(compile_frame(tree), spec)


def draw(traced: TracedTree, spec) -> np.ndarray:
    """A compiled frame (castor.pictures.trace.compile_frame) drawn with the
    picture settings ``spec``, its camera framing it."""
    low, high = traced.box
    camera = make_camera(low, high, spec.size, spec.view, spec.eye, spec.look)
    return render_traced(traced, camera, spec.sun, spec.samples, spec.edges)


def framing(boxes: list, spec) -> tuple[Camera, float]:
    """The camera that frames every box (an animation's frames: it does not jump),
    and the height of the ground, at the foot of the lowest."""
    boxes = boxes or [(np.zeros(3),) * 2]
    low = np.min([b[0] for b in boxes], axis=0)
    high = np.max([b[1] for b in boxes], axis=0)
    return make_camera(low, high, spec.size, spec.view, spec.eye, spec.look), float(low[2])


def draw_tree(tree, camera: Camera, spec, ground: float) -> np.ndarray:
    """A frame's evaluated tree drawn from ``camera`` (an animation's frame, in
    whatever process draws it: the picture comes back as an array)."""
    return render_traced(compile_frame(tree), camera, spec.sun, spec.samples, spec.edges,
                        ground=ground)


PROBES = 32  # rays on a side of the grid that looks for something in a frame


def probe(traced: TracedTree) -> bool | None:
    """Whether a compiled frame draws nothing: True when it has no solid or a flat
    box, False as soon as one of the rays along each axis through a grid over its
    box meets a solid (almost every frame, at once); None when they all miss
    (only its polygons can tell then)."""
    if traced.root is None:
        return True
    low, high = (np.asarray(corner, float) for corner in traced.box)
    if not np.all(high > low):
        return True
    steps = (np.arange(PROBES) + 0.5) / PROBES
    for axis in range(3):
        u, v = (a for a in range(3) if a != axis)
        grid_u, grid_v = np.meshgrid(low[u] + steps * (high[u] - low[u]),
                                     low[v] + steps * (high[v] - low[v]))
        origins = np.empty((grid_u.size, 3))
        origins[:, u], origins[:, v] = grid_u.ravel(), grid_v.ravel()
        origins[:, axis] = low[axis] - 1.0
        directions = np.zeros_like(origins)
        directions[:, axis] = 1.0
        t = traced.spans(origins, directions)[0]
        with np.errstate(invalid="ignore"):
            if np.any(t[:, 1::2] - t[:, 0::2] > 0):
                return False
    return None


def sample_offsets(samples: int) -> np.ndarray:
    """Where a pixel's samples lie within it: (N, 2) in 0..1 (a rotated grid for
    4, a Halton sequence otherwise), the same for every picture."""
    if samples <= 1:
        return np.array([[0.5, 0.5]])
    if samples == 4:
        return np.array([[0.375, 0.125], [0.875, 0.375], [0.125, 0.625], [0.625, 0.875]])

    def halton(i: int, base: int) -> float:
        f, r = 1.0, 0.0
        while i > 0:
            f /= base
            r += f * (i % base)
            i //= base
        return r

    return np.array([[halton(i + 1, 2), halton(i + 1, 3)] for i in range(samples)])


class _Samples:
    """What the rays through some picture points see."""

    def __init__(self, n: int):
        self.colour = np.empty((n, 3))
        self.key = np.full(n, -1, np.int64)  # the surface's face number; -1 nothing
        self.depth = np.full(n, np.inf)
        self.normal = np.zeros((n, 3))
        self.lit = np.ones(n, bool)


def render_traced(traced: TracedTree, camera: Camera, sun, samples: int, edges: bool,
                 ground: float | None = None) -> np.ndarray:
    """The picture of a compiled frame (a TracedTree) from ``camera``: sun ``(az, el)``, None or a
    castor.settings.CameraSun beside the camera (castor.pictures.shade.sun_light);
    the ground at height ``ground`` (by default, the foot of the scene)."""
    width, height = camera.width, camera.height
    low, high = traced.box
    if ground is None:
        ground = float(low[2])
    size = float(np.linalg.norm(high - low)) or 1.0
    light, shadows = shade.sun_light(sun, camera)
    tracer = _Tracer(traced, camera, light, shadows, ground, size)
    # one ray through each pixel's centre, tile by tile
    order = _tile_order(width, height)
    xs = (order % width) + 0.5
    ys = (order // width) + 0.5
    centre = tracer.trace(xs, ys)
    image = np.empty((height * width, 3))
    image[order] = centre.colour
    key = np.empty(height * width, np.int64)
    key[order] = centre.key
    depth = np.empty(height * width)
    depth[order] = centre.depth
    lit = np.empty(height * width, bool)
    lit[order] = centre.lit
    normal = np.empty((height * width, 3))
    normal[order] = centre.normal
    key, depth, lit = (a.reshape(height, width) for a in (key, depth, lit))
    normal = normal.reshape(height, width, 3)
    # with --edges, the samples of a pixel on a k x k grid, so that the edges
    # are found on the finer grid and come out anti-aliased
    k = max(2, round(samples ** 0.5)) if edges and samples > 1 else 1
    fine = _Fine(key, depth, normal, k) if k > 1 else None
    if samples > 1:
        rough = _differs(key, lit, depth, normal)
        pixels = np.flatnonzero(rough.ravel())
        pixels = pixels[np.argsort(_tile_of(pixels, width), kind="stable")]
        if len(pixels):
            if fine is not None:
                offsets = [((i + 0.5) / k, (j + 0.5) / k) for j in range(k) for i in range(k)]
            else:
                offsets = sample_offsets(samples)
            total = np.zeros((len(pixels), 3))
            px, py = pixels % width, pixels // width
            for number, (dx, dy) in enumerate(offsets):
                seen = tracer.trace(px + dx, py + dy)
                total += seen.colour
                if fine is not None:
                    fine.put(px, py, number % k, number // k, seen)
            image[pixels] = total / len(offsets)
    image = image.reshape(height, width, 3)
    if edges:
        strength = fine.edges() if fine is not None else shade.edges(key, depth, normal)
        image = image * (1 - strength[..., None]) + shade.EDGE_COLOUR * strength[..., None]
    return np.clip(np.rint(image * 255), 0, 255).astype(np.uint8)


class _Fine:
    """Surface numbers, depths and normals on a grid k times finer than the
    pixels: a pixel's centre sample everywhere, its own samples where it was
    traced again; the edges found there are averaged back to the pixels."""

    def __init__(self, key, depth, normal, k: int):
        self.k = k
        self.key = np.repeat(np.repeat(key, k, axis=0), k, axis=1)
        self.depth = np.repeat(np.repeat(depth.astype(np.float32), k, axis=0), k, axis=1)
        self.normal = np.repeat(np.repeat(normal.astype(np.float32), k, axis=0), k, axis=1)

    def put(self, px, py, i: int, j: int, seen: "_Samples") -> None:
        rows, cols = py * self.k + j, px * self.k + i
        self.key[rows, cols] = seen.key
        self.depth[rows, cols] = seen.depth
        self.normal[rows, cols] = seen.normal

    def edges(self) -> np.ndarray:
        k = self.k
        strength = shade.edges(self.key, self.depth, self.normal)
        # lines k fine cells wide: one pixel, spread over the pixels they cross
        for _ in range(k - 1):
            strength[:-1] = np.maximum(strength[:-1], strength[1:])
            strength[:, :-1] = np.maximum(strength[:, :-1], strength[:, 1:])
        h, w = strength.shape[0] // k, strength.shape[1] // k
        return strength.reshape(h, k, w, k).mean(axis=(1, 3))


def _tile_of(pixels: np.ndarray, width: int) -> np.ndarray:
    tiles_across = (width + TILE - 1) // TILE
    return (pixels // width // TILE) * tiles_across + (pixels % width) // TILE


def _tile_order(width: int, height: int) -> np.ndarray:
    """Pixel numbers tile by tile."""
    pixels = np.arange(width * height)
    return pixels[np.argsort(_tile_of(pixels, width), kind="stable")]


def _differs(key, lit, depth, normal) -> np.ndarray:
    """Pixels that differ from a neighbour: another surface, light, or a step in depth."""
    rough = np.zeros(key.shape, bool)
    for a, b in (((slice(None, -1), slice(None)), (slice(1, None), slice(None))),
                 ((slice(None), slice(None, -1)), (slice(None), slice(1, None)))):
        with np.errstate(invalid="ignore"):
            step = np.abs(depth[a] - depth[b]) > 0.01 * np.minimum(depth[a], depth[b])
        d = (key[a] != key[b]) | (lit[a] != lit[b]) | step
        rough[a] |= d
        rough[b] |= d
    return rough


class _Tracer:
    def __init__(self, traced: TracedTree, camera: Camera, light, shadows: bool, ground: float,
                 size: float):
        self.traced, self.camera = traced, camera
        self.light, self.shadows = light, shadows
        self.ground, self.size = ground, size
        if camera.orthographic:
            self.view = Projection(None, camera.forward, camera.right, camera.up)
        else:
            self.view = Projection(camera.eye, camera.forward, camera.right, camera.up)
        self.sun = Projection(None, light)

    def trace(self, xs: np.ndarray, ys: np.ndarray) -> _Samples:
        out = _Samples(len(xs))
        for start in range(0, len(xs), CHUNK):
            part = slice(start, start + CHUNK)
            self._trace(xs[part], ys[part], out, part)
        return out

    def _trace(self, xs, ys, out: _Samples, part: slice) -> None:
        traced = self.traced
        origins, directions = self.camera.rays(xs, ys)
        t, face = traced.first_hit(origins, directions, 0.0, self.view)
        n = len(xs)
        colour = np.tile(shade.BACKGROUND, (n, 1))
        key = np.full(n, -1, np.int64)
        normal = np.zeros((n, 3))
        lit = np.ones(n, bool)
        hit = np.flatnonzero(np.isfinite(t))
        points = origins[hit] + t[hit, None] * directions[hit]
        normals = traced.normals(points, face[hit])
        facing = np.einsum("ij,ij->i", normals, directions[hit])
        normals[facing > 0] *= -1
        # the ground at the foot of the scene, where the rays miss the solids
        dz = directions[:, 2]
        with np.errstate(divide="ignore", invalid="ignore"):
            tg = (self.ground - origins[:, 2]) / dz
        on_ground = np.flatnonzero(~np.isfinite(t) & (dz < 0) & (tg > 0))
        if self.shadows:
            eps = 1e-6 * self.size
            # a face turned away from the sun is in its own shadow: no ray needed
            towards = normals @ self.light > 0
            lit_hit = towards.copy()
            lit_hit[towards] = ~self._blocked(points[towards] + normals[towards] * eps)
            ground_points = origins[on_ground] + tg[on_ground, None] * directions[on_ground]
            ground_points[:, 2] += eps
            lit_ground = ~self._blocked(ground_points)
            lit[hit], lit[on_ground] = lit_hit, lit_ground
            shadowed = on_ground[~lit_ground]
            colour[shadowed] = shade.GROUND_SHADOW
            key[shadowed] = -2
        else:
            lit_hit = np.ones(len(hit), bool)
        strength = shade.intensity(normals, -directions[hit], self.light, lit_hit)
        colour[hit] = traced.colours(face[hit]) * strength[:, None]
        key[hit] = traced.surface_keys(face[hit])
        normal[hit] = normals
        depth = np.full(n, np.inf)
        depth[hit] = t[hit]
        out.colour[part], out.key[part], out.depth[part] = colour, key, depth
        out.normal[part], out.lit[part] = normal, lit

    def _blocked(self, points: np.ndarray) -> np.ndarray:
        if len(points) == 0:
            return np.zeros(0, bool)
        directions = np.broadcast_to(self.light, points.shape).copy()
        return self.traced.blocked(points, directions, 0.0, self.sun)
