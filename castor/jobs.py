"""One frame's work, done in this process, another process, or on a Dask cluster.

The interpreter hands each frame's evaluated CSG tree over as a ``Job``: plain,
picklable data with the settings of the stages that make it (castor.settings). ``make`` turns it into a ``Result``
(the bytes to write, the messages to print, the figures of --stats) in
whatever process runs it; the driver (castor.run) writes results in frame
order, so the output is the same byte for byte however the frames were made.
Each process keeps one facetizer, whose caches of shared subtrees (by key)
and primitive shapes serve every frame it makes.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

from castor.csg import tree
from castor.diagnostics import CastorError, Location
from castor.settings import FrameSettings, MeshSettings, OutputSettings


@dataclass(frozen=True)
class Job:
    """One frame's work: its evaluated CSG tree and what to make of it, by stage."""

    scene: tree.FrameTree
    settings: FrameSettings


@dataclass
class Result:
    number: int
    location: Location
    data: object = None  # the frame in its format: castor.formats.output.Data (None: nothing)
    companions: dict[str, bytes] = field(default_factory=dict)  # files beside it (.mtl)
    errors: list[CastorError] = field(default_factory=list)
    warnings: list[tuple[str, Location | None]] = field(default_factory=list)
    stats: str | None = None
    summary: dict | None = None
    picture: object = None  # an image array, for an animation gathered by the driver
    mesh: object = None  # the mesh frame, when the output settings keep it


# a frame of more polygons than this, made in a worker process, is written to
# a file in OutputSettings.spool rather than handed back as bytes through a pipe (a
# 5 M-polygon stream is about 700 MB, pickled and held twice on its way)
SPOOL_POLYGONS = 100_000

_facetizers: dict[tuple, object] = {}


def _facetizer(mesh: MeshSettings, merge: bool):
    from castor.mesh.facetize import Facetizer

    key = (mesh.max_polygons, merge)
    facetizer = _facetizers.get(key)
    if facetizer is None:
        facetizer = _facetizers[key] = Facetizer(mesh.max_polygons, merge)
    return facetizer


def make(job: Job) -> Result:
    """The frame's output, and what is to be said about it; never raises for
    an error of the scene (it is in the result)."""
    scene = job.scene
    result = Result(scene.number, scene.location)
    try:
        _make(scene, job.settings, result)
    except CastorError as exc:
        result.errors.append(exc)
        result.data = None
    except MemoryError:
        from castor.diagnostics import LimitError

        result.errors.append(LimitError("out of memory for this frame; simplify the scene, "
                                        "raise the tolerance or lower --max-polygons",
                                        scene.location))
        result.data = None
    return result


def _make(scene: tree.FrameTree, settings: FrameSettings, result: Result) -> None:
    from castor.formats import FORMATS

    output = settings.output
    chosen = FORMATS.get(output.format)
    kind = chosen.kind if chosen is not None else "mesh"
    if kind == "picture":
        from castor.pictures import picture

        started = time.perf_counter()
        if _draws_nothing(scene, settings.mesh) and not scene.spaces:
            result.warnings.append((f"frame {scene.number} is empty: its objects have no volume",
                                    scene.location))
        if not chosen.one_frame:
            # an animation is drawn at the end, with one camera for all its frames
            from castor.pictures.trace import compile_frame

            result.picture = compile_frame(scene)
        else:
            result.data = chosen.write(picture(scene, settings.picture))
        if output.stats:
            size = settings.picture.size
            result.stats = (f"castor: frame {scene.number} {scene.where}: picture "
                            f"{size[0]}x{size[1]}, {settings.picture.samples} samples per pixel, "
                            f"{time.perf_counter() - started:.3f} s")
        if output.summary:  # the take-off is written whatever the output (OUTPUT.md)
            from castor.quantities import summary_record

            facetizer = _facetizer(settings.mesh, merge=True)
            result.summary = summary_record(facetizer.frame(scene), scene, facetizer)
        return
    # a file of triangles skips merging them into polygons, unless the take-off
    # counts the frame's polygons
    merge = chosen is None or not chosen.triangles_only or output.summary
    facetizer = _facetizer(settings.mesh, merge=merge)
    frame = facetizer.frame(scene)
    if frame.polygon_count == 0 and not scene.spaces:  # rooms only: not an empty frame
        result.warnings.append((f"frame {scene.number} is empty: its objects have no volume",
                                scene.location))
    if kind == "drawing":
        from castor.drawings import sheet_of

        result.data = chosen.write(sheet_of(
            scene, frame, settings.drawing, output.title,
            lambda message: result.warnings.append((message, scene.location))))
    elif kind == "bim":
        result.data = chosen.write(scene, frame, settings)
    elif chosen is not None:
        from castor.formats import output as destination

        written = frame if output.model_scale == 1 else _scaled(frame, output.model_scale)
        pieces, result.companions = destination.encode_pieces(written, output.format,
                                                              output.target)
        if output.pieces:
            result.data = pieces  # made as they are written
        elif output.spool is not None and frame.polygon_count > SPOOL_POLYGONS:
            result.data = _spooled(pieces, frame, output)
        else:
            result.data = b"".join(pieces)
    if output.keep_mesh:
        result.mesh = frame
    if output.stats or output.summary:
        from castor.quantities import stats_line, summary_record

        stats = facetizer.stats
        if output.stats:
            result.stats = stats_line(frame, stats.primitives, stats.booleans, stats.seconds)
        if output.summary:
            result.summary = summary_record(frame, scene, facetizer)


