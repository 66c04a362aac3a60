"""The live preview's page in Debian's chromium (playwright): the browser's
flags and page size, screenshots as pixels, pixels of a hue, and waiting for
the page's next version."""

from __future__ import annotations

import io

import numpy as np


CHROMIUM = "/usr/bin/chromium"


FLAGS = ["--headless", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--no-first-run", "--disable-gpu-sandbox"]


WIDTH, HEIGHT, BAR = 900, 650, 38  # the page, and its bar of controls at the top


def picture(page, name: str) -> np.ndarray:
    """The view (below the bar), as RGB; also kept in /tmp to be looked at."""
    from PIL import Image

    png = page.screenshot()
    with open(f"/tmp/castor-serve-{name}.png", "wb") as handle:
        handle.write(png)
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"))[BAR:].astype(int)


def drawn(image: np.ndarray) -> np.ndarray:
    """Pixels that are not the white background."""
    return np.any(image < 245, axis=2)


def outline(image: np.ndarray, bottom: int = 0) -> np.ndarray:
    """Drawn pixels, leaving out the status and the pointed face's box (at the top)
    and ``bottom`` rows (where the list of errors is)."""
    return drawn(image)[80:image.shape[0] - bottom]


def near(image: np.ndarray, colour, tolerance: float = 0.1) -> np.ndarray:
    """Pixels of this hue, at any light: their colour over its brightest channel."""
    rgb = image / np.maximum(image.max(axis=2, keepdims=True), 1)
    target = np.array(colour) / max(colour)
    return np.all(np.abs(rgb - target) < tolerance, axis=2) & (image.max(axis=2) > 60)


def next_version(page, version: str, seconds: float = 10) -> str:
    page.wait_for_function("(seen) => document.body.dataset.version !== seen", arg=version,
                           timeout=seconds * 1000)
    return page.evaluate("document.body.dataset.version")


ROOF, REVEAL, GREEN = (0.70, 0.28, 0.18), (0.25, 0.45, 0.85), (0.15, 0.65, 0.25)


def well_inside(mask: np.ndarray, margin: int, least: int) -> tuple[int, int]:
    """A page point of the pixels of ``mask`` (a picture of the view, below the
    bar) at least ``margin`` pixels from their edges; ``least`` such pixels expected."""
    inner = mask.copy()
    for dy in (-margin, 0, margin):
        for dx in (-margin, 0, margin):
            inner &= np.roll(np.roll(mask, dy, axis=0), dx, axis=1)
    ys, xs = np.nonzero(inner)
    assert len(ys) > least
    return int(xs[len(xs) // 2]), int(ys[len(ys) // 2]) + BAR


def inside_reveal(image: np.ndarray) -> tuple[int, int]:
    """A point of the page well inside the blue window reveals of a picture of the
    view (away from their edges), in page pixels."""
    return well_inside(near(image, REVEAL), 2, 20)


def painted(page) -> None:
    """Wait until the page has drawn what it was last told (two animation
    frames later, so that the screenshot shows it): a state, not a time."""
    page.evaluate("() => new Promise(done => requestAnimationFrame(() => requestAnimationFrame(done)))")
