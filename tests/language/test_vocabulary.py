"""One declaration per primitive and transformation, read by every stage."""

import re
from pathlib import Path

from castor.primitives import PRIMITIVES
from castor.transformations import TRANSFORMS
from castor.mesh.primitives import build
from castor.pictures.spans import SPANS
from tests.support.cli import run
from tests.support.vocabulary import example_shape

ROOT = Path(__file__).resolve().parents[2]


def test_every_primitive_comes_from_its_own_module():
    import castor.primitives as package

    for name, primitive in PRIMITIVES.items():
        assert SPANS[name] is primitive
        module = primitive.mesh.__module__
        assert module.startswith(package.__name__ + "."), module
    places = [p.place for p in PRIMITIVES.values()]
    assert places == sorted(places) and len(set(places)) == len(places)


def test_every_transformation_but_the_tolerance_and_smoothing_has_its_matrix():
    assert {name for name, t in TRANSFORMS.items() if t.matrix is None} == {"f", "s"}


def test_each_mesh_says_which_faces_are_flat():
    # every primitive, with a shape its check accepts; these ones as chosen here
    sizes = {name: example_shape(name) for name in PRIMITIVES}
    sizes.update({"to": (0.3,), "pr": (6,), "py": (5,), "ex": (0, 0, 1, 0, 0, 1),
                  "rv": (0, 0, 1, 0, 1, 1, 0, 1)})
    for name in PRIMITIVES:
        mesh = build(name, sizes[name], 0.1)
        assert len(mesh.surfaces) == mesh.faces.max() + 1, name
        curved = set(mesh.surfaces.tolist()) - {-1}
        assert bool(curved) == PRIMITIVES[name].curved, name
        low, high = PRIMITIVES[name].box(sizes[name])
        assert (mesh.vertices.min(axis=0) >= low).all() and (mesh.vertices.max(axis=0) <= high).all()
    assert build("cy", (), 0.1).surfaces[:2].tolist() == [-1, -1]
    assert set(build("cy", (), 0.1).surfaces[2:].tolist()) == {0}
    # !rv: the level segments sweep flat rings, the others one surface each
    assert sorted(set(build("rv", sizes["rv"], 0.1).surfaces.tolist())) == [-1, 1]


def test_vim_syntax_knows_exactly_the_vocabulary():
    # written by scripts/vim_syntax.py from the declarations
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