def _scaled(frame, factor: float):
    """The frame's polygons times ``factor``: a model at its scale (--scale 1:N)."""
    from dataclasses import replace

    return replace(frame, objects=[replace(obj, vertices=obj.vertices * factor)
                                   for obj in frame.objects])


def _draws_nothing(scene: tree.FrameTree, mesh: MeshSettings) -> bool:
    """Whether the frame's objects have no volume, as its polygons would say, for a
    picture, which is traced from the solids and never facetized: rays along each
    axis through a grid over the frame's box find something in almost every frame
    at once; only when they all miss is the frame facetized to be sure."""
    import numpy as np

    from castor.pictures.trace import compile_frame

    compiled = compile_frame(scene)
    if compiled.root is None:
        return True
    low, high = (np.asarray(corner, float) for corner in compiled.box)
    if not np.all(high > low):
        return True
    steps = (np.arange(PROBES) + 0.5) / PROBES
    for axis in range(3):
        u, v = (a for a in range(3) if a != axis)
        grid_u, grid_v = np.meshgrid(low[u] + steps * (high[u] - low[u]),
                                     low[v] + steps * (high[v] - low[v]))
        origins = np.empty((grid_u.size, 3))
        origins[:, u], origins[:, v] = grid_u.ravel(), grid_v.ravel()
        origins[:, axis] = low[axis] - 1.0
        directions = np.zeros_like(origins)
        directions[:, axis] = 1.0
        t = compiled.spans(origins, directions)[0]
        with np.errstate(invalid="ignore"):
            if np.any(t[:, 1::2] - t[:, 0::2] > 0):
                return False
    return _facetizer(mesh, merge=True).frame(scene).polygon_count == 0


PROBES = 32  # rays on a side of the grid that looks for something in a picture's frame


def _spooled(pieces, frame, output: OutputSettings):
    """The frame's bytes written a piece at a time to a file in ``output.spool``
    (hidden, beside the output where it can be renamed into place); as bytes
    when that file cannot be written (a full disk)."""
    import os
    import tempfile

    from castor.formats import output as destination

    try:
        fd, path = tempfile.mkstemp(prefix=f".castor-{output.spool_owner}-", suffix=".tmp",
                                    dir=output.spool)
    except OSError:
        return b"".join(pieces)
    try:
        with os.fdopen(fd, "wb") as handle:
            for piece in pieces:
                handle.write(piece)
    except BaseException as exc:
        os.unlink(path)
        if not isinstance(exc, OSError):
            raise
        return b"".join(destination.encode_pieces(frame, output.format, output.target)[0])
    if output.spool_owner and not _alive(output.spool_owner):
        os.unlink(path)  # the driver was stopped: nobody will write or remove the file
        return b""
    return destination.Spooled(path)


def worker_started() -> None:
    """A worker process's first step: Ctrl-C is for the driver, which stops the
    workers itself (a worker would print a traceback otherwise), and a worker
    ends when its parent, the forkserver, does (it ends with castor), even if
    castor was killed outright."""
    import signal
    import sys

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(1, signal.SIGKILL, 0, 0, 0)  # PR_SET_PDEATHSIG
        except (OSError, AttributeError):
            pass


def _alive(pid: int) -> bool:
    import os

    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:
        pass
    return True
