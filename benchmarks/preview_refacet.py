"""The live preview's facets following the camera (issue 34 item 3): the
triangles shown and the time of a refacet (castor.serve.evaluation.refaceted,
as after ``POST /camera``) on an example, as the page's camera moves.

The scene is evaluated once with its own tolerance (what the page first
shows); then, in turn, the page's fitted view (azimuth -60°, elevation 25°,
the page's field of view of 40° on a 900 x 612 view), the same turned by 90°,
zoomed towards its middle four times closer, and back to the fitted view.
Each line: triangles, objects faceted again, seconds.

    python benchmarks/preview_refacet.py [SCENE (examples/bus_shelter.cas)]
"""

from __future__ import annotations

import math
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

FOV, WIDTH, HEIGHT = 40.0, 900, 612


def page_view(box, azimuth: float, elevation: float, closer: float = 1.0) -> dict:
    """The camera request the page sends for this view of the box (viewer.js fit)."""
    low, high = box
    target = [(a + b) / 2 for a, b in zip(low, high)]
    radius = max(math.dist(low, high) / 2, 1e-6)
    half = min(math.radians(FOV) / 2, math.atan(math.tan(math.radians(FOV) / 2) * WIDTH / HEIGHT))
    distance = radius / math.sin(half) * 1.02 / closer
    az, el = math.radians(azimuth), math.radians(elevation)
    towards = [math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)]
    return {"eye": [t + d * distance for t, d in zip(target, towards)], "target": target,
            "up": [-math.sin(el) * math.cos(az), -math.sin(el) * math.sin(az), math.cos(el)],
            "fov": FOV, "width": WIDTH, "height": HEIGHT}


def main() -> int:
    from castor.serve.evaluation import Facets, Watched, evaluate, refaceted
    from castor.serve.camera import page_camera
    from castor.settings import Source

    scene = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "examples",
                                                                "bus_shelter.cas")
    started = time.perf_counter()
    shown = evaluate(Watched(Source((scene,)), quiet=True), facets=Facets())
    assert shown.errors == 0, shown.printed
    seconds = time.perf_counter() - started
    print(f"{os.path.basename(scene)}: evaluated with its tolerance: "
          f"{sum(f.triangles for f in shown.frames):,} triangles, {seconds:.2f} s")
    box = shown.frames[0].box
    for label, view in (("fitted view", page_view(box, -60, 25)),
                        ("turned 90 degrees", page_view(box, 30, 25)),
                        ("zoomed 4x closer", page_view(box, 30, 25, 4.0)),
                        ("fitted view again", page_view(box, -60, 25))):
        facets = Facets(page_camera(view), shown.faceted)
        started = time.perf_counter()
        moved = refaceted(shown, facets)
        seconds = time.perf_counter() - started
        again = sum(sum(a is not b for a, b in zip(moved.faceted[n].objects,
                                                  shown.faceted[n].objects))
                    for n in moved.faceted)
        print(f"  {label:18} {sum(f.triangles for f in moved.frames):>9,} triangles, "
              f"{again} object(s) faceted again, {seconds:.2f} s")
        shown = moved
    return 0


if __name__ == "__main__":
    sys.exit(main())
