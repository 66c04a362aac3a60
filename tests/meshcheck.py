"""Read castor's polygon stream back and check the geometry a test needs.

Kept independent of castor's own modules, so that the tests judge the output
as any other program reading the stream would.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
from collections import Counter
from dataclasses import dataclass, field

import numpy as np


@dataclass
class Polygon:
    path: str
    colour: tuple[float, float, float]
    points: np.ndarray  # (n, 3)


@dataclass
class Frame:
    number: int
    where: str
    polygons: list[Polygon] = field(default_factory=list)

    def volume(self) -> float:
        return sum(_fan_volume(p.points) for p in self.polygons)

    def box(self) -> np.ndarray:
        pts = np.concatenate([p.points for p in self.polygons])
        return np.array([pts.min(axis=0), pts.max(axis=0)])

    def area(self, colour=None, path_part=None) -> float:
        total = 0.0
        for p in self.polygons:
            if colour is not None and p.colour != tuple(colour):
                continue
            if path_part is not None and path_part not in p.path:
                continue
            total += np.linalg.norm(_newell(p.points)) / 2
        return total

    def colours(self) -> set:
        return {p.colour for p in self.polygons}

    def paths(self) -> set:
        return {p.path for p in self.polygons}


def parse_stream(text: str) -> list[Frame]:
    lines = text.splitlines()
    assert lines and lines[0] == "castor-polygons 1", "missing header"
    frames: list[Frame] = []
    current = None
    for line in lines[1:]:
        fields = line.split(" ")
        if fields[0] == "frame":
            assert current is None, "frame inside a frame"
            current = Frame(int(fields[1]), fields[2])
        elif fields[0] == "poly":
            path = fields[1]
            colour = tuple(float(x) for x in fields[2:5])
            n = int(fields[5])
            coords = [float(x) for x in fields[6:]]
            assert len(coords) == 3 * n, f"vertex count mismatch in {line[:80]}"
            current.polygons.append(Polygon(path, colour, np.array(coords).reshape(n, 3)))
        elif fields[0] == "endframe":
            assert int(fields[1]) == current.number
            assert int(fields[2]) == len(current.polygons), "endframe count mismatch"
            frames.append(current)
            current = None
        else:
            raise AssertionError(f"unknown record: {line[:80]}")
    assert current is None, "frame not ended"
    return frames


def _newell(points: np.ndarray) -> np.ndarray:
    """Twice the polygon's vector area (Newell), taken about its centre: about
    the origin, the rounding of coordinates of 2 swamps the normal of a
    triangle 2e-4 long and 1e-10 high, and a planar one read as tilted."""
    points = points - points.mean(axis=0)
    nxt = np.roll(points, -1, axis=0)
    return np.cross(points, nxt).sum(axis=0)


def _fan_volume(points: np.ndarray) -> float:
    a = points[0]
    total = 0.0
    for i in range(1, len(points) - 1):
        total += float(np.dot(a, np.cross(points[i], points[i + 1]))) / 6
    return total


def check_closed(frame: Frame) -> None:
    """Every directed edge is matched by exactly one opposite edge (by exact position)."""
    edges = Counter()
    for p in frame.polygons:
        pts = [tuple(v) for v in p.points.tolist()]
        for i in range(len(pts)):
            edges[(pts[i], pts[(i + 1) % len(pts)])] += 1
    for (a, b), count in edges.items():
        assert count == 1, f"edge {a}->{b} used {count} times"
        assert edges.get((b, a)) == 1, f"edge {a}->{b} has no opposite edge"


def check_convex_planar(frame: Frame, slack: float = 1e-7) -> None:
    for p in frame.polygons:
        pts = p.points
        assert len(pts) >= 3
        normal = _newell(pts)
        length = np.linalg.norm(normal)
        assert length > 0, f"degenerate polygon {p.path}"
        normal /= length
        size = np.ptp(pts, axis=0).max()
        distance = (pts - pts.mean(axis=0)) @ normal
        assert np.abs(distance).max() <= slack * max(size, 1.0), f"non-planar polygon {p.path}"
        edges = np.roll(pts, -1, axis=0) - pts
        turns = np.cross(edges, np.roll(edges, -1, axis=0)) @ normal
        scale = np.linalg.norm(edges, axis=1) * np.linalg.norm(np.roll(edges, -1, axis=0), axis=1)
        assert np.all(turns >= -slack * scale), f"non-convex polygon {p.path}"


def check_solid(frame: Frame) -> None:
    check_closed(frame)
    check_convex_planar(frame)
    if frame.polygons:
        assert frame.volume() > 0, "surface is not outward oriented"


def write(tmp_path, name, text):
    """Write a test's file (its folders made as needed); its path."""
    path = tmp_path / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


