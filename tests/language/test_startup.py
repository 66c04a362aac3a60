"""The parser's tables ship in the package, made at build time (issue 18, item 18).

Building lark's LALR parser from castor.lark took about 0.04 s of a 0.19 s start-up
(more where lark's cache in the temporary directory is cold or unwritable).
setup.py's build step saves the tables beside the grammar in the built package;
castor loads them and never writes into the package at run time; tables made
from another grammar or lark are ignored.
"""

import os
import subprocess
import sys
from pathlib import Path

from lark import Lark

from castor.language import tables
from castor.language.parse import grammar_text

ROOT = Path(__file__).resolve().parents[2]
PROGRAM = "L = 2;\nmur = @t(0, 0, 1) @h(L, 0.2, 3) !cu(0.9, 0.9, 0.8);\n> $D(mur, @t(1, -1, 1) !cu(0, 0, 1));\n"


def test_saved_tables_parse_as_the_grammar_does(tmp_path):
    tables.save(tmp_path / "castor.tables")
    loaded = tables.load(grammar_text(), None, tmp_path / "castor.tables")
    assert loaded is not None
    built = Lark(grammar_text(), **tables.OPTIONS)
    assert loaded.parse(PROGRAM, start="program") == built.parse(PROGRAM, start="program")


def test_tables_of_another_grammar_are_ignored_and_left_alone(tmp_path):
    target = tmp_path / "castor.tables"
    tables.save(target, grammar_text() + "\n// edited\n")
    before = target.read_bytes()
    assert tables.load(grammar_text(), None, target) is None
    assert target.read_bytes() == before
    target.write_bytes(b"castor-lark-tables nonsense\n")
    assert tables.load(grammar_text(), None, target) is None
    assert tables.load(grammar_text(), None, tmp_path / "absent.tables") is None


def test_the_build_ships_the_tables_and_castor_uses_them_without_writing(tmp_path):
    """setup.py's build_py (what `pip install .` runs) puts castor.tables in the
    built package; castor run from there loads them and writes nothing into it."""
    build = tmp_path / "build"
    done = subprocess.run([sys.executable, "setup.py", "-q", "build_py", "--build-lib", str(build)],
                          cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    package = build / "castor" / "language"
    assert (package / "castor.tables").stat().st_size > 1000
    listing = sorted(p.name for p in package.iterdir())
    env = {**os.environ, "PYTHONPATH": str(build)}
    code = ("import castor.language.tables as t, castor.language.parse as p;"
            "assert t.__file__.startswith(%r), t.__file__;"
            "print(t.load(p.grammar_text(), None) is not None)" % str(build))
    check = subprocess.run([sys.executable, "-c", code], env=env, cwd=tmp_path,
                           capture_output=True, text=True, timeout=60)
    assert check.stdout.strip() == "True", check.stderr
    cube = subprocess.run([sys.executable, "-B", "-m", "castor", "--no-cpp"], input="> !cu(1, 0, 0);\n",
                          env=env, cwd=tmp_path, capture_output=True, text=True, timeout=60)
    assert cube.returncode == 0 and "endframe 1 6" in cube.stdout, cube.stderr
    assert sorted(p.name for p in package.iterdir()) == listing


# What castor imports to run, beyond what Python had imported before it (the
# probe's own start): modules a run of that kind has no use for, each of which
# cost start-up time (issue 18, item 18). A module is named with its package
# ("numpy" covers numpy.linalg).
NEVER = ("lark", "trimesh", "PIL", "ifcopenshell", "ezdxf", "reportlab", "cairosvg", "pygls",
         "urllib", "ipaddress", "pathlib", "hashlib", "tempfile", "castor.pictures",
         "castor.drawings", "castor.lsp", "castor.serve", "castor.view")
NOT_FOR = {
    # the stream of a cube: no smooth solid, no key of a shared subtree
    "stream": NEVER + ("castor.mesh.smooth", "castor.mesh.subdivide"),
    # --check makes no mesh: neither numpy nor the engine nor the facetizer
    "check": NEVER + ("numpy", "manifold3d", "castor.mesh"),
    # ... nor with turns, scales and a named object (whose key hashlib makes)
    "check a scene": tuple(n for n in NEVER if n != "hashlib") + ("numpy", "manifold3d",
                                                                  "castor.mesh"),
    "version": NEVER + ("numpy", "manifold3d", "castor.mesh", "castor.language", "castor.csg",
                        "dataclasses"),
}

IMPORTS = """
import sys
before = set(sys.modules)
from castor import cli
try:
    cli.main(sys.argv[1:])
except SystemExit:
    pass
print("IMPORTED", " ".join(sorted(set(sys.modules) - before)), file=sys.stderr)
"""


def _imported_by(args, cwd):
    env = {**os.environ, "PYTHONPATH": str(ROOT), "TMPDIR": str(cwd)}
    done = subprocess.run([sys.executable, "-c", IMPORTS, *args], capture_output=True, text=True,
                          cwd=cwd, timeout=120, env=env)
    line = [x for x in done.stderr.splitlines() if x.startswith("IMPORTED")]
    assert line, done.stderr
    return done.stdout, set(line[0].split()[1:])


def _named(modules, names):
    return sorted(m for m in modules if any(m == n or m.startswith(n + ".") for n in names))


def test_a_run_imports_only_what_it_uses(tmp_path):
    (tmp_path / "cube.cas").write_text("> !cu(1, 0, 0);\n")
    # turned, scaled, a named object, every primitive but !ex and !rv (whose
    # checks read their outlines with numpy)
    (tmp_path / "scene.cas").write_text(
        "x = @rz(30) @h(2) !cu(1, 0, 0);\n"
        "> x, @r(1, 1, 0, 20) @h(1, 2, 3) !sp(0, 1, 0), !cy(0, 0, 1), !co(0, 0, 1),\n"
        "  !to(1, 1, 0, 0.3), !pr(1, 0, 1, 6), !py(0, 1, 1, 5), !we(1, 1, 1);\n")
    _imported_by(["--check", "cube.cas"], tmp_path)  # a checkout's first run keeps the tables
    for kind, args in (("stream", ["cube.cas"]), ("check", ["--check", "cube.cas"]),
                       ("check a scene", ["--check", "scene.cas"]), ("version", ["--version"])):
        out, modules = _imported_by(args, tmp_path)
        if kind == "stream":
            assert "endframe 1 6" in out and "numpy" in modules  # it ran, and made a mesh
        assert _named(modules, NOT_FOR[kind]) == [], kind
