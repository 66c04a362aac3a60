"""The same error met by several frames of one '>[T = ...]' command while they
are made (after their evaluation: over --max-polygons) is said once, naming the
frames, in one process or several (CLI.md: "The same error reported for several
frames ... is printed once, with the frames or the count it concerns")."""

import pytest

from tests.support.cli import run, write

SPHERE = "b = !sp(0.5, 0.5, 0.5);\n>[T = 0, 3] @rz(10 * T) b;\n"
MESSAGE = ("the frame would need about 1,122 polygons, more than --max-polygons 10; is an "
           "object used twice at every level of a deep chain?")


@pytest.mark.parametrize("jobs", ["1", "2"])
def test_frames_over_the_polygon_limit_are_one_message(tmp_path, jobs):
    scene = write(tmp_path, "spin.cas", SPHERE)
    status, _, err = run("--max-polygons", "10", "--jobs", jobs, "-o",
                         str(tmp_path / "spin%02d.stl"), str(scene))
    assert status == 1
    assert err.count("error:") == 1, err
    assert f"spin.cas:2:1: error: {MESSAGE} (in frames 1 to 4)\n" in err
    assert not list(tmp_path.glob("spin*.stl"))


def test_errors_of_frames_apart_are_said_apart(tmp_path):
    # frame 2 is made (under the limit at its tolerance): frames 1 and 3 are said on
    # their own, each where it comes
    scene = write(tmp_path, "apart.cas", "b = !sp(0.5, 0.5, 0.5);\n"
                  ">[T = 0, 2] @f(1 - abs(T - 1) * 0.99) b;\n")
    status, _, err = run("--max-polygons", "200", "-o", str(tmp_path / "apart%02d.stl"),
                         str(scene))
    assert status == 1
    assert err.count("error:") == 2, err
    assert "(in frames" not in err
    assert [p.name for p in tmp_path.glob("apart*.stl")] == ["apart02.stl"]


def test_as_many_frames_failing_alike_as_errors_stop_a_run_stop_it(tmp_path):
    # once merged, the frames' errors no longer counted towards the 50 that stop a
    # run: every frame of a long animation was made, each failing the same way
    scene = write(tmp_path, "long.cas", SPHERE.replace("[T = 0, 3]", "[T = 0, 79]"))
    status, _, err = run("--max-polygons", "10", "-o", str(tmp_path / "long%02d.stl"), str(scene))
    assert status == 1
    assert err.count("error:") == 1, err
    assert f"long.cas:2:1: error: {MESSAGE} (in frames 1 to 50)\n" in err
    assert err.endswith("castor: the same error in 50 frames, stopping\n"), err
