"""Light for presentation: the sun, a soft sky, and outline edges.

A face takes its own colour times an intensity: a sky term (more from above),
a term for facing the viewer and the sun's (zero in shadow), capped at 1, so
that a lit face turned to the viewer shows its own colour at full strength
while faces in shadow keep their colour, darker. With ``--sun none`` a light
over the viewer's shoulder, without shadows, tells the faces of a box apart.
"""

from __future__ import annotations

import numpy as np

BACKGROUND = np.array([1.0, 1.0, 1.0])
GROUND_SHADOW = np.array([0.78, 0.79, 0.82])  # the ground in shadow (lit: the background)
EDGE_COLOUR = np.array([0.12, 0.12, 0.14])

SKY, FACING, SUN = 0.10, 0.22, 0.55
BASE = 0.42


def intensity(normals: np.ndarray, towards_viewer: np.ndarray, light: np.ndarray,
              lit: np.ndarray) -> np.ndarray:
    """How much of its own colour a surface shows (0..1), for unit normals
    turned to the viewer, unit vectors to the viewer, the unit vector to the
    light, and whether the light reaches each point."""
    sky = 0.5 + 0.5 * normals[:, 2]
    facing = np.clip(np.einsum("ij,ij->i", normals, towards_viewer), 0, 1)
    sun = np.clip(normals @ light, 0, 1) * lit
    return np.clip(BASE + SKY * sky + FACING * facing + SUN * sun, 0, 1)


def sun_light(sun, camera) -> tuple[np.ndarray, bool]:
    """The unit vector towards the light of a picture, and whether it casts shadows.

    ``sun`` is ``(azimuth, elevation)`` (``--sun AZ,EL``), None (``--sun none``:
    a light over the viewer's shoulder, no shadows) or a castor.settings.CameraSun,
    the default: the sun ``turn`` degrees beside the camera's azimuth, so that every
    face the camera sees is lit and the shadows fall back and to the side. The
    camera's azimuth is that of the direction from the point looked at to the eye,
    for --view AZ,EL (AZ itself), --eye/--look and the orthographic elevations
    alike; a camera looking straight down or up (top, bottom) takes the direction
    from the picture's middle to its bottom edge (south for a plan)."""
    from castor.pictures.camera import direction

    if sun is None:
        return shoulder_light(camera.right, camera.up, camera.forward), False
    if hasattr(sun, "turn"):
        back = -np.asarray(camera.forward, dtype=np.float64)
        if np.hypot(back[0], back[1]) < 1e-6:
            back = -np.asarray(camera.up, dtype=np.float64)
        azimuth = np.degrees(np.arctan2(back[1], back[0]))
        return direction(float(azimuth) + sun.turn, sun.elevation), True
    return direction(*sun), True


def shoulder_light(right: np.ndarray, up: np.ndarray, forward: np.ndarray) -> np.ndarray:
    """A light from over the viewer's left shoulder, for pictures without a sun."""
    light = -forward * 0.55 + up * 0.65 - right * 0.45
    return light / np.linalg.norm(light)


def edges(key: np.ndarray, depth: np.ndarray, normals: np.ndarray) -> np.ndarray:
    """(H, W) strengths 0..1 of outline edges from per-pixel surface numbers
    (-1: nothing; equal on one flat face or one curved surface of one
    primitive), depths and normals: a silhouette where the surface ends or
    the depth jumps, a crease where two surfaces meet (castor.mesh.creases);
    never between two coplanar pieces of a face, whatever primitives they
    come from, nor within one curved surface, however fast it turns."""
    from castor.mesh.creases import creases

    h, w = key.shape
    strength = np.zeros((h, w), np.float32)
    hit = key >= 0
    for axis in (0, 1):
        a = (slice(None, -1), slice(None)) if axis == 0 else (slice(None), slice(None, -1))
        b = (slice(1, None), slice(None)) if axis == 0 else (slice(None), slice(1, None))
        ha, hb = hit[a], hit[b]
        da, db = depth[a], depth[b]
        near = np.minimum(np.where(ha, da, np.inf), np.where(hb, db, np.inf))
        with np.errstate(invalid="ignore"):
            jump = np.abs(da - db) > 0.02 * near + 1e-9
        turn = creases(np.einsum("ijk,ijk->ij", normals[a], normals[b]), key[a] == key[b])
        line = (ha != hb) | (ha & hb & (jump | turn))
        # draw on the nearer side, so that a silhouette sits on the object
        a_nearer = np.where(ha & ~hb, True, np.where(hb & ~ha, False, da <= db))
        strength[a] = np.maximum(strength[a], line & a_nearer)
        strength[b] = np.maximum(strength[b], line & ~a_nearer)
    return strength
