"""castor --lsp: diagnostics after an edit of the bus shelter, and hovers.

Spawns the language server as an editor does and speaks the protocol to it
(the test suite's client, tests/support/lsp.py). Two figures, median and worst of
BENCH_RUNS edits: edit -> the diagnostics of that version published, for
examples/bus_shelter.cas (seven files, #included); and the hover on a
parameter and on an object (its box and volume, made once per analysis).
And the live preview's parameters panel: a change of the H slider of the house
(annotated [2.5:0.1:4]) to the new frame drawn in Debian's chromium (software
WebGL), when chromium and playwright are there.
Targets: diagnostics <= 0.5 s, hover <= 0.1 s, slider to frame <= 0.3 s.
Beside each wall-clock figure, the CPU seconds the server spent on it (the
language server's process from /proc; the preview's, which runs in this
process, from time.process_time): on a shared machine the wall clock also
counts the waits for a core. Run ``uptime`` beside it to know the load.
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
sys.path.insert(0, str(HERE.parent))  # the checkout: castor and the tests' support package
from tests.support.lsp import Client  # noqa: E402


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
        edits, edits_cpu = [], []
        for k in range(runs):
            started, cpu = time.perf_counter(), _cpu(client.process.pid)
            client.change(uri, text.replace("PHASE = 0;", f"PHASE = 0;\nX{k} = {k};"), k + 2)
            client.diagnostics(uri, k + 2, timeout=60)
            edits.append(time.perf_counter() - started)
            edits_cpu.append(_cpu(client.process.pid) - cpu)
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
             f"{max(edits):.3f}", f"{statistics.median(edits_cpu):.3f}", "0.5"]]
    for what, times in hovers.items():
        rows.append([f"house: hover on {what}", f"{statistics.median(times):.3f}",
                     f"{max(times):.3f}", "", "0.1"])
    slider, slider_cpu = slider_times(runs)
    if slider:
        rows.append(["house: H slider -> frame drawn", f"{statistics.median(slider):.3f}",
                     f"{max(slider):.3f}", f"{statistics.median(slider_cpu):.3f}", "0.3"])
    print(table(rows, ["", "median s", "worst s", "server CPU s", "target s"]))
    print("(the first object hover makes its figures; the others read them)")


def _cpu(pid: int) -> float:
    """CPU seconds (user and system) a process has used, from /proc."""
    try:
        with open(f"/proc/{pid}/stat") as handle:
            fields = handle.read().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError):
        return 0.0


def slider_times(runs: int) -> tuple[list[float], list[float]]:
    """Seconds from a key moving the H slider to the page's next frame drawn, and
    the CPU seconds this process (the preview's server) spent meanwhile."""
    if not os.path.exists("/usr/bin/chromium"):
        return [], []
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        return [], []
    sys.path.insert(0, str(HERE.parent))
    from castor.serve.evaluation import Watched
    from castor.settings import Source
    from castor.serve.server import PreviewServer
    from tests.support.browser import FLAGS

    work = Path(tempfile.mkdtemp(prefix="castor-panel-"))
    here = os.getcwd()
    times, cpu = [], []
    try:
        os.chdir(work)
        text = (HERE.parent / "examples" / "house.cas").read_text()
        old = next(line for line in text.split("\n") if line.startswith("H = 2.9;"))
        (work / "house.cas").write_text(text.replace(old, "H = 2.9; // [2.5:0.1:4] walls"))
        server = PreviewServer(Watched(Source(("house.cas",))), "127.0.0.1", 0).start()
        with sync_playwright() as driver:
            browser = driver.chromium.launch(executable_path="/usr/bin/chromium", args=FLAGS)
            page = browser.new_page(viewport={"width": 900, "height": 650})
            page.goto(server.url)
            page.wait_for_selector("body[data-version]", timeout=30000)
            page.click("#parameters-toggle")
            page.wait_for_selector("#parameter-H").focus()
            for k in range(runs):
                version = page.evaluate("document.body.dataset.version")
                started, used = time.perf_counter(), time.process_time()
                page.keyboard.press("ArrowRight" if k % 2 == 0 else "ArrowLeft")
                page.wait_for_function("(seen) => document.body.dataset.version !== seen",
                                       arg=version, timeout=30000)
                times.append(time.perf_counter() - started)
                cpu.append(time.process_time() - used)
                page.wait_for_timeout(600)  # the value on release evaluated too
            browser.close()
        server.close()
    finally:
        os.chdir(here)
        shutil.rmtree(work, ignore_errors=True)
    return times, cpu


if __name__ == "__main__":
    os.environ.setdefault("PYTHONPATH", str(HERE.parent))
    main()
