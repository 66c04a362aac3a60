"""Every example runs, every frame is closed, outward and convex; the README
and the CI agree; castor-view draws what it is given."""

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from tests.support.checks import check_solid
from tests.support.cli import run, run_once
from tests.support.stream import parse_stream

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((ROOT / "examples").glob("*.cas"))


@pytest.mark.parametrize("example", EXAMPLES, ids=lambda p: p.name)
def test_example_frames_are_closed_solids(example):
    status, out, err = run_once(str(example))
    assert status == 0, err
    assert "warning" not in err
    frames = parse_stream(out)
    assert frames
    for frame in frames:
        check_solid(frame)
        assert len(frame.colours()) >= 2


def test_door_animation_has_nine_frames():
    status, out, err = run_once(str(ROOT / "examples" / "door.cas"))
    frames = parse_stream(out)
    assert len(frames) == 9
    # the door leaf moves: the frames differ, the wall does not
    boxes = [f.box() for f in frames]
    assert boxes[0].tolist() != boxes[4].tolist()


def test_bus_shelter_reuses_the_unchanging_part():
    """Only the traffic light reads PHASE: the frames after the first send only
    its part to the engine again (one facetizer, as one process keeps)."""
    from castor.mesh.facetize import Facetizer
    from castor.run import evaluated_frames

    path = ROOT / "examples" / "bus_shelter.cas"
    frames, said = evaluated_frames(path.read_text(), str(path))
    assert len(frames) == 3 and "error" not in said
    facetizer = Facetizer()
    counts = []
    for frame in frames:
        facetizer.frame(frame)
        counts.append(facetizer.counter.booleans)
    assert counts[1] < counts[0] / 4 and counts[2] < counts[0] / 4
    # --stats says the frame's booleans, the same figure for every frame
    status, out, err = run("--stats", str(path))
    stated = [int(re.search(r"(\d+) boolean operation", line).group(1))
              for line in err.splitlines() if line.startswith("castor: frame")]
    assert len(set(stated)) == 1 and stated[0] >= counts[0]
    lines = sum(len(p.read_text().splitlines())
                for p in [ROOT / "examples" / "bus_shelter.cas",
                          *(ROOT / "examples" / "bus_shelter").glob("*.cas")])
    assert lines >= 450


def test_readme_starts_with_the_two_commands_and_ci_runs_the_second():
    readme = (ROOT / "README.md").read_text()
    blocks = re.findall(r"```\n(.*?)\n```", readme, re.S)
    install, tests = blocks[0], blocks[1]
    assert "pip install ." in install and "castor examples/" in install
    assert "pytest" in tests
    assert tests in (ROOT / ".ci" / "run").read_text()


def view(args, stdin=None):
    result = subprocess.run([sys.executable, "-m", "castor.view.cli", *args], input=stdin,
                            capture_output=True, timeout=300)
    assert b"Traceback" not in result.stderr
    return result


def test_view_draws_the_house(tmp_path):
    status, out, err = run(str(ROOT / "examples" / "house.cas"))
    target = tmp_path / "house.png"
    result = view(["-o", str(target), "--size", "320x240"], stdin=out.encode())
    assert result.returncode == 0, result.stderr
    image = np.asarray(Image.open(target))
    assert image.shape == (240, 320, 3)
    colours = {tuple(c) for c in image.reshape(-1, 3)[::7].tolist()}
    # background, and distinct shades for roof, walls, reveals
    assert len(colours) > 10
    # the blue of the reveals is there
    rgb = image.reshape(-1, 3).astype(int)
    assert np.any((rgb[:, 2] > rgb[:, 0] + 60) & (rgb[:, 2] > 100))
    # the roof's tile red too
    assert np.any((rgb[:, 0] > rgb[:, 1] + 80) & (rgb[:, 0] > 120))


def test_view_faces_of_a_box_are_told_apart(tmp_path):
    status, out, err = run("--no-cpp", stdin="> !cu(0.8, 0.8, 0.8);\n")
    target = tmp_path / "box.png"
    view(["-o", str(target), "--size", "200x200"], stdin=out.encode())
    image = np.asarray(Image.open(target)).reshape(-1, 3)
    shades, counts = np.unique(image, axis=0, return_counts=True)
    # three large areas of three different greys, besides the white background
    faces = [tuple(s) for s, n in zip(shades.tolist(), counts) if n > 500 and s != [255, 255, 255]]
    assert len(faces) == 3


def test_view_wire_and_gif(tmp_path):
    status, out, err = run(str(ROOT / "examples" / "door.cas"))
    gif = tmp_path / "door.gif"
    result = view(["-o", str(gif), "--size", "160x120"], stdin=out.encode())
    assert result.returncode == 0, result.stderr
    assert Image.open(gif).n_frames == 9
    wire = tmp_path / "wire.png"
    view(["--wire", "-o", str(wire), "--size", "160x120"], stdin=out.encode())
    pixels = np.asarray(Image.open(wire)).reshape(-1, 3)
    dark = np.count_nonzero(pixels.sum(axis=1) < 200)
    assert 0 < dark < len(pixels) / 4  # lines, not filled faces


def test_view_reads_mesh_files(tmp_path):
    target = tmp_path / "car.glb"
    run("-o", str(target), str(ROOT / "examples" / "car.cas"), check_status=0)
    png = tmp_path / "car.png"
    result = view([str(target), "-o", str(png), "--size", "160x120"])
    assert result.returncode == 0, result.stderr
    assert Image.open(png).size == (160, 120)


def test_view_without_output_explains():
    result = view([], stdin=b"")
    assert result.returncode == 2
    assert b"give -o FILE.png" in result.stderr


def test_view_rejects_garbage():
    result = view(["-o", "/tmp/x.png"], stdin=b"hello\n")
    assert result.returncode == 1
    assert b"not a castor polygon stream" in result.stderr
