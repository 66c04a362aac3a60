"""What a face is travels with it: an edge is a crease unless both sides are
facets of one curved surface of one primitive (castor.mesh.creases), the
same in drawings, in ``castor --edges`` pictures and in castor-view.

A column ``@h(1, 1, 3) !pr(..., N)`` seen from the front shows the vertical
edges of its front half: N/2 + 1 of them for an even N, whatever the angle
between its sides; a cylinder only its two outlines."""

from __future__ import annotations

import io
import subprocess
import sys

import numpy as np
import pytest

from tests.support.cli import run
from tests.support.drawings import Drawn, draw_svg

LINES = {6: 4, 10: 6, 12: 7, 16: 9}


def column(n: int) -> str:
    return f"colonne = @h(1, 1, 3) !pr(0.8, 0.8, 0.8, {n});\n> colonne;\n"


TUBE = "colonne = @h(1, 1, 3) !cy(0.8, 0.8, 0.8);\n> colonne;\n"


def _vertical_xs(segments, top=3.0) -> list[float]:
    """The distinct x of the segments that run up the whole column."""
    xs = set()
    for a, b in segments:
        if abs(a[0] - b[0]) < 1e-6 and abs(abs(a[1] - b[1]) - top) < 1e-6:
            xs.add(round(float(a[0]), 6))
    return sorted(xs)


@pytest.mark.parametrize("n", sorted(LINES))
def test_a_prism_column_in_elevation_shows_each_edge_in_front_svg(tmp_path, n):
    drawn = Drawn(draw_svg(tmp_path, column(n), "--view", "front"), 100)
    xs = _vertical_xs([(s[0], s[-1]) for s in drawn.lines["colonne"]])
    assert len(xs) == LINES[n]
    # the corners of the N-gon in front, first vertex at (1, 0)
    corners = np.cos(2 * np.pi * np.arange(n // 2 + 1) / n)
    assert np.allclose(sorted(xs), sorted(corners) - np.min(corners) - 1, atol=1e-3)


@pytest.mark.parametrize("n", sorted(LINES))
def test_a_prism_column_in_elevation_shows_each_edge_in_front_dxf(tmp_path, n):
    ezdxf = pytest.importorskip("ezdxf")
    draw_svg(tmp_path, column(n), "--view", "front", name="e.dxf")
    lines = ezdxf.readfile(tmp_path / "e.dxf").modelspace().query("LINE")
    segments = [((l.dxf.start.x, l.dxf.start.y), (l.dxf.end.x, l.dxf.end.y)) for l in lines]
    assert len(_vertical_xs(segments)) == LINES[n]


def test_a_cylinder_in_elevation_shows_its_outlines_only(tmp_path):
    drawn = Drawn(draw_svg(tmp_path, TUBE, "--view", "front"), 100)
    assert len(_vertical_xs([(s[0], s[-1]) for s in drawn.lines["colonne"]])) == 2


def _dark_columns(png: bytes) -> int:
    """Vertical lines across the middle of a picture: runs of pixel columns
    dark from 35% to 65% of the height. A pixel is dark beside the brighter of
    the pixels three columns to either side (under 3/4 of it), so that a line
    between two pixels, drawn as two half-dark ones, counts however the sun
    lights the faces around it (the default sun stands beside the camera)."""
    from PIL import Image

    image = np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(int)
    h = image.shape[0]
    band = image[int(h * 0.35):int(h * 0.65)].sum(axis=2)
    padded = np.pad(band, ((0, 0), (3, 3)), mode="edge")
    beside = np.maximum(padded[:, :-6], padded[:, 6:])
    line = (band < 0.75 * beside).mean(axis=0) > 0.9
    return int(np.count_nonzero(np.diff(np.concatenate([[0], line.astype(int)])) == 1))


def _picture(scene: str, tmp_path) -> bytes:
    (tmp_path / "s.cas").write_text(scene)
    run("--edges", "--view", "front", "--size", "400x300", "-o", str(tmp_path / "p.png"),
        str(tmp_path / "s.cas"), check_status=0)
    return (tmp_path / "p.png").read_bytes()


def _viewed(scene: str, tmp_path) -> bytes:
    (tmp_path / "s.cas").write_text(scene)
    status, stream, err = run(str(tmp_path / "s.cas"))
    assert status == 0, err
    out = tmp_path / "v.png"
    done = subprocess.run([sys.executable, "-m", "castor.view.cli", "--edges", "--view", "front",
                           "--size", "400x300", "-o", str(out)], input=stream.encode(),
                          capture_output=True)
    assert done.returncode == 0, done.stderr
    return out.read_bytes()


@pytest.mark.parametrize("n", sorted(LINES))
def test_a_prism_column_shows_each_edge_in_pictures(tmp_path, n):
    assert _dark_columns(_picture(column(n), tmp_path)) == LINES[n]
    assert _dark_columns(_viewed(column(n), tmp_path)) == LINES[n]


def test_a_cylinder_shows_its_outlines_only_in_pictures(tmp_path):
    # fine facets (the 3 m stretch no longer refines them: 0.05 would give 12, and
    # a flat-shaded facet facing the viewer then reads as a line); not creases
    scene = "colonne = @h(1, 1, 3) @f(0.0167) !cy(0.8, 0.8, 0.8);\n> colonne;\n"
    assert _dark_columns(_picture(scene, tmp_path)) == 2
    assert _dark_columns(_viewed(scene, tmp_path)) == 2


def test_the_frame_knows_which_polygons_are_facets_of_one_surface():
    from castor.mesh.facetize import Facetizer
    from castor.run import evaluated_frames

    frames, said = evaluated_frames("> $U(!cy(1, 0, 0), @t(3, 0, 0) !pr(0, 1, 0, 16), "
                                    "@t(6, 0, 0) !we(0, 0, 1));", "<scene>")
    obj, = Facetizer().frame(frames[0]).objects
    kinds = [o.kind for o in obj.origins]
    assert sorted(kinds) == ["cy", "pr", "we"]
    for k, kind in enumerate(kinds):
        surfaces = set(obj.surface_of[obj.origin_of == k].tolist())
        assert surfaces == ({-1, 0} if kind == "cy" else {-1}), kind


def test_a_batch_without_curved_polygons_beside_one_with_them():
    # parts apart go to the engine's output in batches: a small cube in one,
    # the sphere (a large part) alone in another
    status, out, err = run("--no-cpp", stdin="> $U(!cu(1, 0, 0), @t(2, 0, 0) !sp(0, 1, 0));\n")
    assert status == 0, err
    assert out.count("\npoly U1!cu ") == 6
