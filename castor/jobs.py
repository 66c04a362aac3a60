"""One frame's work, done in this process, another process, or on a Dask cluster.

The interpreter hands each frame's evaluated CSG tree over as a ``Job``: plain,
picklable data with the output wanted. ``make`` turns it into a ``Result``
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
from castor.options import (DEFAULT_MAX_POLYGONS, DEFAULT_SAMPLES, DEFAULT_SCALE, DEFAULT_SIZE,
                            DEFAULT_SUN)


@dataclass(frozen=True)
class Spec:
    """What to make of each frame: the format and the options that shape it."""

    format: str | None = "cps"  # None: the mesh frame only, in this process
    target: str | None = None  # -o PATH (a pattern is filled in per frame)
    max_polygons: int = DEFAULT_MAX_POLYGONS
    stats: bool = False
    summary: bool = False
    keep_mesh: bool = False  # hand the mesh frame back (the live preview wants it)
    size: tuple[int, int] = DEFAULT_SIZE
    view: object = None  # castor.options.View
    eye: tuple | None = None
    look: tuple | None = None
    sun: tuple | None = DEFAULT_SUN
    samples: int = DEFAULT_SAMPLES
    edges: bool = False
    section: object = None  # castor.options.Section
    scale: float = DEFAULT_SCALE
    title: str | None = None  # --title (a drawing's, an IFC project's)
    ifc_classes: tuple[tuple[str, str], ...] = ()  # --ifc-class NAME=CLASS, parsed
    # how a frame's bytes are handed on: made a piece at a time as they are
    # written (``pieces``, in the process that writes them), written by a worker
    # into a file in ``spool`` when the frame is large, or else as bytes
    pieces: bool = False
    spool: str | None = None
    spool_owner: int = 0  # the driver's process: a worker left alone removes its file


@dataclass(frozen=True)
class Job:
    scene: tree.Frame
    spec: Spec


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
    mesh: object = None  # the mesh frame, when the spec keeps it


# a frame of more polygons than this, made in a worker process, is written to
# a file in Spec.spool rather than handed back as bytes through a pipe (a
# 5 M-polygon stream is about 700 MB, pickled and held twice on its way)
SPOOL_POLYGONS = 100_000

_facetizers: dict[tuple, object] = {}


def _facetizer(spec: Spec, merge: bool):
    from castor.mesh.facetize import Facetizer

    key = (spec.max_polygons, merge)
    facetizer = _facetizers.get(key)
    if facetizer is None:
        facetizer = _facetizers[key] = Facetizer(spec.max_polygons, merge)
    return facetizer


def make(job: Job) -> Result:
    """The frame's output, and what is to be said about it; never raises for
    an error of the scene (it is in the result)."""
    scene, spec = job.scene, job.spec
    result = Result(scene.number, scene.location)
    try:
        _make(scene, spec, result)
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


def _make(scene: tree.Frame, spec: Spec, result: Result) -> None:
    from castor.formats import FORMATS

    chosen = FORMATS.get(spec.format)
    kind = chosen.kind if chosen is not None else "mesh"
    if kind == "picture":
        from castor.pictures import picture

        started = time.perf_counter()
        if all(obj.root is None for obj in scene.objects):
            result.warnings.append((f"frame {scene.number} is empty: its objects have no volume",
                                    scene.location))
        if chosen.all_frames:
            # an animation is drawn at the end, with one camera for all its frames
            from castor.pictures.trace import compile_frame

            result.picture = compile_frame(scene)
        else:
            image = picture(scene, spec)
            from castor.formats.png import export_picture

            result.data = export_picture(image)
        if spec.stats:
            result.stats = (f"castor: frame {scene.number} {scene.where}: picture "
                            f"{spec.size[0]}x{spec.size[1]}, {spec.samples} samples per pixel, "
                            f"{time.perf_counter() - started:.3f} s")
        return
    facetizer = _facetizer(spec, merge=chosen is None or not chosen.triangles_only)
    frame = facetizer.frame(scene)
    if frame.polygon_count == 0:
        result.warnings.append((f"frame {scene.number} is empty: its objects have no volume",
                                scene.location))
    if kind == "drawing":
        from castor.drawings import drawing

        result.data = drawing(scene, frame, spec)
    elif spec.format == "ifc":  # the IFC writer takes options: the title, the classes
        from castor.formats.ifc import export

        result.data = export(frame, spec.target, spec.title, dict(spec.ifc_classes))
    elif chosen is not None:
        from castor.formats import output

        pieces, result.companions = output.encode_pieces(frame, spec.format, spec.target)
        if spec.pieces:
            result.data = pieces  # made as they are written
        elif spec.spool is not None and frame.polygon_count > SPOOL_POLYGONS:
            result.data = _spooled(pieces, frame, spec)
        else:
            result.data = b"".join(pieces)
    if spec.keep_mesh:
        result.mesh = frame
    if spec.stats or spec.summary:
        from castor.quantities import stats_line, summary_record

        stats = facetizer.stats
        if spec.stats:
            result.stats = stats_line(frame, stats.primitives, stats.booleans, stats.seconds)
        if spec.summary:
            result.summary = summary_record(frame)


def _spooled(pieces, frame, spec: Spec):
    """The frame's bytes written a piece at a time to a file in ``spec.spool``
    (hidden, beside the output where it can be renamed into place); as bytes
    when that file cannot be written (a full disk)."""
    import os
    import tempfile

    from castor.formats import output

    try:
        fd, path = tempfile.mkstemp(prefix=".castor-", suffix=".tmp", dir=spec.spool)
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
        return b"".join(output.encode_pieces(frame, spec.format, spec.target)[0])
    if spec.spool_owner and not _alive(spec.spool_owner):
        os.unlink(path)  # the driver was stopped: nobody will write or remove the file
        return b""
    return output.Spooled(path)


def _alive(pid: int) -> bool:
    import os

    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:
        pass
    return True
