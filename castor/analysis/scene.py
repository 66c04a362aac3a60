"""The one adapter between the editing tools and castor's pipeline: a scene's analysis.

``analyse`` runs a scene (an editor's unsaved buffer, or files) through
castor.pipeline.evaluate as ``castor --check`` does (preprocess, reader,
parser, interpreter; every frame evaluated into its CSG tree, none facetized)
and keeps what an editor asks about: every diagnostic with its location as
written (out of macro expansions), each parameter and object definition in
the order they ran (with the parameter's value there), the files ``#include``
opened, and the symbol tables at the end. ``castor --params``, ``-p``/``-P``,
the live preview's parameters panel and the language server read the
pipeline through this module only (``analyse_buffers`` for an editor's unsaved
texts).
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from typing import Callable

from castor.diagnostics import (CastorError, CollectingReporter, Diagnostic, Location,
                                Reporter)
from castor.pipeline import Overtaken, evaluate
from castor.settings import EvaluationSettings, ReadSettings, Source

__all__ = ["Analysis", "Definition", "Diagnostic", "Overtaken", "analyse", "analyse_buffers",
           "macro_definitions", "object_classes", "object_figures", "parameters",
           "primitive_places", "shown_name", "written_at"]


@dataclass(frozen=True)
class Definition:
    """A parameter or object definition, or a '>' command, where it ran."""

    kind: str  # "parameter", "object" or "frame"
    name: str
    location: Location
    value: float | None = None  # a parameter's value just after its definition
    node: object = None  # an object's scene-graph node


@dataclass
class Analysis:
    file: str  # the main file's name as locations give it
    diagnostics: list[Diagnostic] = field(default_factory=list)
    definitions: list[Definition] = field(default_factory=list)
    included: list[str] = field(default_factory=list)
    parameters: dict[str, float] = field(default_factory=dict)  # at the end
    objects: dict[str, object] = field(default_factory=dict)
    texts: dict[str, str] = field(default_factory=dict)  # file -> its text as analysed
    seconds: float = 0.0

    def source_text(self, file: str) -> str | None:
        """A file's text: the buffer for the main file, else as it is on disk."""
        if file not in self.texts:
            try:
                with open(file, encoding="utf-8", errors="replace") as handle:
                    self.texts[file] = handle.read()
            except (OSError, ValueError):
                return None
        return self.texts[file]


class _Collector(CollectingReporter):
    """Keeps each diagnostic with its location mapped out of macro expansions,
    as castor prints it; prints nothing (an editor shows the diagnostics)."""

    def _keep(self, kind: str, message: str, location: Location | None) -> None:
        self.diagnostics.append(Diagnostic(kind, message, written_at(self, location)))

    def _emit_plain(self, text: str) -> None:
        pass


def written_at(reporter: Reporter, location: Location | None) -> Location | None:
    """A location as written: out of a macro's expansion to the macro's use in the
    line as the user wrote it (as castor's diagnostics point)."""
    if location is None or reporter.expansions is None:
        return location
    text = reporter.source_lines.get((location.file, location.line))
    mapped = reporter.expansions(location.file, location.line, text)
    if mapped is None:
        return location
    column, _ = mapped.locate(location.column)
    return Location(location.file, location.line, column)


def primitive_places(frame, reporter: Reporter) -> dict[str, str]:
    """``FILE:LINE:COL`` where each primitive of an evaluated frame is written,
    by its path (as the faces made of it carry), through macros and includes."""
    from castor.csg.tree import leaves

    places: dict[str, str] = {}
    for obj in frame.objects:
        if obj.root is None:
            continue
        for leaf, _, path in leaves(obj.root):
            if path not in places:
                places[path] = f"{written_at(reporter, leaf.location)}: !{leaf.kind}"
    return places


def analyse(source: Source, reading: ReadSettings = ReadSettings(),
            evaluation: EvaluationSettings | None = None,
            cancelled: Callable[[], bool] = lambda: False, quiet: bool = False,
            unreadable: Callable[[str, str], None] | None = None) -> Analysis:
    """Check a scene as ``castor --check`` does, with castor.pipeline.evaluate;
    raises Overtaken as soon as ``cancelled()`` says so (between statements).
    A file that cannot be read goes to ``unreadable`` (None: UsageError)."""
    import time

    from castor.language.scene import FrameCommand, ObjectDef, ParamDef
    from castor.analysis.reuse import ReusingInterpreter

    started = time.perf_counter()
    reporter = _Collector(quiet)
    files = source.files if source.text is None else (source.name,)
    shown = shown_name(files[0]) if files else "<stdin>"
    analysis = Analysis(shown, texts={shown: source.text} if source.text is not None else {})

    class Recording(ReusingInterpreter):
        def check_annotation(self, statement) -> None:
            pass  # parameters() says it, against the text as written

        def execute(self, item) -> None:
            super().execute(item)
            if isinstance(item, ParamDef):
                analysis.definitions.append(Definition(
                    "parameter", item.name, item.location, self.tables.parameters.get(item.name)))
            elif isinstance(item, ObjectDef):
                analysis.definitions.append(Definition("object", item.name, item.location,
                                                       node=item.node))
            elif isinstance(item, FrameCommand):
                analysis.definitions.append(Definition("frame", ">", item.location,
                                                       node=item.objects))

    interpreter = None
    try:
        interpreter = evaluate(source, reporter, None, reading=reading, evaluation=evaluation,
                               included=analysis.included, unreadable=unreadable,
                               cancelled=cancelled, interpreter=Recording)
        interpreter.warn_if_no_frame()  # as castor --check
    except RecursionError:
        reporter.diagnostics.append(Diagnostic("error", "the scene is nested too deeply",
                                               Location(shown, 1, 1)))
    analysis.diagnostics = reporter.diagnostics
    if interpreter is not None:
        analysis.parameters = dict(interpreter.tables.parameters)
        analysis.objects = dict(interpreter.tables.objects)
    analysis.seconds = time.perf_counter() - started
    return analysis


