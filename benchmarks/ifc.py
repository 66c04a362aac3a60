"""IFC4 (-o model.ifc): what writing it costs, and what ifcopenshell's part of
that is against castor's own work.

Scenes: the house (examples/house.cas), the bus shelter (one frame:
-D ONE_FRAME), and 1,024 houses (benchmarks/houses.py's house in a 32 x 32
block) twice: as the union of them all, one element of about 600,000
triangles, and as 1,024 objects of one '>' command, 1,024 elements (what a
site model is).

For each: the whole process (`castor -o x.ifc`, median wall-clock and CPU
seconds, peak memory), the same with `-o x.glb` for reference, and in one
process the stages (CPU seconds, as the machine may be shared): evaluate +
facetize (castor), the IFC model built with ifcopenshell's entity API
(castor's loop and ifcopenshell's entities), the STEP text written by
ifcopenshell; and the import of ifcopenshell itself.

Targets: house <= 2 s, bus shelter <= 10 s; 1,024 houses measured.
"""

import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _common import castor_command, runs_from_env, table
from houses import CASTOR

RUNS = runs_from_env(3)
ROOT = Path(__file__).resolve().parent.parent

BLOCK = CASTOR.replace("> $U[I = 0, 7]($U[J = 0, 7](@t(15 * I, 15 * J, 0) maison));",
                       "> $U[I = 0, 31]($U[J = 0, 31](@t(15 * I, 15 * J, 0) maison));")
SITE = CASTOR.replace("> $U[I = 0, 7]($U[J = 0, 7](@t(15 * I, 15 * J, 0) maison));", "")
SITE += "".join(f"maison_{i:02d}_{j:02d} = @t({15 * i}, {15 * j}, 0) maison;\n"
                for i in range(32) for j in range(32))
SITE += "> " + ", ".join(f"maison_{i:02d}_{j:02d}" for i in range(32) for j in range(32)) + ";\n"


def _whole(args: list[str], cwd: str) -> tuple[float, float, float]:
    """Median wall-clock and CPU seconds, and the largest peak memory (MB), of a
    whole castor process (each process's own figures, from wait4)."""
    walls, cpus, peaks = [], [], []
    for _ in range(RUNS):
        with tempfile.TemporaryFile() as errors:
            started = time.perf_counter()
            child = subprocess.Popen(castor_command() + args, cwd=cwd,
                                     stdout=subprocess.DEVNULL, stderr=errors)
            _, status, usage = os.wait4(child.pid, 0)
            walls.append(time.perf_counter() - started)
            child.returncode = os.waitstatus_to_exitcode(status)
            if child.returncode != 0:
                errors.seek(0)
                raise SystemExit(f"castor {' '.join(args)} failed: {errors.read()[:400]}")
        cpus.append(usage.ru_utime + usage.ru_stime)
        peaks.append(usage.ru_maxrss / 1024)
    return sorted(walls)[len(walls) // 2], sorted(cpus)[len(cpus) // 2], max(peaks)


def _stages(text: str, name: str, defines=()) -> dict[str, float]:
    from castor.formats import ifc
    from castor.mesh.facetize import Facetizer
    from castor.pipeline import evaluated_frames

    started = time.process_time()
    [scene], said = evaluated_frames(text, name, defines=defines)
    frame = Facetizer().frame(scene)
    castor_seconds = time.process_time() - started
    started = time.process_time()
    model = ifc.model(scene, frame)
    built = time.process_time() - started
    started = time.process_time()
    data = model.to_string().encode("utf-8")
    written = time.process_time() - started
    faces = len(model.by_type("IfcIndexedPolygonalFace"))
    return {"castor": castor_seconds, "build": built, "write": written, "faces": faces,
            "elements": len(model.by_type("IfcElement")), "megabytes": len(data) / 1e6}


def main() -> None:
    started = time.process_time()
    import ifcopenshell  # noqa: F401  (what a run pays once)

    imported = time.process_time() - started
    work = tempfile.mkdtemp()
    scenes = [("house", ROOT / "examples" / "house.cas", None, (), "2"),
              ("bus shelter", ROOT / "examples" / "bus_shelter.cas", None, ("ONE_FRAME",), "10"),
              ("1,024 houses, one element", Path(work) / "block.cas", BLOCK, (), "-"),
              ("1,024 houses, 1,024 elements", Path(work) / "site.cas", SITE, (), "-")]
    rows = []
    for label, path, text, defines, target in scenes:
        if text is not None:
            path.write_text(text)
        flags = [f"-D{d}" for d in defines]
        ifc_time, ifc_cpu, ifc_peak = _whole([*flags, "-o", os.path.join(work, "x.ifc"),
                                              str(path)], work)
        glb_time, glb_cpu, glb_peak = _whole([*flags, "-o", os.path.join(work, "x.glb"),
                                              str(path)], work)
        stages = _stages(path.read_text(), str(path), defines)
        rows.append([label, f"{stages['elements']:,}", f"{stages['faces']:,}",
                     f"{stages['megabytes']:.1f}", f"{ifc_time:.2f}", f"{ifc_cpu:.2f}",
                     f"{ifc_peak:.0f}", target, f"{glb_time:.2f}", f"{glb_cpu:.2f}",
                     f"{glb_peak:.0f}", f"{stages['castor']:.2f}",
                     f"{stages['build']:.2f}", f"{stages['write']:.2f}"])
        print(f"{label}: done", file=sys.stderr)
    print(f"import ifcopenshell: {imported:.2f} s CPU; {os.getloadavg()[0]:.1f} load average "
          f"on {os.cpu_count()} cores")
    print(table(rows, ["scene", "elements", "faces", "MB", "ifc s", "ifc CPU s", "ifc MB peak",
                       "target s", "glb s", "glb CPU s", "glb MB peak", "castor CPU s",
                       "IFC model CPU s", "STEP text CPU s"]))


if __name__ == "__main__":
    main()
