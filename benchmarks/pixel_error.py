"""Facets sized to the screen (issue 34 item 3, ``--pixel-error``): a street of columns.

A street of ``COLUMNS`` columns (``@h(R, R, H) !cy``, a named object) receding
from a camera that stands beside the first: the polygons castor writes with
``--pixel-error E`` (and a frame tolerance so fine that it never binds),
against those of a uniform ``--tolerance`` that gives the nearest column the
same facets, hence the same pixel error (the tolerance --pixel-error gives
it). For both, the segments of the nearest and farthest columns, and the
largest chord error in pixels, computed from the written polygons with the
camera's own projection (castor.pictures.camera): each chord of a column's
foot (an edge of its base), its midpoint carried up the column at 81 heights
(the side facet is as far from the side at every height), against the circle
at its angle, where the picture shows it.

    python benchmarks/pixel_error.py [--columns N (24)] [--error E (0.5)]
"""

from __future__ import annotations

import argparse
import io
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

from castor.mesh.screen import Screen  # noqa: E402
from castor.formats.cps import load  # noqa: E402
from castor.pictures.camera import make_camera  # noqa: E402

RADIUS, HEIGHT, SPACING = 0.3, 4.0, 4.0
EYE, LOOK = (1.2, -2.0, 1.7), (0.0, 30.0, 1.5)
SIZE = (800, 600)


def scene(columns: int) -> str:
    uses = ", ".join(f"@t(0, {SPACING * k:g}, 0) col" for k in range(columns))
    return (f"col = @h({RADIUS}, {RADIUS}, {HEIGHT}) !cy(0.8, 0.8, 0.7);\n"
            f"street = $U({uses});\n> street;\n")


def castor(text: str, *options: str):
    env = dict(os.environ, PYTHONPATH=os.path.dirname(HERE))
    done = subprocess.run([sys.executable, "-m", "castor", *options, "-"], input=text.encode(),
                          capture_output=True, env=env, check=True)
    return next(load(io.StringIO(done.stdout.decode())))


def camera():
    return make_camera((0, 0, 0), (0, 0, 0), SIZE, eye=EYE, look=LOOK)


def chord_errors(frame, view) -> tuple[np.ndarray, np.ndarray]:
    """For each chord of a column's circle: its column and its error in pixels."""
    starts = frame.offsets[:-1]
    counts = np.diff(frame.offsets)
    index = np.arange(len(frame.points))
    polygon = np.repeat(np.arange(frame.polygon_count), counts)
    following = np.where(index + 1 == frame.offsets[polygon + 1], starts[polygon], index + 1)
    a, b = frame.points, frame.points[following]
    level = np.abs(a[:, 2] - b[:, 2]) < 1e-9
    bottom = level & (np.abs(a[:, 2]) < 1e-9)
    a, b = a[bottom], b[bottom]
    # a side facet is as far from the side at every height: the chord's midpoint
    # at heights up the column, where the picture may show it
    heights = np.linspace(0.0, HEIGHT, 81)
    middle = np.repeat((a + b) / 2, len(heights), axis=0)
    middle[:, 2] = np.tile(heights, len(a))
    column = np.rint(middle[:, 1] / SPACING).astype(int)
    axis = np.column_stack([np.zeros(len(middle)), column * SPACING])
    across = middle[:, :2] - axis
    length = np.linalg.norm(across, axis=1)
    keep = length > 1e-9
    true = middle.copy()
    true[keep, :2] = axis[keep] + across[keep] / length[keep, None] * RADIUS
    seen, depth = view.project(middle)
    ideal, _ = view.project(true)
    inside = ((depth > 0) & (seen[:, 0] >= 0) & (seen[:, 0] <= SIZE[0]) & (seen[:, 1] >= 0)
              & (seen[:, 1] <= SIZE[1]) & keep)
    return column[inside], np.linalg.norm(seen - ideal, axis=1)[inside]


def segments(frame, columns: int) -> list[int]:
    """The sides of each column: its polygons but its two caps."""
    centres = np.add.reduceat(frame.points, frame.offsets[:-1]) / np.diff(frame.offsets)[:, None]
    which = np.rint(centres[:, 1] / SPACING).astype(int)
    return [int(np.sum(which == k)) - 2 for k in range(columns)]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--columns", type=int, default=24)
    parser.add_argument("--error", type=float, default=0.5)
    args = parser.parse_args()
    text = scene(args.columns)
    view = camera()
    # the world tolerance --pixel-error gives the nearest column
    matrix = (RADIUS, 0, 0, 0, 0, RADIUS, 0, 0, 0, 0, HEIGHT, 0)
    nearest = Screen(view, args.error).world_tolerance(matrix, (-1, -1, 0), (1, 1, 1))
    where = ["--eye", ",".join(map(str, EYE)), "--look", ",".join(map(str, LOOK)),
             "--size", "%dx%d" % SIZE]
    sized = castor(text, "--pixel-error", str(args.error), "--tolerance", "1e-6", *where)
    uniform = castor(text, "--tolerance", repr(nearest))
    print(f"{args.columns} columns (radius {RADIUS}, {SPACING} apart), camera at {EYE} looking "
          f"at {LOOK}, {SIZE[0]}x{SIZE[1]}, --pixel-error {args.error}; the nearest column's "
          f"tolerance {nearest:.3g}")
    for name, frame in (("--pixel-error", sized), ("uniform --tolerance", uniform)):
        column, error = chord_errors(frame, view)
        sides = segments(frame, args.columns)
        worst = [float(error[column == k].max()) if np.any(column == k) else 0.0
                 for k in range(args.columns)]
        print(f"{name:>20}: {frame.polygon_count:6d} polygons; segments per column "
              f"{sides[0]} (nearest) ... {sides[-1]} (farthest); largest chord error "
              f"{max(worst):.3f} px (nearest column {worst[0]:.3f}, farthest "
              f"{worst[-1]:.3f})")
    print(f"polygons saved: {uniform.polygon_count / sized.polygon_count:.2f}x")


if __name__ == "__main__":
    main()
