"""How much memory a frame needs, and how much the machine has (CLI.md, limits).

A frame is refused with a clear error before it is built when its estimate
exceeds the memory available, rather than being killed by the system half way.
The figures per triangle are measured (benchmarks/memory.py): the engine's own
mesh of a boolean's operands and result, the triangles and polygons castor
makes from it, and the frame's arrays.
"""

from __future__ import annotations

import os

# bytes per triangle of the frame's estimate (operands of its booleans added
# up): the engine's mesh (about 250 B a triangle while a boolean runs, operands
# and result) and the arrays castor makes from it (about 150 B); the writers
# work in pieces of 32,768 polygons, and add little
BYTES_PER_TRIANGLE = 400
# what the process holds before any frame: Python, numpy, manifold3d, the parser
BASE_BYTES = 150 * 2 ** 20


def frame_bytes(triangles: int) -> int:
    """About how many bytes a frame whose estimate is ``triangles`` needs at its peak."""
    return BASE_BYTES + BYTES_PER_TRIANGLE * max(int(triangles), 0)


def available_bytes() -> int | None:
    """The memory this process may still use: MemAvailable, or less if a cgroup
    limit or an address-space limit says so; None if nothing can be read."""
    found = []
    try:
        with open("/proc/meminfo") as handle:
            for line in handle:
                if line.startswith("MemAvailable:"):
                    found.append(int(line.split()[1]) * 1024)
                    break
    except OSError:
        pass
    for limit, usage in (("/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory.current"),
                         ("/sys/fs/cgroup/memory/memory.limit_in_bytes",
                          "/sys/fs/cgroup/memory/memory.usage_in_bytes")):
        try:
            with open(limit) as handle:
                text = handle.read().strip()
            if text.isdigit() and int(text) < 2 ** 60:
                with open(usage) as handle:
                    found.append(int(text) - int(handle.read().strip()))
            break
        except (OSError, ValueError):
            continue
    try:
        import resource

        soft, _ = resource.getrlimit(resource.RLIMIT_AS)
        if soft != resource.RLIM_INFINITY:
            with open(f"/proc/{os.getpid()}/statm") as handle:
                size = int(handle.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
            found.append(soft - size)
    except (OSError, ValueError, ImportError):
        pass
    return max(min(found), 0) if found else None


def too_big(triangles: int) -> tuple[int, int] | None:
    """(needed, available) bytes if a frame of ``triangles`` would not fit, else None."""
    needed = frame_bytes(triangles)
    available = available_bytes()
    if available is not None and needed > available:
        return needed, available
    return None