def hear_ctrl_c() -> None:
    """For ``preexec_fn``: the castor a test starts hears Ctrl-C (SIGINT) even when
    the tests themselves were started as a background job of a shell, which
    starts them with SIGINT ignored and would pass that on to castor."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)


def run(*args, stdin: str | None = None, cwd=None, check_status=None):
    """Run castor; returns (status, stdout, stderr)."""
    # run outside the source tree, so that the installed package is what runs
    result = subprocess.run([sys.executable, "-m", "castor", *args], input=stdin,
                            capture_output=True, text=True, cwd=cwd or tempfile.gettempdir(),
                            timeout=600)
    assert "Traceback" not in result.stderr, result.stderr
    if check_status is not None:
        assert result.returncode == check_status, result.stderr
    return result.returncode, result.stdout, result.stderr


def frames_of(scene: str, *args) -> list[Frame]:
    """Facetize a scene given as text; fails on any error message. castor's
    command line runs in this process (what it writes is read back as from a
    pipe): the tests make hundreds of scenes, and each process start costs more
    than most of them; the process as a whole is tested through ``run``."""
    status, out, err = run_here("--no-cpp", *args, stdin=scene)
    assert status == 0, err
    return parse_stream(out)


def run_here(*args, stdin: str = ""):
    """castor's command line in this process: (status, stdout, stderr)."""
    import io

    from castor.cli import main

    saved = sys.stdin, sys.stdout, sys.stderr
    sys.stdin, sys.stdout, sys.stderr = io.StringIO(stdin), io.StringIO(), io.StringIO()
    try:
        status = main(list(args))
    except SystemExit as exc:  # usage errors exit through argparse
        status = exc.code
    finally:
        out, err = sys.stdout.getvalue(), sys.stderr.getvalue()
        sys.stdin, sys.stdout, sys.stderr = saved
    assert "Traceback" not in err, err
    return status, out, err


# --- regularity (LANGUAGE.md §7): judged on the stream alone ---------------

def polygon_defects(polygon: Polygon, slack: float = 1e-7) -> list[str]:
    """What is wrong with one polygon: too few vertices, a repeated vertex,
    zero area, not planar, not convex, or winding more than once."""
    pts = polygon.points
    n = len(pts)
    if n < 3:
        return ["fewer than 3 vertices"]
    defects = []
    rounded = [tuple(p) for p in pts.tolist()]
    if len(set(rounded)) != n:
        defects.append("a repeated vertex")
    size = max(float(np.ptp(pts, axis=0).max()), 1e-300)
    normal = _newell(pts)
    length = float(np.linalg.norm(normal))
    if length <= 1e-12 * size * size:
        return defects + ["zero area"]
    normal /= length
    if np.abs((pts - pts.mean(axis=0)) @ normal).max() > slack * max(size, 1.0):
        defects.append("not planar")
    edges = np.roll(pts, -1, axis=0) - pts
    following = np.roll(edges, -1, axis=0)
    turns = np.cross(edges, following) @ normal
    lengths = np.linalg.norm(edges, axis=1) * np.linalg.norm(following, axis=1)
    if np.any(turns < -slack * lengths):
        defects.append("not convex")
    # the exterior angles of a simple convex polygon add up to one turn
    u = edges - np.outer(edges @ normal, normal)
    angle = np.arctan2(np.cross(u, np.roll(u, -1, axis=0)) @ normal,
                       np.einsum("ij,ij->i", u, np.roll(u, -1, axis=0)))
    if abs(angle.sum() - 2 * np.pi) > 1e-6:
        defects.append(f"winds {angle.sum() / (2 * np.pi):.2f} times")
    return defects


def shells(frame: Frame) -> list[list[int]]:
    """The polygons of each connected shell (polygons sharing a vertex position)."""
    parent = {}

    def find(k):
        while parent.setdefault(k, k) != k:
            parent[k] = parent[parent[k]]
            k = parent[k]
        return k

    for i, p in enumerate(frame.polygons):
        for v in p.points.tolist():
            parent[find(("v", tuple(v)))] = find(("p", i))
    groups: dict = {}
    for i in range(len(frame.polygons)):
        groups.setdefault(find(("p", i)), []).append(i)
    return list(groups.values())


