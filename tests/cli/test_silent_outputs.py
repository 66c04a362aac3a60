"""Nothing castor leaves unwritten or unused passes in silence: a writer that gives
no bytes for a frame is an error naming the file that is not written (as any
output castor cannot write), and --ifc-class naming no object of the scene is
warned about, naming the name (CLI.md: an option's message names it)."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.support.cli import run

ROOT = Path(__file__).resolve().parents[2]
SCENE = "maison = !cu(1, 0, 0);\n> maison;\n"

# castor with one format's writer replaced by one that gives nothing (None, or no bytes)
NOTHING = """
import sys
from castor import cli, formats
name, nothing = sys.argv[1], (None if sys.argv[2] == "none" else b"")
record = formats.registry()[name]
write = lambda *args, **kwargs: nothing
formats.registry()[name] = record._replace(write=write)
sys.exit(cli.main(sys.argv[3:]))
"""


def _with_writer_of_nothing(name, nothing, *args, cwd):
    done = subprocess.run([sys.executable, "-c", NOTHING, name, nothing, *args],
                          capture_output=True, text=True, cwd=cwd, timeout=300,
                          env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert "Traceback" not in done.stderr, done.stderr
    return done.returncode, done.stdout, done.stderr


@pytest.mark.parametrize("name, target", [("svg", "x.svg"), ("png", "x.png"), ("obj", "x.obj"),
                                          ("stl", "x-%d.stl"), ("ifc", "x.ifc")])
@pytest.mark.parametrize("nothing", ["none", "empty"])
def test_a_writer_that_gives_nothing_is_an_error_naming_the_file_not_written(
        tmp_path, name, target, nothing):
    (tmp_path / "s.cas").write_text(SCENE)
    (tmp_path / "x.svg").write_text("the old drawing")
    small = ["--size", "40x30", "--samples", "1"] if name == "png" else []
    status, out, err = _with_writer_of_nothing(name, nothing, *small, "-o", target, "s.cas",
                                               cwd=tmp_path)
    written = target.replace("%d", "1")
    assert status == 1, err
    assert (f"s.cas:2:1: error: {written} not written: the {name} writer gave no bytes "
            f"for frame 1") in err, err
    assert sorted(os.listdir(tmp_path)) == sorted({"s.cas", "x.svg"})  # no empty file
    assert (tmp_path / "x.svg").read_text() == "the old drawing"  # the old file kept


def test_a_writer_that_gives_nothing_to_standard_output_says_so(tmp_path):
    (tmp_path / "s.cas").write_text(SCENE)
    status, out, err = _with_writer_of_nothing("off", "empty", "-f", "off", "s.cas",
                                               cwd=tmp_path)
    assert status == 1 and out == ""
    assert ("s.cas:2:1: error: standard output not written: the off writer gave no bytes "
            "for frame 1") in err, err


def test_the_writers_give_bytes_for_an_empty_frame(tmp_path):
    """An empty frame is warned about, and still written (a file with no polygons)."""
    (tmp_path / "e.cas").write_text("> $I(!cu(1, 0, 0), @t(5, 0, 0) !cu(1, 0, 0));\n")
    for target in ["x.off", "x.obj", "x.stl", "x.ply", "x.glb", "x.3mf"]:
        status, out, err = run("-o", target, "e.cas", cwd=tmp_path)
        assert status == 0 and "not written" not in err, (target, err)
        assert (tmp_path / target).stat().st_size > 0


IFC_SCENE = "mur = !cu(0.9, 0.9, 0.9);\ntoit = @t(0, 0, 1) !py(0.6, 0.1, 0.1, 4);\n> mur, toit;\n"


def test_an_ifc_class_of_no_object_of_the_scene_is_warned_about_by_its_name(tmp_path):
    (tmp_path / "m.cas").write_text(IFC_SCENE)
    status, out, err = run("--ifc-class", "mur=wall", "--ifc-class", "toi=roof",
                           "--ifc-class", "porte=door", "-o", "m.ifc", "m.cas", cwd=tmp_path)
    assert status == 0, err
    assert ("castor: warning: --ifc-class toi: the scene has no object 'toi', so nothing is "
            "made an IfcRoof; did you mean 'toit'?") in err, err
    assert ("castor: warning: --ifc-class porte: the scene has no object 'porte', so nothing "
            "is made an IfcDoor\n") in err, err
    assert "'mur'" not in err  # a name the scene has is not warned about
    assert (tmp_path / "m.ifc").exists()


def test_an_ifc_class_of_an_object_of_the_scene_is_not_warned_about(tmp_path):
    (tmp_path / "m.cas").write_text(IFC_SCENE)
    status, out, err = run("--ifc-class", "mur=wall", "--ifc-class", "toit=roof",
                           "--check", "-o", "m.ifc", "m.cas", cwd=tmp_path)
    assert status == 0 and err == "", err
    status, out, err = run("--ifc-class", "murs=wall", "--check", "-o", "m.ifc", "m.cas",
                           cwd=tmp_path)
    assert status == 0 and "--ifc-class murs: the scene has no object 'murs'" in err, err
