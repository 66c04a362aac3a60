"""Start-up: `echo '> !cu(1,1,1);' | castor --no-cpp`, whole process, median of runs.

Target: at most 0.15 s. Prints bare Python and the imports for comparison, each
as wall-clock and as CPU time (user + system of the process: steadier on a busy
machine), and the parser's three ways to start: the tables shipped in the package
(castor/language/castor.tables, made by `pip install .`; in a checkout,
`python castor/language/tables.py castor/language` makes them), lark's cache in
the temporary directory (warm), and no tables at all (an empty TMPDIR each run).
"""

import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _common import castor_command, runs_from_env

RUNS = runs_from_env(15)
SHIPPED = Path(__file__).resolve().parent.parent / "castor" / "language" / "castor.tables"


def timed(command, stdin=None, env=None, fresh_tmp=False):
    """Median wall-clock and CPU seconds of running a whole process."""
    walls, cpus = [], []
    for _ in range(RUNS):
        run_env = dict(env or os.environ)
        with tempfile.TemporaryDirectory() as tmp:
            if fresh_tmp:
                run_env["TMPDIR"] = tmp
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            started = time.perf_counter()
            done = subprocess.run(command, input=stdin, stdout=subprocess.DEVNULL,
                                  stderr=subprocess.PIPE, env=run_env)
            walls.append(time.perf_counter() - started)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
        if done.returncode != 0:
            raise SystemExit(f"{' '.join(command)} failed: {done.stderr.decode()[:400]}")
        cpus.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    return statistics.median(walls), statistics.median(cpus)


def show(label, figures, note=""):
    wall, cpu = figures
    print(f"{label:38} {wall:.3f} s wall  {cpu:.3f} s CPU{note}")


CUBE = b"> !cu(1,1,1);\n"
show("bare python", timed([sys.executable, "-c", "pass"]))
show("import numpy, manifold3d", timed([sys.executable, "-c", "import numpy, manifold3d"]))
show("import lark", timed([sys.executable, "-c", "import lark"]))
show("castor --no-cpp, one cube", timed(castor_command() + ["--no-cpp"], stdin=CUBE),
     "   (target <= 0.15 s)" + ("" if SHIPPED.exists() else "  [no shipped tables here]"))
show("castor --no-cpp --check", timed(castor_command() + ["--no-cpp", "--check"], stdin=CUBE))
if SHIPPED.exists():
    hidden = SHIPPED.with_suffix(".hidden")
    SHIPPED.rename(hidden)
    try:
        show("  without shipped tables, lark's cache", timed(castor_command() + ["--no-cpp"], stdin=CUBE))
        show("  without any tables (cold TMPDIR)",
             timed(castor_command() + ["--no-cpp"], stdin=CUBE, fresh_tmp=True))
    finally:
        hidden.rename(SHIPPED)
