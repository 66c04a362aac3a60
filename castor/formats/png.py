"""PNG: one ray-traced picture (Pillow, imported only when a picture is written)."""

from __future__ import annotations

import io

from castor.formats import Format


def export_picture(image) -> bytes:
    """The (H, W, 3) uint8 picture as PNG bytes."""
    from PIL import Image

    buffer = io.BytesIO()
    Image.fromarray(image, "RGB").save(buffer, format="PNG", optimize=False, compress_level=6)
    return buffer.getvalue()


FORMATS = (Format("png", (".png",), "picture", "a ray-traced picture of the exact solids",
                  export_picture, listed=70),)
