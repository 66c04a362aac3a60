"""castor's SVG drawings read back (``Drawn``): cut loops and seen lines per
object, in scene metres, the sheet's texts and pens; ``draw_svg`` runs castor
to make one."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from .cli import run


SVG = "{http://www.w3.org/2000/svg}"


def _path_points(d: str) -> list[list[tuple[float, float]]]:
    """The subpaths of an SVG path made of M, L and Z, as lists of points."""
    subpaths = []
    for command, numbers in re.findall(r"([MLZ])([^MLZ]*)", d):
        values = [float(v) for v in numbers.replace(",", " ").split()]
        points = list(zip(values[0::2], values[1::2]))
        if command == "M":
            subpaths.append(points)
        elif command == "L":
            subpaths[-1].extend(points)
    return subpaths


class Drawn:
    """An SVG drawing read back: its cut loops and seen segments per object's
    group, in scene metres on the page (x right, y up), through the paper
    origin and scale the drawing's group declares (which must be the scale
    asked for); also the sheet's texts, and the pens of each kind of line."""

    def __init__(self, svg: bytes, scale: float):
        root = ET.fromstring(svg)
        self.root = root
        self.width_mm = float(root.get("width").removesuffix("mm"))
        self.height_mm = float(root.get("height").removesuffix("mm"))
        assert root.get("viewBox") == f"0 0 {root.get('width')[:-2]} {root.get('height')[:-2]}"
        drawing = root.find(f"{SVG}g[@id='drawing']")
        ox, oy = (float(v) for v in drawing.get("data-origin").split())
        mm = float(drawing.get("data-mm-per-metre"))
        assert mm == pytest.approx(1000 / scale)
        self.cuts, self.lines, self.pens = {}, {}, {}
        for group in drawing.findall(SVG + "g"):
            name = group.get("id")
            self.cuts[name], self.lines[name] = [], []
            for path in group.iter(SVG + "path"):
                self.pens.setdefault(path.get("class"), set()).add(float(path.get("stroke-width")))
                for sub in _path_points(path.get("d")):
                    p = np.array(sub)
                    p = np.column_stack([(p[:, 0] - ox) / mm, (oy - p[:, 1]) / mm])
                    if path.get("class") == "cut":
                        self.cuts[name].append(p)
                    else:
                        self.lines[name].append(p)
        self.texts = {group.get("id"): ["".join(t.itertext()) for t in group.iter(SVG + "text")]
                      for group in root.findall(SVG + "g")}

    def extent(self, name: str) -> np.ndarray:
        """(2, 2): the corners of what the group draws, in metres."""
        points = np.concatenate(self.lines[name] + self.cuts[name])
        return np.array([points.min(axis=0), points.max(axis=0)])

    def cut_area(self, name: str) -> float:
        total = 0.0
        for loop in self.cuts[name]:
            x, y = loop[:, 0], loop[:, 1]
            total += np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) / 2
        return total

    def in_poche(self, name: str, x: float, y: float) -> bool:
        inside = False
        for loop in self.cuts[name]:
            a, b = loop, np.roll(loop, -1, axis=0)
            crosses = (a[:, 1] > y) != (b[:, 1] > y)
            with np.errstate(divide="ignore", invalid="ignore"):
                at = a[:, 0] + (y - a[:, 1]) * (b[:, 0] - a[:, 0]) / (b[:, 1] - a[:, 1])
            inside ^= bool(np.sum(crosses & (at > x)) % 2)
        return inside

    def has_line(self, name: str, p, q, tol=1e-3) -> bool:
        """Whether a seen segment goes from p to q (either way)."""
        p, q = np.array(p), np.array(q)
        for s in self.lines[name]:
            a, b = s[0], s[-1]
            if (np.allclose(a, p, atol=tol) and np.allclose(b, q, atol=tol)) or \
               (np.allclose(a, q, atol=tol) and np.allclose(b, p, atol=tol)):
                return True
        return False

    def covered(self, name: str, p, q, tol=1e-3) -> float:
        """The length of the segment p→q covered by seen lines lying along it."""
        p, q = np.array(p, float), np.array(q, float)
        d = q - p
        length = np.linalg.norm(d)
        u = d / length
        pieces = []
        for s in self.lines[name]:
            a, b = s[0] - p, s[-1] - p
            if abs(u[0] * a[1] - u[1] * a[0]) < tol and abs(u[0] * b[1] - u[1] * b[0]) < tol:
                t = sorted((a @ u, b @ u))
                pieces.append((max(t[0], 0), min(t[1], length)))
        covered, reach = 0.0, 0.0
        for lo, hi in sorted(pieces):
            lo = max(lo, reach)
            if hi > lo:
                covered += hi - lo
                reach = hi
        return covered


def draw_svg(tmp_path, scene: str, *options, name="d.svg") -> bytes:
    (tmp_path / "s.cas").write_text(scene)
    out = tmp_path / name
    run(*options, "-o", str(out), str(tmp_path / "s.cas"), check_status=0)
    return b"" if "%" in name else out.read_bytes()
