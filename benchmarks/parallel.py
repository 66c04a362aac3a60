"""Frames in parallel: a 24-frame animation of a block of houses whose windows
slide from frame to frame (about half a second of work a frame), made by plain
castor, with --jobs 1, --jobs 2, and on a Dask cluster of two one-thread workers started
from the command line as a user would (`dask scheduler`, `dask worker`).
The outputs are compared byte for byte.

Targets: plain castor at least as fast as --jobs 1; --jobs 2 at least 1.7x
faster than plain castor; the cluster at least 1.5x. Besides the wall-clock
seconds, the CPU seconds of castor and the processes it waited for
(RUSAGE_CHILDREN: the workers of --jobs 2, children of the forkserver, are not
counted), since the machine may be shared. NO_DASK=1 leaves the cluster out.
"""

import os
import resource
import shutil
import socket
import subprocess
import tempfile
import time

from _common import castor_command, runs_from_env, table
from houses import CASTOR

RUNS = runs_from_env(1)

# the 64 houses of houses.py, their windows sliding with the frame (T) and the house (I, J)
SCENE = (CASTOR
         .replace("fen_s = @t(1 + K * 1.8, -1, 1)",
                  "fen_s = @t(1 + K * 1.8 + 0.02 * T + 0.01 * I, -1, 1)")
         .replace("fen_n = @t(1 + K * 1.8, P - 2, 1)",
                  "fen_n = @t(1 + K * 1.8 - 0.02 * T + 0.01 * J, P - 2, 1)")
         .replace("> $U[I = 0, 7]($U[J = 0, 7](@t(15 * I, 15 * J, 0) maison));",
                  "bloc = $U[I = 0, 7]($U[J = 0, 7](@t(15 * I, 15 * J, 0) maison));\n"
                  ">[T = 0, 23] bloc;"))


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def run(args, scene_path, runs=None):
    """The best wall-clock seconds of ``runs`` runs (RUNS), the CPU seconds of that
    run, the output."""
    best, cpu, out = None, None, None
    for _ in range(RUNS if runs is None else runs):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        started = time.perf_counter()
        result = subprocess.run([*castor_command(), *args, scene_path], capture_output=True)
        seconds = time.perf_counter() - started
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        if result.returncode != 0:
            raise SystemExit(result.stderr.decode()[:500])
        if best is None or seconds < best:
            best = seconds
            cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        out = result.stdout
    return best, cpu, out


def on_a_new_cluster(dask: str, scene: str, directory: str):
    """One run of the animation on a cluster started for it (a scheduler and two
    one-thread workers, from the command line as a user starts them), warmed by
    one cube so that the workers have imported castor but made nothing of the
    block: a worker keeps the solids it made, and a second run of the same scene
    on the same workers would find them made (the figure of an earlier version
    of this benchmark, 6.6 s, was that)."""
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    quiet = dict(stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=directory)
    scheduler = subprocess.Popen([dask, "scheduler", "--host", "127.0.0.1", "--port",
                                  str(port), "--dashboard-address", ":0"], **quiet)
    workers = [subprocess.Popen([dask, "worker", address, "--nthreads", "1",
                                 "--nworkers", "1", "--dashboard-address", ":0"], **quiet)
               for _ in range(2)]
    try:
        time.sleep(6)  # the workers join the scheduler
        cube = os.path.join(directory, "cube.cas")
        with open(cube, "w") as handle:
            handle.write(">[T = 0, 3] @t(T, 0, 0) !cu(1, 0, 0);\n")
        run(["--scheduler", address], cube, runs=1)  # the workers import castor
        return run(["--scheduler", address], scene, runs=1)
    finally:
        for process in [*workers, scheduler]:
            process.terminate()
        for process in [*workers, scheduler]:
            process.wait(timeout=30)


def main():
    directory = tempfile.mkdtemp()
    scene = os.path.join(directory, "block.cas")
    with open(scene, "w") as handle:
        handle.write(SCENE)
    rows = []
    plain, cpu, reference = run([], scene)
    rows.append(["plain castor", f"{plain:.2f}", f"{cpu:.2f}", f"{plain / 24:.2f}", "1.00",
                 "yes"])
    for how in (["--jobs", "1"], ["--jobs", "2"]):
        seconds, cpu, out = run(how, scene)
        rows.append([" ".join(how), f"{seconds:.2f}", f"{cpu:.2f}", f"{seconds / 24:.2f}",
                     f"{plain / seconds:.2f}", "yes" if out == reference else "NO"])
    dask = shutil.which("dask") if not os.environ.get("NO_DASK") else None
    if dask:
        best = None
        for _ in range(RUNS):  # a new cluster each run: workers keep what they made
            seconds, cpu, out = on_a_new_cluster(dask, scene, directory)
            if best is None or seconds < best[0]:
                best = (seconds, cpu, out)
        cluster, cpu, out = best
        rows.append(["Dask, 2 one-thread workers", f"{cluster:.2f}", f"{cpu:.2f}",
                     f"{cluster / 24:.2f}", f"{plain / cluster:.2f}",
                     "yes" if out == reference else "NO"])
    print("24 frames of 64 houses whose windows slide (whole processes, best of "
          f"{RUNS}):")
    print(table(rows, ["how", "seconds", "CPU s", "s/frame", "speed-up", "same bytes"]))
    shutil.rmtree(directory, ignore_errors=True)


if __name__ == "__main__":
    main()
