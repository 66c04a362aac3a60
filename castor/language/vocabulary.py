"""The vocabulary of the language: every primitive, transformation and boolean.

Each primitive is declared once, in its own module of ``castor.primitives``
(name, arguments, checks, unit box, mesh, ray spans); each transformation in
``castor.transformations`` (name, arguments, matrix). This module is where the
parser and the editor files find them all by name.
"""

from __future__ import annotations

from castor.primitives import PRIMITIVES, Argument, PrimitiveKind
from castor.transformations import TRANSFORMS, Transformation

# the names the rest of castor knew them by
TransformKind = Transformation

BOOLEANS = {"U": "union", "I": "intersection", "D": "difference"}

__all__ = ["BOOLEANS", "PRIMITIVES", "TRANSFORMS", "Argument", "PrimitiveKind", "TransformKind",
           "vim_syntax"]


def vim_syntax() -> list[str]:
    """The lines of vim/syntax/castor.vim that name the primitives and the
    transformations (scripts/vim_syntax.py writes them there)."""
    return ['syn match castorPrimitive "!\\(' + "\\|".join(PRIMITIVES) + '\\)\\>"',
            'syn match castorTransform "@\\(' + "\\|".join(TRANSFORMS) + '\\)\\>"']
