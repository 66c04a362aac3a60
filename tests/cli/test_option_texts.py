"""Hypothesis over the command-line options' texts: no traceback, no hang, exit 0, 1 or 2.

The option parsers run in-process (fast, many examples), each on a thread with a
time limit; a few hundred whole runs of ``castor`` check the same end to end.
"""

import contextlib
import io
import subprocess
import sys
import tempfile
import threading

from hypothesis import HealthCheck, given, settings, strategies as st

# text that looks like what people type into options, and some that does not
PIECES = st.sampled_from([
    "X", "=", "2", "-", ",", ";", "//", "/*", "*/", "(", ")", " ", "1e308", "1e999", "nan",
    "inf", "x", "%d", "%", "%%", "%03d", ".stl", ".png", "/", "1:", ":", "z", "top", "none",
    "#", "\\", "\n", "\t", "é", "\x00", "0", "-1", "99999999999999999999", "^", "sin(",
    "PI", "a", "A", "1.5", "'", '"', "$", "[", "]",
])
TEXT = st.one_of(st.text(max_size=30), st.lists(PIECES, max_size=12).map("".join))
OPTIONS = ["--set", "-D", "-U", "-I", "-o", "--size", "--view", "--eye", "--look", "--sun",
           "--samples", "--section", "--scale", "--jobs", "--port", "--tolerance",
           "--max-polygons", "--summary", "-f", "--sheet", "--title"]


def _within(seconds, function, *args):
    """Run ``function`` on a thread; its outcome, or fail if it does not end in time."""
    outcome = []

    def work():
        try:
            outcome.append(("value", function(*args)))
        except BaseException as exc:  # judged by the caller
            outcome.append(("raised", exc))

    thread = threading.Thread(target=work, daemon=True)
    thread.start()
    thread.join(seconds)
    assert not thread.is_alive(), f"hangs on {args!r}"
    return outcome[0]


def _parse(argv):
    from castor import cli

    with contextlib.redirect_stderr(io.StringIO()), contextlib.redirect_stdout(io.StringIO()):
        parser, args = cli._arguments(argv)
        return cli._overrides(parser, args.sets)


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(option=st.sampled_from(OPTIONS), text=TEXT)
def test_option_texts_parse_or_give_a_usage_error(option, text):
    kind, result = _within(10, _parse, [option, text, "--check"])
    if kind == "raised":
        assert isinstance(result, SystemExit) and result.code in (0, 2), repr(result)


def cpp_or_not(option):
    """The preprocessor's options need it; the others run without (faster)."""
    return [] if option in ("-D", "-U", "-I") else ["--no-cpp"]


@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(option=st.sampled_from(OPTIONS), text=TEXT)
def test_whole_runs_end_with_a_known_status(option, text):
    if "\x00" in text:
        text = text.replace("\x00", "")  # the system refuses NUL in arguments
    with tempfile.TemporaryDirectory() as directory:
        result = subprocess.run(
            [sys.executable, "-m", "castor", *cpp_or_not(option), option, text],
            input="X = 1;\n> @h(X, 1, 1) !cu(1, 1, 1);\n", capture_output=True, text=True,
            timeout=60, cwd=directory)
    assert result.returncode in (0, 1, 2), result.stderr
    assert "Traceback" not in result.stderr and "internal error" not in result.stderr, \
        result.stderr
