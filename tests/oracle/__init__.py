"""A differential oracle for castor's geometry (LANGUAGE.md §3-§8).

It generates random valid scenes as Python structures (parameters, a DAG of
named objects, nested transformations with mirrors and ``@m``, nested
``$U/$I/$D``, repetitions, several ``>`` with late binding) over the
primitives whose geometry is known exactly (``!cu !pr !py !we !ex``), prints each
as Castor text for castor, and evaluates the same structure itself, written
apart from castor's modules: its own matrices, its own paths, its own
primitive meshes, manifold3d called directly with the booleans in another
order. Each frame is then judged: volume, box and area against the oracle;
closed and outward; every polygon planar, convex, of positive area, winding
once; no shell of zero volume, no sheet (a polygon with the same side on both
faces); every path names a primitive of the frame, every polygon lies on a
face of that primitive, faces as that face does (outward, or inward where
the path cuts the primitive away an odd number of times) and has its colour.

    python -m tests.oracle --cases 3000 [--seed S] [--batch 40] [--wide] [--exact]

(from the checkout; ``python tests/oracle ...`` works as well). The modules:
``scene`` (the structures and their text), ``solids`` (primitives and
matrices), ``evaluate`` (``Oracle``), ``generate`` (random scenes), ``judge``
(one frame), ``check`` (castor run on many scenes), ``shrink``, ``cli``;
``exact`` (a third opinion from exact booleans) and ``reference_subdivision``
(a plain-Python Catmull-Clark for smooth solids).

``--wide`` mixes in what the random choices above almost never make
(``WideGenerator``): coincident twins (one primitive at one place in two
operands, each inside a boolean of its own, in colours of their own) and
rows of touching cubes turned about slanted axes by angles that are not
multiples of 90°, mirrored, with a pyramid or an extrusion beside them.

It prints the figures and the smallest reproduction of each kind of failure.
"""

from .check import FIGURES, FINER, castor_frames, check_scenes, judged_finer
from .evaluate import NOT_MADE, Oracle, convex_caps, frame_commands, smooth_solid
from .generate import Generator, WideGenerator, scenes
from .judge import (ORACLE_WRONG, UNSURE, closed_defects, faces_the_right_way, has_sheets, judge,
                    kind_of, lies_on_face)
from .scene import (Bool, Param, Prim, Ref, Rep, Scene, Smooth, Tf, expression, number, read_scene,
                    scene_text, text)
from .shrink import shrink
from .solids import (Use, _value, cut_parity, outward_normals, polygon_points, primitive_faces,
                     primitive_solid, step_matrix, without_thin_shells)

__all__ = [name for name in dir() if not name.startswith("__")]
