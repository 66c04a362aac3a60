"""castor --serve: from the save of examples/house.cas to the new frame.

Two figures, median and worst of BENCH_RUNS saves (each changes the walls'
height): the server's (save -> the event that says the new frames are ready,
read from the event stream as a browser does) and the page's (save -> the new
frame drawn in Debian's chromium with software WebGL, when it is installed).
Target: the house shows its new frame within 0.5 s of the save.
"""

from __future__ import annotations

import http.client
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

from _common import castor_command, runs_from_env

HERE = os.path.dirname(os.path.abspath(__file__))
HOUSE = os.path.join(HERE, "..", "examples", "house.cas")
CHROMIUM = "/usr/bin/chromium"
FLAGS = ["--headless", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--no-first-run"]


def save(path: str, height: float) -> None:
    with open(path) as handle:
        text = handle.read()
    start = text.index("H = ")
    end = text.index(";", start)
    with open(path, "w") as handle:
        handle.write(text[:start] + f"H = {height:.2f}" + text[end:])


def events(port: int):
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
    connection.request("GET", "/events")
    stream = connection.getresponse()
    while True:
        line = stream.readline().decode()
        if line.startswith("data: "):
            yield json.loads(line[6:])


def main() -> None:
    runs = runs_from_env(15)
    folder = tempfile.mkdtemp()
    scene = os.path.join(folder, "house.cas")
    shutil.copy(HOUSE, scene)
    process = subprocess.Popen([*castor_command(), "--serve", "--port", "0", "house.cas"],
                               cwd=folder, stderr=subprocess.PIPE, text=True)
    try:
        line = process.stderr.readline()
        url = line.split(" at ")[1].split()[0]
        port = int(url.rsplit(":", 1)[1].strip("/"))
        stream = events(port)
        while (news := next(stream))["evaluating"]:
            pass
        server = []
        for run in range(runs):
            time.sleep(0.15)
            saved = time.perf_counter()
            save(scene, 2.9 + 0.01 * (run % 2 + 1))
            version = news["version"]
            while (news := next(stream))["version"] == version or news["evaluating"]:
                pass
            server.append(time.perf_counter() - saved)
        print(f"house.cas, {runs} saves; seconds from the save")
        print(f"  to the event (server, whole process): median {statistics.median(server):.3f}, "
              f"worst {max(server):.3f}")
        if not os.path.exists(CHROMIUM):
            print(f"  to the picture: {CHROMIUM} is not installed")
            return
        from playwright.sync_api import sync_playwright

        with sync_playwright() as driver:
            browser = driver.chromium.launch(executable_path=CHROMIUM, args=FLAGS)
            page = browser.new_page(viewport={"width": 1000, "height": 700})
            page.goto(url)
            page.wait_for_selector("body[data-version]")
            drawn = []
            for run in range(runs):
                time.sleep(0.15)
                version = page.evaluate("document.body.dataset.version")
                saved = time.perf_counter()
                save(scene, 3.0 + 0.01 * (run % 2 + 1))
                page.wait_for_function("(seen) => document.body.dataset.version !== seen",
                                       arg=version, polling="raf")
                drawn.append(time.perf_counter() - saved)
            browser.close()
        print(f"  to the new frame drawn in chromium (SwiftShader): median "
              f"{statistics.median(drawn):.3f}, worst {max(drawn):.3f}")
    finally:
        process.terminate()
        process.wait()
        shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
