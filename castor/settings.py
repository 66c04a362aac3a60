"""The settings of each stage of the pipeline: plain, frozen, picklable data.

The command line (castor.cli) fills them from its options, the live preview
and an editor's language server from their own; the library (castor.pipeline,
castor.jobs, castor.run) reads them and never sees an argparse namespace.
Each stage has its own: what the reader and the preprocessor take, what the
evaluation takes (``EvaluationSettings``), then for each frame what the
facetizer, the ray tracer, the drawings, a building model and the output take.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from castor.options import (DEFAULT_MAX_POLYGONS, DEFAULT_SAMPLES, DEFAULT_SCALE, DEFAULT_SIZE,
                            DEFAULT_SUN)


@dataclass(frozen=True)
class Source:
    """What the scene is read from: files in order as one input (none or '-': standard
    input), or a text held in memory (an editor's buffer), named ``name``."""

    files: tuple[str, ...] = ()
    text: str | None = None
    name: str = "<scene>"  # the text's file name: for messages, and #include beside it

    @property
    def streamed(self) -> bool:
        """Read from standard input, as it arrives."""
        return self.text is None and (not self.files or "-" in self.files)


@dataclass(frozen=True)
class ReadSettings:
    """Reading and preprocessing: -D, -U, -I and --no-cpp."""

    defines: tuple[str, ...] = ()  # NAME or NAME=VALUE
    undefines: tuple[str, ...] = ()
    include_dirs: tuple[str, ...] = ()
    no_cpp: bool = False  # no preprocessor: statements run as they arrive


@dataclass
class EvaluationSettings:
    """Evaluation: the parameters given on the command line and the facet tolerance."""

    overrides: dict[str, float] = field(default_factory=dict)  # --set NAME=value
    tolerance: float | None = None  # --tolerance: TOLERANCE's value, where the scene sets none


@dataclass(frozen=True)
class MeshSettings:
    """Facetizing a frame into polygons."""

    max_polygons: int = DEFAULT_MAX_POLYGONS


@dataclass(frozen=True)
class PictureSettings:
    """Ray tracing a picture (castor.pictures)."""

    size: tuple[int, int] = DEFAULT_SIZE
    view: object = None  # castor.options.View
    eye: tuple | None = None
    look: tuple | None = None
    sun: tuple | None = DEFAULT_SUN  # (az, el), None, or castor.options.CameraSun
    samples: int = DEFAULT_SAMPLES
    edges: bool = False


@dataclass(frozen=True)
class DrawingSettings:
    """Drawing a plan, section or elevation (castor.drawings)."""

    section: object = None  # castor.options.Section: cut by this plane
    view: object = None  # castor.options.View: seen from this side
    scale: float = DEFAULT_SCALE  # 1:scale on paper
    sheet: object = None  # castor.options.Paper (--sheet); None: paper as large as the drawing


@dataclass(frozen=True)
class BimSettings:
    """Making a building model of the frame (castor.formats.ifc)."""

    # --ifc-class NAME=CLASS: the IFC class of the objects so named, as
    # (name, class) pairs (castor.formats.ifc.parse_ifc_classes); the others
    # are IfcBuildingElementProxy
    classes: tuple[tuple[str, str], ...] = ()


@dataclass(frozen=True)
class OutputSettings:
    """What a frame is written as, what is said about it, and how its bytes travel."""

    format: str | None = "cps"  # castor.formats; None: the mesh frame only, in this process
    target: str | None = None  # -o PATH (a pattern is filled in per frame)
    stats: bool = False  # one line of figures per frame
    summary: bool = False  # a quantity take-off record per frame
    title: str | None = None  # --title: a drawing's, an IFC project's (None: its default)
    keep_mesh: bool = False  # hand the mesh frame back (the live preview wants it)
    # how a frame's bytes are handed on: made a piece at a time as they are
    # written (``pieces``, in the process that writes them), written by a worker
    # into a file in ``spool`` when the frame is large, or else as bytes
    pieces: bool = False
    spool: str | None = None
    spool_owner: int = 0  # the driver's process: a worker left alone removes its file


@dataclass(frozen=True)
class FrameSettings:
    """What to make of each evaluated frame, stage by stage: what travels with a
    frame's tree to the process that makes it (castor.jobs.Job)."""

    output: OutputSettings = OutputSettings()
    mesh: MeshSettings = MeshSettings()
    picture: PictureSettings = PictureSettings()
    drawing: DrawingSettings = DrawingSettings()
    bim: BimSettings = BimSettings()

    @property
    def format(self) -> str | None:
        return self.output.format


@dataclass(frozen=True)
class RunSettings:
    """How a whole run goes (castor.run): --check, --jobs, --scheduler, --summary."""

    check: bool = False  # evaluate everything, write nothing
    jobs: int = 1  # frames made at once in worker processes (0: one per core)
    scheduler: str | None = None  # a Dask scheduler's address
    summary: str | None = None  # where the quantity take-off goes
