"""GIF: every frame of a run as one looping animation (Pillow, imported lazily)."""

from __future__ import annotations

import io
from typing import Iterator

from castor.formats import WriteInfo


FRAME_TIME = 100  # milliseconds per frame


def export_animation(images: list) -> bytes:
    """The (H, W, 3) uint8 pictures as one animated GIF (frames of different
    sizes are padded to the largest)."""
    from PIL import Image

    pictures = [Image.fromarray(image, "RGB") for image in images]
    width = max(p.width for p in pictures)
    height = max(p.height for p in pictures)
    frames = []
    for p in pictures:
        if p.size != (width, height):
            canvas = Image.new("RGB", (width, height), (255, 255, 255))
            canvas.paste(p, (0, 0))
            p = canvas
        frames.append(p.quantize(colors=256, method=Image.Quantize.MEDIANCUT,
                                 dither=Image.Dither.NONE))
    buffer = io.BytesIO()
    if len(frames) == 1:
        frames[0].save(buffer, format="GIF")
    else:
        frames[0].save(buffer, format="GIF", save_all=True, append_images=frames[1:],
                       duration=FRAME_TIME, loop=0)
    return buffer.getvalue()


def write(images: list, info: WriteInfo) -> Iterator[bytes]:
    """The registry's writer (castor.formats): every frame's picture, one animation."""
    return iter([export_animation(images)])
