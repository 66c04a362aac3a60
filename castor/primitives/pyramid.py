"""``!py``: the pyramid on the regular N-gon base of ``!pr`` in z = 0, apex
(0, 0, 1): every face flat; a ray meets it as N + 1 half-spaces."""

from __future__ import annotations

from castor.primitives import rays
from castor.primitives.base import PrimitiveKind
from castor.primitives.cylinder import ROUND
from castor.primitives.facets import spire
from castor.primitives.prism import SIDES, check_sides


PRIMITIVE = PrimitiveKind(
    place=70, name="py", title="pyramid", solid="a regular N-gon base of circumradius 1, apex (0, 0, 1)",
    arguments=(SIDES,), pair_names=None, curved=False, check=check_sides,
    box=lambda shape: ROUND, mesh=lambda shape, facets: spire(int(shape[0])),
    triangles=lambda shape, facets: 4 * int(shape[0]),
    spans=rays.polygon_spans(True), normal=rays.polygon_normal(True))
