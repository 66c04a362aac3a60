"""Evaluate the scene into frames the page can draw, with the diagnostics it gave.

The same pipeline as ``castor`` itself (castor.pipeline.frames), in this
process, so that a save costs the evaluation only and not castor's start-up.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Callable

from castor.diagnostics import CollectingReporter, Diagnostic
from castor.pipeline import Overtaken, frames
from castor.settings import EvaluationSettings, MeshSettings, ReadSettings, Source

__all__ = ["Diagnostic", "DrawnFrame", "Evaluation", "Overtaken", "Watched", "drawn", "evaluate"]


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

    @property
    def errors(self) -> int:
        return sum(d.kind == "error" for d in self.diagnostics)


def evaluate(watched: Watched, cancelled: Callable[[], bool] = lambda: False) -> Evaluation:
    """Evaluate the scene files and facetize each frame here, whose facetizer keeps
    the shared subtrees of one save for the next; raises Overtaken as soon as
    ``cancelled()`` says so (between statements and between frames). Each face
    knows where its primitive is written (FILE:LINE:COL, through macros), and
    its element and class (castor.serve.layers)."""
    from castor.analysis.scene import primitive_places
    from castor.analysis.reuse import ReusingInterpreter
    from castor.serve.layers import classified

    shown: list[DrawnFrame] = []
    reporter = CollectingReporter(watched.quiet)
    checked = frames(watched.source, reading=watched.reading, evaluation=watched.evaluation,
                     mesh=MeshSettings(), quiet=watched.quiet,
                     on_mesh=lambda mesh: shown.append(drawn(mesh)), cancelled=cancelled,
                     reporter=reporter, interpreter=ReusingInterpreter)
    trees = {tree.number: tree for tree in checked.trees}
    placed = tuple(classified(replace(frame, sources=primitive_places(trees[frame.number],
                                                                      reporter)),
                              trees[frame.number])
                   if frame.number in trees else frame for frame in shown)
    return Evaluation(placed, checked.diagnostics, checked.included, checked.seconds,
                      checked.printed)


def drawn(frame) -> DrawnFrame:
    """A castor.mesh.frame.Frame as triangles for the page."""
    import numpy as np

    from castor.mesh.arrays import fan_triangles

    corners, numbers, origins = [], [], []
    for obj in frame.objects:
        tris, polygon = fan_triangles(obj.offsets, obj.indices)
        corners.append(np.asarray(obj.vertices, dtype="<f4")[tris].reshape(-1, 9))
        numbers.append((np.asarray(obj.origin_of)[polygon] + len(origins)).astype("<u4"))
        origins.extend((o.path, tuple(float(c) for c in o.colour)) for o in obj.origins)
    positions = np.concatenate(corners) if corners else np.zeros((0, 9), "<f4")
    box = None
    if len(positions):
        points = np.concatenate([np.asarray(o.vertices, dtype=float) for o in frame.objects])
        box = (tuple(float(v) for v in points.min(axis=0)),
               tuple(float(v) for v in points.max(axis=0)))
    number_array = np.concatenate(numbers) if numbers else np.zeros(0, "<u4")
    return DrawnFrame(frame.number, frame.where, frame.polygon_count, len(positions), box,
                      tuple(origins), positions.tobytes() + number_array.tobytes())
