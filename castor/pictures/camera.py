"""Cameras of castor's pictures and castor-view: one definition, so that both
draw the same frame from the same place (CLI.md, the picture options).

A ``Camera`` maps picture coordinates (x to the right, y down, in pixels, the
centre of pixel (i, j) at (i + 0.5, j + 0.5)) to rays, and scene points back to
the picture: perspective (``fov`` the vertical field of view) or orthographic
(``half_height`` the half height of the picture in scene units).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

FIELD_OF_VIEW = 35.0  # degrees, vertical
MARGIN = 0.94  # the framed scene fills this much of the picture

@dataclass(frozen=True)
class Camera:
    eye: np.ndarray  # perspective: the eye; orthographic: the picture's centre, before the scene
    forward: np.ndarray  # unit vector looked along
    right: np.ndarray
    up: np.ndarray
    width: int
    height: int
    fov: float = FIELD_OF_VIEW  # perspective: vertical field of view in degrees
    half_height: float | None = None  # orthographic: half the picture's height, scene units

    @property
    def orthographic(self) -> bool:
        return self.half_height is not None

    @property
    def scale(self) -> float:
        """Pixels per unit: on the picture plane at distance 1 (perspective),
        or per scene unit (orthographic)."""
        if self.orthographic:
            return (self.height / 2) / self.half_height
        return (self.height / 2) / math.tan(math.radians(self.fov) / 2)

    def rays(self, x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Origins and unit directions (each (n, 3)) of the rays through the
        picture points (x, y), in pixels."""
        u = (np.asarray(x, dtype=np.float64) - self.width / 2) / self.scale
        v = (self.height / 2 - np.asarray(y, dtype=np.float64)) / self.scale
        if self.orthographic:
            origins = self.eye + u[:, None] * self.right + v[:, None] * self.up
            directions = np.broadcast_to(self.forward, origins.shape).copy()
            return origins, directions
        directions = self.forward + u[:, None] * self.right + v[:, None] * self.up
        directions /= np.linalg.norm(directions, axis=1, keepdims=True)
        return np.broadcast_to(self.eye, directions.shape).copy(), directions

    def project(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Picture coordinates (n, 2) of scene points, and their depth along ``forward``."""
        rel = np.asarray(points, dtype=np.float64) - self.eye
        x, y, z = rel @ self.right, rel @ self.up, rel @ self.forward
        if self.orthographic:
            sx, sy = x, y
        else:
            safe = np.where(z > 1e-9, z, 1e-9)
            sx, sy = x / safe, y / safe
        return np.column_stack([self.width / 2 + sx * self.scale,
                                self.height / 2 - sy * self.scale]), z


def _basis(forward: np.ndarray, up: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    forward = forward / np.linalg.norm(forward)
    right = np.cross(forward, up)
    if np.linalg.norm(right) < 1e-9:
        right = np.cross(forward, np.array([0.0, 1.0, 0.0]))
    right /= np.linalg.norm(right)
    return forward, right, np.cross(right, forward)


def direction(azimuth: float, elevation: float) -> np.ndarray:
    """The unit vector towards (azimuth around z from +x, elevation above the horizon)."""
    a, e = math.radians(azimuth), math.radians(elevation)
    return np.array([math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)])


def _corners(low, high) -> np.ndarray:
    return np.array([[x, y, z] for x in (low[0], high[0]) for y in (low[1], high[1])
                     for z in (low[2], high[2])], dtype=np.float64)


def make_camera(low, high, size: tuple[int, int], view=None, eye=None, look=None) -> Camera:
    """The camera of the picture options: ``view`` a castor.settings.View (or
    None: the default direction), or an explicit ``eye`` and ``look``; the
    named views are orthographic, every camera but --eye frames the box
    (``low``, ``high``) of the scene."""
    from castor.settings import DEFAULT_VIEW, ORTHOGRAPHIC

    width, height = size
    low = np.asarray(low, dtype=np.float64)
    high = np.asarray(high, dtype=np.float64)
    if not (np.all(np.isfinite(low)) and np.all(np.isfinite(high)) and np.all(high >= low)):
        low, high = np.zeros(3), np.zeros(3)
    z_up = np.array([0.0, 0.0, 1.0])
    if eye is not None and look is not None:
        eye, look = np.asarray(eye, dtype=np.float64), np.asarray(look, dtype=np.float64)
        if np.linalg.norm(look - eye) == 0:
            look = eye + np.array([1.0, 0.0, 0.0])
        forward, right, up = _basis(look - eye, z_up)
        return Camera(eye, forward, right, up, width, height)
    centre = (low + high) / 2
    corners = _corners(low, high) - centre
    radius = max(float(np.linalg.norm(high - low)) / 2, 1e-6)
    if view is not None and view.name is not None:
        axes = ORTHOGRAPHIC[view.name]
        forward, right, up = _basis(-np.array(axes.towards, dtype=np.float64),
                                    np.array(axes.up, dtype=np.float64))
        across, along = corners @ right, corners @ up
        aspect = width / height
        half = max(float(np.max(np.abs(along))), float(np.max(np.abs(across))) / aspect, 1e-6)
        return Camera(centre - forward * radius * 4, forward, right, up, width, height,
                      half_height=half / MARGIN)
    azimuth, elevation = (view.azimuth, view.elevation) if view is not None else DEFAULT_VIEW
    forward, right, up = _basis(-direction(azimuth, elevation), z_up)
    tan_v = math.tan(math.radians(FIELD_OF_VIEW) / 2) * MARGIN
    tan_h = tan_v * width / height
    distance = radius * 3
    for _ in range(3):  # fit, move sideways to centre the picture, and fit again
        rel = _corners(low, high) - centre
        across, along, depth = rel @ right, rel @ up, rel @ forward
        distance = float(np.max(np.maximum(np.abs(across) / tan_h, np.abs(along) / tan_v)
                                - depth))
        distance = max(distance, radius * 0.5, 1e-6)
        u, v = across / (distance + depth), along / (distance + depth)
        centre = centre + (right * (u.max() + u.min()) / 2
                           + up * (v.max() + v.min()) / 2) * distance
    return Camera(centre - forward * distance, forward, right, up, width, height)
