"""castor run once on many scenes, each of its frames judged against the
oracle's evaluation."""

from __future__ import annotations

import subprocess
import sys

from tests.support.stream import parse_stream

from .evaluate import Oracle
from .judge import judge, kind_of
from .scene import Scene, scene_text


# --- running castor on many scenes at once ------------------------------------

def castor_frames(text: str, *options: str):
    """castor's frames for a scene text (one process), and its stderr."""
    result = subprocess.run([sys.executable, "-m", "castor", "--no-cpp", "-q", *options],
                            input=text, capture_output=True, text=True, timeout=600)
    if result.returncode != 0 or "Traceback" in result.stderr:
        raise RuntimeError(result.stderr[-2000:])
    return parse_stream(result.stdout), result.stderr


def check_scenes(scenes: list[Scene], sheets: bool = True,
                 exact: bool = False) -> list[tuple[Scene, int, list[str]]]:
    """Run castor once on all the scenes; the failures as (scene, frame, problems).
    With ``exact``, a frame whose volume castor and manifold3d disagree on is
    decided by exact booleans (exact.py)."""
    text = "".join(scene_text(s) for s in scenes)
    frames, _ = castor_frames(text)
    expected = sum(s.frames() for s in scenes)
    if len(frames) != expected:
        raise RuntimeError(f"castor wrote {len(frames)} frames, the scenes have {expected}")
    failures = []
    k = 0
    for scene in scenes:
        known: list = []

        def truth(number: int, scene=scene, known=known) -> tuple[float, float]:
            if not known:
                from . import exact as third
                known.extend(third.frame_figures(scene))
            return known[number - 1]

        oracle = Oracle(scene)
        # exact.py knows no smooth solid: a scene with @s is judged without it
        decide = exact and "@s(" not in scene_text(scene)
        for number, (solids, uses) in enumerate(oracle.frames(), 1):
            smooth = (oracle.smooth, oracle.loose, oracle.smooth_objects)
            problems = judge(frames[k], solids, uses, sheets,
                             (lambda n=number: truth(n)) if decide else None, smooth)
            k += 1
            if problems and oracle.smooth and all(kind_of(p) in FIGURES for p in problems):
                problems = judged_finer(scene, number, solids, uses, sheets, smooth, problems)
            if problems:
                failures.append((scene, number, problems))
    return failures


FIGURES = ("volume", "area", "box")
FINER: list[int] = []  # smooth frames within the distance only at a tenth of the tolerance


def judged_finer(scene: Scene, number: int, solids, uses, sheets, smooth, problems):
    """A smooth frame whose volume, area or box is off by more than the
    distance its smooth solids allow, judged again with castor at a tenth of
    the tolerance (0.001). Where two smooth solids meet at a grazing angle
    (an intersection of two rounded wedges, smooth seed 60), a facet's
    distance of 0.01 moves their seam by far more: castor's box there was
    0.019 short at 0.01, 0.00005 at 0.001. Passes if castor, made finer,
    comes within the finer distance: it converges to the oracle's surface."""
    try:
        frames, _ = castor_frames(scene_text(scene), "--tolerance", "0.001")
    except (RuntimeError, subprocess.TimeoutExpired) as exc:
        return problems + [f"at --tolerance 0.001 castor failed: {exc}"]
    again = judge(frames[number - 1], solids, uses, sheets, None, smooth, fine=True)
    if again:
        return problems + [f"at --tolerance 0.001: {p}" for p in again]
    FINER.append(number)
    return []
