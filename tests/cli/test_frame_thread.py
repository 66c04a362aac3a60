"""--jobs 1's executor (castor.jobs.FrameThread, in place of a
ThreadPoolExecutor whose concurrent.futures imported logging and traceback at
every run): frames made in order on one thread of their own, a failure handed
to whoever asks for the result, callbacks called once done."""

import threading

import pytest

from castor.jobs import FrameThread


def test_frames_are_made_in_order_on_one_thread_of_their_own():
    frames = FrameThread()
    seen: list = []

    def made(number):
        seen.append((number, threading.current_thread().name))
        return number * 10

    futures = [frames.submit(made, n) for n in range(5)]
    assert [f.result() for f in futures] == [0, 10, 20, 30, 40]
    assert [n for n, _ in seen] == [0, 1, 2, 3, 4]
    assert {name for _, name in seen} == {"castor-frames_0"}
    assert list(frames.map(made, [7, 8])) == [70, 80]
    frames.shutdown(wait=True)
    with pytest.raises(RuntimeError):
        frames.submit(made, 9)


def test_a_failure_reaches_the_result_and_callbacks_run_once_done():
    frames = FrameThread()
    release = threading.Event()
    called: list = []

    def failing():
        release.wait(5)
        raise ValueError("no frame")

    future = frames.submit(failing)
    future.add_done_callback(lambda f: called.append(f.exception()))
    assert not future.done() and not called
    release.set()
    with pytest.raises(ValueError, match="no frame"):
        future.result()
    frames.shutdown(wait=True)
    assert future.done() and not future.cancelled()
    assert len(called) == 1 and isinstance(called[0], ValueError)
    late: list = []
    future.add_done_callback(late.append)  # done already: called at once
    assert late == [future]
