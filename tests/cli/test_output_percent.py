"""-o reads '%' as printf does (CLI.md: a bad pattern is a usage error): '%%' is
a '%' in the name, with or without a frame-number pattern, and a conversion other
than the frame number's ('%s', '%i') is a usage error naming it. Before, 'f-%s.glb'
and 'f-%%.glb' were written as such, exit 0 (issue 29's trial)."""

import os

import pytest

from tests.support.cli import run

SCENE = "> !cu(1, 1, 1);\n"
ADVICE = "write %d (or %03d for 001, 002, ...) for the frame number, '%%' for a '%' in the name"


@pytest.mark.parametrize("name, conversion", [
    ("f-%s.glb", "%s"), ("f-%i.stl", "%i"), ("%-3d.stl", "%-3d"), ("a-%x-%d.stl", "%x"),
])
def test_another_conversion_is_a_usage_error_naming_it(tmp_path, name, conversion):
    status, out, err = run("--no-cpp", "-o", name, stdin=SCENE, cwd=tmp_path)
    assert status == 2
    assert err.splitlines()[0] == (f"castor: error: -o {name}: '{conversion}' is not a "
                                   f"frame-number pattern; {ADVICE}")
    assert os.listdir(tmp_path) == []


def test_a_lone_percent_is_a_usage_error_even_without_a_pattern(tmp_path):
    status, out, err = run("--no-cpp", "-o", "50%.stl", stdin=SCENE, cwd=tmp_path)
    assert status == 2
    assert err.splitlines()[0] == ("castor: error: -o 50%.stl: a '%' that is not the "
                                   "frame-number pattern; write '%%' for a '%' in the name")
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("name, written", [
    ("f-%%.glb", "f-%.glb"), ("f-%%d.stl", "f-%d.stl"), ("100%%.cps", "100%.cps"),
])
def test_a_double_percent_is_one_percent(tmp_path, name, written):
    status, out, err = run("--no-cpp", "-o", name, stdin=SCENE, cwd=tmp_path)
    assert status == 0, err
    assert os.listdir(tmp_path) == [written]
    assert (tmp_path / written).stat().st_size > 0


def test_a_companion_file_is_named_from_the_file_s_own_name(tmp_path):
    status, out, err = run("--no-cpp", "-o", "a%%.obj", stdin=SCENE, cwd=tmp_path)
    assert status == 0, err
    names = sorted(os.listdir(tmp_path))
    assert "a%.obj" in names and not any("%%" in name for name in names)


def test_a_second_frame_names_the_file_it_would_write(tmp_path):
    status, out, err = run("--no-cpp", "-o", "f-%%.glb", stdin=SCENE + SCENE, cwd=tmp_path)
    assert status == 1
    assert "this is frame 2 for f-%.glb; give a pattern such as -o f-%%-%03d.glb" in err


def test_the_summary_is_a_plain_name(tmp_path):
    status, out, err = run("--no-cpp", "--summary", "s-%s.json", "-o", "/dev/null",
                           stdin=SCENE, cwd=tmp_path)
    assert status == 0, err
    assert os.listdir(tmp_path) == ["s-%s.json"]


def test_castor_view_reads_percent_as_castor_does(tmp_path):
    import subprocess
    import sys

    status, stream, err = run("--no-cpp", stdin=SCENE, cwd=tmp_path)
    assert status == 0, err
    for name in ("v%%.png", "w%s.png"):
        result = subprocess.run([sys.executable, "-m", "castor.view.cli", "-o", name],
                                input=stream, capture_output=True, text=True, cwd=tmp_path,
                                timeout=120)
        if name == "w%s.png":
            assert result.returncode == 2
            assert result.stderr.startswith("castor-view: error: -o w%s.png: '%s' is not a "
                                            "frame-number pattern")
        else:
            assert result.returncode == 0, result.stderr
    assert os.listdir(tmp_path) == ["v%.png"]
