"""Frames in parallel: a 24-frame animation of a block of houses whose windows
slide from frame to frame (about half a second of work a frame), made with
--jobs 1, --jobs 2, and on a Dask cluster of two one-thread workers started
from the command line as a user would (`dask scheduler`, `dask worker`).
The outputs are compared byte for byte.

Targets: --jobs 2 at least 1.7x faster than --jobs 1; the cluster at least 1.5x.
"""

import os
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


def run(args, scene_path):
    best, out = None, None
    for _ in range(RUNS):
        started = time.perf_counter()
        result = subprocess.run([*castor_command(), *args, scene_path], capture_output=True)
        seconds = time.perf_counter() - started
        if result.returncode != 0:
            raise SystemExit(result.stderr.decode()[:500])
        best = seconds if best is None else min(best, seconds)
        out = result.stdout
    return best, out


def main():
    directory = tempfile.mkdtemp()
    scene = os.path.join(directory, "block.cas")
    with open(scene, "w") as handle:
        handle.write(SCENE)
    rows = []
    one, reference = run(["--jobs", "1"], scene)
    rows.append(["--jobs 1", f"{one:.2f}", f"{one / 24:.2f}", "1.00", "yes"])
    two, out = run(["--jobs", "2"], scene)
    rows.append(["--jobs 2", f"{two:.2f}", f"{two / 24:.2f}", f"{one / two:.2f}",
                 "yes" if out == reference else "NO"])
    dask = shutil.which("dask")
    if dask:
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
            run(["--scheduler", address], scene)  # warm the workers (imports)
            cluster, out = run(["--scheduler", address], scene)
            rows.append(["Dask, 2 one-thread workers", f"{cluster:.2f}", f"{cluster / 24:.2f}",
                         f"{one / cluster:.2f}", "yes" if out == reference else "NO"])
        finally:
            for process in [*workers, scheduler]:
                process.terminate()
            for process in [*workers, scheduler]:
                process.wait(timeout=30)
    print("24 frames of 64 houses whose windows slide (whole processes, best of "
          f"{RUNS}):")
    print(table(rows, ["how", "seconds", "s/frame", "speed-up", "same bytes"]))
    shutil.rmtree(directory, ignore_errors=True)


if __name__ == "__main__":
    main()
