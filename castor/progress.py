"""A line on the terminal while a frame takes more than a second.

Only when standard error is a terminal: never in a pipeline's logs. The line
is cleared when the frame is done.
"""

from __future__ import annotations

import threading
import time


class Progress:
    DELAY = 1.0

    def __init__(self, what: str, stream):
        self.what = what
        self.stream = stream
        self.shown = False
        self.done = threading.Event()
        self.thread = None

    def __enter__(self):
        try:
            terminal = self.stream.isatty()
        except (AttributeError, ValueError):
            terminal = False
        if terminal:
            self.thread = threading.Thread(target=self._run, daemon=True)
            self.thread.start()
        return self

    def _run(self):
        started = time.monotonic()
        if self.done.wait(self.DELAY):
            return
        spinner = "|/-\\"
        tick = 0
        while not self.done.wait(0.25):
            tick += 1
            self.stream.write(f"\rcastor: {self.what}: facetizing {spinner[tick % 4]} "
                              f"{time.monotonic() - started:.0f} s ")
            self.stream.flush()
            self.shown = True

    def __exit__(self, *exc):
        self.done.set()
        if self.thread is not None:
            self.thread.join()
            if self.shown:
                self.stream.write("\r\033[K")
                self.stream.flush()
        return False
