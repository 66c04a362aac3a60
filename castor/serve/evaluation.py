"""Evaluate the scene into frames the page can draw, with the diagnostics it gave.

The same pipeline as ``castor`` itself (castor.pipeline.frames), in this
process, so that a save costs the evaluation only and not castor's start-up.

Facets sized to the page's camera (CLI.md, "Live preview"): once the page's
camera stops, ``Facets`` holds it, every frame is faceted for it with
``--pixel-error`` PIXEL_ERROR (castor.mesh.screen), and ``refaceted`` facets
the frames of the last evaluation again, without evaluating: a curved leaf
whose needed tolerance changed by no more than a factor of two keeps its
facets (castor.mesh.screen.kept_where_close), and with them the facetizer's
caches; flat faces are never changed.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Callable

from castor.diagnostics import CollectingReporter, Diagnostic
from castor.pipeline import Overtaken, frames
from castor.settings import EvaluationSettings, MeshSettings, ReadSettings, Source

__all__ = ["Diagnostic", "DrawnFrame", "Evaluation", "Facets", "Overtaken", "PIXEL_ERROR",
           "Watched", "drawn", "evaluate", "refaceted"]

# The preview's facets, once its page has said its camera: a chord error of at
# most half a pixel where each curved surface is nearest (--pixel-error 0.5)
PIXEL_ERROR = 0.5


@dataclass(frozen=True)
class DrawnFrame:
    """One frame as triangles: ``data`` holds float32 corners (nine numbers per
    triangle) then the uint32 number of each triangle's origin in ``origins``,
    little-endian, as the page's typed arrays read them."""

    number: int
    where: str  # FILE:LINE of the '>' command
    polygons: int
    triangles: int
    box: tuple[tuple[float, float, float], tuple[float, float, float]] | None
    origins: tuple[tuple[str, tuple[float, float, float]], ...]  # (path, colour)
    data: bytes = field(repr=False)
    sources: dict = field(default_factory=dict, repr=False, compare=False)  # path -> FILE:LINE:COL
    # each origin's element and class (castor.serve.layers): (name, short name or None)
    layers: tuple[tuple[str | None, str | None], ...] = ()

    def as_json(self) -> dict:
        layers = self.layers or ((None, None),) * len(self.origins)
        return {"number": self.number, "where": self.where, "polygons": self.polygons,
                "triangles": self.triangles, "box": self.box,
                "origins": [{"path": path, "colour": colour, "source": self.sources.get(path),
                             "element": element, "class": kind}
                            for (path, colour), (element, kind) in zip(self.origins, layers)]}


@dataclass(frozen=True)
class Watched:
    """What the live preview evaluates at each save: the scene files and the
    settings of the stages it runs."""

    source: Source
    reading: ReadSettings = ReadSettings()
    evaluation: EvaluationSettings = field(default_factory=EvaluationSettings)
    quiet: bool = False

    @property
    def files(self) -> tuple[str, ...]:
        return self.source.files


@dataclass(frozen=True)
class Evaluation:
    frames: tuple[DrawnFrame, ...]
    diagnostics: tuple[Diagnostic, ...]
    included: tuple[str, ...]  # every file that #include opened
    seconds: float
    printed: str  # the diagnostics as castor prints them on standard error
    # frame number -> its evaluated tree (castor.csg.tree.FrameTree), to facet again,
    # and the tree its frame was faceted from (sized to the camera)
    trees: dict = field(default_factory=dict, compare=False, repr=False)
    faceted: dict = field(default_factory=dict, compare=False, repr=False)

    @property
    def errors(self) -> int:
        return sum(d.kind == "error" for d in self.diagnostics)


class Facets:
    """How one evaluation or refacet facets the frames: for ``camera`` (the
    page's, castor.pictures.camera.Camera; None: the scene's own tolerance
    everywhere) with a chord error of at most ``pixel_error`` pixels, keeping
    each leaf of ``previous`` (frame number -> the tree its shown frame was
    faceted from) that is close enough; ``made`` collects the trees faceted."""

    def __init__(self, camera=None, previous: dict | None = None,
                 pixel_error: float = PIXEL_ERROR):
        self.camera = camera
        self.previous = previous or {}
        self.error = pixel_error
        self.made: dict[int, object] = {}

    def __call__(self, frame_tree):
        """The tree to facetize for the evaluated ``frame_tree``."""
        sized = frame_tree
        if self.camera is not None:
            from castor.mesh.screen import kept_where_close, sized_to_screen

            sized = kept_where_close(self.previous.get(frame_tree.number),
                                     sized_to_screen(frame_tree, None, self.error, self.camera))
        self.made[frame_tree.number] = sized
        return sized


