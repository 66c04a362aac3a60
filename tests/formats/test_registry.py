"""One table of formats, one writer signature: the table names each format's module
and kind, and the module is imported when its writer is first called, so the command
line knows every format (``-f``, ``--help``, ``-o x.glb``) without importing numpy or
any writer (issue 18, item 18: start-up; issue 28, item 1)."""

import importlib
import inspect
import os
import pickle
import subprocess
import sys
from pathlib import Path

import pytest

from castor.formats import FORMATS, KINDS, OnUse, WriteInfo, kinds

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "castor" / "formats"
MODULES = sorted(p.stem for p in PACKAGE.glob("*.py")
                 if not p.stem.startswith("_") and p.stem not in ("output", "kinds"))


@pytest.mark.parametrize("name", sorted(FORMATS))
def test_each_format_has_one_writer_of_the_one_signature(name):
    """write(product, info): the product of the format's kind and a WriteInfo."""
    record = FORMATS[name]
    assert record.kind in KINDS
    function = record.write.resolve()
    assert list(inspect.signature(function).parameters) in (["frame", "info"], ["image", "info"],
                                                            ["images", "info"], ["sheet", "info"],
                                                            ["building", "info"])
    for field in ("read", "companions", "unavailable"):
        value = getattr(record, field)
        assert value is None or (isinstance(value, OnUse) and value.module == record.write.module
                                 and callable(value.resolve())), (name, field)


def test_every_format_module_is_in_the_table():
    """A module of castor/formats with a writer that the table forgets is never used."""
    assert sorted({f.write.module.rsplit(".", 1)[1] for f in FORMATS.values()}) == MODULES


def test_a_writer_s_bytes_are_the_module_s_whole_file():
    from castor.formats import cps, output
    from castor.run import evaluated_frames
    from castor.formats.kinds import facetizer_for
    from castor.settings import MeshSettings

    (scene,), _ = evaluated_frames("> !cu(1, 0, 0);\n")
    frame = facetizer_for(MeshSettings(), True).frame(scene)
    assert b"".join(FORMATS["cps"].write(frame, WriteInfo())) == cps.export(frame)
    assert output.render(frame, "cps") == cps.export(frame)


def test_a_kind_pickles_as_itself():
    for kind in KINDS:
        assert pickle.loads(pickle.dumps(kind)) is kind
    assert {kind.name for kind in KINDS} == {"stream", "mesh", "picture", "drawing", "bim"}
    assert kinds.MESH.polygons and kinds.STREAM.streamed and not kinds.PICTURE.polygons


def test_a_function_named_by_a_record_is_imported_on_its_first_call_and_pickles_by_name():
    reader = OnUse("castor.formats.cps", "number_strings")
    again = pickle.loads(pickle.dumps(reader))
    assert again == reader and again._function is None
    import numpy as np

    assert list(again(np.array([1.0, 0.5]))) == list(importlib.import_module(
        "castor.formats.cps").number_strings(np.array([1.0, 0.5])))


# What the command line may import to start: no writer, no numpy, no lark where it
# has nothing to parse.
PROBE = """
import sys
from castor import cli
try:
    status = cli.main(sys.argv[1:])
except SystemExit as exc:
    status = exc.code
heavy = sorted(m for m in sys.modules if m.split(".")[0] in ("numpy", "lark", "manifold3d",
               "trimesh", "PIL", "ifcopenshell", "ezdxf", "reportlab", "dataclasses", "tempfile"))
formats = sorted(m for m in sys.modules if m.startswith("castor.formats."))
print("STATUS", status, file=sys.stderr)
print("HEAVY", " ".join(sorted({m.split(".")[0] for m in heavy})), file=sys.stderr)
print("FORMATS", " ".join(formats), file=sys.stderr)
"""


def _imported(*args, stdin=""):
    done = subprocess.run([sys.executable, "-c", PROBE, *args], input=stdin, capture_output=True,
                          text=True, cwd=ROOT, timeout=120,
                          env={**os.environ, "PYTHONPATH": str(ROOT)})
    lines = dict(line.split(" ", 1) if " " in line else (line, "")
                 for line in done.stderr.splitlines() if line.split(" ")[0] in
                 ("STATUS", "HEAVY", "FORMATS"))
    return lines, done.stderr


@pytest.mark.parametrize("args", [["--version"], ["--help"], ["-f", "nope", "x.cas"]])
def test_help_and_version_import_no_writer_and_neither_numpy_nor_lark(args):
    lines, err = _imported(*args)
    assert "HEAVY" in lines, err
    assert lines["HEAVY"] == "", err
    assert lines["FORMATS"] in ("", "castor.formats.kinds"), err


def test_the_stream_of_a_cube_imports_only_the_stream_s_writer():
    lines, err = _imported("--no-cpp", "-", stdin="> !cu(1, 0, 0);\n")
    assert lines["STATUS"] in ("0", "None"), err
    assert set(lines["FORMATS"].split()) <= {"castor.formats._mesh", "castor.formats.cps",
                                             "castor.formats.kinds",
                                             "castor.formats.output"}, lines["FORMATS"]


def test_checking_a_scene_imports_no_writer():
    lines, err = _imported("--no-cpp", "--check", "-o", "x.glb", "-", stdin="> !cu(1, 0, 0);\n")
    assert lines["STATUS"] in ("0", "None"), err
    assert set(lines["FORMATS"].split()) <= {"castor.formats.kinds",
                                             "castor.formats.output"}, lines["FORMATS"]
