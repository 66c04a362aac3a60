"""The drawing register's index page and titles, read back: the index fits its
page whatever paper the register gives (none: as large as each drawing), and
shows the project's fields as the title blocks do (the register's, else the
command line's); a sheet's title is its SVG's and PDF's title; a TOML syntax
error is a usage error at its line and column, as the register's others."""

from __future__ import annotations

import re
import shutil
import subprocess
import xml.etree.ElementTree as ET

import pytest

from tests.support.symbols import HOUSE, castor

# no [project], no sheet key: each sheet as large as its drawing
BARE = """\
[[sheet]]
number = "A-101"
title = "Plan du rez"
drawing = "plan z=1.2"

[[sheet]]
number = "A-201"
drawing = "section x=3"
"""

needs_poppler = pytest.mark.skipif(shutil.which("pdftotext") is None,
                                   reason="poppler's pdftotext")


def words(pdf, page: int) -> tuple[tuple[float, float], list]:
    """The page's size (pt) and its words with their boxes (pdftotext -bbox)."""
    out = subprocess.run(["pdftotext", "-bbox", "-f", str(page), "-l", str(page), str(pdf), "-"],
                         capture_output=True, text=True, check=True).stdout
    size = re.search(r'<page width="([\d.]+)" height="([\d.]+)"', out)
    found = [(html_unescape(m[5]), *(float(m[k]) for k in range(1, 5))) for m in re.finditer(
        r'<word xMin="([\d.]+)" yMin="([\d.]+)" xMax="([\d.]+)" yMax="([\d.]+)">([^<]*)</word>',
        out)]
    return (float(size[1]), float(size[2])), found


def html_unescape(text: str) -> str:
    import html

    return html.unescape(text)


def page_text(pdf, page: int) -> str:
    return subprocess.run(["pdftotext", "-layout", "-f", str(page), "-l", str(page), str(pdf),
                           "-"], capture_output=True, text=True, check=True).stdout


@needs_poppler
def test_the_index_fits_its_page_when_the_register_gives_no_paper(tmp_path):
    (tmp_path / "r.toml").write_text(BARE)
    said = castor(tmp_path, HOUSE, "--sheets", "r.toml", "--revision", "Z", "--project", "Proj X",
                  "-o", "set.pdf")
    assert said == ""
    (width, height), found = words(tmp_path / "set.pdf", 1)
    # A4 landscape: the first sheet's page (240 x 170 mm) is too narrow for the table
    assert (width, height) == pytest.approx((841.89, 595.28), abs=0.01)
    texts = [w[0] for w in found]
    for header in ("Sheet", "Title", "Drawing", "Scale", "Paper", "Rev"):
        assert header in texts
    for text, x0, y0, x1, y1 in found:
        assert 0 <= x0 and x1 <= width - 20 * 72 / 25.4 + 0.5 and 0 <= y0 and y1 <= height, text
    # the project's fields as the title blocks show them: the command line's
    index = page_text(tmp_path / "set.pdf", 1)
    assert index.splitlines()[0].strip() == "Proj X"
    assert "Rev Z" in index
    rows = [line.split() for line in index.splitlines() if line.strip().startswith("A-")]
    assert [row[-1] for row in rows] == ["Z", "Z"]
    assert [row[-2] for row in rows] == ["-", "-"]  # no paper: as large as the drawing
    sheet = page_text(tmp_path / "set.pdf", 2)
    assert "Proj X" in sheet and "Rev Z" in sheet
    info = subprocess.run(["pdfinfo", str(tmp_path / "set.pdf")], capture_output=True,
                          text=True).stdout
    assert re.search(r"Title:\s+Proj X: drawing set", info)


@needs_poppler
def test_the_registers_project_comes_before_the_command_line_and_says_so(tmp_path):
    (tmp_path / "r.toml").write_text('[project]\ntitle = "Maison"\nrevision = "B"\nsheet = "A3"\n'
                                     + BARE.replace('drawing = "section x=3"',
                                                    'drawing = "section x=3"\nrevision = "C"'))
    said = castor(tmp_path, HOUSE, "--sheets", "r.toml", "--revision", "Z", "--project", "Proj X",
                  "--drawn", "MB", "-o", "set.pdf")
    assert sorted(said.splitlines()) == [
        f"castor: warning: --{name} has no effect where the register gives its own (r.toml); "
        "the register's is printed there" for name in ("project", "revision")]
    index = page_text(tmp_path / "set.pdf", 1)
    assert index.splitlines()[0].strip() == "Maison"
    assert re.search(r"Drawn MB\s+Rev B", index)
    rows = [line.split() for line in index.splitlines() if line.strip().startswith("A-")]
    assert [row[-2:] for row in rows] == [["A3", "B"], ["A3", "C"]]
    # A3 landscape, the sheets' own paper, holds the table
    (width, height), _ = words(tmp_path / "set.pdf", 1)
    assert (width, height) == pytest.approx((1190.55, 841.89), abs=0.01)
    assert "Rev C" in page_text(tmp_path / "set.pdf", 3)


