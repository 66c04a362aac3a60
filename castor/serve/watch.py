"""Notice a save of the scene or of a file it includes, by polling.

Polling a few files' status twenty times a second costs nothing and
works the same on every system, and with every editor: vi writes in place or
writes a new file and renames it over the old one, and either changes the
modification time, the size or the inode.
"""

from __future__ import annotations

import os
import time

Signature = tuple[int, int, int] | None  # mtime in ns, size, inode; None: absent


def signature(path: str) -> Signature:
    try:
        status = os.stat(path)
    except OSError:
        return None
    return status.st_mtime_ns, status.st_size, status.st_ino


class Watcher:
    """The files to watch and how each was when last seen."""

    def __init__(self, paths=()):
        self.seen: dict[str, Signature] = {}
        self.watch(paths)

    def watch(self, paths, since_ns: int | None = None) -> None:
        """Watch these files from now on (and no others), keeping what was seen of
        those already watched so that a save during an evaluation is not missed;
        a new file modified after ``since_ns`` (when the evaluation that found it
        began) counts as changed at the next call."""
        seen = {}
        for path in dict.fromkeys(paths):
            if path in self.seen:
                seen[path] = self.seen[path]
                continue
            now = signature(path)
            seen[path] = (-1, -1, -1) if now and since_ns is not None and now[0] >= since_ns else now
        self.seen = seen

    def changed(self) -> list[str]:
        """The files whose signature changed since the last call."""
        changes = []
        for path, before in self.seen.items():
            now = signature(path)
            if now != before:
                self.seen[path] = now
                changes.append(path)
        return changes

    def settle(self, wait, lock, pause: float, patience: float) -> bool:
        """After a change, wait for the editor to finish writing: until the files
        have not changed for ``pause`` seconds, and none is empty (an editor that
        writes in place empties the file first), for at most ``patience`` seconds
        (a file left empty is then taken as it is). ``wait(seconds)`` is true
        when the server stops; so is the answer."""
        deadline = time.monotonic() + patience
        while True:
            if wait(pause):
                return True
            with lock:
                moved = self.changed()
                empty = any(seen is not None and seen[1] == 0 for seen in self.seen.values())
            if not (moved or empty) or time.monotonic() >= deadline:
                return False
