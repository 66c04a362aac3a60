"""One declaration per primitive and transformation, read by every stage."""

import re
from pathlib import Path

from castor.csg.transforms import MATRICES
from castor.language.vocabulary import PRIMITIVES, TRANSFORMS
from castor.mesh.primitives import BUILDERS
from meshcheck import run

ROOT = Path(__file__).resolve().parent.parent


def test_every_primitive_is_built_and_every_transformation_has_its_matrix():
    assert set(BUILDERS) == set(PRIMITIVES)
    assert set(MATRICES) | {"f", "s"} == set(TRANSFORMS)


def test_vim_syntax_knows_exactly_the_vocabulary():
    syntax = (ROOT / "vim" / "syntax" / "castor.vim").read_text()
    primitives = re.search(r'castorPrimitive "!\\\((.*?)\\\)', syntax).group(1).split("\\|")
    transforms = re.search(r'castorTransform "@\\\((.*?)\\\)', syntax).group(1).split("\\|")
    assert sorted(primitives) == sorted(PRIMITIVES)
    assert sorted(transforms) == sorted(TRANSFORMS)


def test_argument_counts_come_from_the_declaration():
    status, out, err = run("--no-cpp", stdin="> !to(1, 0, 0);\n> @r(1, 2, 3) !cu(1, 0, 0);\n")
    assert status == 1
    assert "'!to' takes 4 arguments (R, G, B, K), but 3 were given" in err
    assert "'@r' takes 4 arguments (X, Y, Z, A), but 3 were given" in err
    status, out, err = run("--no-cpp", stdin="> !ex(1, 0, 0, 0, 0, 1, 0);\n")
    assert "'!ex' takes at least 9 arguments (R, G, B, x1, y1, x2, y2, x3, y3, ...)" in err