def shell_defects(frame: Frame, thickness: float = 1e-9) -> list[str]:
    """Shells of (about) zero volume: their volume over half their area, a mean
    thickness, is below ``thickness`` times the frame's size."""
    if not frame.polygons:
        return []
    size = max(float(np.abs(frame.box()).max()), 1.0)
    defects = []
    for members in shells(frame):
        volume = sum(_fan_volume(frame.polygons[i].points) for i in members)
        area = sum(np.linalg.norm(_newell(frame.polygons[i].points)) / 2 for i in members)
        if abs(volume) <= thickness * size * area / 2:  # a cavity's volume is negative
            defects.append(f"a shell of {len(members)} polygons has volume {volume:.3g} "
                           f"for area {area:.3g}")
    return defects


def _fan_arrays(frame: Frame) -> np.ndarray:
    tris = []
    for p in frame.polygons:
        for k in range(1, len(p.points) - 1):
            tris.append((p.points[0], p.points[k], p.points[k + 1]))
    return np.array(tris, dtype=np.float64).reshape(-1, 3, 3)


def winding_numbers(triangles: np.ndarray, points: np.ndarray) -> np.ndarray:
    """The generalized winding number of a closed triangle surface at each point
    (Van Oosterom and Strackee's solid angle of each triangle)."""
    out = np.zeros(len(points))
    for start in range(0, len(points), 64):
        q = points[start:start + 64]
        a = triangles[None, :, 0, :] - q[:, None, :]
        b = triangles[None, :, 1, :] - q[:, None, :]
        c = triangles[None, :, 2, :] - q[:, None, :]
        la, lb, lc = (np.linalg.norm(x, axis=2) for x in (a, b, c))
        det = np.einsum("qtj,qtj->qt", a, np.cross(b, c))
        div = (la * lb * lc + np.einsum("qtj,qtj->qt", a, b) * lc
               + np.einsum("qtj,qtj->qt", b, c) * la + np.einsum("qtj,qtj->qt", c, a) * lb)
        out[start:start + 64] = np.arctan2(det, div).sum(axis=1) / (2 * np.pi)
    return out


def sheet_defects(frame: Frame, offset: float = 1e-8) -> list[str]:
    """Polygons that do not part inside from outside: just behind each polygon
    (at a point inside it) the winding number must be 1, just in front 0. A
    sheet of two coincident faces, or a face folded back on itself, fails."""
    if not frame.polygons:
        return []
    triangles = _fan_arrays(frame)
    size = max(float(np.abs(frame.box()).max()), 1.0)
    points, names = [], []
    for index, p in enumerate(frame.polygons):
        normal = _newell(p.points)
        length = np.linalg.norm(normal)
        if length == 0:
            continue
        # a needle narrower than the offset (a strip 1.4e-9 wide along an
        # edge of the solid, which the engine's rounding leaves) has no point
        # that far behind it that is not past the edge: the test cannot see it
        extent = float(np.ptp(p.points, axis=0).max())
        if length / 2 < offset * size * extent:
            continue
        normal /= length
        # four points well inside the (convex) polygon, none on a line through
        # its centre and a corner: solids that touch along a line (which is no
        # sheet) often touch along a diagonal, and one point may lie on it
        centre = p.points.mean(axis=0)
        n = len(p.points)
        for q in [0.47 * p.points[k % n] + 0.31 * p.points[(k + 1) % n] + 0.22 * centre
                  for k in range(4)]:
            points += [q - offset * size * normal, q + offset * size * normal]
        names.append((index, p.path))
    if not names:
        return []
    w = winding_numbers(triangles, np.array(points)).reshape(-1, 4, 2)
    wrong = (np.abs(w[:, :, 0] - 1) > 0.01) | (np.abs(w[:, :, 1]) > 0.01)
    bad = np.flatnonzero(wrong.sum(axis=1) >= 2)
    return [f"polygon {names[i][0]} of {names[i][1]} has winding {w[i, 0, 0]:.3f} behind and "
            f"{w[i, 0, 1]:.3f} in front" for i in bad.tolist()]


def regularity_defects(frame: Frame, sheets: bool = True) -> list[str]:
    """Every defect LANGUAGE.md §7 rules out, as readable lines (empty if none)."""
    defects = [f"polygon {i} of {p.path}: {', '.join(d)}"
               for i, p in enumerate(frame.polygons) if (d := polygon_defects(p))]
    defects += shell_defects(frame)
    if sheets:
        defects += sheet_defects(frame)
    return defects
