"""The simple polygons !ex and !rv take, checked: a polygon, or a profile in r >= 0.

Both are refused with the primitive's path when they repeat a vertex, cross
themselves, fold back or enclose no area (LANGUAGE.md §4.1). numpy is imported
in the functions: castor.primitives imports this module when it gathers the
primitives, and reading a scene needs no numpy.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from castor.diagnostics import GeometryError, Location

if TYPE_CHECKING:
    import numpy as np


def _check_simple(points: np.ndarray, what: str, location: Location, path: object) -> None:
    """Refuse repeated vertices, self-intersection and zero area."""
    import numpy as np

    n = len(points)
    nxt = np.roll(points, -1, axis=0)
    if np.any(np.all(points == nxt, axis=1)):
        raise GeometryError(f"the {what} of {path} repeats a vertex", location)
    a, b = points, nxt
    d = b - a
    for i in range(n):
        p, r = a[i], d[i]
        # edges that do not share a vertex with edge i
        others = np.array([j for j in range(n) if j != i and j != (i + 1) % n and (j + 1) % n != i])
        if len(others) == 0:
            continue
        q, s = a[others], d[others]
        denom = r[0] * s[:, 1] - r[1] * s[:, 0]
        qp = q - p
        t_num = qp[:, 0] * s[:, 1] - qp[:, 1] * s[:, 0]
        u_num = qp[:, 0] * r[1] - qp[:, 1] * r[0]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = t_num / denom
            u = u_num / denom
        crossing = (denom != 0) & (t >= 0) & (t <= 1) & (u >= 0) & (u <= 1)
        # parallel edges on one line that overlap
        collinear = (denom == 0) & (t_num == 0)
        if np.any(collinear):
            rr = float(r @ r)
            t0 = (qp[collinear] @ r) / rr
            t1 = ((qp[collinear] + s[collinear]) @ r) / rr
            overlap = (np.maximum(t0, t1) >= 0) & (np.minimum(t0, t1) <= 1)
            crossing[np.flatnonzero(collinear)[overlap]] = True
        if np.any(crossing):
            raise GeometryError(f"the {what} of {path} intersects itself (edge {i + 1} crosses "
                                f"edge {int(others[np.argmax(crossing)]) + 1})", location)
        # adjacent edges folding back onto each other
        r_next = d[(i + 1) % n]
        if r[0] * r_next[1] - r[1] * r_next[0] == 0 and float(r @ r_next) < 0:
            raise GeometryError(f"the {what} of {path} folds back on itself at vertex "
                                f"{(i + 1) % n + 1}", location)
    if signed_area(points) == 0:
        raise GeometryError(f"the {what} of {path} has zero area", location)


def signed_area(points: np.ndarray) -> float:
    import numpy as np

    x, y = points[:, 0], points[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def polygon(values: tuple, what: str, location: Location, path: object) -> np.ndarray:
    import numpy as np

    points = np.array(values, dtype=np.float64).reshape(-1, 2)
    if len(points) > 3 and np.all(points[0] == points[-1]):
        points = points[:-1]  # a closing vertex repeating the first is allowed
    if len(points) < 3:
        raise GeometryError(f"the {what} of {path} needs at least 3 vertices", location)
    _check_simple(points, what, location, path)
    return points


def profile(values: tuple, location: Location, path: object) -> np.ndarray:
    """A revolution's profile: a simple polygon in the half-plane r >= 0."""
    import numpy as np

    points = polygon(values, "profile", location, path)
    if np.any(points[:, 0] < 0):
        i = int(np.argmax(points[:, 0] < 0))
        raise GeometryError(f"the profile of {path} has r < 0 at vertex {i + 1} "
                            f"(r = {points[i, 0]:g}); a profile lies in the half-plane r >= 0",
                            location)
    return points
