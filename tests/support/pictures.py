"""Pictures made in this process (``draw``), the camera castor chooses for a
scene, and the pixels a picture covers."""

from __future__ import annotations

import numpy as np

from castor.pictures import picture
from castor.pictures.camera import make_camera
from castor.pictures.trace import compile_frame
from castor.run import evaluated_frames
from castor.settings import PictureSettings


WHITE = 255


def scene_frames(text, name="<scene>", defines=()):
    """The frames' trees; the scene must have no error."""
    frames, said = evaluated_frames(text, name, defines=defines)
    assert "error" not in said, said
    return frames


def draw(text: str, **options) -> np.ndarray:
    spec = PictureSettings(**{"size": (160, 120), "sun": None, **options})
    return picture(scene_frames(text)[0], spec)


def camera_of(text: str, **options):
    spec = PictureSettings(**{"size": (160, 120), **options})
    low, high = compile_frame(scene_frames(text)[0]).box
    return make_camera(low, high, spec.size, spec.view, spec.eye, spec.look)


def covered(image: np.ndarray) -> np.ndarray:
    return np.any(image != WHITE, axis=2)
