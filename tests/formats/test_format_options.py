"""A format with an option of its own is its module, its record and the option's
declaration (issue 28, item 1): the command line takes the option, warns of it for
other outputs, and the format's writer finds its value in ``WriteInfo.options``,
with nothing written for it in the command line, the settings, the jobs or the run."""

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

# castor with one more format, ".q" files of kind mesh, and its option --quality,
# added as a format's module would add them: one record, one declaration
WITH_FORMAT = """
import sys
from castor import formats, options
from castor.formats import Format, kinds

def write(frame, info):  # the one writer signature: (product, WriteInfo)
    yield f"quality {info.option('quality', 'none')}, {frame.polygon_count} polygons\\n".encode()

options.OUTPUT_OPTIONS += (options.OutputOption("--quality", "N", "how good", "q files",
                                                parse=int),)
formats.registry()["q"] = Format("q", (".q",), kinds.MESH, "a test format", write,
                                 options=("--quality",))
from castor import cli
sys.exit(cli.main(sys.argv[1:]))
"""


def _castor(*args, cwd):
    done = subprocess.run([sys.executable, "-c", WITH_FORMAT, *args], capture_output=True,
                          text=True, cwd=cwd, timeout=300,
                          env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert "Traceback" not in done.stderr, done.stderr
    return done.returncode, done.stderr


def test_a_format_s_own_option_reaches_its_writer(tmp_path):
    (tmp_path / "c.cas").write_text("> !cu(1, 0, 0);\n")
    status, err = _castor("--quality", "7", "-o", "x.q", "c.cas", cwd=tmp_path)
    assert status == 0 and err == "", err
    assert (tmp_path / "x.q").read_text() == "quality 7, 6 polygons\n"
    status, err = _castor("-o", "y.q", "c.cas", cwd=tmp_path)
    assert status == 0 and (tmp_path / "y.q").read_text() == "quality none, 6 polygons\n"


def test_a_format_s_own_option_is_warned_of_for_another_output(tmp_path):
    (tmp_path / "c.cas").write_text("> !cu(1, 0, 0);\n")
    status, err = _castor("--quality", "7", "-o", "x.off", "c.cas", cwd=tmp_path)
    assert status == 0
    assert err == ("castor: warning: --quality has no effect on off output (it acts on q); "
                   "it is ignored\n"), err
    # its parser's ValueError is a usage error, as for castor's own options
    status, err = _castor("--quality", "good", "-o", "x.q", "c.cas", cwd=tmp_path)
    assert status == 2 and err.startswith("castor: error: "), err
