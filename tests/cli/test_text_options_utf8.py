"""An option's text that is not UTF-8 is a usage error showing the byte.

``castor --title $'Caf\\xe9' -o t.ifc maison.cas`` (a Latin-1 terminal's 'é')
said "frame 1 could not be made: an internal error" (the IFC library refused
the text), and the SVG, PDF and DXF writers dropped the byte without a word;
``--set $'H=2\\xe9'`` showed Python's surrogate escape, ``H=2\\udce9``. Every
option's text (all but the paths) is now checked as the command line is read:
exit status 2, the byte shown as 0xe9, nothing written.
"""

import subprocess
import sys

import pytest

from castor.cli import _parser
from tests.support.cli import run_here

CUBE = "> !cu(1, 1, 1);\n"
TYPED = {"--format", "--max-polygons", "--tolerance"}
PATHS = {"files", "output", "summary", "include_dirs", "parameter_file", "sheets"}


def text_options() -> list[str]:
    """Every option that takes a value which is not a path, by its long name."""
    return sorted(max(action.option_strings, key=len) for action in _parser()._actions
                  if action.option_strings and action.dest not in PATHS
                  and action.nargs != 0 and action.dest not in ("help", "version"))


def test_the_text_options_are_the_ones_a_user_meets():
    found = text_options()
    for option in ("--title", "--project", "--number", "--revision", "--drawn", "--checked",
                   "--set", "-D", "-U", "-P", "--ifc-class", "--size", "--view", "--section"):
        assert option in found


@pytest.mark.parametrize("option", text_options())
def test_a_byte_that_is_not_utf8_is_a_usage_error(tmp_path, monkeypatch, option):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "maison.cas").write_text(CUBE)
    status, out, err = run_here(option, "Caf\udce9", "-o", "t.svg", "maison.cas")
    assert (status, out) == (2, "")
    if option in TYPED:  # argparse's own check comes first: not a number, not a format
        assert err.startswith(f"castor: error: argument ") and "'Caf<0xe9>'" in err, err
    else:
        assert err == (f"castor: error: {option}: byte 0xe9 after 'Caf' is not UTF-8; castor "
                       f"takes UTF-8 text, such as 'Café' if it was Latin-1\ntry 'castor --help'\n")
    assert "\udce9" not in err and "udce9" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["maison.cas"]


def test_a_set_shows_the_byte_not_the_surrogate(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "maison.cas").write_text("H = 1;\n" + CUBE)
    status, _, err = run_here("--set", "H=2\udce9", "--check", "maison.cas")
    assert status == 2
    assert err.splitlines()[0] == ("castor: error: --set: byte 0xe9 after 'H=2' is not UTF-8; "
                                   "castor takes UTF-8 text, such as 'H=2é' if it was Latin-1")
    assert "udce9" not in err


@pytest.mark.parametrize("output", ["t.ifc", "t.svg"])
def test_a_title_in_latin1_from_the_shell(tmp_path, output):
    """The bytes as a shell passes them, through the real argv."""
    (tmp_path / "maison.cas").write_text(CUBE)
    done = subprocess.run([sys.executable, "-m", "castor", b"--title", b"Caf\xe9",
                           "--section", "z=0.5", "-o", output, "maison.cas"], cwd=tmp_path,
                          capture_output=True, timeout=120)
    err = done.stderr.decode()
    assert done.returncode == 2, err
    assert err.startswith("castor: error: --title: byte 0xe9 after 'Caf' is not UTF-8")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["maison.cas"]


def test_a_title_in_utf8_is_written(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "maison.cas").write_text(CUBE)
    status, _, err = run_here("--title", "Café", "--section", "z=0.5", "-o", "t.svg",
                              "maison.cas")
    assert (status, err) == (0, "")
    assert "Café" in (tmp_path / "t.svg").read_text(encoding="utf-8")
