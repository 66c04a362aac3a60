"""Input that went through an external cpp keeps its files and lines.

After a line marker (``# 1 "h.cas"``) and a run of more than six blank lines,
castor's own preprocessor wrote a ``#line`` marker of its own that counted the
lines of standard input: ``cpp -C house.cas | castor`` (``-C`` keeps the
comments, and with them the class annotations) placed the frame at
``<stdin>:129`` and every message after the first long blank run at
``<stdin>``. Text whose only directives are line markers needs no second
pass: the reader follows the markers.
"""

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.support.cli import run_here

REPO = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("marker", ['# 1 "h.cas"', '# 1 "h.cas" 1 3', '#line 1 "h.cas"'])
@pytest.mark.parametrize("blank", [1, 8, 30])
def test_positions_after_blank_lines_follow_the_markers(marker, blank):
    text = marker + "\n" + "\n" * blank + "X = 1 +;\n"
    status, _, err = run_here("--check", "-", stdin=text)
    assert status == 1
    assert err.splitlines()[0] == f"h.cas:{blank + 1}:8: error: expected an expression, found ';'"


def test_a_frame_after_blank_lines_is_placed_in_its_file():
    text = '# 0 "h.cas"\n# 0 "<built-in>"\n# 1 "h.cas"\n' + "\n" * 12 + "> !cu(1, 1, 1);\n"
    status, out, err = run_here("-", stdin=text)
    assert (status, err) == (0, "")
    assert out.splitlines()[1] == "frame 1 h.cas:13"


@pytest.mark.skipif(shutil.which("cpp") is None, reason="no external cpp here")
def test_cpp_with_comments_kept_gives_what_castor_gives():
    """The README's word: 'cpp -C' keeps the class annotations, plain cpp drops them."""
    house = REPO / "examples" / "house.cas"

    def summary(command_input: bytes | None, *args) -> str:
        done = subprocess.run([sys.executable, "-m", "castor", "--summary", "/dev/stdout",
                               "-o", "/dev/null", *args], input=command_input,
                              capture_output=True, cwd=REPO / "examples", timeout=300)
        assert done.returncode == 0 and done.stderr == b"", done.stderr
        return done.stdout.decode()

    def cpp(*options) -> bytes:
        return subprocess.run(["cpp", *options, "house.cas"], capture_output=True, check=True,
                              cwd=house.parent).stdout

    own = summary(None, "house.cas")
    assert '"classes"' in own
    assert summary(cpp("-C"), "-") == own
    assert '"classes"' not in summary(cpp(), "-")  # the annotations went with the comments
