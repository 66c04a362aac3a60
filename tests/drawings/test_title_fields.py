"""The title block's project fields (CLI.md: --project, --number, --revision,
--drawn, --checked), markup characters and all, in SVG, PDF and DXF."""

from __future__ import annotations

import shutil
import subprocess
import xml.etree.ElementTree as ET

import pytest

from tests.support.symbols import HOUSE, SVG, castor

FIELDS = ("--project", "Maison <Dupont> & fils", "--number", "2026-014", "--revision", "B",
          "--drawn", "MB", "--checked", 'P"M')


def test_the_fields_are_in_the_title_block(tmp_path):
    castor(tmp_path, HOUSE, "--section", "z=1.2", "--sheet", "A3", *FIELDS, "-o", "d.svg")
    root = ET.fromstring((tmp_path / "d.svg").read_bytes())  # markup escaped: it parses
    sheet = ["".join(t.itertext()) for t in root.find(f"{SVG}g[@id='sheet']").iter(SVG + "text")]
    for text in ("Maison <Dupont> & fils", "2026-014", "Rev B", "Drawn MB", 'Checked P"M'):
        assert text in sheet


def test_without_fields_the_title_block_is_as_before(tmp_path):
    castor(tmp_path, HOUSE, "--section", "z=1.2", "-o", "d.svg")
    root = ET.fromstring((tmp_path / "d.svg").read_bytes())
    sheet = ["".join(t.itertext()) for t in root.find(f"{SVG}g[@id='sheet']").iter(SVG + "text")]
    assert not any(t.startswith(("Rev", "Drawn", "Checked")) for t in sheet)


def test_the_fields_in_dxf_and_pdf(tmp_path):
    import ezdxf

    castor(tmp_path, HOUSE, "--section", "z=1.2", *FIELDS, "-o", "d.dxf")
    texts = [t.dxf.text for t in ezdxf.readfile(tmp_path / "d.dxf").modelspace().query("TEXT")]
    assert "Maison <Dupont> & fils" in texts and 'Checked P"M' in texts
    if shutil.which("pdftotext"):
        castor(tmp_path, HOUSE, "--section", "z=1.2", *FIELDS, "-o", "d.pdf")
        text = subprocess.run(["pdftotext", str(tmp_path / "d.pdf"), "-"], capture_output=True,
                              text=True).stdout
        assert "Maison <Dupont> & fils" in text and "2026-014" in text


def test_a_field_for_a_picture_is_warned_about(tmp_path):
    said = castor(tmp_path, "> @h(1, 1, 1) !cu(1, 0, 0);\n", "--project", "X", "--size", "8x8",
                  "-o", "d.png")
    assert "--project" in said


@pytest.mark.parametrize("field", ["--drawn", "--project"])
def test_a_field_with_control_characters_gives_a_whole_file(tmp_path, field):
    castor(tmp_path, HOUSE, "--section", "z=1.2", field, "a\x01b\x1b[0m", "-o", "d.svg")
    ET.fromstring((tmp_path / "d.svg").read_bytes())
