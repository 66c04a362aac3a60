"""castor run as a process (``run``), or its command line in this process
(``run_here``, ``frames_of``), and files a test writes."""

from __future__ import annotations

import functools
import subprocess
import sys
import tempfile
from pathlib import Path

from .stream import Frame, parse_stream


# where castor runs as a process: an empty folder of its own, so that the
# installed castor is what ``python -m castor`` finds (the checkout's parent
# folder, or /tmp, may hold a folder named castor)
OUTSIDE = Path(tempfile.mkdtemp(prefix="castor-tests-"))


def write(tmp_path, name, text):
    """Write a test's file (its folders made as needed); its path."""
    path = tmp_path / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


def hear_ctrl_c() -> None:
    """For ``preexec_fn``: the castor a test starts hears Ctrl-C (SIGINT) even when
    the tests themselves were started as a background job of a shell, which
    starts them with SIGINT ignored and would pass that on to castor."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)


def run(*args, stdin: str | None = None, cwd=None, check_status=None):
    """Run castor; returns (status, stdout, stderr)."""
    result = subprocess.run([sys.executable, "-m", "castor", *args], input=stdin,
                            capture_output=True, text=True, cwd=cwd or OUTSIDE,
                            timeout=600)
    assert "Traceback" not in result.stderr, result.stderr
    if check_status is not None:
        assert result.returncode == check_status, result.stderr
    return result.returncode, result.stdout, result.stderr


@functools.lru_cache(maxsize=None)
def run_once(*args):
    """``run(*args)`` made once per session: for runs over files the tests only
    read (the examples), which several tests check for different things (one
    process and two jobs agree, every frame closed, volumes as a fresh
    evaluation's). Returns (status, stdout, stderr) as ``run`` does."""
    return run(*args)


def frames_of(scene: str, *args) -> list[Frame]:
    """Facetize a scene given as text; fails on any error message. castor's
    command line runs in this process (what it writes is read back as from a
    pipe): the tests make hundreds of scenes, and each process start costs more
    than most of them; the process as a whole is tested through ``run``."""
    status, out, err = run_here("--no-cpp", *args, stdin=scene)
    assert status == 0, err
    return parse_stream(out)


def run_here(*args, stdin: str = ""):
    """castor's command line in this process: (status, stdout, stderr)."""
    import io

    from castor.cli import main

    saved = sys.stdin, sys.stdout, sys.stderr
    sys.stdin, sys.stdout, sys.stderr = io.StringIO(stdin), io.StringIO(), io.StringIO()
    try:
        status = main(list(args))
    except SystemExit as exc:  # usage errors exit through argparse
        status = exc.code
    finally:
        out, err = sys.stdout.getvalue(), sys.stderr.getvalue()
        sys.stdin, sys.stdout, sys.stderr = saved
    assert "Traceback" not in err, err
    return status, out, err
