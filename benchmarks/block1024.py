"""The union of 1,024 houses (a 32 x 32 block, about 600,000 triangles): the
whole process timed, and where the time goes, stage by stage, measured in one
process with the same calls castor makes (evaluate, facetize: the engine's
booleans, reading its triangles back, merging polygons; writing the stream).
"""

import os
import subprocess
import sys
import tempfile
import time

from _common import castor_command
from houses import CASTOR

SCENE = CASTOR.replace("> $U[I = 0, 7]($U[J = 0, 7](@t(15 * I, 15 * J, 0) maison));",
                       "> $U[I = 0, 31]($U[J = 0, 31](@t(15 * I, 15 * J, 0) maison));")


def stages():
    import cProfile
    import pstats

    from castor.formats.cps import format_frame
    from castor.settings import MeshSettings
    from castor.mesh.facetize import Facetizer
    from castor.run import evaluated_frames

    started = time.perf_counter()
    [scene], said = evaluated_frames(SCENE, "block.cas")
    evaluated = time.perf_counter() - started
    facetizer = Facetizer(MeshSettings().max_polygons)
    profile = cProfile.Profile()
    started = time.perf_counter()
    profile.enable()
    frame = facetizer.frame(scene)
    profile.disable()
    facetized = time.perf_counter() - started
    started = time.perf_counter()
    text = format_frame(frame)
    written = time.perf_counter() - started
    stats = pstats.Stats(profile)
    by_function = {f"{func[0].split('/')[-1]}:{func[2]}": row[3]
                   for func, row in stats.stats.items()}

    def cumulative(suffix):
        return max((t for name, t in by_function.items() if name.endswith(suffix)), default=0.0)

    print(f"polygons {frame.polygon_count:,}; stream {len(text) / 1e6:.0f} MB")
    print(f"evaluate (the tree)          {evaluated:6.2f} s")
    print(f"facetize, of which:          {facetized:6.2f} s (profiled)")
    print(f"  engine booleans (union)    {cumulative('booleans.py:union'):6.2f} s")
    print(f"  engine triangles back      {cumulative('provenance.py:triangles'):6.2f} s")
    print(f"  their regularization       {cumulative('regularize.py:regular_triangles'):6.2f} s")
    print(f"  polygon merging            {cumulative('merge.py:merge'):6.2f} s")
    print(f"write the stream             {written:6.2f} s")


def main():
    with tempfile.NamedTemporaryFile("w", suffix=".cas", delete=False) as handle:
        handle.write(SCENE)
    for format_name in ("cps", "stl"):
        started = time.perf_counter()
        result = subprocess.run([*castor_command(), "--stats", "-f", format_name, handle.name],
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        seconds = time.perf_counter() - started
        print(f"whole process, 1,024 houses as {format_name}: {seconds:.2f} s; "
              f"{result.stderr.decode().strip()}")
    os.unlink(handle.name)
    stages()


if __name__ == "__main__":
    sys.path.insert(0, os.path.dirname(__file__))
    main()
