"""An animation made by worker processes (issue 29, item 3): `--jobs 2 -o x.gif`
of a smooth solid failed in every frame, pickling the ray tracer's compiled tree;
the frames' pictures now come back as arrays, the file the same as --jobs 1's. A
frame whose process fails is said in the user's words, once for all the frames
that failed alike (CLI.md)."""

import io
import os
import subprocess
import sys
from concurrent.futures import Future
from pathlib import Path

from PIL import Image

from castor.diagnostics import Reporter
from castor.failures import FrameFailure, failure_reason
from castor.run import Sequencer, evaluated_frames
from castor.settings import FrameSettings

ROOT = Path(__file__).resolve().parents[2]
SMOOTH = "b = @s(120) !cu(0.8, 0.7, 0.6);\n>[T = 0, 1] @rz(45 * T) b;\n"


def _castor(*args, cwd):
    done = subprocess.run([sys.executable, "-m", "castor", *args], capture_output=True,
                          text=True, cwd=cwd, timeout=600,
                          env={**os.environ, "PYTHONPATH": str(ROOT)})
    return done.returncode, done.stderr


def test_an_animation_of_a_smooth_solid_is_made_by_worker_processes(tmp_path):
    (tmp_path / "s.cas").write_text(SMOOTH)
    small = ["--size", "64x48", "--samples", "1"]
    status, err = _castor("--jobs", "2", *small, "-o", "two.gif", "s.cas", cwd=tmp_path)
    assert status == 0 and err == "", err
    status, err = _castor("--jobs", "1", *small, "-o", "one.gif", "s.cas", cwd=tmp_path)
    assert status == 0 and err == "", err
    assert (tmp_path / "two.gif").read_bytes() == (tmp_path / "one.gif").read_bytes()
    with Image.open(tmp_path / "two.gif") as gif:
        assert gif.n_frames == 2 and gif.size == (64, 48)
        gif.seek(1)
        turned = gif.convert("RGB")
    # the second frame is turned by 45 degrees: not the first one's pixels
    with Image.open(tmp_path / "one.gif") as gif:
        assert gif.convert("RGB").tobytes() != turned.tobytes()


def test_an_animation_made_on_a_dask_cluster_is_the_one_process_s(tmp_path):
    import pytest

    distributed = pytest.importorskip("distributed", reason="Dask's distributed is not installed")
    (tmp_path / "s.cas").write_text(SMOOTH)
    small = ["--size", "48x36", "--samples", "1"]
    status, err = _castor(*small, "-o", "one.gif", "s.cas", cwd=tmp_path)
    assert status == 0 and err == "", err
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        status, err = _castor("--scheduler", cluster.scheduler_address, *small, "-o",
                              "dask.gif", "s.cas", cwd=tmp_path)
    assert status == 0 and err == "", err
    assert (tmp_path / "dask.gif").read_bytes() == (tmp_path / "one.gif").read_bytes()


class _Failing:
    """An executor whose every frame fails as a process pool's does when the
    frame's result cannot be handed back (what --jobs 2 -o x.gif met)."""

    def submit(self, function, job, *args):
        future = Future()
        future.set_exception(TypeError("self.scene_i cannot be converted to a Python object "
                                       "for pickling"))
        return future


def test_frames_that_fail_alike_are_one_message_without_python_s_words():
    frames, said = evaluated_frames(SMOOTH.replace("[T = 0, 1]", "[T = 0, 1, 0.25]"))
    assert said == "" and len(frames) == 5
    stream = io.StringIO()
    reporter = Reporter(stream=stream)
    sequencer = Sequencer(reporter, None, FrameSettings(), _Failing(), window=8)
    for frame in frames:
        sequencer.submit(frame)
    sequencer.finish()
    errors = [line for line in stream.getvalue().splitlines() if "error:" in line]
    assert len(errors) == 1, stream.getvalue()
    assert "frames 1 to 5 could not be made: an internal error" in errors[0], errors
    assert "TypeError" not in stream.getvalue() and "pickl" not in stream.getvalue()
    assert reporter.errors == 1


def test_the_frames_that_failed_are_named_in_words():
    frames, _ = evaluated_frames(SMOOTH.replace("[T = 0, 1]", "[T = 0, 1, 0.5]"))
    location = frames[0].location
    first = FrameFailure((1,), "its process ended before it was done", location)
    assert first.message == "frame 1 could not be made: its process ended before it was done"
    both = first.joined(FrameFailure((2,), first.reason, location))
    assert both.message.startswith("frames 1 and 2 could not be made: ")
    assert FrameFailure((1, 3, 4), "r", location).message.startswith("frames 1, 3 and 4 ")
    assert not first.alike(FrameFailure((2,), "another reason", location))


def test_a_failure_s_reason_names_no_python_exception():
    from concurrent.futures.process import BrokenProcessPool

    for exc in (TypeError("cannot pickle 'x' object"), BrokenProcessPool("A child died"),
                OSError(104, "Connection reset by peer"), AttributeError("no attribute x")):
        reason = failure_reason(exc)
        assert type(exc).__name__ not in reason and str(exc) not in reason, reason
