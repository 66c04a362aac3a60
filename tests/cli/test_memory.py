"""Limits in polygons and in memory (CLI.md): refused before building, with a clear error."""

import pytest

from castor.mesh import memory
from tests.support.cli import run
from tests.support.stream import parse_stream

CUBES = "> $U[I = 0, 99](@t(2 * I, 0, 0) !cu(1, 1, 1));\n"  # 600 quads, 1,200 triangles


def test_the_polygon_limit_counts_polygons_not_triangles():
    status, out, err = run("--no-cpp", "--max-polygons", "700", stdin=CUBES)
    assert status == 0, err
    (frame,) = parse_stream(out)
    assert len(frame.polygons) == 600
    status, out, err = run("--no-cpp", "--max-polygons", "500", stdin=CUBES)
    assert status == 1
    assert "error: the frame needs more than 500 polygons (--max-polygons)" in err


def test_a_frame_bigger_than_the_memory_is_refused_before_it_is_built():
    scene = "> $U[I = 0, 99](@t(3 * I, 0, 0) !sp(1, 1, 1));\n"  # about 99 M triangles
    needed = memory.frame_bytes(98_000_000)
    available = memory.available_bytes()
    if available is None or available > needed:
        pytest.skip("this machine has the memory for it")
    status, out, err = run("--no-cpp", "-t", "0.00001", "--max-polygons", "1000000000",
                           stdin=scene)
    assert status == 1
    assert "GB of memory, more than the" in err and "GB available" in err
    assert parse_stream(out) == []


def test_memory_estimate_and_refusal(monkeypatch):
    assert memory.frame_bytes(1_000_000) == memory.BASE_BYTES + memory.BYTES_PER_TRIANGLE * 10 ** 6
    monkeypatch.setattr(memory, "available_bytes", lambda: 10 ** 9)
    assert memory.too_big(100_000) is None
    needed, available = memory.too_big(10_000_000)
    assert needed > available == 10 ** 9
    monkeypatch.setattr(memory, "available_bytes", lambda: None)
    assert memory.too_big(10 ** 12) is None


def test_available_memory_is_read():
    assert memory.available_bytes() > 0
