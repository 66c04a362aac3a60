"""Ctrl-C and SIGTERM stop castor at once while it makes a frame in its own
process (``--jobs 1``), inside one of the engine's long booleans too, which
hold Python's interpreter lock for tens of seconds (issue 29: castor ended
26 s after the signal, when the frame was done). The old output stays as it
was, no temporary file is left, and no process (CLI.md, --jobs)."""

import os
import signal
import subprocess
import sys
import time

import pytest

from tests.support.cli import hear_ctrl_c

# a quick frame, then one whose booleans take some 30 s (more on a loaded machine)
SCENE = ("> !cu(1, 1, 1);\n"
         "b = $D(@h(20, 20, 1) !cu(1, 1, 1), $U[I = 0, 19]($U[J = 0, 19]("
         "@t(I + 0.5, J + 0.5, 0.5) @h(0.45) !sp(1, 0, 0))));\n"
         "> b;\n")
OLD = b"the old file, which stays as it was\n"


def _until(seen, timeout: float = 120.0) -> None:
    deadline = time.monotonic() + timeout
    while not seen():
        assert time.monotonic() < deadline, "castor never reached its second frame"
        time.sleep(0.05)


@pytest.mark.skipif(not hasattr(os, "fork"), reason="castor forks its run")
@pytest.mark.parametrize("signum, whom, status, output", [
    (signal.SIGINT, "group", 130, "keep-%d.glb"),  # Ctrl-C in a terminal; a file a frame
    (signal.SIGTERM, "main", 143, "keep.cps"),     # kill PID; the stream's file half made
], ids=["ctrl-c-glb", "sigterm-stream"])
def test_a_signal_stops_a_frame_in_the_middle_of_a_boolean(tmp_path, signum, whom, status,
                                                           output):
    (tmp_path / "slow.cas").write_text(SCENE)
    old = tmp_path / output.replace("%d", "2")  # the slow frame's file
    old.write_bytes(OLD)
    if output.endswith(".glb"):
        def started():  # the first frame written: the second is being made
            return (tmp_path / "keep-1.glb").exists()
    else:
        def started():  # the first frame in the stream's file, still beside its name
            return any(p.name.startswith(".castor-") for p in tmp_path.iterdir())
    castor = subprocess.Popen([sys.executable, "-m", "castor", "-t", "0.002", "-o", output,
                               "slow.cas"], cwd=tmp_path, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, start_new_session=True,
                              preexec_fn=hear_ctrl_c)
    try:
        _until(lambda: started() or castor.poll() is not None)
        assert castor.poll() is None, castor.communicate()[1].decode()
        time.sleep(2)  # well into the second frame's booleans
        if whom == "group":
            os.killpg(castor.pid, signum)
        else:
            os.kill(castor.pid, signum)
        sent = time.monotonic()
        try:
            err = castor.communicate(timeout=15)[1].decode()
        except subprocess.TimeoutExpired:
            pytest.fail("castor still ran 15 s after the signal")
        ended = time.monotonic() - sent
        time.sleep(0.2)
        try:
            os.killpg(castor.pid, 0)
            left = True  # a process of castor's outlived it
        except ProcessLookupError:
            left = False
    finally:
        try:
            os.killpg(castor.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
    assert ended < 5, f"{ended:.1f} s from the signal to the end"
    assert (castor.returncode, err) == (status, "castor: interrupted\n")
    assert not left
    assert old.read_bytes() == OLD
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == sorted({"slow.cas", old.name} | ({"keep-1.glb"} if "%d" in output else set()))
