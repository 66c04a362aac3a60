"""The default sun lights every face the camera sees (CLI.md, issue 18 item 12).

The sun stands at the camera's azimuth + 20 degrees and 45 degrees high: for a
perspective --view AZ,EL at AZ + 20; for --eye/--look and the orthographic views
at the azimuth of the direction from the look point to the eye + 20 (for top and
bottom, which look straight down or up, from the picture's middle towards its
bottom edge: the sun stands south-south-west of a plan). Checked by pixels: the
façades of a white box are brighter than the shadow the box casts on the ground.
"""

import subprocess
import sys

import numpy as np
import pytest

from castor.settings import DEFAULT_SUN, View
from castor.pictures import picture
from castor.pictures.camera import make_camera
from castor.pictures.shade import GROUND_SHADOW, sun_light
from castor.pictures.trace import compile_frame
from castor.run import evaluated_frames
from castor.settings import PictureSettings

BOX = "> @h(2, 2, 1.5) !cu(1, 1, 1);\n"
SHADOW = np.round(GROUND_SHADOW * 255)
LIT = 0.75 * 765  # a lit white face: at least this sum of R, G and B


def frame_of(text):
    frames, said = evaluated_frames(text, "<box>")
    assert "error" not in said, said
    return frames[0]


def default_picture(**options):
    """The box drawn with the default sun (the settings' default, as the command's)."""
    spec = PictureSettings(**{"size": (320, 240), "samples": 1, **options})
    assert spec.sun == DEFAULT_SUN
    frame = frame_of(BOX)
    image = picture(frame, spec).astype(int)
    low, high = compile_frame(frame).box
    camera = make_camera(low, high, spec.size, spec.view, spec.eye, spec.look)
    return image, camera


def brightness_at(image, camera, point):
    (x, y), = camera.project(np.array([point], dtype=float))[0]
    return image[int(y), int(x)].sum()


def shadow_brightness(image):
    """The ground in the box's shadow: pixels of the shadow's colour; there must be some."""
    shadow = np.all(np.abs(image - SHADOW) <= 4, axis=2)
    assert shadow.sum() > 20, "no shadow on the ground"
    return np.median(image[shadow].sum(axis=1))


def test_both_facades_the_default_camera_sees_are_lit():
    image, camera = default_picture()
    ground = shadow_brightness(image)
    south = brightness_at(image, camera, (1.0, 0.0, 0.75))  # the face towards -y
    east = brightness_at(image, camera, (2.0, 1.0, 0.75))  # the face towards +x
    assert south > ground + 10 and east > ground + 10, (south, east, ground)
    # and each shows its colour nearly at full strength, as a lit face does (in
    # shadow, as the old default sun left them, they were about 0.64 of it)
    assert south > LIT and east > LIT, (south, east)


# each perspective view sees two faces, 30 degrees to one side and 60 to the
# other, as the default view does
@pytest.mark.parametrize("view, faces", [
    (View(None, 30.0, 20.0), [(2.0, 1.0, 0.75), (1.0, 2.0, 0.75)]),  # sees +x and +y
    (View(None, 120.0, 30.0), [(0.0, 1.0, 0.75), (1.0, 2.0, 0.75)]),  # sees -x and +y
    (View(None, -150.0, 20.0), [(0.0, 1.0, 0.75), (1.0, 0.0, 0.75)]),  # sees -x and -y
    (View("front", 0, 0), [(1.0, 0.0, 0.75)]),
    (View("left", 0, 0), [(0.0, 1.0, 0.75)]),
    (View("back", 0, 0), [(1.0, 2.0, 0.75)]),
])
def test_the_sun_follows_the_camera(view, faces):
    image, camera = default_picture(view=view)
    for point in faces:
        assert brightness_at(image, camera, point) > LIT, (view, point)


def test_an_explicit_camera_is_followed_too():
    image, camera = default_picture(eye=(-4.0, 9.0, 4.0), look=(1.0, 1.0, 0.5))
    for point in [(0.0, 1.0, 0.75), (1.0, 2.0, 0.75)]:  # the -x and +y faces
        assert brightness_at(image, camera, point) > LIT, point


def test_the_default_suns_direction():
    frame = frame_of(BOX)
    low, high = compile_frame(frame).box
    camera = make_camera(low, high, (320, 240), View(None, -60.0, 25.0))
    light, shadows = sun_light(DEFAULT_SUN, camera)
    a, e = np.radians(-40.0), np.radians(45.0)
    assert shadows
    assert light == pytest.approx([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
    top = make_camera(low, high, (320, 240), View("top", 0, 0))
    a = np.radians(-70.0)  # the bottom of a plan is south (-90), and 20 degrees beside
    assert sun_light(DEFAULT_SUN, top)[0] == pytest.approx(
        [np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])


def test_an_explicit_sun_is_kept():
    frame = frame_of(BOX)
    low, high = compile_frame(frame).box
    camera = make_camera(low, high, (320, 240), View(None, -60.0, 25.0))
    light, _ = sun_light((0.0, 90.0), camera)
    assert light == pytest.approx([0, 0, 1], abs=1e-12)
    assert sun_light(None, camera)[1] is False


def test_the_command_uses_the_default_sun(tmp_path):
    from PIL import Image

    subprocess.run([sys.executable, "-m", "castor", "--no-cpp", "--samples", "1",
                    "--size", "320x240", "-o", str(tmp_path / "box.png")],
                   input=BOX.encode(), check=True, timeout=60)
    image = np.asarray(Image.open(tmp_path / "box.png").convert("RGB")).astype(int)
    expected, _ = default_picture()
    assert np.abs(image - expected).max() <= 1
