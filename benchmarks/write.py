"""Writing a frame of about 1,000,000 triangles (a finely faceted sphere):
the time to format and write the polygon stream and binary STL, measured
in-process after facetization, and the whole processes for reference.

Targets: polygon stream at most 3 s, binary STL at most 1 s.
"""

import os
import statistics
import tempfile
import time

from _common import castor_command, runs_from_env, timed

RUNS = runs_from_env(3)
TOLERANCE = 1.2e-5  # about 1.1 million triangles for the unit sphere


def main() -> None:
    from castor.mesh.facetize import Facetizer
    from castor.language.parse import Parser
    from castor.language.reader import Chunk
    from castor.language.scene import Tables
    from castor.formats import cps, stl

    (statement,) = list(Parser(Tables()).parse(Chunk("> !sp(1, 1, 1);", (("bench", 1),), 0)))
    started = time.perf_counter()
    frame = Facetizer().frame(statement.objects, {"TOLERANCE": TOLERANCE}, 1, "bench:1", None)
    facetize = time.perf_counter() - started
    triangles = sum(len(o.indices) - 2 * o.polygon_count for o in frame.objects)
    stream_times, stl_times = [], []
    for _ in range(RUNS):
        with tempfile.TemporaryFile("wb") as handle:
            started = time.perf_counter()
            handle.write(cps.export(frame))
            handle.flush()
            stream_times.append(time.perf_counter() - started)
        with tempfile.TemporaryFile("wb") as handle:
            started = time.perf_counter()
            handle.write(stl.export(frame))
            handle.flush()
            stl_times.append(time.perf_counter() - started)
    print(f"frame: {triangles} triangles in {frame.polygon_count} polygons "
          f"(facetized in {facetize:.2f} s)")
    print(f"polygon stream: {statistics.median(stream_times):.2f} s (target <= 3 s)")
    print(f"binary STL:     {statistics.median(stl_times):.2f} s (target <= 1 s)")
    work = tempfile.mkdtemp()
    scene = b"> !sp(1, 1, 1);\n"
    whole_cps = timed(castor_command() + ["--no-cpp", "-t", repr(TOLERANCE), "-o",
                                          os.path.join(work, "s.cps")], stdin=scene, runs=1)
    whole_stl = timed(castor_command() + ["--no-cpp", "-t", repr(TOLERANCE), "-o",
                                          os.path.join(work, "s.stl")], stdin=scene, runs=1)
    print(f"whole process, polygon stream: {whole_cps:.2f} s; binary STL (no polygon "
          f"merging needed): {whole_stl:.2f} s")


if __name__ == "__main__":
    main()