def evaluate(watched: Watched, cancelled: Callable[[], bool] = lambda: False,
             facets: Facets | None = None) -> Evaluation:
    """Evaluate the scene files and facetize each frame here, whose facetizer keeps
    the shared subtrees of one save for the next; raises Overtaken as soon as
    ``cancelled()`` says so (between statements and between frames). Each face
    knows where its primitive is written (FILE:LINE:COL, through macros), and
    its element and class (castor.serve.layers); with ``facets``, each frame
    is faceted as it says (sized to the page's camera)."""
    from castor.analysis.scene import primitive_places
    from castor.analysis.reuse import ReusingInterpreter
    from castor.serve.layers import classified

    shown: list[DrawnFrame] = []
    reporter = CollectingReporter(watched.quiet)
    checked = frames(watched.source, reading=watched.reading, evaluation=watched.evaluation,
                     mesh=MeshSettings(), quiet=watched.quiet,
                     on_mesh=lambda mesh: shown.append(drawn(mesh)), cancelled=cancelled,
                     reporter=reporter, interpreter=ReusingInterpreter, sized=facets)
    trees = {tree.number: tree for tree in checked.trees}
    placed = tuple(classified(replace(frame, sources=primitive_places(trees[frame.number],
                                                                      reporter)),
                              trees[frame.number])
                   if frame.number in trees else frame for frame in shown)
    return Evaluation(placed, checked.diagnostics, checked.included, checked.seconds,
                      checked.printed, trees, facets.made if facets is not None else trees)


def refaceted(evaluation: Evaluation, facets: Facets,
              cancelled: Callable[[], bool] = lambda: False) -> Evaluation:
    """The frames of ``evaluation`` faceted again as ``facets`` says (for a new
    camera; its ``previous``, the evaluation's ``faceted``), without
    evaluating the scene: a frame none of whose objects changes is kept as it
    is; ``seconds``, the time this took. Raises Overtaken as soon as
    ``cancelled()`` says so (between frames)."""
    import time

    from castor.jobs import Job, make
    from castor.serve.layers import classified
    from castor.settings import FrameSettings, OutputSettings

    started = time.perf_counter()
    settings = FrameSettings(output=OutputSettings(format=None, keep_mesh=True),
                             mesh=MeshSettings())
    shown = []
    faceted = dict(evaluation.faceted)
    for frame in evaluation.frames:
        if cancelled():
            raise Overtaken()
        frame_tree = evaluation.trees.get(frame.number)
        before = evaluation.faceted.get(frame.number)
        if frame_tree is None or before is None:
            shown.append(frame)
            continue
        sized = facets(frame_tree)
        if (len(sized.objects) == len(before.objects)
                and all(a is b for a, b in zip(sized.objects, before.objects))):
            shown.append(frame)  # every object keeps its facets
            continue
        result = make(Job(sized, settings))
        if result.mesh is None:  # as it was evaluated, it could be made: keep that
            shown.append(frame)
            continue
        faceted[frame.number] = sized
        shown.append(classified(replace(drawn(result.mesh), sources=frame.sources), frame_tree))
    return replace(evaluation, frames=tuple(shown), seconds=time.perf_counter() - started,
                   faceted=faceted)


def drawn(frame) -> DrawnFrame:
    """A castor.mesh.frame.Frame as triangles for the page."""
    import numpy as np

    from castor.mesh.arrays import fan_triangles

    corners, numbers, origins = [], [], []
    colours: dict = {}  # a colour as floats, once per colour (most origins share a few)
    for obj in frame.objects:
        tris, polygon = fan_triangles(obj.offsets, obj.indices)
        corners.append(np.asarray(obj.vertices, dtype="<f4")[tris].reshape(-1, 9))
        numbers.append((np.asarray(obj.origin_of)[polygon] + len(origins)).astype("<u4"))
        for o in obj.origins:
            colour = colours.get(o.colour)
            if colour is None:
                colour = colours[o.colour] = tuple(float(c) for c in o.colour)
            origins.append((o.path, colour))
    positions = np.concatenate(corners) if corners else np.zeros((0, 9), "<f4")
    box = None
    if len(positions):
        points = np.concatenate([np.asarray(o.vertices, dtype=float) for o in frame.objects])
        box = (tuple(float(v) for v in points.min(axis=0)),
               tuple(float(v) for v in points.max(axis=0)))
    number_array = np.concatenate(numbers) if numbers else np.zeros(0, "<u4")
    return DrawnFrame(frame.number, frame.where, frame.polygon_count, len(positions), box,
                      tuple(origins), positions.tobytes() + number_array.tobytes())
