"""What the classes of LANGUAGE.md §11 cost: the bus shelter (annotated) run with
its annotations and with them removed (the same scene, comments stripped), then
with --summary, whose take-off makes each element's own solid.

    PYTHONPATH=. python benchmarks/classes.py        (BENCH_RUNS=N: median of N runs)

The annotations are read as the statements run and travel with each frame's
tree; no solid of an element is made unless an output asks (--summary here),
so the first two lines should be within noise of each other.
"""

from __future__ import annotations

import os
import re
import shutil
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.dirname(__file__))
from _common import castor_command, runs_from_env, table, timed  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ANNOTATION = re.compile(r"[ \t]*//[ \t]*\[[^\n]*")


def stripped_copy(where: str) -> str:
    """The examples with every '// [...]' annotation removed."""
    target = os.path.join(where, "examples")
    shutil.copytree(os.path.join(ROOT, "examples"), target)
    for folder, _, files in os.walk(target):
        for name in files:
            if name.endswith(".cas"):
                path = os.path.join(folder, name)
                with open(path, encoding="utf-8") as handle:
                    text = handle.read()
                with open(path, "w", encoding="utf-8") as handle:
                    handle.write(ANNOTATION.sub("", text))
    return target


def interleaved(first: list[str], second: list[str], runs: int) -> tuple[float, float]:
    """Median seconds of two commands run in turn (a busy machine's drift falls
    on both alike)."""
    a, b = [], []
    for _ in range(runs):
        a.append(timed(first, runs=1))
        b.append(timed(second, runs=1))
    return statistics.median(a), statistics.median(b)


def main() -> None:
    runs = runs_from_env(5)
    env_path = os.environ.get("PYTHONPATH", "")
    os.environ["PYTHONPATH"] = ROOT + (os.pathsep + env_path if env_path else "")
    # as installed: modules compiled once (an environment that writes no bytecode
    # would charge every run the compiling of the modules the annotations need)
    os.environ.pop("PYTHONDONTWRITEBYTECODE", None)
    castor = castor_command()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        plain = os.path.join(stripped_copy(tmp), "bus_shelter.cas")
        annotated = os.path.join(ROOT, "examples", "bus_shelter.cas")
        out = os.path.join(tmp, "out.cps")
        summary = os.path.join(tmp, "s.json")
        for label, options in (("--check (read and evaluate)", ["--check"]),
                               ("-o out.cps", ["-o", out]),
                               ("-o out.cps --summary", ["-o", out, "--summary", summary])):
            timed(castor + [annotated, "--check"], runs=1)  # compiles what is not yet
            with_them, without = interleaved(castor + [annotated] + options,
                                             castor + [plain] + options, runs)
            rows.append([label, f"{with_them:.3f}", f"{without:.3f}",
                         f"{100 * (with_them / without - 1):+.0f}%"])
    print(table(rows, ["bus shelter, 3 frames", "annotated s", "annotations removed s",
                       "difference"]))


if __name__ == "__main__":
    main()
