"""Ctrl-C and SIGTERM end castor and every process it started, at once, and
leave no half-written file nor spooled frame (CLI.md, --jobs)."""

import os
import signal
import subprocess
import sys
import time

import pytest

from tests.support.cli import hear_ctrl_c

# two frames, each long enough to be caught in the middle of its making
BIG = "a = $U(" + ", ".join(f"@t({i * 0.7:g}, 0, 0) !sp(1, 0, 0)" for i in range(41)) + ");\n" \
      ">[T = 0, 1] @f(0.0005) a;\n"


def _session(sid: int) -> list[str]:
    """The processes of session ``sid``: what castor started and left behind."""
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as handle:
                fields = handle.read().rsplit(")", 1)[1].split()
            with open(f"/proc/{entry}/cmdline", "rb") as handle:
                command = handle.read().replace(b"\0", b" ").decode(errors="replace")
        except OSError:
            continue
        if int(fields[3]) == sid and fields[0] != "Z":  # fields[3]: the session
            found.append(f"{entry} {command[:80]}")
    return found


def _workers_started(sid: int, count: int, timeout: float = 30.0) -> None:
    deadline = time.monotonic() + timeout
    while len(_session(sid)) < count + 1:
        assert time.monotonic() < deadline, _session(sid)
        time.sleep(0.1)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
@pytest.mark.parametrize("signum, whom, status", [
    (signal.SIGINT, "group", 130),   # Ctrl-C in a terminal
    (signal.SIGINT, "main", 130),    # kill -INT PID
    (signal.SIGTERM, "main", 143),   # kill PID
    (signal.SIGTERM, "group", None),  # kill -- -PGID (each process ends by the signal)
], ids=["int-group", "int-main", "term-main", "term-group"])
def test_an_interrupt_ends_every_process_and_leaves_no_file(tmp_path, signum, whom, status):
    (tmp_path / "big.cas").write_text(BIG)
    castor = subprocess.Popen([sys.executable, "-m", "castor", "--jobs", "2", "-o", "big-%d.glb",
                               "big.cas"], cwd=tmp_path, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, start_new_session=True,
                              preexec_fn=hear_ctrl_c)
    try:
        _workers_started(castor.pid, 4)  # castor, the forkserver and two workers at least
        time.sleep(2)  # the workers are in the middle of their frames
        if whom == "group":
            os.killpg(castor.pid, signum)
        else:
            os.kill(castor.pid, signum)
        started = time.monotonic()
        # standard error reaches its end only when no process holds it open any more
        try:
            err = castor.communicate(timeout=10)[1].decode()
        except subprocess.TimeoutExpired:
            pytest.fail(f"still running 10 s after the signal: {_session(castor.pid)}")
        ended = time.monotonic() - started
        time.sleep(0.3)
        left = _session(castor.pid)
    finally:
        try:
            os.killpg(castor.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
    assert left == [], left
    assert ended < 3, f"{ended:.1f} s to end"
    if status is not None:
        assert castor.returncode == status, err
        assert err == "castor: interrupted\n"
    else:
        assert castor.returncode in (-signum, 128 + signum), err
        assert "Traceback" not in err and "leaked" not in err, err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["big.cas"]
