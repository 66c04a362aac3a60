"""The drawing register (CLI.md, --sheets): one PDF with an index and a page
per sheet, one DXF with a paper-space layout per sheet and a viewport at its
scale, a file per sheet for a %d pattern; plans with the set's marks; a
register's mistakes are usage errors naming their line."""

from __future__ import annotations

import shutil
import subprocess
import xml.etree.ElementTree as ET

import pytest

from tests.support.symbols import HOUSE, SVG, castor

REGISTER = """\
[project]
title = "Maison <Dupont>"
number = "2026-014"
drawn = "MB"
checked = "PM"
revision = "B"
sheet = "A3"
scale = "1:50"

[[sheet]]
number = "A-101"
title = "Plan du rez-de-chaussée"
drawing = "plan z=1.2"

[[sheet]]
number = "A-201"
title = "Coupe"
drawing = "section x=3"
scale = "1:100"

[[sheet]]
number = "A-301"
drawing = "elevation front"
"""


def with_register(tmp_path, text=REGISTER, *options, status=0):
    (tmp_path / "r.toml").write_text(text)
    return castor(tmp_path, HOUSE, "--sheets", "r.toml", *options, status=status)


@pytest.mark.skipif(shutil.which("pdftotext") is None, reason="poppler's pdftotext")
def test_one_pdf_an_index_then_a_page_per_sheet(tmp_path):
    with_register(tmp_path, REGISTER, "-o", "set.pdf")
    info = subprocess.run(["pdfinfo", str(tmp_path / "set.pdf")], capture_output=True,
                          text=True).stdout
    assert "Pages:           4" in info
    pages = [subprocess.run(["pdftotext", "-f", str(k), "-l", str(k), str(tmp_path / "set.pdf"),
                             "-"], capture_output=True, text=True).stdout for k in range(1, 5)]
    index = pages[0]
    for text in ("Maison <Dupont>", "A-101", "Plan du rez-de-chaussée", "A-201", "1:100", "A-301"):
        assert text in index
    assert "Plan du rez-de-chaussée" in pages[1] and "Sheet A-101" in pages[1]
    assert "Section x = 3.00" in pages[2] and "Rev B" in pages[2]
    assert "Elevation front" in pages[3]
    # the plan carries the section's and the elevation's marks
    assert "A-201" in pages[1] and "A-301" in pages[1]


def test_one_dxf_a_layout_per_sheet_with_a_viewport_at_its_scale(tmp_path):
    import ezdxf

    with_register(tmp_path, REGISTER, "-o", "set.dxf")
    doc = ezdxf.readfile(tmp_path / "set.dxf")
    assert not doc.audit().has_errors
    names = [layout.name for layout in doc.layouts if layout.name != "Model"]
    assert names == ["A-101", "A-201", "A-301"]
    for name, scale in (("A-101", 50), ("A-201", 100), ("A-301", 50)):
        layout = doc.layouts.get(name)
        viewports = [v for v in layout.query("VIEWPORT") if v.dxf.status != 1]
        assert len(viewports) == 1
        vp = viewports[0]
        # paper mm over model metres: 1000 / N
        assert vp.dxf.height / vp.dxf.view_height == pytest.approx(1000 / scale)
        # the title block is in paper space, in millimetres
        texts = [t.dxf.text for t in layout.query("TEXT")]
        assert f"Sheet {name}" in texts
        assert all(0 <= t.dxf.insert.x <= 420 for t in layout.query("TEXT"))
    # the drawings are in model space in metres, each with its dimensions
    assert doc.header["$INSUNITS"] == 6
    assert len(doc.modelspace().query("DIMENSION")) > 10


def test_a_pattern_gives_a_file_per_sheet(tmp_path):
    with_register(tmp_path, REGISTER, "-o", "sheet-%d.svg")
    titles = []
    for k in (1, 2, 3):
        root = ET.fromstring((tmp_path / f"sheet-{k}.svg").read_bytes())
        titles.append("".join(root.find(SVG + "title").itertext()))
    assert "Plan z = 1.20" in titles[0] and "Section x = 3.00" in titles[1]
    assert "Elevation front" in titles[2]
    assert not (tmp_path / "sheet-4.svg").exists()


def test_an_svg_without_a_pattern_is_a_usage_error(tmp_path):
    said = with_register(tmp_path, REGISTER, "-o", "set.svg", status=2)
    assert "-o sheet-%d.svg" in said


@pytest.mark.parametrize("change, line, words", [
    (("scale = \"1:100\"", "scal = \"1:100\""), 19, "unknown key 'scal'"),
    (("drawing = \"section x=3\"", "drawing = \"cut x=3\""), 18, "unknown drawing 'cut x=3'"),
    (("sheet = \"A3\"", "sheet = \"B5\""), 7, "unknown sheet size 'B5'"),
    (("drawn = \"MB\"", "author = \"MB\""), 4, "unknown key 'author' in [project]"),
    (("drawing = \"plan z=1.2\"", "drawing = \"plan x=1.2\""), 13, "unknown drawing"),
])
def test_a_register_mistake_is_a_usage_error_at_its_line(tmp_path, change, line, words):
    said = with_register(tmp_path, REGISTER.replace(*change), "-o", "set.pdf", status=2)
    assert f"r.toml:{line}:" in said and words in said
    assert not (tmp_path / "set.pdf").exists()


def test_a_sheet_that_does_not_fit_names_its_line_and_the_scale_that_fits(tmp_path):
    text = REGISTER.replace('scale = "1:100"', 'scale = "1:20"\nsheet = "A4"')
    said = with_register(tmp_path, text, "-o", "set.pdf", status=1)
    assert "r.toml:15:1: error: sheet A-201" in said
    assert "the largest scale that fits is 1:50: scale = \"1:50\"" in said
    assert not (tmp_path / "set.pdf").exists()