@needs_poppler
def test_an_index_longer_than_its_page_goes_on_to_a_second(tmp_path):
    sheets = "".join(f'[[sheet]]\nnumber = "E-{k:02d}"\ndrawing = "elevation front"\n'
                     for k in range(1, 24))
    (tmp_path / "r.toml").write_text('[project]\nscale = "1:200"\n' + sheets)
    castor(tmp_path, HOUSE, "--sheets", "r.toml", "-o", "set.pdf")
    first, second = page_text(tmp_path / "set.pdf", 1), page_text(tmp_path / "set.pdf", 2)
    on_first = re.findall(r"E-\d\d", first)
    on_second = re.findall(r"E-\d\d", second)
    assert on_first + on_second == [f"E-{k:02d}" for k in range(1, 24)]
    assert len(on_first) == 20 and "continued, 21–23" in second
    info = subprocess.run(["pdfinfo", str(tmp_path / "set.pdf")], capture_output=True,
                          text=True).stdout
    assert "Pages:           25" in info


def test_a_register_sheets_title_is_its_svgs_title(tmp_path):
    (tmp_path / "r.toml").write_text(BARE)
    castor(tmp_path, HOUSE, "--sheets", "r.toml", "-o", "s-%d.svg")
    titles = [ET.fromstring((tmp_path / f"s-{k}.svg").read_bytes()).findtext(
        "{http://www.w3.org/2000/svg}title") for k in (1, 2)]
    # the first sheet's own title; the second has none: the object's name
    assert titles == ["Plan du rez: Plan z = 1.20, Rez ±0.00, 1:100",
                      "maison: Section x = 3.00, 1:100"]


@needs_poppler
def test_a_register_sheets_title_is_its_pdfs_title(tmp_path):
    (tmp_path / "r.toml").write_text(BARE)
    castor(tmp_path, HOUSE, "--sheets", "r.toml", "-o", "s-%d.pdf")
    info = subprocess.run(["pdfinfo", str(tmp_path / "s-1.pdf")], capture_output=True,
                          text=True).stdout
    assert re.search(r"Title:\s+Plan du rez: Plan z = 1.20", info)


@needs_poppler
def test_without_a_project_title_the_index_is_titled_as_the_scene_not_its_first_sheet(tmp_path):
    (tmp_path / "r.toml").write_text(BARE)
    castor(tmp_path, HOUSE, "--sheets", "r.toml", "-o", "set.pdf")
    assert page_text(tmp_path / "set.pdf", 1).splitlines()[0].strip() == "maison"
    info = subprocess.run(["pdfinfo", str(tmp_path / "set.pdf")], capture_output=True,
                          text=True).stdout
    assert re.search(r"Title:\s+maison: drawing set", info)


@pytest.mark.parametrize("text, message", [
    ('[[sheet]]\nnumber = "A-101\ndrawing = "plan z=1.2"\n',
     "r.toml:2:16: not valid TOML: illegal character '\\n' (is a string's closing quote "
     "missing?)"),
    ('[[sheet]\nnumber = "A"\n', "r.toml:1:8: not valid TOML: expected ']]' at the end of an "
     "array declaration"),
    ('[[sheet]]\nnumber = "A"\ndrawing = ', "r.toml:3:11: not valid TOML: invalid value"),
])
def test_a_toml_syntax_error_is_a_usage_error_at_its_line_and_column(tmp_path, text, message):
    (tmp_path / "r.toml").write_text(text)
    said = castor(tmp_path, HOUSE, "--sheets", "r.toml", "-o", "set.pdf", status=2)
    assert said.splitlines()[0] == f"castor: error: {message}"
    assert not (tmp_path / "set.pdf").exists()


def test_a_field_the_register_gives_alike_is_no_warning(tmp_path):
    (tmp_path / "r.toml").write_text('[project]\ntitle = "Maison"\nrevision = "B"\n' + BARE)
    said = castor(tmp_path, HOUSE, "--sheets", "r.toml", "--revision", "B", "--project", "Maison",
                  "--number", "7", "-o", "s-%d.svg")
    assert said == ""
    said = castor(tmp_path, HOUSE, "--sheets", "r.toml", "--revision", "C", "-o", "s-%d.svg")
    assert said.splitlines() == ["castor: warning: --revision has no effect where the register "
                                 "gives its own (r.toml); the register's is printed there"]


def test_a_title_the_register_gives_a_sheet_is_warned_of(tmp_path):
    # --title stands on the sheets without a title of their own, the
    # register's on the others: said, as for the other fields
    (tmp_path / "r.toml").write_text(BARE)
    said = castor(tmp_path, HOUSE, "--sheets", "r.toml", "--title", "X", "-o", "s-%d.svg")
    assert said.splitlines() == ["castor: warning: --title has no effect on the sheets the "
                                 "register gives a title (r.toml); the register's is printed there"]
    titles = [ET.parse(tmp_path / f"s-{n}.svg").getroot().find("{http://www.w3.org/2000/svg}title")
              .text for n in (1, 2)]
    assert titles[0].startswith("Plan du rez") and titles[1].startswith("X")
    (tmp_path / "r.toml").write_text(BARE.replace('title = "Plan du rez"\n', ""))
    assert castor(tmp_path, HOUSE, "--sheets", "r.toml", "--title", "X", "-o", "s-%d.svg") == ""


def test_a_register_saved_with_a_byte_order_mark_is_read(tmp_path):
    # Notepad's UTF-8 starts with a BOM: skipped, as in scene files (tomllib
    # called it "invalid statement" at 1:1)
    (tmp_path / "r.toml").write_bytes(b"\xef\xbb\xbf" + BARE.encode())
    assert castor(tmp_path, HOUSE, "--sheets", "r.toml", "-o", "s-%d.svg") == ""
    assert (tmp_path / "s-1.svg").exists() and (tmp_path / "s-2.svg").exists()
