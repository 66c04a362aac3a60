"""--section, --view, --scale and --sheet beside --sheets: the register says
every sheet's drawing, scale and paper, so each of them is warned about once,
by name (CLI.md: an option without effect is warned about), and ignored."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import pytest

from tests.support.symbols import HOUSE, castor, register

REGISTER = register(("A-101", "plan z=1.2"), ("A-201", "section x=3"))


def message(option: str) -> str:
    return (f"castor: warning: {option} has no effect with --sheets (each sheet's drawing, "
            "scale and paper are the register's); it is ignored")


@pytest.mark.parametrize("option, value", [("--section", "y=2"), ("--view", "top"),
                                           ("--scale", "1:20"), ("--sheet", "A1")])
def test_an_option_the_register_overrides_is_warned_about_by_name(tmp_path, option, value):
    (tmp_path / "r.toml").write_text(REGISTER)
    said = castor(tmp_path, HOUSE, "--sheets", "r.toml", option, value, "-o", "s-%d.svg")
    assert said.splitlines() == [message(option)]
    # and ignored: the register's two sheets, its paper and scale
    for k, what in ((1, "Plan z = 1.20"), (2, "Section x = 3.00")):
        root = ET.fromstring((tmp_path / f"s-{k}.svg").read_bytes())
        assert root.get("width") == "420mm" and root.get("height") == "297mm"
        assert what in root.findtext("{http://www.w3.org/2000/svg}title")
        assert "1:50" in root.findtext("{http://www.w3.org/2000/svg}title")
    assert not (tmp_path / "s-3.svg").exists()


def test_all_four_each_once_and_none_without_them(tmp_path):
    (tmp_path / "r.toml").write_text(REGISTER)
    said = castor(tmp_path, HOUSE, "--sheets", "r.toml", "--sheet", "A1", "--scale", "1:20",
                  "--view", "top", "--section", "z=1", "-o", "s.pdf")
    assert sorted(said.splitlines()) == sorted(message(o) for o in
                                               ("--section", "--view", "--scale", "--sheet"))
    # the title block's fields are not the register's to override: no warning
    said = castor(tmp_path, HOUSE, "--sheets", "r.toml", "--project", "P", "-o", "s.pdf")
    assert said == ""
