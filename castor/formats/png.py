"""PNG: one ray-traced picture (Pillow, imported only when a picture is written)."""

from __future__ import annotations

import io
from typing import Iterator

from castor.formats import WriteInfo


def export_picture(image) -> bytes:
    """The (H, W, 3) uint8 picture as PNG bytes."""
    from PIL import Image

    buffer = io.BytesIO()
    Image.fromarray(image, "RGB").save(buffer, format="PNG", optimize=False, compress_level=6)
    return buffer.getvalue()


def write(image, info: WriteInfo) -> Iterator[bytes]:
    """The registry's writer (castor.formats): the picture as one piece."""
    return iter([export_picture(image)])
