"""The process the user started waits while a child makes the run (``--jobs 1``).

The engine (manifold3d) keeps Python's interpreter lock for the whole of one
boolean, which takes tens of seconds in a large scene: while it runs, no other
thread of the process runs, not even Python's handler of Ctrl-C, which waits
for the boolean to end. So a run that makes its frames in its own process
forks first: the child makes the run, SIGINT and SIGTERM ignored, and this
process waits, its interpreter free. On Ctrl-C or SIGTERM it kills the child
at once (a frame's work cannot be stopped more gently), removes the files the
child was writing (the child tells their names through a pipe before it makes
each, castor.formats.output.tell_temporaries), says ``castor: interrupted``
and exits 130 or 143. Otherwise it ends as the child did: with its status, or
killed by the same signal (SIGPIPE, when the reader of standard output went).
A child whose parent is killed outright ends too (castor.jobs.end_with_parent).
"""

from __future__ import annotations

import os
import signal
import sys

_STOPS = (signal.SIGINT, signal.SIGTERM)


def supervise() -> bool:
    """Fork: in the child, which makes the run, True; where there is no fork,
    False (the run is made here, as before). This process waits for the child
    and ends as it ends: the call never returns in it."""
    if not hasattr(os, "fork"):
        return False
    for stream in (sys.stdout, sys.stderr):  # else both processes would write it
        try:
            stream.flush()
        except (OSError, ValueError, AttributeError):  # (None: started closed)
            pass
    reading, writing = map(_above_standard, os.pipe())
    # a signal that comes before each process has its own handlers waits for them
    signal.pthread_sigmask(signal.SIG_BLOCK, _STOPS)
    parent = os.getpid()
    try:
        child = os.fork()
    except OSError:
        signal.pthread_sigmask(signal.SIG_UNBLOCK, _STOPS)
        os.close(reading)
        os.close(writing)
        return False
    if child == 0:
        os.close(reading)
        _become_child(parent, writing)
        return True
    os.close(writing)
    _wait(child, reading)


def _become_child(parent: int, writing: int) -> None:
    from castor.formats.output import tell_temporaries
    from castor.jobs import end_with_parent

    for signum in _STOPS:  # the waiting process stops the run: it kills this one
        signal.signal(signum, signal.SIG_IGN)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, _STOPS)  # one that came is dropped
    end_with_parent()
    if os.getppid() != parent:  # it ended before this process could follow it
        os._exit(1)
    tell_temporaries(writing)


def _wait(child: int, reading: int) -> None:
    """Wait for the child; end this process as it ended, or as interrupted."""
    import select

    came: list[int] = []
    wake_reading, wake_writing = map(_above_standard, os.pipe())
    os.set_blocking(wake_writing, False)
    signal.set_wakeup_fd(wake_writing)  # a signal wakes the select below
    for signum in _STOPS:  # (started with Ctrl-C ignored, as a background job: kept so)
        if signum != signal.SIGINT or signal.getsignal(signum) is not signal.SIG_IGN:
            signal.signal(signum, lambda number, frame: came.append(number))
    _leave_standard_streams()
    signal.pthread_sigmask(signal.SIG_UNBLOCK, _STOPS)
    written: set[bytes] = set()
    told = bytearray()
    while not came:
        ready = select.select([reading, wake_reading], [], [])[0]
        if wake_reading in ready:
            os.read(wake_reading, 64)
        if reading in ready and not came:
            piece = os.read(reading, 65536)
            if not piece:  # the child has ended: every descriptor of it closed
                break
            _follow(told, piece, written)
    if came:
        _interrupted(came[0], child, reading, told, written)
    _, status = os.waitpid(child, 0)
    _end_as(status)


def _follow(told: bytearray, piece: bytes, written: set[bytes]) -> None:
    """Take in the child's news: ``+NAME\\0`` a file it is about to make,
    ``-NAME\\0`` one it has renamed into place or removed."""
    told += piece
    *complete, rest = bytes(told).split(b"\0")
    told[:] = rest
    for item in complete:
        if item[:1] == b"+":
            written.add(item[1:])
        else:
            written.discard(item[1:])


def _interrupted(signum: int, child: int, reading: int, told: bytearray,
                 written: set[bytes]) -> None:
    """Ctrl-C or SIGTERM: the child killed, its files removed, one line, the exit."""
    signal.pthread_sigmask(signal.SIG_BLOCK, _STOPS)  # a second Ctrl-C changes nothing
    try:
        os.kill(child, signal.SIGKILL)
        os.waitpid(child, 0)
    except OSError:
        pass
    os.set_blocking(reading, False)
    while True:  # what the child said before it was killed
        try:
            piece = os.read(reading, 65536)
        except OSError:
            break
        if not piece:
            break
        _follow(told, piece, written)
    for path in written:
        try:
            os.unlink(path)
        except OSError:
            pass
    try:  # on a terminal, over the line of a frame's progress
        os.write(2, (b"\r\033[K" if os.isatty(2) else b"") + b"castor: interrupted\n")
    except OSError:
        pass
    os._exit(128 + signum)


def _above_standard(fd: int) -> int:
    """``fd``, or a copy of it above 2 where castor was started with standard
    input, output or error closed ('>&-'), which a new pipe then takes."""
    if fd > 2:
        return fd
    import fcntl

    copy = fcntl.fcntl(fd, fcntl.F_DUPFD_CLOEXEC, 3)
    os.close(fd)
    return copy


def _leave_standard_streams() -> None:
    """Standard input and output are the child's: a reader of castor's output
    sees its end when the child's is closed."""
    try:
        null = os.open(os.devnull, os.O_RDWR)
    except OSError:
        return
    for fd in (0, 1):
        try:
            os.dup2(null, fd)
        except OSError:
            pass
    os.close(null)


def _end_as(status: int) -> None:
    """End with the child's exit status, or by the signal that ended it."""
    if os.WIFSIGNALED(status):
        signum = os.WTERMSIG(status)
        try:
            signal.signal(signum, signal.SIG_DFL)  # SIGKILL has no handler to reset
        except (OSError, ValueError):
            pass
        signal.pthread_sigmask(signal.SIG_UNBLOCK, [signum])
        os.kill(os.getpid(), signum)
        os._exit(128 + signum)  # were it still to come
    os._exit(os.waitstatus_to_exitcode(status))
