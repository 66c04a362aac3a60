"""Which scene a file is part of: the scene files of a workspace that ``#include`` it.

A part (``bus_shelter/shelter.cas``) means nothing alone: its parameters and
macros come from the scene that includes it. ``scenes_including`` looks through
the workspace's ``*.cas`` files (bounded: hidden folders skipped, at most
``MAX_FOLDERS`` folders looked through and ``MAX_FILES`` files of at most
``MAX_BYTES`` read) for the ``#include "..."``
lines that name the file, directly or through other parts, and gives the
scenes at the top: those no other file includes. A file that cannot be read,
or an ``#include`` name no file can have (a NUL byte), is skipped.
"""

from __future__ import annotations

import os
import re

MAX_FILES = 2000
MAX_FOLDERS = 5000
MAX_BYTES = 4_000_000
_INCLUDE = re.compile(r'^[ \t]*#[ \t]*include[ \t]*"([^"\n]+)"', re.M)
_SKIPPED = {"node_modules", "__pycache__", "venv", "build", "dist"}


def scene_files(roots: list[str]) -> list[str]:
    """The ``*.cas`` files under the roots (real paths), in a stable order."""
    found: list[str] = []
    folders = 0
    for root in roots:
        for folder, subfolders, files in os.walk(root):
            folders += 1
            if folders > MAX_FOLDERS:
                return list(dict.fromkeys(found))
            subfolders[:] = sorted(d for d in subfolders
                                   if not d.startswith(".") and d not in _SKIPPED)
            for name in sorted(files):
                if name.endswith(".cas"):
                    found.append(os.path.realpath(os.path.join(folder, name)))
                    if len(found) >= MAX_FILES:
                        return list(dict.fromkeys(found))
    return list(dict.fromkeys(found))


def includes(path: str) -> list[str]:
    """The files ``path`` names in its ``#include "..."`` lines (real paths)."""
    try:
        if os.path.getsize(path) > MAX_BYTES:
            return []
        with open(path, encoding="utf-8", errors="replace") as handle:
            text = handle.read()
    except (OSError, ValueError):
        return []
    here = os.path.dirname(path)
    found = (_real(os.path.join(here, name)) for name in _INCLUDE.findall(text))
    return [name for name in found if name is not None]


def _real(path: str) -> str | None:
    """The real path, or None for a name no file can have (a NUL byte in an
    ``#include`` of some file of the workspace: that file's own diagnostics say so)."""
    try:
        return os.path.realpath(path)
    except (OSError, ValueError):
        return None


def scenes_including(path: str, roots: list[str]) -> list[str]:
    """The scene files at the top of the chains of ``#include`` that reach
    ``path`` (real paths, shortest chain first), or [] when none includes it."""
    target = os.path.realpath(path)
    included_by: dict[str, list[str]] = {}
    for scene in scene_files(roots):
        for name in includes(scene):
            included_by.setdefault(name, []).append(scene)
    if target not in included_by:
        return []
    tops, seen, layer = [], {target}, [target]
    while layer:
        following = []
        for name in layer:
            for scene in included_by.get(name, []):
                if scene in seen:
                    continue
                seen.add(scene)
                (following if scene in included_by else tops).append(scene)
        layer = following
    return tops or included_by[target][:1]
