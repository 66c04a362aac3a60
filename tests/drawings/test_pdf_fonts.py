"""Characters outside Helvetica's encoding in a PDF (a title 'Maison Œuvre — ĉ',
a room 'Séjour – Œil ĉ'): set in an embedded TrueType font that has them
(reportlab's Vera, DejaVu Sans where the system has it), read back with
poppler; a text within Helvetica's encoding stays Helvetica (the PDFs of today
keep their bytes); where no font has them, a warning names them."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys

import pytest

from tests.support.symbols import HOUSE, ROOT, castor

pytestmark = pytest.mark.skipif(shutil.which("pdftotext") is None, reason="poppler's pdftotext")

ROOM = HOUSE.replace('[space "Sejour"]', '[space "Séjour – Œil ĉ"]')
TITLE = "Maison Œuvre — ĉ"


def text_of(pdf, *pages) -> str:
    first = ["-f", str(pages[0]), "-l", str(pages[-1])] if pages else []
    return subprocess.run(["pdftotext", *first, str(pdf), "-"], capture_output=True, text=True,
                          check=True).stdout


def fonts_of(pdf) -> list[str]:
    out = subprocess.run(["pdffonts", str(pdf)], capture_output=True, text=True,
                         check=True).stdout
    return [line.split()[0].split("+")[-1] for line in out.splitlines()[2:]]


def has_dejavu() -> bool:
    from castor.formats._pdf_fonts import SYSTEM_FONTS

    return any(os.path.isfile(path) for path in SYSTEM_FONTS)


@pytest.mark.skipif(not has_dejavu(), reason="DejaVu Sans (Debian's fonts-dejavu-core)")
def test_a_title_and_a_room_outside_latin_1_are_printed(tmp_path):
    said = castor(tmp_path, ROOM, "--section", "z=1.2", "--title", TITLE, "-o", "d.pdf")
    assert said == ""
    text = text_of(tmp_path / "d.pdf")
    assert TITLE in text and "Séjour – Œil ĉ" in text and "■" not in text
    assert sorted(fonts_of(tmp_path / "d.pdf")) == ["DejaVuSans", "Helvetica"]


@pytest.mark.skipif(not has_dejavu(), reason="DejaVu Sans (Debian's fonts-dejavu-core)")
def test_a_sets_project_title_outside_latin_1_is_printed_on_its_index(tmp_path):
    (tmp_path / "r.toml").write_text('[project]\ntitle = "Œuvre ĉ"\n[[sheet]]\nnumber = "1"\n'
                                     'title = "Plan ŝ"\ndrawing = "plan z=1.2"\n')
    assert castor(tmp_path, HOUSE, "--sheets", "r.toml", "-o", "set.pdf") == ""
    index = text_of(tmp_path / "set.pdf", 1)
    assert "Œuvre ĉ" in index and "Plan ŝ" in index and "■" not in index
    assert "Plan ŝ" in text_of(tmp_path / "set.pdf", 2)


def test_text_within_helveticas_encoding_stays_helvetica(tmp_path):
    castor(tmp_path, HOUSE.replace('"Sejour"', '"Séjour – Œil"'), "--section", "z=1.2",
           "--title", "Maison Œuvre — €", "-o", "d.pdf")
    assert "Séjour – Œil" in text_of(tmp_path / "d.pdf")
    assert fonts_of(tmp_path / "d.pdf") == ["Helvetica"]


def without_system_fonts(tmp_path, *options) -> subprocess.CompletedProcess:
    """castor with no system font to embed: reportlab's Vera alone."""
    (tmp_path / "s.cas").write_text(ROOM)
    code = ("import sys, castor.formats._pdf_fonts as fonts\nfonts.SYSTEM_FONTS = ()\n"
            "from castor.cli import main\nsys.argv = ['castor', *sys.argv[1:]]\nmain()\n")
    env = dict(os.environ, PYTHONPATH=str(ROOT), SOURCE_DATE_EPOCH="1700000000")
    return subprocess.run([sys.executable, "-c", code, "s.cas", *options], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=300)


def test_characters_no_font_has_are_named_in_a_warning(tmp_path):
    done = without_system_fonts(tmp_path, "--section", "z=1.2", "--title", TITLE, "-o", "d.pdf")
    assert done.returncode == 0, done.stderr
    warnings = [line for line in done.stderr.splitlines() if "warning" in line]
    # the texts named (the title from the command line, the room's name from its annotation)
    assert warnings == ["s.cas:12:1: warning: no font the PDF can have has 'ĉ' (in 'Maison "
                        "Œuvre — ĉ', 'Séjour – Œil ĉ'): printed as a box "
                        "(castor embeds reportlab's Vera, or DejaVu Sans where the system has "
                        "it: Debian's fonts-dejavu-core)"]
    text = text_of(tmp_path / "d.pdf")
    assert "Maison Œuvre — ■" in text  # the rest of it printed


def test_reportlabs_vera_prints_what_it_has(tmp_path):
    done = without_system_fonts(tmp_path, "--section", "z=1.2", "--title", "Łódka Čačak Ş",
                                "-o", "d.pdf")
    assert done.returncode == 0, done.stderr
    assert "'Ł'" not in done.stderr and "'Č'" not in done.stderr  # only the room's ĉ
    assert "Łódka Čačak Ş" in text_of(tmp_path / "d.pdf")
    assert "BitstreamVeraSans-Roman" in fonts_of(tmp_path / "d.pdf")
