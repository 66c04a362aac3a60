"""The up and down pieces of a plane whose boxes meet are found in work that
grows as the pieces, not as their product (issue 29: at ``-t 1e-8`` the car's
body side, 14,038 triangles, against its wheel's cap, 7,016, was a matrix of
98 million box tests, 400 MB at its peak, though no box met another).

The work is measured by the memory numpy allocates (tracemalloc), not timed;
benchmarks/README.md gives the car's times. The pairs found are those a test
of every pair finds."""

import tracemalloc

import numpy as np
import pytest

from castor.mesh.broadphase import meeting_boxes
from castor.mesh.sheets import without_sheets


def _strips(count: int):
    """A plane z = 0 where ``count`` thin triangles facing up (face 0, y from 0
    to 1) touch ``count`` facing down (face 1, y from -1 to 0) along y = 0
    without overlapping: the plane has both turns, and nothing to cancel."""
    x = np.linspace(0.0, 1.0, count + 1)
    vertices = np.vstack([np.column_stack([x, np.full_like(x, y), np.zeros_like(x)])
                          for y in (-1.0, 0.0, 1.0)])
    low, mid, high = (np.arange(count + 1) + k * (count + 1) for k in range(3))
    up = np.column_stack([mid[:-1], mid[1:], high[:-1]])  # counter-clockwise from +z
    down = np.column_stack([mid[:-1], mid[1:], low[:-1]])  # clockwise from +z
    triangles = np.vstack([up, down]).astype(np.int64)
    faces = np.repeat(np.array([0, 1], np.int64), count)
    return vertices, triangles, np.zeros(2 * count, np.int64), faces


def _peak_bytes(count: int) -> tuple[int, tuple]:
    arrays = _strips(count)
    tracemalloc.start()
    try:
        result = without_sheets(*arrays)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    return peak, (arrays, result)


def test_a_plane_of_many_pieces_needs_memory_as_its_pieces():
    small, (arrays, result) = _peak_bytes(500)
    # nothing overlaps: the solid is given back as it was
    assert all(a is b for a, b in zip(arrays, result))
    large, _ = _peak_bytes(4_000)
    # eight times the pieces, about eight times the memory (1.4 and 11 MB;
    # the matrix of every pair made it twenty times: 2.1 and 43 MB)
    assert large < 12 * small, (small, large)
    assert large < 20_000_000, large


def _every_pair(a, b, eps):
    meet = ((a[:, None, 0] < b[None, :, 2] - eps) & (b[None, :, 0] < a[:, None, 2] - eps)
            & (a[:, None, 1] < b[None, :, 3] - eps) & (b[None, :, 1] < a[:, None, 3] - eps))
    return np.stack(np.nonzero(meet), axis=1)


@pytest.mark.parametrize("seed", range(40))
def test_the_pairs_are_those_of_a_test_of_every_pair(seed):
    rng = np.random.default_rng(seed)
    step = rng.choice([0.1, 0.25, 1.0])  # on a grid: boxes that touch, and within eps

    def boxes(count):
        low = np.round(rng.random((count, 2)) * 4 / step) * step
        size = np.round(rng.random((count, 2)) * 2 / step) * step
        size *= rng.random((count, 2)) > 0.1  # some flat
        return np.column_stack([low, low + size])

    a, b = boxes(int(rng.integers(0, 60))), boxes(int(rng.integers(0, 60)))
    eps = float(rng.choice([0.0, 1e-12, 0.1]))
    found = meeting_boxes(a, b, eps, chunk=int(rng.integers(1, 50)))
    assert found.tolist() == _every_pair(a, b, eps).tolist()
