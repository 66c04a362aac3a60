"""Where rays are inside each unit primitive, computed on its exact surface.

Each primitive declares its own spans and normals (``castor.primitives``;
what they compute is described in ``castor.primitives.rays``): this is the
ray tracer's way in, by kind.
"""

from __future__ import annotations

from castor.primitives import PRIMITIVES

SPANS = PRIMITIVES  # kind -> its spans(shape, o, d), normal(shape, p, face), box(shape)
