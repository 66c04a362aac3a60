"""The registry reads each format's record from its module's source, without running
the module, and imports the module when one of its functions is first called: the
command line knows every format (``-f``, ``--help``, ``-o x.glb``) without importing
numpy or any writer (issue 18, item 18: start-up)."""

import importlib
import os
import pickle
import subprocess
import sys
from pathlib import Path

import pytest

from castor import formats
from castor.formats import FORMATS, Format, OnUse, declared

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "castor" / "formats"
MODULES = sorted(p.stem for p in PACKAGE.glob("*.py")
                 if not p.stem.startswith("_") and p.stem != "output")


@pytest.mark.parametrize("name", MODULES)
def test_each_module_s_records_read_from_its_source_are_the_ones_python_makes(name):
    """One registry: the records the registry reads unrun are the module's FORMATS,
    field by field, and each function named is the module's own."""
    module = f"castor.formats.{name}"
    read = declared(module, (PACKAGE / f"{name}.py").read_text(encoding="utf-8"))
    assert read is not None, (f"{name}.py's FORMATS is not plain data (literals and the names "
                              "of its functions): the registry must import it to read it")
    made = importlib.import_module(module).FORMATS
    assert len(read) == len(made)
    for lazy, real in zip(read, made):
        for field in Format._fields:
            value, expected = getattr(lazy, field), getattr(real, field)
            if isinstance(value, OnUse):
                assert value.resolve() is expected, (name, field)
            else:
                assert value == expected, (name, field)


def test_the_stream_header_written_in_the_record_is_the_stream_s():
    from castor.formats import cps

    assert FORMATS["cps"].header == cps.HEADER.encode("utf-8")


def test_a_record_that_is_not_plain_data_is_read_by_importing_its_module():
    source = 'x = 1\nFORMATS = (Format("a", (".a",), "mesh", "d", export, header=H.encode()),)\n'
    assert declared("m", source) is None
    source = 'FORMATS = (Format("a", (".a",), "mesh", "d", export, listed=3),)\n'
    (record,) = declared("castor.formats.m", "\n" + source)
    assert record.name == "a" and record.listed == 3 and record.write == OnUse("castor.formats.m", "export")
    assert declared("m", "\nFORMATS = (Format('a', ('.a',), 'mesh', 'd', export, colour=1),)\n") is None
    assert declared("m", "nothing declared here\n") is None


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
    assert lines["FORMATS"] == "", err


def test_the_stream_of_a_cube_imports_only_the_stream_s_writer():
    lines, err = _imported("--no-cpp", "-", stdin="> !cu(1, 0, 0);\n")
    assert lines["STATUS"] in ("0", "None"), err
    assert set(lines["FORMATS"].split()) <= {"castor.formats._mesh", "castor.formats.cps",
                                             "castor.formats.output"}, lines["FORMATS"]


def test_checking_a_scene_imports_no_writer():
    lines, err = _imported("--no-cpp", "--check", "-o", "x.glb", "-", stdin="> !cu(1, 0, 0);\n")
    assert lines["STATUS"] in ("0", "None"), err
    assert lines["FORMATS"].split() in (["castor.formats.output"], []), lines["FORMATS"]
