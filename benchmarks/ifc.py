"""IFC4 (-o model.ifc): what writing it costs, and what ifcopenshell's part of
that is against castor's own work.

Scenes: the house (examples/house.cas), the two-storey pavilion
(examples/pavilion.cas), the bus shelter (one frame: -D ONE_FRAME), and
1,024 houses (benchmarks/houses.py's house in a 32 x 32 block) three times: as
the union of them all, one element of about 600,000 triangles; as 1,024
objects of one '>' command, 1,024 elements (what a site model is); and as
1,024 houses annotated (LANGUAGE.md §11: walls, windows, a door, a roof,
columns), each with its 13 openings filled by its doors and windows.

For each: the whole process (`castor -o x.ifc`, median wall-clock and CPU
seconds, peak memory), the same with `-o x.glb` for reference, and in one
process the stages (CPU seconds, as the machine may be shared): evaluate +
facetize (castor), the building model (castor.bim: the elements' own solids,
openings, quantities), the IFC entities made with ifcopenshell's entity API,
the STEP text written by ifcopenshell; and the import of ifcopenshell itself.

Targets: house and pavilion <= 1 s, bus shelter <= 10 s; 1,024 houses measured.

CASTOR_IFC_SCENES=house,pavilion runs some of the scenes only (by the start
of their label); CASTOR_IFC_SIDE=N makes the blocks N x N houses instead of
32 x 32 (the labels say how many).
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
SIDE = int(os.environ.get("CASTOR_IFC_SIDE", "32"))  # houses along each side of a block
HOUSES = f"{SIDE * SIDE:,} houses"

BLOCK = CASTOR.replace("> $U[I = 0, 7]($U[J = 0, 7](@t(15 * I, 15 * J, 0) maison));",
                       f"> $U[I = 0, {SIDE - 1}]($U[J = 0, {SIDE - 1}](@t(15 * I, 15 * J, 0) "
                       f"maison));")
SITE = CASTOR.replace("> $U[I = 0, 7]($U[J = 0, 7](@t(15 * I, 15 * J, 0) maison));", "")
SITE += "".join(f"maison_{i:02d}_{j:02d} = @t({15 * i}, {15 * j}, 0) maison;\n"
                for i in range(SIDE) for j in range(SIDE))
SITE += "> " + ", ".join(f"maison_{i:02d}_{j:02d}" for i in range(SIDE)
                         for j in range(SIDE)) + ";\n"

# the same house, saying what it is: each of its openings an IfcOpeningElement
# filled by a window or the door
CLASSED = """
L = 10; P = 8; H = 3; E = 0.3;
murs = $D(@h(L, P, H) !cu(0.9, 0.9, 0.8), @t(E, E, -1) @h(L - 2 * E, P - 2 * E, H + 2) !cu(0.9, 0.9, 0.8));  // [wall]
fen_s = @t(1 + K * 1.8, -1, 1) @h(1, 3, 1.2) !cu(0.2, 0.4, 0.9);  // [window]
fen_n = @t(1 + K * 1.8, P - 2, 1) @h(1, 3, 1.2) !cu(0.2, 0.4, 0.9);  // [window]
fen_o = @t(-1, 3, 1) @h(3, 1, 1.2) !cu(0.2, 0.4, 0.9);  // [window]
fen_e = @t(L - 2, 3, 1) @h(3, 1, 1.2) !cu(0.2, 0.4, 0.9);  // [window]
porte = @t(4.5, -1, -0.5) @h(1, 3, 2.6) !cu(0.2, 0.4, 0.9);  // [door]
ouvertures = $U($U[K = 0, 4](fen_s), $U[K = 0, 4](fen_n), fen_o, fen_e, porte);
toit = @t(L / 2, P / 2, H) @rz(45) @h(7.5, 7.5, 2.5) !py(0.7, 0.2, 0.1, 4);  // [roof]
colonne = @t(1 + C * 2.6, -1.5, 0) @h(0.2, 0.2, H) !pr(0.8, 0.8, 0.8, 16);  // [column]
maison = $U($D(murs, ouvertures), toit, $U[C = 0, 3](colonne));
"""
CLASSED_SITE = CLASSED + "".join(f"maison_{i:02d}_{j:02d} = @t({15 * i}, {15 * j}, 0) maison;\n"
                                 for i in range(SIDE) for j in range(SIDE))
CLASSED_SITE += "> " + ", ".join(f"maison_{i:02d}_{j:02d}" for i in range(SIDE)
                                 for j in range(SIDE)) + ";\n"


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
    from castor.bim import build
    from castor.formats import ifc
    from castor.mesh.facetize import Facetizer
    from castor.pipeline import evaluated_frames

    started = time.process_time()
    [scene], said = evaluated_frames(text, name, defines=defines)
    facetizer = Facetizer()
    frame = facetizer.frame(scene)
    castor_seconds = time.process_time() - started
    started = time.process_time()
    building = build(scene, frame, facetizer)
    bim = time.process_time() - started
    started = time.process_time()
    model = ifc.model(building)
    built = time.process_time() - started
    started = time.process_time()
    data = model.to_string().encode("utf-8")
    written = time.process_time() - started
    faces = len(model.by_type("IfcIndexedPolygonalFace"))
    return {"castor": castor_seconds, "bim": bim, "build": built, "write": written,
            "faces": faces, "elements": len(model.by_type("IfcElement")),
            "openings": len(building.openings), "megabytes": len(data) / 1e6}


def main() -> None:
    started = time.process_time()
    import ifcopenshell  # noqa: F401  (what a run pays once)

    imported = time.process_time() - started
    work = tempfile.mkdtemp()
    scenes = [("house", ROOT / "examples" / "house.cas", None, (), "1"),
              ("pavilion (two storeys)", ROOT / "examples" / "pavilion.cas", None, (), "1"),
              ("bus shelter", ROOT / "examples" / "bus_shelter.cas", None, ("ONE_FRAME",), "10"),
              (f"{HOUSES}, one element", Path(work) / "block.cas", BLOCK, (), "-"),
              (f"{HOUSES}, {SIDE * SIDE:,} elements", Path(work) / "site.cas", SITE, (), "-"),
              (f"{HOUSES} with openings", Path(work) / "classed.cas", CLASSED_SITE, (), "-")]
    chosen = os.environ.get("CASTOR_IFC_SCENES")  # e.g. "house,pavilion": some of them
    # ("1" chooses the blocks of houses whatever their number: "1,024 houses", "16 houses")
    if chosen:
        scenes = [s for s in scenes if any(s[0].startswith(c) for c in chosen.split(","))]
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
        rows.append([label, f"{stages['elements']:,}", f"{stages['openings']:,}",
                     f"{stages['faces']:,}",
                     f"{stages['megabytes']:.1f}", f"{ifc_time:.2f}", f"{ifc_cpu:.2f}",
                     f"{ifc_peak:.0f}", target, f"{glb_time:.2f}", f"{glb_cpu:.2f}",
                     f"{glb_peak:.0f}", f"{stages['castor']:.2f}",
                     f"{stages['bim']:.2f}", f"{stages['build']:.2f}",
                     f"{stages['write']:.2f}"])
        print(f"{label}: done", file=sys.stderr)
    print(f"import ifcopenshell: {imported:.2f} s CPU; {os.getloadavg()[0]:.1f} load average "
          f"on {os.cpu_count()} cores")
    print(table(rows, ["scene", "elements", "openings", "faces", "MB", "ifc s", "ifc CPU s",
                       "ifc MB peak", "target s", "glb s", "glb CPU s", "glb MB peak",
                       "castor CPU s", "building model CPU s", "IFC entities CPU s",
                       "STEP text CPU s"]))


if __name__ == "__main__":
    main()
