"""castor.snap on the bus shelter: the time of one snap once the frame is prepared.

The scene is evaluated and its first frame prepared once (as the language
server and the preview keep it while the cursor moves); then a camera
looking at the shelter from the street corner, 1200x800 pixels of 0.001 rad,
snaps at a grid of pixels across the view (some on faces, some near edges
and corners, some on the sky, which snaps to the ground's grid), each with
and without a previous point (axes and parallels inferred). Prints the
median, the 90th percentile and the worst time (wall clock and CPU), and
what the snaps found.
Target (CLI.md): <= 50 ms per snap.
"""

from __future__ import annotations

import collections
import statistics
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

from castor.editing.commands import Cache, snap  # noqa: E402
from castor.editing.document import path_to_uri  # noqa: E402
from castor.settings import ReadSettings  # noqa: E402


def main() -> None:
    uri = path_to_uri(str(HERE.parent / "examples" / "bus_shelter.cas"))
    cache = Cache(reading=ReadSettings(defines=("ONE_FRAME",)))
    started = time.perf_counter()
    document = cache.document(uri)
    evaluated = time.perf_counter()
    prepared = document.prepared(1)
    ready = time.perf_counter()
    low, high = prepared.solids.traced.box
    eye = np.array([low[0] - 8.0, low[1] - 10.0, 6.0])
    target = (low + high) / 2
    forward = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    pixel = 0.001
    times, cpus, features = [], [], collections.Counter()
    previous = None
    for row in np.linspace(-380, 380, 12):
        for column in np.linspace(-580, 580, 16):
            direction = forward + pixel * (column * right + row * up)
            for use_previous in (False, True):
                arguments = {"uri": uri, "frame": 1, "origin": eye.tolist(),
                             "direction": direction.tolist(), "pixel": pixel}
                if use_previous and previous is not None:
                    arguments["from"] = previous
                began, cpu = time.perf_counter(), time.process_time()
                found = snap(arguments, cache)
                times.append(time.perf_counter() - began)
                cpus.append(time.process_time() - cpu)
                features[found["feature"].split()[0] if found else "nothing"] += 1
                if found and not use_previous:
                    previous = found["point"]
    times.sort()
    cpus.sort()
    print(f"bus shelter: evaluated in {evaluated - started:.3f} s, prepared for snapping in "
          f"{ready - evaluated:.3f} s ({len(prepared.solids.traced.leaves)} primitives)")
    print(f"{len(times)} snaps: median {statistics.median(times) * 1000:.1f} ms, "
          f"90% {times[int(len(times) * 0.9)] * 1000:.1f} ms, "
          f"worst {times[-1] * 1000:.1f} ms (target <= 50 ms); CPU time: median "
          f"{statistics.median(cpus) * 1000:.1f} ms, 90% {cpus[int(len(cpus) * 0.9)] * 1000:.1f} ms, "
          f"worst {cpus[-1] * 1000:.1f} ms (on a shared machine the wall clock counts the "
          f"waits for a core: run uptime beside it)")
    print("found: " + ", ".join(f"{k} {v}" for k, v in features.most_common()))


if __name__ == "__main__":
    main()
