"""A curved primitive faceted so finely that its booleans will be slow is
warned of, at the primitive as written, once a run, before the frame is made
(issue 29: ``castor --stats -t 1e-8 examples/car.cas`` took 10 s, and 77 s at
1e-9, saying nothing of why).

The engine's boolean time grows with the square of a curved primitive's
segments around (benchmarks/README.md, "A fine tolerance"): past
castor.csg.fineness.SLOW_SEGMENTS (6,000) castor says so, with a coarser
tolerance. The counts are the facetizer's own (a unit cylinder: n =
⌈π / acos(1 − t)⌉ with t rounded down to a power of 2^(1/4)).
"""

from pathlib import Path

import pytest

from castor.analysis.scene import analyse
from castor.csg.fineness import SLOW_SEGMENTS
from castor.mesh.primitives import circle_segments
from castor.primitives.facets import quantize
from castor.settings import Source
from tests.support.cli import run_here, write

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

# a box and a wheel of radius 0.35 whose circle crosses the box's face
WHEEL = ("roue = @h(0.35, 0.35, 0.25) !cy(0.5, 0.5, 0.5);\n"
         "> $U(!cu(1, 1, 1), @t(0.5, 0, 0.5) @rx(90) roue);\n")
SLOW = ("warning: '!cy' gets 14,033 segments around at tolerance 1e-08: a boolean with it "
        "may take several seconds (the time grows as the square of the segments); a coarser -t "
        "(such as 1e-05) is still finer than a printer or a screen shows")


def warnings(err: str) -> list[str]:
    return [line for line in err.splitlines() if ": warning: " in line]


def test_the_counts_are_the_facetizers():
    assert circle_segments(1.0, quantize(quantize(1e-8) / 0.35)) == 14_033
    assert circle_segments(1.0, quantize(1e-7 / 0.35)) < SLOW_SEGMENTS < \
        circle_segments(1.0, quantize(3e-8 / 0.35))


def test_a_fine_tolerance_is_warned_of_at_the_primitive(tmp_path):
    scene = write(tmp_path, "wheel.cas", WHEEL)
    status, out, err = run_here("--check", "-t", "1e-8", str(scene))
    assert status == 0 and out == ""
    assert warnings(err) == [f"{scene}:1:29: {SLOW}"]


def test_none_below_the_threshold(tmp_path):
    scene = write(tmp_path, "wheel.cas", WHEEL)
    for tolerance in ("1e-7", "0.01"):
        status, _, err = run_here("--check", "-t", tolerance, str(scene))
        assert status == 0 and warnings(err) == [], (tolerance, err)


def test_once_a_run_for_every_use_and_frame(tmp_path):
    """Four wheels in three frames: one warning; a second primitive its own."""
    scene = write(tmp_path, "car.cas",
                  "roue = @h(0.35, 0.35, 0.25) @rx(90) !cy(0.5, 0.5, 0.5);\n"
                  ">[T = 0, 2] $U(@h(3, 1, 1) !cu(1, 1, 1), @t(T, 0, 0.5) roue,\n"
                  "               @t(2, 0, 0.5) roue, @t(0, 1.25, 0.5) roue, @t(2, 1.25, 0.5) roue);\n"
                  "> @h(0.35) !sp(1, 1, 1);\n")
    status, _, err = run_here("--check", "-t", "1e-8", str(scene))
    said = warnings(err)
    assert status == 0 and len(said) == 2, err
    assert said[0] == f"{scene}:1:37: {SLOW}"
    assert said[1].startswith(f"{scene}:4:12: warning: '!sp' gets 19,8")


def test_a_run_warns_and_writes_the_same(tmp_path):
    """A run that makes the mesh says it once for two frames; the file is the
    one a quiet run writes (the cylinder alone: no boolean, so it is quick)."""
    scene = write(tmp_path, "cy.cas", ">[T = 1, 2] @h(0.35, 0.35, 0.25) !cy(0.5, 0.5, 0.5);\n")
    status, _, err = run_here("-t", "1e-8", "-o", str(tmp_path / "cy%d.stl"), str(scene))
    assert status == 0
    assert warnings(err) == [f"{scene}:1:34: {SLOW}"]
    status, _, err = run_here("-q", "-t", "1e-8", "-o", str(tmp_path / "q%d.stl"), str(scene))
    assert status == 0 and err == ""
    assert (tmp_path / "cy1.stl").read_bytes() == (tmp_path / "q1.stl").read_bytes()


def test_minutes_past_25000_segments(tmp_path):
    scene = write(tmp_path, "wheel.cas", WHEEL)
    _, _, err = run_here("--check", "-t", "1e-9", str(scene))
    assert warnings(err) == [
        f"{scene}:1:29: warning: '!cy' gets 43,283 segments around at tolerance 1e-09: a boolean "
        "with it may take minutes (the time grows as the square of the segments); a coarser -t "
        "(such as 1e-05) is still finer than a printer or a screen shows"]


def test_an_f_names_no_command_line_tolerance(tmp_path):
    scene = write(tmp_path, "f.cas", "> @f(1e-8) @h(0.35, 0.35, 0.25) !cy(0.5, 0.5, 0.5);\n")
    _, _, err = run_here("--check", str(scene))
    assert warnings(err) == [
        f"{scene}:1:33: warning: '!cy' gets 14,033 segments around at its tolerance: a boolean "
        "with it may take several seconds (the time grows as the square of the segments); a tolerance "
        "1000 times coarser (-t or '@f') is still finer than a printer or a screen shows"]


def test_the_language_server_shows_it_at_the_primitive(tmp_path):
    text = "TOLERANCE = 1e-8;\n" + WHEEL
    found = [(d.kind, d.location.line, d.location.column, d.message)
             for d in analyse(Source(text=text, name=str(tmp_path / "scene.cas"))).diagnostics]
    assert found == [("warning", 2, 29, SLOW.removeprefix("warning: "))]


@pytest.mark.parametrize("example", sorted(p.name for p in EXAMPLES.glob("*.cas")))
def test_none_for_the_examples(example):
    status, _, err = run_here("--check", str(EXAMPLES / example))
    assert "segments around" not in err, err
