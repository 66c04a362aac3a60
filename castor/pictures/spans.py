"""Where rays are inside each unit primitive, computed on its exact surface.

Each primitive declares its own spans and normals (``castor.primitives``;
what they compute is described in ``castor.primitives.rays``): this is the
ray tracer's way in, by kind.
"""

from __future__ import annotations

from castor.primitives import PRIMITIVES



class _MeshSpans:
    """A smooth solid's way in (LANGUAGE.md §7.1; not a primitive the user
    writes): its shape is its refined facets, ready for rays
    (castor.pictures.mesh_rays.MeshRays), its box theirs."""

    @staticmethod
    def spans(rays, o, d):
        return rays.spans(o, d)

    @staticmethod
    def normal(rays, p, face):
        return rays.normal(p, face)

    @staticmethod
    def box(rays):
        return rays.box()


# kind -> its spans(shape, o, d), normal(shape, p, face), box(shape): each
# primitive, and the leaves of smooth solids (castor.pictures.mesh_rays)
SPANS = {**PRIMITIVES, "smooth": _MeshSpans}
