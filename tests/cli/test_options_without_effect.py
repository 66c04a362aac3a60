"""An option with no effect on the chosen output is warned about once, naming
the option and the output (CLI.md); `--scale 1:N` scales a 3MF model."""

import io
import re
import zipfile

import numpy as np
import pytest

from tests.support.cli import run

CUBE = "> !cu(1, 1, 1);\n> @t(1, 0, 0) !cu(1, 1, 1);\n"


@pytest.mark.parametrize("option, output", [
    (["--samples", "2"], "x-%d.glb"),
    (["--edges"], "x-%d.glb"),
    (["--sun", "none"], "x-%d.stl"),
    (["--size", "10x10"], "x.cps"),
    (["--section", "z=0.5"], "x-%d.png"),
    (["--scale", "1:50"], "x-%d.glb"),
    (["--scale", "1:50"], "x-%d.png"),
    (["--samples", "2"], "x-%d.svg"),
])
def test_an_option_without_effect_is_warned_about_once(tmp_path, option, output):
    (tmp_path / "c.cas").write_text(CUBE)
    small = ["--size", "20x10"] if output.endswith(".png") else []  # quick pictures
    status, out, err = run(*option, *small, "-o", output, "c.cas", cwd=tmp_path)
    assert status == 0, err
    name = output.rsplit(".", 1)[1]
    lines = [line for line in err.splitlines() if option[0] in line]
    assert len(lines) == 1, err
    assert lines[0].startswith("castor: warning: ") and f"{name} output" in lines[0], err
    assert len(err.splitlines()) == 1, err


@pytest.mark.parametrize("option, output", [
    (["--samples", "2", "--edges", "--sun", "none", "--size", "20x10"], "x-%d.png"),
    (["--section", "z=0.5", "--scale", "1:50"], "x-%d.svg"),
    (["--scale", "1:50"], "x-%d.3mf"),
])
def test_an_option_with_effect_is_not_warned_about(tmp_path, option, output):
    (tmp_path / "c.cas").write_text(CUBE)
    status, out, err = run(*option, "-o", output, "c.cas", cwd=tmp_path)
    assert status == 0 and err == "", err


def _vertices(path) -> np.ndarray:
    with zipfile.ZipFile(path) as package:
        model = package.read("3D/3dmodel.model").decode()
    return np.array([[float(v) for v in m] for m in
                     re.findall(r'<vertex x="([^"]+)" y="([^"]+)" z="([^"]+)"', model)])


def test_scale_makes_a_3mf_model_at_that_scale(tmp_path):
    (tmp_path / "c.cas").write_text("> @h(9, 4, 3) !cu(1, 1, 1);\n")
    run("-o", "full.3mf", "c.cas", cwd=tmp_path, check_status=0)
    run("--scale", "1:100", "-o", "model.3mf", "c.cas", cwd=tmp_path, check_status=0)
    full, model = _vertices(tmp_path / "full.3mf"), _vertices(tmp_path / "model.3mf")
    assert np.allclose(full.max(axis=0) - full.min(axis=0), [9000, 4000, 3000])  # 1 unit = 1 m
    assert np.allclose(model.max(axis=0) - model.min(axis=0), [90, 40, 30])  # 1:100: 1 unit = 10 mm


def test_output_options_with_check_are_said_to_do_nothing_there(tmp_path):
    """--check writes nothing: it said '--size has no effect on cps output (it acts
    on pictures)', as if a cps output were written."""
    (tmp_path / "c.cas").write_text(CUBE)
    status, out, err = run("--check", "--size", "40x30", "--scale", "1:50", "c.cas", cwd=tmp_path)
    assert (status, out) == (0, "")
    assert err.splitlines() == [
        "castor: warning: --size has no effect with --check (it writes nothing); it is ignored",
        "castor: warning: --scale has no effect with --check (it writes nothing); it is ignored"]
