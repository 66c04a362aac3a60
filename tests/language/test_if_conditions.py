"""An #if whose condition is missing or cut short is an error at the #if, and
the #if still stands (read as false): its #else and #endif match it, so no
"misplaced #endif" follows, and the lines after the #endif are read
(pcpp failed with an IndexError on a file's first '#if !', found by the fuzzer
of test_robustness.py)."""

from __future__ import annotations

import pytest

from tests.support.cli import run_here

HINT = "write a condition of numbers, macros, defined(NAME) and C's operators"


@pytest.mark.parametrize("condition", ["!", "! defined", "!defined("])
def test_a_condition_cut_short_is_said_and_read_as_false(tmp_path, condition):
    scene = tmp_path / "f.cas"
    scene.write_text(f"#if {condition}\n> !cu(1, 0, 0);\n#else\n> !cu(0, 1, 0);\n#endif\n")
    status, out, err = run_here("--check", str(scene))
    assert status == 1
    assert err.splitlines() == [f"{scene}:1:1: error: #if or #elif cannot evaluate "
                                f"'{condition}'; {HINT}"] + err.splitlines()[1:]
    assert "error" not in "\n".join(err.splitlines()[1:]), err
    assert "internal error" not in err and "#endif" not in err


def test_an_if_without_a_condition_keeps_its_endif(tmp_path):
    scene = tmp_path / "g.cas"
    scene.write_text("#if\n#endif\n> !cu(1, 0, 0);\n")
    status, out, err = run_here("-o", str(tmp_path / "g.stl"), str(scene))
    assert status == 1
    assert f"{scene}:1:1: error: #if needs a condition" in err
    assert "#endif" not in err  # was: "Misplaced #endif"
    assert (tmp_path / "g.stl").stat().st_size > 0  # the frame after it is written
