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

import threading
from typing import NamedTuple

from castor.records import Record

# Deeply nested scenes recurse deeply: whoever runs the pipeline on a thread of
# its own (castor, castor --serve, a worker of --jobs N: castor.jobs.make_deep)
# gives it this much stack, and Python this recursion limit. A chain of names
# recurses some 4 calls a level, and the parser allows up to 100,000 levels.
STACK_BYTES = 512 * 1024 * 1024
RECURSION_LIMIT = 1_000_000


def started_thread(target, name: str, stack_bytes: int = STACK_BYTES):
    """A daemon thread running ``target``, started with ``stack_bytes`` of stack
    (0: the default): the stack size is the process's setting, so it is set for
    this start only, one start at a time."""
    with _STACK_LOCK:
        previous = threading.stack_size()
        if stack_bytes:
            threading.stack_size(stack_bytes)
        try:
            thread = threading.Thread(target=target, name=name, daemon=True)
            thread.start()
        finally:
            threading.stack_size(previous)
    return thread


_STACK_LOCK = threading.Lock()

# --- every default, and the records the options' values are made of (castor.options
# parses the command line's text into them; the stages read them from here)


class CameraSun(NamedTuple):
    """The default sun: ``turn`` degrees beside the camera's azimuth and
    ``elevation`` high, so that every face the camera sees is lit
    (castor.pictures.shade.sun_light turns it into a direction)."""

    turn: float
    elevation: float


DEFAULT_FORMAT = "cps"  # the polygon stream: standard output's, and a device's (-o /dev/null)
DEFAULT_TOLERANCE = 0.01
DEFAULT_MAX_POLYGONS = 20_000_000
DEFAULT_SIZE = (800, 600)
DEFAULT_VIEW = (-60.0, 25.0)
DEFAULT_SUN = CameraSun(20.0, 45.0)  # the camera's azimuth + 20, 45 high (CLI.md)
DEFAULT_SAMPLES = 4
DEFAULT_SCALE = 100  # 1:100
DEFAULT_PORT = 8000


class Orthographic(NamedTuple):
    """A named orthographic view (CLI.md --view NAME): the page's right and up,
    and the direction towards the viewer (right x up = towards), unit vectors
    of the scene. A picture looks along -towards with this up; a drawing
    projects on the three."""

    name: str
    right: tuple[int, int, int]
    up: tuple[int, int, int]
    towards: tuple[int, int, int]

    def basis(self):
        """(3, 3) numpy array: rows right, up, towards; a point p is seen at basis @ p."""
        import numpy as np

        return np.array([self.right, self.up, self.towards], dtype=np.float64)

    def plane_depth(self, section) -> float | None:
        """The depth (along ``towards``) of a Section's plane, or None."""
        if section is None:
            return None
        axis = "xyz".index(section.axis)
        return float(self.towards[axis]) * section.value


# the six named views, declared here only
ORTHOGRAPHIC = {view.name: view for view in (
    Orthographic("top", (1, 0, 0), (0, 1, 0), (0, 0, 1)),
    Orthographic("bottom", (1, 0, 0), (0, -1, 0), (0, 0, -1)),
    Orthographic("front", (1, 0, 0), (0, 0, 1), (0, -1, 0)),
    Orthographic("back", (-1, 0, 0), (0, 0, 1), (0, 1, 0)),
    Orthographic("left", (0, -1, 0), (0, 0, 1), (-1, 0, 0)),
    Orthographic("right", (0, 1, 0), (0, 0, 1), (1, 0, 0)),
)}
VIEW_NAMES = tuple(ORTHOGRAPHIC)


class View(NamedTuple):
    """A camera: a direction (azimuth, elevation in degrees) for a perspective
    view framing the scene, or a name for an orthographic one."""

    name: str | None  # "top", "front", ... (orthographic) or None (perspective)
    azimuth: float
    elevation: float


class Section(NamedTuple):
    axis: str  # "x", "y" or "z"
    value: float


class Paper(NamedTuple):
    """A sheet of the ISO 216 A series as a drawing is laid on it (millimetres)."""

    name: str  # "A3", "A3-portrait"
    width: float
    height: float


# ISO 216, landscape: width x height in millimetres
PAPER_SIZES = {"A4": (297, 210), "A3": (420, 297), "A2": (594, 420), "A1": (841, 594),
               "A0": (1189, 841)}


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

    __slots__ = ("max_polygons", "pixel_error")

    def __init__(self, max_polygons: int = DEFAULT_MAX_POLYGONS, pixel_error: float | None = None):
        self.max_polygons = max_polygons
        # --pixel-error: facets sized to the screen of the picture settings' camera
        # (castor.mesh.screen); None: the tolerance alone
        self.pixel_error = pixel_error


class PictureSettings(Record):
    """Ray tracing a picture (castor.pictures)."""

    __slots__ = ("size", "view", "eye", "look", "sun", "samples", "edges")

    def __init__(self, size: tuple[int, int] = DEFAULT_SIZE, view: object = None,
                 eye: tuple | None = None, look: tuple | None = None,
                 sun: tuple | None = DEFAULT_SUN, samples: int = DEFAULT_SAMPLES,
                 edges: bool = False):
        self.size = size
        self.view = view  # castor.settings.View
        self.eye = eye
        self.look = look
        self.sun = sun  # (az, el), None, or castor.settings.CameraSun
        self.samples = samples
        self.edges = edges


class DrawingSettings(Record):
    """Drawing a plan, section or elevation (castor.drawings)."""

    __slots__ = ("section", "view", "scale", "sheet", "fields", "register")

    def __init__(self, section: object = None, view: object = None, scale: float = DEFAULT_SCALE,
                 sheet: object = None, fields: tuple[tuple[str, str], ...] = (),
                 register: object = None):
        self.section = section  # castor.settings.Section: cut by this plane
        self.view = view  # castor.settings.View: seen from this side
        self.scale = scale  # 1:scale on paper
        self.sheet = sheet  # castor.settings.Paper (--sheet); None: paper as large as the drawing
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
