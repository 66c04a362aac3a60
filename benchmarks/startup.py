"""Start-up: castor run as a whole process on one cube, and for --check, --help and
--version; this checkout beside others, before and after.

    python benchmarks/startup.py                      this checkout
    python benchmarks/startup.py --repo ../before     ... and the checkout in ../before
    python benchmarks/startup.py --commit 490f77f     ... and that commit (git archive)
    python benchmarks/startup.py --built ...          ... and each built as pip installs it

Target (issue 18): at most 0.15 s for one cube. Each figure is the median of
BENCH_RUNS runs (15) after one run not counted, as wall-clock and as CPU time
(user + system of the process: steadier on a busy machine; say the load when you
quote them). Every castor is run as ``python -m castor`` with PYTHONPATH set to its
checkout, from an empty directory.

Compiled modules: a checkout run with PYTHONDONTWRITEBYTECODE set (as some
environments set it) compiles every module on every run, which an installed
package never does. The runs here unset it and keep the compiled files in a
directory of their own (PYTHONPYCACHEPREFIX), written by the run not counted: the
figures are an installed package's, and no checkout is written to.

The parser's tables: an installed castor reads them from the package (made by
``pip install .``; in a checkout ``python castor/language/tables.py castor/language``
makes them); a checkout keeps them in the temporary directory from its first run.
The line "first run, cold temporary directory" is that first run (lark imported
and the parser built), with an empty TMPDIR each time. ``--built`` adds, for each
checkout with a setup.py, the package as its build step makes it
(``setup.py build_py``, what ``pip install .`` runs), tables shipped inside.
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

from _common import runs_from_env

RUNS = runs_from_env(15)
HERE = Path(__file__).resolve().parent.parent
CUBE = "> !cu(1, 1, 1);\n"


def _environment(cache: str, tmp: str | None = None, path: str | None = None) -> dict:
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    env["PYTHONPYCACHEPREFIX"] = cache
    env.pop("PYTHONPATH", None)
    if path is not None:
        env["PYTHONPATH"] = path
    if tmp is not None:
        env["TMPDIR"] = tmp
    return env


def timed(command: list[str], env: dict, cwd: str, fresh_tmp: bool = False) -> tuple[float, float]:
    """Median wall-clock and CPU seconds of a whole process, after a run not counted."""
    walls, cpus = [], []
    for run in range(RUNS + 1):
        with tempfile.TemporaryDirectory() as tmp:
            run_env = dict(env, TMPDIR=tmp) if fresh_tmp else env
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            started = time.perf_counter()
            done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                  env=run_env, cwd=cwd)
            wall = time.perf_counter() - started
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
        if done.returncode != 0:
            raise SystemExit(f"{' '.join(command)} failed: {done.stderr.decode()[:400]}")
        if run:
            walls.append(wall)
            cpus.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    return statistics.median(walls), statistics.median(cpus)


def _exported(commit: str, into: Path) -> Path:
    """The commit's files (git archive) in ``into``: a checkout of it, nothing written
    to this repository."""
    archive = into / "source.tar"
    with open(archive, "wb") as handle:
        subprocess.run(["git", "-C", str(HERE), "archive", commit], stdout=handle, check=True)
    target = into / commit
    target.mkdir()
    with tarfile.open(archive) as tar:
        tar.extractall(target, filter="data")
    return target


def _built(checkout: Path, into: Path) -> Path | None:
    """The package as the checkout's build step makes it, or None (no setup.py); built
    from a copy, as the build writes beside its sources (egg-info)."""
    if not (checkout / "setup.py").exists():
        return None
    source = into.with_name(into.name + "-source")
    shutil.copytree(checkout, source, ignore=shutil.ignore_patterns(
        ".git", "__pycache__", "build", "*.egg-info", "castor.tables", "castor.lalr"))
    done = subprocess.run([sys.executable, "setup.py", "-q", "build_py", "--build-lib", str(into)],
                          cwd=source, capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"building {checkout} failed: {done.stderr[:400]}")
    return into


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repo", action="append", default=[], metavar="DIR",
                    help="another checkout to measure beside this one")
    ap.add_argument("--commit", action="append", default=[], metavar="REV",
                    help="a commit of this repository to measure beside this one")
    ap.add_argument("--built", action="store_true",
                    help="also each checkout built as `pip install .` builds it")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as work:
        work_dir = Path(work)
        cache, run_dir = work_dir / "pycache", work_dir / "run"
        cache.mkdir()
        run_dir.mkdir()
        scene = run_dir / "one-cube.cas"
        scene.write_text(CUBE)
        checkouts = [("this checkout", HERE)] + [(d, Path(d).resolve()) for d in args.repo]
        for commit in args.commit:
            checkouts.append((commit, _exported(commit, work_dir)))
        if args.built:
            for label, checkout in list(checkouts):
                built = _built(checkout, work_dir / f"built-{len(checkouts)}")
                if built is not None:
                    checkouts.append((f"{label[-16:]} (built)", built))
        python = [sys.executable]
        reference = _environment(str(cache))
        print(f"{RUNS} runs each, median; load average {os.getloadavg()[0]:.2f} "
              f"on {os.cpu_count()} cores; compiled modules kept, PYTHONDONTWRITEBYTECODE unset")
        for label, code in [("bare python", "pass"), ("import numpy", "import numpy"),
                            ("import lark", "import lark")]:
            wall, cpu = timed(python + ["-c", code], reference, str(run_dir))
            print(f"{label:44} {wall:6.3f} s wall {cpu:6.3f} s CPU")
        rows = [("castor --no-cpp one-cube.cas", ["--no-cpp", scene.name], False),
                ("castor one-cube.cas (with cpp)", [scene.name], False),
                ("castor --no-cpp --check one-cube.cas", ["--no-cpp", "--check", scene.name], False),
                ("castor --help", ["--help"], False),
                ("castor --version", ["--version"], False),
                ("first run, cold temporary directory", ["--no-cpp", scene.name], True)]
        print()
        print(f"{'':44}" + "".join(f"{label[-24:]:>26}" for label, _ in checkouts))
        print(f"{'':44}" + "".join(f"{'wall / CPU s':>26}" for _ in checkouts))
        for label, arguments, cold in rows:
            cells = []
            for _, checkout in checkouts:
                env = _environment(str(cache), path=str(checkout))
                wall, cpu = timed(python + ["-m", "castor"] + arguments, env, str(run_dir),
                                  fresh_tmp=cold)
                cells.append(f"{wall:.3f} / {cpu:.3f}")
            print(f"{label:44}" + "".join(f"{cell:>26}" for cell in cells))
        shipped = [label for label, checkout in checkouts
                   if (checkout / "castor" / "language" / "castor.lalr").exists()]
        print(f"\nparser tables shipped in the package: {', '.join(shipped) or 'none'} "
              "(the others read them from the temporary directory, or have none)")
        print("target (issue 18): one cube <= 0.15 s")


if __name__ == "__main__":
    main()
