"""The live preview's step on the bus shelter: a slider's value and a save.

Evaluates examples/bus_shelter.cas as ``castor --serve`` does at each change
(castor.serve.evaluation.evaluate, in this process, its caches kept from one
evaluation to the next), after a first evaluation that fills them:

- a slider step: the shelter's length ``LA`` changed through the panel's
  values (an override, as the page sends it), BENCH_RUNS steps;
- a save of an included part: ``LA = ...;`` written in a copy of
  bus_shelter/shelter.cas, BENCH_RUNS saves.

Each step is split into stages (CPU seconds of this process, median over the
steps, and the best and worst; the machine may be shared, CPU time is
what changes least, and the best step what changes least with the load): the
engine's booleans, provenance (the triangles with their origins), the
regularization, merging into polygons, the frame's compaction, the page's
triangles (drawn) and layers, and the evaluation (the rest). Targets (CLI.md,
issue 34): a slider step within 0.3 s, a save within 0.5 s.

    PYTHONPATH=$PWD python benchmarks/slider.py
"""

from __future__ import annotations

import os
import shutil
import statistics
import sys
import tempfile
import time
from collections import defaultdict

from _common import runs_from_env

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.join(HERE, "..", "examples")

spent: dict[str, float] = defaultdict(float)
calls: dict[str, int] = defaultdict(int)
_inside: set[str] = set()


def _timed(stage: str, function):
    """``function``, its CPU time added to ``stage`` (once, when a stage's
    function calls another of the same stage)."""
    def wrapper(*args, **kwargs):
        if stage in _inside:
            return function(*args, **kwargs)
        _inside.add(stage)
        started = time.process_time()
        try:
            return function(*args, **kwargs)
        finally:
            spent[stage] += time.process_time() - started
            calls[stage] += 1
            _inside.discard(stage)
    return wrapper


def instrument() -> None:
    from castor.analysis import scene as analysis_scene
    from castor.mesh import booleans, facetize, merge, provenance
    from castor.serve import evaluation, layers

    for name in ("union", "intersection", "difference"):
        setattr(booleans, name, _timed("booleans", getattr(booleans, name)))
    provenance.triangles = _timed("provenance", provenance.triangles)
    provenance.batches = _timed("provenance", provenance.batches)
    facetize.regular_triangles = _timed("regularize", facetize.regular_triangles)
    merge.Merger.merge = _timed("merge", merge.Merger.merge)
    facetize.compact = _timed("compact", facetize.compact)
    facetize.polygon_surfaces = _timed("compact", facetize.polygon_surfaces)
    evaluation.drawn = _timed("drawn", evaluation.drawn)
    layers.classified = _timed("layers", layers.classified)
    analysis_scene.primitive_places = _timed("layers", analysis_scene.primitive_places)
    facetize.Facetizer.frame = _timed("facetize", facetize.Facetizer.frame)


STAGES = ("booleans", "provenance", "regularize", "merge", "compact", "facetize other",
          "drawn", "layers", "evaluation")


def step(change) -> dict[str, float]:
    """One evaluation after ``change()``, its stages' CPU seconds."""
    spent.clear()
    change_started = time.process_time()
    wall = time.perf_counter()
    result = change()
    total = time.process_time() - change_started
    assert result.errors == 0, result.printed
    figures = {stage: spent.get(stage, 0.0) for stage in STAGES[:5]}
    figures["facetize other"] = spent.get("facetize", 0.0) - sum(figures.values())
    figures["drawn"] = spent.get("drawn", 0.0)
    figures["layers"] = spent.get("layers", 0.0)
    figures["evaluation"] = total - spent.get("facetize", 0.0) - figures["drawn"] - figures["layers"]
    figures["total (CPU)"] = total
    figures["total (wall)"] = time.perf_counter() - wall
    return figures


def report(title: str, steps: list[dict[str, float]]) -> None:
    print(f"{title}: median of {len(steps)} (CPU seconds of this process)")
    for stage in (*STAGES, "total (CPU)", "total (wall)"):
        values = [s[stage] for s in steps]
        print(f"  {stage:16s} {statistics.median(values):7.3f}   best {min(values):7.3f}"
              f"   worst {max(values):7.3f}")


def caches_line() -> str:
    from castor.mesh.caches import PROCESS

    names = [name for name, value in vars(PROCESS).items() if hasattr(value, "hits")]
    return ", ".join(f"{name} {getattr(PROCESS, name).hits} hits" for name in names)


def main() -> None:
    runs = runs_from_env(5)
    from castor.serve.evaluation import Watched, evaluate
    from castor.settings import EvaluationSettings, Source

    instrument()
    folder = tempfile.mkdtemp()
    try:
        shutil.copytree(EXAMPLES, os.path.join(folder, "examples"))
        scene = os.path.join(folder, "examples", "bus_shelter.cas")
        part = os.path.join(folder, "examples", "bus_shelter", "shelter.cas")
        watched = Watched(Source((scene,)), quiet=True)
        started = time.perf_counter()
        first = evaluate(watched)
        assert first.errors == 0, first.printed
        print(f"bus_shelter.cas: first evaluation {time.perf_counter() - started:.2f} s (wall), "
              f"{len(first.frames)} frames, {sum(f.triangles for f in first.frames):,} triangles")

        def slider(value):
            job = Watched(watched.source, evaluation=EvaluationSettings(overrides={"LA": value}),
                          quiet=True)
            return lambda: evaluate(job)

        evaluate(Watched(watched.source, evaluation=EvaluationSettings(overrides={"LA": 5.0}),
                         quiet=True))
        steps = [step(slider(5.0 + 0.05 * (run + 1))) for run in range(runs)]
        report("slider step (LA)", steps)
        print(f"  caches: {caches_line()}")

        with open(part) as handle:
            text = handle.read()
        at = text.index("LA = 5;")

        def save(value):
            def change():
                with open(part, "w") as handle:
                    handle.write(text[:at] + f"LA = {value:.2f};" + text[at + len("LA = 5;"):])
                return evaluate(watched)
            return change

        steps = [step(save(4.9 - 0.05 * (run + 1))) for run in range(runs)]
        report("save of bus_shelter/shelter.cas (LA)", steps)
        print(f"  caches: {caches_line()}")
    finally:
        shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
