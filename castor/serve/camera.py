"""``POST /camera`` on the live preview's server: the page's camera, once it
stops (CLI.md, "Live preview"), for which the frames are faceted again
(castor.serve.evaluation.refaceted).

A request is ``{"eye": [x, y, z], "target": [x, y, z], "up": [x, y, z],
"fov": degrees (vertical), "width": pixels, "height": pixels,
"orthographic": false, "server": name}``: where the page's camera stands and
looks, and the size of its view in pixels (orthographic: the picture's half
height is the distance to the target times tan(fov / 2), as the page draws it);
``server``, the name of the castor --serve the page was loaded from (another's
page is refused). The answer comes once the frames faceted for that camera are
shown, or after CAMERA_WAIT seconds: ``{"version": N}``, the version then shown.
Anything else is refused with a message (400), never a traceback.
"""

from __future__ import annotations

import json
import math

CAMERA_WAIT = 5.0  # seconds a request waits for the frames faceted for it
MAX_BODY = 4096
MAX_PIXELS = 16384  # a side of the page's view, at most


class CameraError(ValueError):
    """A camera request the page should not have sent: what is wrong with it."""


def answer_post(preview, body: bytes) -> tuple[int, bytes]:
    """The HTTP status and the JSON answer to a camera request for ``preview``
    (castor.serve.server.Preview)."""
    try:
        request = json.loads(body or b"null")
        camera = page_camera(request)
    except CameraError as exc:
        return 400, json.dumps({"error": str(exc)}).encode()
    except (ValueError, RecursionError):
        return 400, json.dumps({"error": "the request is not JSON"}).encode()
    if request.get("server", preview.name) != preview.name:
        return 409, json.dumps({"error": "this page is another castor --serve's: "
                                         "load it again"}).encode()
    return 200, json.dumps({"version": preview.look(camera, CAMERA_WAIT)}).encode()


def page_camera(request):
    """The camera (castor.pictures.camera.Camera) of a ``POST /camera`` request:
    ``{"eye": [x, y, z], "target": [x, y, z], "up": [x, y, z], "fov": degrees
    (vertical), "width": pixels, "height": pixels, "orthographic": false}``
    (orthographic: the picture's half height is the distance to the target
    times tan(fov / 2), as the page draws it). CameraError says what is wrong."""
    import numpy as np

    from castor.pictures.camera import Camera

    if not isinstance(request, dict):
        raise CameraError('send one JSON object: {"eye": [x, y, z], "target": [x, y, z], '
                          '"up": [x, y, z], "fov": degrees, "width": pixels, "height": pixels}')
    eye, target, up = (_vector(request, name) for name in ("eye", "target", "up"))
    fov = _number(request, "fov")
    if not 0 < fov < 180:
        raise CameraError(f"'fov' is the vertical field of view in degrees, between 0 and 180 "
                          f"(not {fov:g})")
    width, height = (_pixels(request, name) for name in ("width", "height"))
    orthographic = request.get("orthographic", False)
    if not isinstance(orthographic, bool):
        raise CameraError("'orthographic' is true or false")
    forward = np.array(target) - np.array(eye)
    distance = float(np.linalg.norm(forward))
    if not distance > 0:
        raise CameraError("'eye' and 'target' are one point: the camera looks nowhere")
    forward /= distance
    right = np.cross(forward, np.array(up))
    if not float(np.linalg.norm(right)) > 1e-9 * max(1.0, float(np.linalg.norm(up))):
        raise CameraError("'up' is along the line of sight (or zero)")
    right /= np.linalg.norm(right)
    half = distance * math.tan(math.radians(fov) / 2) if orthographic else None
    if half is not None and not (math.isfinite(half) and half > 0):
        raise CameraError("the orthographic picture is of no size")
    return Camera(np.array(eye), forward, right, np.cross(right, forward), width, height,
                  fov, half)


def _number(request: dict, name: str) -> float:
    value = request.get(name)
    if isinstance(value, bool) or not isinstance(value, (int, float)) \
            or not math.isfinite(value) or abs(value) > 1e15:
        raise CameraError(f"'{name}' is a number (not {json.dumps(value)[:40]})")
    return float(value)


def _vector(request: dict, name: str) -> tuple[float, float, float]:
    value = request.get(name)
    if not isinstance(value, list) or len(value) != 3:
        raise CameraError(f"'{name}' is three numbers [x, y, z] (not {json.dumps(value)[:40]})")
    return tuple(_number({name: v}, name) for v in value)


def _pixels(request: dict, name: str) -> int:
    value = request.get(name)
    if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= MAX_PIXELS:
        raise CameraError(f"'{name}' is a whole number of pixels from 1 to {MAX_PIXELS} "
                          f"(not {json.dumps(value)[:40]})")
    return value
