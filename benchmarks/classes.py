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


def main() -> None:
    runs = runs_from_env(5)
    env_path = os.environ.get("PYTHONPATH", "")
    os.environ["PYTHONPATH"] = ROOT + (os.pathsep + env_path if env_path else "")
    castor = castor_command()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        plain = stripped_copy(tmp)
        out = os.path.join(tmp, "out.cps")
        summary = os.path.join(tmp, "s.json")
        for label, folder in (("annotated", os.path.join(ROOT, "examples")),
                              ("annotations removed", plain)):
            scene = os.path.join(folder, "bus_shelter.cas")
            rows.append([f"bus shelter, {label}",
                         f"{timed(castor + [scene, '-o', out], runs=runs):.3f}"])
        for label, folder in (("annotated", os.path.join(ROOT, "examples")),
                              ("annotations removed", plain)):
            scene = os.path.join(folder, "bus_shelter.cas")
            rows.append([f"bus shelter --summary, {label}",
                         f"{timed(castor + [scene, '-o', out, '--summary', summary], runs=runs):.3f}"])
    print(table(rows, ["run (3 frames)", "seconds (median)"]))


if __name__ == "__main__":
    main()
