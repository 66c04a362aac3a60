"""The settings of each stage of the pipeline: plain, frozen, picklable data.

The command line (castor.cli) fills them from its options, the live preview
and an editor's language server from their own; the library (castor.pipeline,
castor.jobs, castor.run) reads them and never sees an argparse namespace.
Each stage has its own: what the reader and the preprocessor take, what the
evaluation takes (``EvaluationSettings``), then for each frame what the
facetizer, the ray tracer, the drawings, a building model and the output take.

They are plain records (castor.records), not dataclasses: making these ten
dataclasses cost about 5 ms of every start-up (issue 18). ``replace`` gives a
copy with some fields changed, as ``dataclasses.replace`` did.
"""

from __future__ import annotations

from castor.options import (DEFAULT_FORMAT, DEFAULT_MAX_POLYGONS, DEFAULT_SAMPLES, DEFAULT_SCALE,
                            DEFAULT_SIZE, DEFAULT_SUN)
from castor.records import Record


class Source(Record):
    """What the scene is read from: files in order as one input (none or '-': standard
    input), or a text held in memory (an editor's buffer), named ``name``."""

    __slots__ = ("files", "text", "name")

    def __init__(self, files: tuple[str, ...] = (), text: str | None = None, name: str = "<scene>"):
        self.files = files
        self.text = text
        self.name = name  # the text's file name: for messages, and #include beside it

    @property
    def streamed(self) -> bool:
        """Read from standard input, as it arrives."""
        return self.text is None and (not self.files or "-" in self.files)


class ReadSettings(Record):
    """Reading and preprocessing: -D, -U, -I and --no-cpp."""

    __slots__ = ("defines", "undefines", "include_dirs", "no_cpp")

    def __init__(self, defines: tuple[str, ...] = (), undefines: tuple[str, ...] = (),
                 include_dirs: tuple[str, ...] = (), no_cpp: bool = False):
        self.defines = defines  # NAME or NAME=VALUE
        self.undefines = undefines
        self.include_dirs = include_dirs
        self.no_cpp = no_cpp  # no preprocessor: statements run as they arrive


class EvaluationSettings(Record):
    """Evaluation: the parameters given on the command line and the facet tolerance."""

    __slots__ = ("overrides", "tolerance")
    __hash__ = None  # its overrides may change (the live preview's)

    def __init__(self, overrides: dict[str, float] | None = None, tolerance: float | None = None):
        self.overrides = {} if overrides is None else overrides  # --set NAME=value
        self.tolerance = tolerance  # --tolerance: TOLERANCE's value, where the scene sets none


class MeshSettings(Record):
    """Facetizing a frame into polygons."""

    __slots__ = ("max_polygons",)

    def __init__(self, max_polygons: int = DEFAULT_MAX_POLYGONS):
        self.max_polygons = max_polygons


class PictureSettings(Record):
    """Ray tracing a picture (castor.pictures)."""

    __slots__ = ("size", "view", "eye", "look", "sun", "samples", "edges")

    def __init__(self, size: tuple[int, int] = DEFAULT_SIZE, view: object = None,
                 eye: tuple | None = None, look: tuple | None = None,
                 sun: tuple | None = DEFAULT_SUN, samples: int = DEFAULT_SAMPLES,
                 edges: bool = False):
        self.size = size
        self.view = view  # castor.options.View
        self.eye = eye
        self.look = look
        self.sun = sun  # (az, el), None, or castor.options.CameraSun
        self.samples = samples
        self.edges = edges


class DrawingSettings(Record):
    """Drawing a plan, section or elevation (castor.drawings)."""

    __slots__ = ("section", "view", "scale", "sheet", "fields", "register")

    def __init__(self, section: object = None, view: object = None, scale: float = DEFAULT_SCALE,
                 sheet: object = None, fields: tuple[tuple[str, str], ...] = (),
                 register: object = None):
        self.section = section  # castor.options.Section: cut by this plane
        self.view = view  # castor.options.View: seen from this side
        self.scale = scale  # 1:scale on paper
        self.sheet = sheet  # castor.options.Paper (--sheet); None: paper as large as the drawing
        # the title block's fields given ("project", "number", "revision", "drawn",
        # "checked", and a register's "sheet_number", "sheet_title"), as (name, text)
        self.fields = fields
        self.register = register  # castor.drawings.register.Register (--sheets), or None


class BimSettings(Record):
    """Making a building model of the frame (castor.formats.ifc)."""

    __slots__ = ("classes",)

    def __init__(self, classes: tuple[tuple[str, str], ...] = ()):
        # --ifc-class NAME=CLASS: the IFC class of the objects so named, as
        # (name, class) pairs (castor.formats.ifc.parse_ifc_classes); the others
        # are IfcBuildingElementProxy
        self.classes = classes


class OutputSettings(Record):
    """What a frame is written as, what is said about it, and how its bytes travel."""

    __slots__ = ("format", "target", "stats", "summary", "title", "keep_mesh", "options",
                 "pieces", "spool", "spool_owner")

    def __init__(self, format: str | None = DEFAULT_FORMAT, target: str | None = None,
                 stats: bool = False, summary: bool = False, title: str | None = None,
                 keep_mesh: bool = False,
                 options: tuple[tuple[str, object], ...] = (), pieces: bool = False,
                 spool: str | None = None, spool_owner: int = 0):
        self.format = format  # castor.formats; None: the mesh frame only, in this process
        self.target = target  # -o PATH (a pattern is filled in per frame)
        self.stats = stats  # one line of figures per frame
        self.summary = summary  # a quantity take-off record per frame
        self.title = title  # --title: a drawing's, an IFC project's (None: its default)
        self.keep_mesh = keep_mesh  # hand the mesh frame back (the live preview wants it)
        # the format's own options given, as (name, value) pairs: what its writer
        # finds in WriteInfo.options (castor.options.OUTPUT_OPTIONS; 3MF's scale)
        self.options = options
        # how a frame's bytes are handed on: made a piece at a time as they are
        # written (``pieces``, in the process that writes them), written by a worker
        # into a file in ``spool`` when the frame is large, or else as bytes
        self.pieces = pieces
        self.spool = spool
        self.spool_owner = spool_owner  # the driver's process: a worker left alone removes its file


class FrameSettings(Record):
    """What to make of each evaluated frame, stage by stage: what travels with a
    frame's tree to the process that makes it (castor.jobs.Job)."""

    __slots__ = ("output", "mesh", "picture", "drawing", "bim")

    def __init__(self, output: OutputSettings = OutputSettings(),
                 mesh: MeshSettings = MeshSettings(), picture: PictureSettings = PictureSettings(),
                 drawing: DrawingSettings = DrawingSettings(), bim: BimSettings = BimSettings()):
        self.output = output
        self.mesh = mesh
        self.picture = picture
        self.drawing = drawing
        self.bim = bim

    @property
    def format(self) -> str | None:
        return self.output.format


class RunSettings(Record):
    """How a whole run goes (castor.run): --check, --jobs, --scheduler, --summary."""

    __slots__ = ("check", "jobs", "scheduler", "summary")

    def __init__(self, check: bool = False, jobs: int = 1, scheduler: str | None = None,
                 summary: str | None = None):
        self.check = check  # evaluate everything, write nothing
        self.jobs = jobs  # frames made at once in worker processes (0: one per core)
        self.scheduler = scheduler  # a Dask scheduler's address
        self.summary = summary  # where the quantity take-off goes
