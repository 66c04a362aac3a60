"""castor --lsp: diagnostics after an edit of the bus shelter, and hovers.

Spawns the language server as an editor does and speaks the protocol to it
(the test suite's client, tests/test_lsp.py). Two figures, median and worst of
BENCH_RUNS edits: edit -> the diagnostics of that version published, for
examples/bus_shelter.cas (seven files, #included); and the hover on a
parameter and on an object (its box and volume, made once per analysis).
Targets: diagnostics <= 0.5 s, hover <= 0.1 s.
"""

from __future__ import annotations

import os
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path

from _common import runs_from_env, table

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests"))
from test_lsp import Client  # noqa: E402


def main() -> None:
    runs = runs_from_env(10)
    work = Path(tempfile.mkdtemp(prefix="castor-lsp-"))
    try:
        shutil.copy(HERE.parent / "examples" / "bus_shelter.cas", work)
        shutil.copytree(HERE.parent / "examples" / "bus_shelter", work / "bus_shelter")
        shutil.copy(HERE.parent / "examples" / "house.cas", work)
        client = Client(work)
        client.start(work)
        path = work / "bus_shelter.cas"
        text = path.read_text()
        uri = client.open(path)
        client.diagnostics(uri, 1, timeout=60)
        edits = []
        for k in range(runs):
            started = time.perf_counter()
            client.change(uri, text.replace("PHASE = 0;", f"PHASE = 0;\nX{k} = {k};"), k + 2)
            client.diagnostics(uri, k + 2, timeout=60)
            edits.append(time.perf_counter() - started)
        house = client.open(work / "house.cas")
        client.diagnostics(house, 1, timeout=60)
        lines = (work / "house.cas").read_text().split("\n")
        h = next(i for i, line in enumerate(lines) if line.startswith("H = "))
        murs = next(i for i, line in enumerate(lines) if line.startswith("murs ="))
        hovers = {"parameter": [], "object": []}
        for _ in range(runs):
            for what, line in (("parameter", h), ("object", murs)):
                started = time.perf_counter()
                client.at("textDocument/hover", house, line, 1)
                hovers[what].append(time.perf_counter() - started)
        client.stop()
    finally:
        shutil.rmtree(work, ignore_errors=True)
    rows = [["bus shelter: edit -> diagnostics", f"{statistics.median(edits):.3f}",
             f"{max(edits):.3f}", "0.5"]]
    for what, times in hovers.items():
        rows.append([f"house: hover on {what}", f"{statistics.median(times):.3f}",
                     f"{max(times):.3f}", "0.1"])
    print(table(rows, ["", "median s", "worst s", "target s"]))
    print("(the first object hover makes its figures; the others read them)")


if __name__ == "__main__":
    os.environ.setdefault("PYTHONPATH", str(HERE.parent))
    main()
