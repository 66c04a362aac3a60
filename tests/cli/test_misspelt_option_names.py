"""A misspelt option is named alone, never the scene file beside it.

``castor --sectoin z=1.2 -o a.svg maison.cas`` said ``unrecognized arguments:
--sectoin maison.cas``, as if the scene were at fault: argparse had taken
``z=1.2`` for the file and ``maison.cas`` for an extra. And a scene file after
an option (``castor a.cas -o x.stl b.cas``) was refused the same way; files
are taken wherever they stand, as cpp takes them.
"""

import pytest

from tests.support.cli import run_here

CUBE = "> !cu(1, 1, 1);\n"


@pytest.mark.parametrize("args, named", [
    (["--sectoin", "z=1.2", "-o", "a.svg", "maison.cas"],
     "unrecognized arguments: --sectoin (did you mean --section?)"),
    (["--check", "maison.cas", "--sectoin=z=1.2"],
     "unrecognized arguments: --sectoin=z=1.2 (did you mean --section?)"),
    (["--xyzzy", "--check", "maison.cas", "autre.cas"],
     "unrecognized arguments: --xyzzy"),
    (["--check", "maison.cas", "-Z", "autre.cas"], "unrecognized arguments: -Z"),
], ids=["value-taken-for-the-file", "after-the-file", "before-two-files", "short"])
def test_only_the_unknown_option_is_named(tmp_path, monkeypatch, args, named):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "maison.cas").write_text(CUBE)
    (tmp_path / "autre.cas").write_text(CUBE)
    status, out, err = run_here(*args)
    assert (status, out) == (2, "")
    assert err == f"castor: error: {named}\ntry 'castor --help'\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["autre.cas", "maison.cas"]


def test_scene_files_after_the_options_are_read_in_order(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "a.cas").write_text("L = 2;\n")
    (tmp_path / "b.cas").write_text("> @h(L, 1, 1) !cu(1, 1, 1);\n")
    (tmp_path / "-c.cas").write_text("Q = 1;\n")
    status, out, err = run_here("a.cas", "-o", "x.off", "b.cas", "--", "-c.cas")
    assert (status, out, err) == (0, "", "")
    written = (tmp_path / "x.off").read_text()
    assert written.startswith("OFF") and " 2 " in written  # b.cas saw a.cas's L
    assert run_here("--check", "a.cas", "--", "-c.cas", "b.cas") == (0, "", "")


@pytest.mark.parametrize("args, named", [
    (["--sizee", "10x10", "-o", "x.png", "a.off"], "--sizee"),
    (["a.off", "--wirre"], "--wirre"),
    (["-o", "x.png", "a.off", "b.off"], "b.off"),  # one file: a second is still named
])
def test_castor_view_names_the_unknown_option_alone(tmp_path, monkeypatch, capsys, args, named):
    from castor.view.cli import main

    monkeypatch.chdir(tmp_path)
    with pytest.raises(SystemExit) as stop:
        main(args)
    assert stop.value.code == 2
    assert capsys.readouterr().err.splitlines()[0] == \
        f"castor-view: error: unrecognized arguments: {named}"
