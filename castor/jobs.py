"""One frame's work, done in this process, another process, or on a Dask cluster.

The interpreter hands each frame's evaluated CSG tree over as a ``Job``: plain,
picklable data with the settings of the stages that make it (castor.settings).
``make`` has the output's kind make the frame's product (castor.formats.kinds)
and its format's writer write it, and turns it into a ``Result``
(the bytes to write, the messages to print, the figures of --stats) in
whatever process runs it; the driver (castor.run) writes results in frame
order, so the output is the same byte for byte however the frames were made.
Each process keeps one facetizer (castor.formats.kinds.facetizer_for), whose
caches of shared subtrees (by key) and primitive shapes serve every frame it
makes. Nothing crosses between processes but plain data: the tree and its
settings one way, bytes, arrays and figures back.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from castor.csg.tree import FrameTree
from castor.diagnostics import CastorError, Location
from castor.settings import FrameSettings, OutputSettings


@dataclass(frozen=True)
class Job:
    """One frame's work: its evaluated CSG tree and what to make of it, by stage."""

    tree: FrameTree
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
    # the frame's part of a file made from every frame at once (an animation's
    # frame, castor.formats.kinds.Framing), gathered by the driver
    gathered: object = None
    mesh: object = None  # the mesh frame, when the output settings keep it


# a frame of more polygons than this, made in a worker process, is written to
# a file in OutputSettings.spool rather than handed back as bytes through a pipe (a
# 5 M-polygon stream is about 700 MB, pickled and held twice on its way)
SPOOL_POLYGONS = 100_000


def make(job: Job) -> Result:
    """The frame's output, and what is to be said about it; never raises for
    an error of the scene (it is in the result)."""
    tree = job.tree
    result = Result(tree.number, tree.location)
    try:
        _make(tree, job.settings, result)
    except CastorError as exc:
        result.errors.append(exc)
        result.data = None
    except MemoryError:
        from castor.diagnostics import LimitError

        result.errors.append(LimitError("out of memory for this frame; simplify the scene, "
                                        "raise the tolerance or lower --max-polygons",
                                        tree.location))
        result.data = None
    return result


def _make(tree: FrameTree, settings: FrameSettings, result: Result) -> None:
    """The frame's product, made by its output's kind (castor.formats.kinds), then
    written by its format's writer: its bytes, or the part it gives to a file made
    from every frame at once (an animation)."""
    from castor.formats import FORMATS
    from castor.formats.kinds import MESH

    output = settings.output
    chosen = FORMATS.get(output.format) if output.format is not None else None
    kind = chosen.kind if chosen is not None else MESH  # no format: the mesh frame only
    product = kind.make(tree, settings, chosen, result)
    if chosen is None or product is None:
        return
    if chosen.gathers:
        result.gathered = product
        return
    result.data, result.companions = _encoded(product, kind, output, tree.number)


def _encoded(product, kind, output: OutputSettings, number: int):
    """The product's bytes in the output's format, and the files beside them: made
    a piece at a time as they are written (``output.pieces``), spooled to a file
    when large, else bytes."""
    from castor.formats import output as destination

    pieces, companions = destination.encode_pieces(product, output.format, output.target,
                                                   number=number, options=dict(output.options))
    if output.pieces:
        return pieces, companions  # made as they are written
    if output.spool is not None and kind.weight(product) > SPOOL_POLYGONS:
        return _spooled(pieces, product, output, number), companions
    return b"".join(pieces), companions


def _spooled(pieces, product, output: OutputSettings, number: int):
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
        return b"".join(destination.encode_pieces(product, output.format, output.target,
                                                  number=number,
                                                  options=dict(output.options))[0])
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
