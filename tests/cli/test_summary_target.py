"""'castor --summary house.cas' names the summary's file, not the scene: castor
then read standard input and wrote its figures over the scene file. A scene
file (an existing .cas) as --summary's target is a usage error, and the file
is left as it was."""

import json
import subprocess
import sys


def test_a_scene_file_as_the_summary_s_target_is_a_usage_error(tmp_path):
    scene = tmp_path / "house.cas"
    scene.write_text("> !cu(1, 0, 0);\n")
    result = subprocess.run([sys.executable, "-m", "castor", "--summary", str(scene)],
                            input=b"", capture_output=True, cwd=tmp_path, timeout=60)
    assert result.returncode == 2
    assert (f"--summary {scene}: is a scene file; --summary takes the file the figures go to "
            f"(castor --summary figures.json {scene})") in result.stderr.decode()
    assert scene.read_text() == "> !cu(1, 0, 0);\n"


def test_a_new_summary_file_is_still_written(tmp_path):
    scene = tmp_path / "house.cas"
    scene.write_text("> !cu(1, 0, 0);\n")
    result = subprocess.run([sys.executable, "-m", "castor", "--summary", "figures.json",
                             "-o", "/dev/null", str(scene)], capture_output=True, cwd=tmp_path,
                            timeout=60)
    assert result.returncode == 0, result.stderr
    assert '"volume": 1' in (tmp_path / "figures.json").read_text()


def _castor_on_a_cube(tmp_path):
    """castor run on a scene of one cube in ``tmp_path``, given options."""
    scene = tmp_path / "house.cas"
    scene.write_text("> !cu(1, 0, 0);\n")
    return lambda *args: subprocess.run([sys.executable, "-m", "castor", *args, str(scene)],
                                        capture_output=True, cwd=tmp_path, timeout=60)


def test_a_dash_is_standard_output_for_the_summary_and_for_the_frames(tmp_path):
    """'--summary -' and '-o -' wrote files named '-' (as the help did not say)."""
    castor = _castor_on_a_cube(tmp_path)
    figures = castor("--summary", "-", "-o", "house.stl")
    assert figures.returncode == 0, figures.stderr
    assert json.loads(figures.stdout)["frames"][0]["objects"][0]["volume"] == 1
    assert (tmp_path / "house.stl").stat().st_size == 84 + 12 * 50
    frames = castor("-o", "-")
    assert frames.returncode == 0 and frames.stdout == castor().stdout
    assert frames.stdout.startswith(b"castor-polygons 1\nframe 1 ")
    both = castor("--summary", "-")
    assert both.returncode == 2 and both.stdout == b""
    assert b"--summary -: standard output carries the frames; write them to a file" in both.stderr
    assert not (tmp_path / "-").exists()


def test_the_summary_on_standard_output_is_refused_where_it_cannot_go_there(tmp_path):
    castor = _castor_on_a_cube(tmp_path)
    checked = castor("--check", "--summary", "-")  # --check's own word, not the frames'
    assert checked.returncode == 2
    assert b"--summary needs the frames made; leave out --check" in checked.stderr
    device = castor("--summary", "-", "-o", "/dev/stdout")  # the frames there too
    assert device.returncode == 2 and device.stdout == b""
    assert b"--summary -: standard output carries the frames" in device.stderr
