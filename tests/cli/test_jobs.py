"""Frames made in other processes (--jobs) or on a Dask cluster (--scheduler)
are written exactly as one process writes them."""

import importlib.util
import re
import subprocess
import sys
from pathlib import Path

import pytest

from tests.support.cli import OUTSIDE, run, run_once

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((ROOT / "examples").glob("*.cas"))

WITH_ERRORS = """L = 1;
a = @h(L, 1, 1) !cu(1, 0, 0);
> a;
> @t(X, 0, 0) a;
L = 2;
>[T = 0, 1, 0.5] @t(T, 0, 0) a, @t(0, 3, 0) !sp(0, 0, 1);
> @h(0, 1, 1) a;
> $I(a, @t(5, 0, 0) a);
"""


def _outputs(*args, stdin=None, once=False):
    """castor's status, output and messages, less the seconds of --stats lines;
    ``once``: the session's one run of these arguments (tests.support.cli.run_once)."""
    status, out, err = run_once(*args) if once else run(*args, stdin=stdin)
    return status, out, re.sub(r", \d+\.\d+ s$", ", (seconds)", err, flags=re.M)


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_two_jobs_write_what_one_writes(path):
    assert _outputs("--jobs", "2", str(path)) == _outputs(str(path), once=True)


def test_two_jobs_with_errors_say_and_write_the_same_in_the_same_order():
    one = _outputs("--no-cpp", "--stats", stdin=WITH_ERRORS)
    two = _outputs("--no-cpp", "--stats", "--jobs", "2", stdin=WITH_ERRORS)
    assert one[0] == 1 and one == two
    assert "frame 2 <stdin>:4" not in one[1]  # the failed frame leaves its gap


def test_per_frame_files_from_two_jobs(tmp_path):
    _outputs("--jobs", "2", "-o", str(tmp_path / "a-%02d.stl"), str(ROOT / "examples" / "door.cas"))
    _outputs("-o", str(tmp_path / "b-%02d.stl"), str(ROOT / "examples" / "door.cas"))
    a = sorted(tmp_path.glob("a-*.stl"))
    b = sorted(tmp_path.glob("b-*.stl"))
    assert len(a) == 9 and [p.read_bytes() for p in a] == [p.read_bytes() for p in b]


def test_streamed_frames_come_out_as_they_are_made_with_two_jobs():
    castor = subprocess.Popen([sys.executable, "-m", "castor", "--no-cpp", "--jobs", "2"],
                              stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE)
    castor.stdin.write(b"a = !cu(1, 0, 0);\n> a;\n")
    castor.stdin.flush()
    lines = [castor.stdout.readline() for _ in range(3)]
    assert lines[1].startswith(b"frame 1 ")
    castor.stdin.close()
    castor.wait(timeout=60)
    assert castor.returncode == 0


def test_a_dask_cluster_writes_what_one_process_writes():
    distributed = pytest.importorskip("distributed", reason="Dask's distributed is not installed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        for path in [ROOT / "examples" / "door.cas", ROOT / "examples" / "house.cas"]:
            assert (_outputs("--scheduler", cluster.scheduler_address, str(path))
                    == _outputs(str(path), once=True))
        with_errors = _outputs("--no-cpp", "--scheduler", cluster.scheduler_address,
                               stdin=WITH_ERRORS)
        assert with_errors == _outputs("--no-cpp", stdin=WITH_ERRORS)


@pytest.fixture(scope="module", autouse=True)
def unreachable_scheduler():
    """castor told of a Dask scheduler nobody answers for, started with the
    module's first test: it waits out Dask's connection timeout (10 s) while
    the other tests run, rather than on its own."""
    if importlib.util.find_spec("distributed") is None:
        yield None
        return
    castor = subprocess.Popen([sys.executable, "-m", "castor", "--scheduler", "tcp://127.0.0.1:9",
                               str(ROOT / "examples" / "car.cas")], stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True, cwd=OUTSIDE)
    yield castor
    if castor.poll() is None:
        castor.kill()
    castor.communicate()


def test_an_unreachable_scheduler_is_a_usage_error(unreachable_scheduler):
    pytest.importorskip("distributed", reason="Dask's distributed is not installed")
    out, err = unreachable_scheduler.communicate(timeout=600)
    status = unreachable_scheduler.returncode
    assert "Traceback" not in err, err
    assert status == 2
    assert "castor: error: cannot reach the Dask scheduler at 'tcp://127.0.0.1:9'" in err


def test_a_closed_pipe_ends_two_jobs_quietly():
    """`castor --jobs 2 door.cas | head -1`: no word from multiprocessing's resource
    tracker (leaked semaphores) once castor has gone (CLI.md: a closed pipe ends quietly)."""
    door = ROOT / "examples" / "door.cas"
    result = subprocess.run(f"'{sys.executable}' -m castor --jobs 2 '{door}' | head -1",
                            shell=True, capture_output=True, text=True, timeout=120, cwd=OUTSIDE)
    assert result.stdout == "castor-polygons 1\n"
    assert result.stderr == ""