def analyse_buffers(text: str, name: str | None, buffers: dict[str, str],
                    cancelled: Callable[[], bool] = lambda: False) -> Analysis:
    """Analyse an editor's buffer ``text`` (the file ``name``), reading the other
    open buffers (``buffers``, path -> text) instead of those files wherever
    ``#include`` opens them (castor.language.preprocess.unsaved)."""
    from castor.language.preprocess import unsaved

    with unsaved(buffers):
        analysis = analyse(Source(text=text, name=name), cancelled=cancelled)
    by_path = {os.path.realpath(path): text for path, text in buffers.items()}
    for path in analysis.included:  # ranges and hovers read the buffers too
        if os.path.realpath(path) in by_path:
            analysis.texts[path] = analysis.texts[shown_name(path)] = \
                by_path[os.path.realpath(path)]
    return analysis


def shown_name(name: str) -> str:
    """A file name as locations give it (relative to the current directory when inside)."""
    here = os.path.abspath("") + os.sep
    return name[len(here):] if name.startswith(here) else name


def parameters(analysis: Analysis):
    """The scene's parameters as a customizer offers them, and the warnings
    about malformed annotations (castor.language.annotations)."""
    from castor.language.annotations import annotate

    return annotate([(d.name, d.location, d.value) for d in analysis.definitions
                     if d.kind == "parameter"], analysis.source_text)


# an object larger than this is not made for a hover (its figures say why)
HOVER_POLYGONS = 2_000_000


def object_classes(analysis: Analysis):
    """What each object definition's annotation says it is (LANGUAGE.md §11): for
    each annotated definition, its name, where it is, its class (None when the
    annotation cannot be understood) and the warning about it, if any: what a
    hover, an outline and the warnings as you type read."""
    from castor.language.annotations import object_classes as classes_of

    lines: dict[str, list[str] | None] = {}

    def line_of(file: str, number: int) -> str | None:
        if file not in lines:
            text = analysis.source_text(file)
            lines[file] = None if text is None else text.split("\n")
        found = lines[file]
        return found[number - 1] if found is not None and 0 < number <= len(found) else None

    return classes_of([(d.name, d.location) for d in analysis.definitions
                       if d.kind == "object"], line_of)


def object_figures(analysis: Analysis, name: str, tolerance: float | None = None) -> dict | None:
    """Bounding box and volume of the object ``name`` with the values at the end
    of the scene (castor's summary), ``{"refused": why}`` when it cannot be made
    (over the limit), or None when it has errors."""
    from castor.csg.evaluate import Evaluator
    from castor.jobs import Job, make
    from castor.settings import FrameSettings, MeshSettings, OutputSettings

    node = analysis.objects.get(name)
    if node is None:
        return None
    env = dict(analysis.parameters)
    if tolerance is not None:
        env["TOLERANCE"] = tolerance
    try:
        tree = Evaluator().frame((node,), env, 1, name, node.location)
    except (CastorError, RecursionError):
        return None
    result = make(Job(tree, FrameSettings(output=OutputSettings(format=None, summary=True),
                                           mesh=MeshSettings(max_polygons=HOVER_POLYGONS))))
    if result.errors:
        return {"refused": result.errors[0].message}
    return result.summary


_DEFINE = re.compile(r"^[ \t]*#[ \t]*define[ \t]+([A-Za-z_]\w*)")


def macro_definitions(analysis: Analysis) -> list[tuple[str, Location]]:
    """Every ``#define`` of the main file and the files it includes."""
    out = []
    for file in [analysis.file] + [shown_name(f) for f in analysis.included]:
        text = analysis.source_text(file)
        if text is None:
            continue
        for number, line in enumerate(text.split("\n"), 1):
            match = _DEFINE.match(line)
            if match:
                out.append((match[1], Location(file, number, match.start(1) + 1)))
    return out
