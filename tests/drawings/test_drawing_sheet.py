"""Drawings as an office sends them out: pens, dimensions, levels, the sheet
and its title block, PDF. A box house with known numbers, measured by hand."""

from __future__ import annotations

import re
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from tests.support.cli import run
from tests.support.drawings import Drawn, SVG

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

# 10 x 8 m, walls 0.3 m thick and 3 m high; in the south wall (y = 0) a door
# 1.0 m wide at x = 4.5 .. 5.5 (head 2.10) and two windows 1.2 m wide at
# x = 1.5 and x = 7.3 (sills 0.90, heads 2.10)
BOX_HOUSE = """
plein = @h(10, 8, 3) !cu(0.9, 0.9, 0.8);
dedans = @t(0.3, 0.3, -1) @h(9.4, 7.4, 5) !cu(0.9, 0.9, 0.8);
porte = @t(4.5, -0.1, -0.1) @h(1, 0.5, 2.2) !cu(0.2, 0.4, 0.8);
f1 = @t(1.5, -0.1, 0.9) @h(1.2, 0.5, 1.2) !cu(0.2, 0.4, 0.8);
f2 = @t(7.3, -0.1, 0.9) @h(1.2, 0.5, 1.2) !cu(0.2, 0.4, 0.8);
maison = $D(plein, $U(dedans, porte, f1, f2));
> maison;
"""
# the south wall's breaks by hand: wall 0..1.5, window ..2.7, wall ..4.5, door
# ..5.5, wall ..7.3, window ..8.5, wall ..10
SOUTH_CHAIN = [1.5, 1.2, 1.8, 1.0, 1.8, 1.2, 1.5]
DAY = "2023-11-14"  # SOURCE_DATE_EPOCH 1700000000


@pytest.fixture(autouse=True)
def fixed_date(monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")


def _draw(tmp_path, *options, name="d.svg", scene=BOX_HOUSE, status=0):
    (tmp_path / "s.cas").write_text(scene)
    out = tmp_path / name
    code, _, err = run(*options, "-o", str(out), str(tmp_path / "s.cas"))
    assert code == status, err
    return out, err


def test_plan_dimensions_in_dxf_measure_the_breaks(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    out, _ = _draw(tmp_path, "--section", "z=1.2", name="p.dxf")
    doc = ezdxf.readfile(out)
    assert not doc.audit().has_errors
    dims = list(doc.modelspace().query("DIMENSION"))
    assert dims and all(d.dxf.layer == "dimensions" for d in dims)
    # horizontal along the bottom (south): the chain and the overall
    south = sorted((d for d in dims if d.dxf.angle == 0 and d.dxf.defpoint.y < 0),
                   key=lambda d: (d.dxf.defpoint.y, min(d.dxf.defpoint2.x, d.dxf.defpoint3.x)))
    measured = [round(d.get_measurement(), 9) for d in south]
    assert [round(d.dxf.actual_measurement, 9) for d in south] == measured  # written too
    overall, chain = measured[0], measured[1:]  # the overall lies farther out
    assert overall == 10.0
    assert chain == SOUTH_CHAIN
    # the chain's definition points are on the wall's outer face, at the breaks
    xs = sorted({round(p.x, 9) for d in south[1:] for p in (d.dxf.defpoint2, d.dxf.defpoint3)})
    assert xs == [0, 1.5, 2.7, 4.5, 5.5, 7.3, 8.5, 10]
    assert all(abs(d.dxf.defpoint2.y) < 1e-9 for d in south[1:])
    # the other sides: walls without openings, only the overall
    all_measured = sorted(round(d.get_measurement(), 9) for d in dims)
    assert all_measured == sorted(SOUTH_CHAIN + [10.0, 10.0, 8.0, 8.0])
    assert doc.dimstyles.get("CASTOR").dxf.dimdec == 2


def test_plan_svg_shows_the_same_values(tmp_path):
    out, _ = _draw(tmp_path, "--section", "z=1.2")
    drawn = Drawn(out.read_bytes(), 100)
    texts = drawn.texts["dimensions"]
    assert sorted(texts) == sorted(f"{v:.2f}" for v in SOUTH_CHAIN + [10, 10, 8, 8])
    assert "1.00" in texts and "10.00" in texts  # metres, two decimals


def _text_boxes(root, group: str):
    """Each text's box on paper (x0, y0, x1, y1), from its anchor and width."""
    from castor.drawings.sheet import text_width

    boxes = []
    for t in root.find(f"{SVG}g[@id='{group}']").iter(SVG + "text"):
        x, y, size = float(t.get("x")), float(t.get("y")), float(t.get("font-size"))
        w = text_width(t.text, size)
        start = {"middle": x - w / 2, "end": x - w}.get(t.get("text-anchor"), x)
        if t.get("transform"):  # turned to read from the right: along paper y
            boxes.append((x - 0.75 * size, start + (y - x) - (start - x) - w + (start - x) + 0,
                          x, y + w / 2) if False else (x - 0.75 * size, y - (x - start) - w + (x - start), x, y + (x - start) + w - (x - start)))
        else:
            boxes.append((start, y - 0.75 * size, start + w, y))
    return boxes


def test_dimension_texts_never_overlap(tmp_path):
    # at 1:500 the chain's values no longer fit between their breaks: some are
    # staggered, the rest left out and said so; none overlap
    out, err = _draw(tmp_path, "--section", "z=1.2", "--scale", "1:500")
    assert "left out" in err and "1:500" in err
    missing = int(re.search(r"(\d+) dimension\(s\) left out", err)[1])
    # the DXF has every dimension of the chain, those left out without text
    ezdxf = pytest.importorskip("ezdxf")
    dxf, _ = _draw(tmp_path, "--section", "z=1.2", "--scale", "1:500", name="d.dxf")
    dims = list(ezdxf.readfile(dxf).modelspace().query("DIMENSION"))
    assert sorted(round(d.get_measurement(), 9) for d in dims) == sorted(SOUTH_CHAIN + [10, 10, 8, 8])
    assert sum(d.dxf.text == " " for d in dims) == missing > 0
    root = ET.fromstring(out.read_bytes())
    boxes = [b for b in _text_boxes(root, "dimensions")]
    horizontal = [b for b, t in zip(boxes, root.find(f"{SVG}g[@id='dimensions']").iter(SVG + "text"))
                  if not t.get("transform")]
    for i, a in enumerate(horizontal):
        for b in horizontal[i + 1:]:
            assert a[2] <= b[0] or b[2] <= a[0] or a[3] <= b[1] or b[3] <= a[1], (a, b)
    # and none inside the drawing
    drawing = Drawn(out.read_bytes(), 500)
    (x0, y0), (x1, y1) = drawing.extent("maison")
    g = root.find(f"{SVG}g[@id='drawing']")
    ox, oy = (float(v) for v in g.get("data-origin").split())
    mm = 2.0
    for bx0, by0, bx1, by1 in horizontal:
        inside_x = bx1 > ox + x0 * mm and bx0 < ox + x1 * mm
        inside_y = by1 > oy - y1 * mm and by0 < oy - y0 * mm
        assert not (inside_x and inside_y)


def test_elevation_levels(tmp_path):
    out, _ = _draw(tmp_path, "--view", "front")
    drawn = Drawn(out.read_bytes(), 100)
    assert drawn.texts["levels"] == ["±0.00", "+0.90", "+2.10", "+3.00"]
    assert not drawn.texts["dimensions"]  # an elevation has levels, no dimensions


def test_levels_merge_when_closer_than_their_text(tmp_path):
    # a step 2 cm high beside the house: its level is merged with the ground's
    scene = BOX_HOUSE.replace("> maison;", "marche = @t(-2, 0, 0) @h(1, 1, 0.02) !cu(1, 1, 1);\n"
                              "> maison, marche;")
    out, _ = _draw(tmp_path, "--view", "front", scene=scene)
    assert Drawn(out.read_bytes(), 100).texts["levels"] == ["±0.00", "+0.90", "+2.10", "+3.00"]


@pytest.mark.parametrize("drawing", [("--section", "z=1.2"), ("--section", "x=3"),
                                     ("--view", "front")])
def test_three_pens_cut_heavier_than_profile_heavier_than_seen(tmp_path, drawing):
    source = EXAMPLES / "house.cas"
    out = tmp_path / "h.svg"
    run(*drawing, "-o", str(out), str(source), check_status=0, cwd=EXAMPLES)
    drawn = Drawn(out.read_bytes(), 100)
    pens = {kind: widths for kind, widths in drawn.pens.items()}
    assert pens["profile"] == {0.35} and pens["seen"] == {0.18}
    if drawing[0] == "--section":
        assert pens["cut"] == {0.5}
    # the house's outline against the sky is profile, its window frames seen
    # through are too; a crease inside a face of the roof is not
    assert len(set().union(*pens.values())) >= (3 if drawing[0] == "--section" else 2)
    root = ET.fromstring(out.read_bytes())
    annotation = {float(p.get("stroke-width")) for p in root.iter(SVG + "path")
                  if p.get("class") == "annotation"}
    assert annotation == {0.13}


def test_profile_is_the_outline_against_what_lies_behind(tmp_path):
    # two boxes, one in front of the other: the outline of each is profile;
    # a box whose top is seen from above has no inner seen edge here, so the
    # crease where a sloping roof meets a wall below is seen, not profile
    scene = ("bas = @h(4, 2, 2) !cu(1, 1, 1);\n"
             "haut = @t(1, 0.5, 2) @h(2, 1, 1) !cu(1, 1, 1);\n"
             "tout = $U(bas, haut);\n> tout;\n")
    out, _ = _draw(tmp_path, "--view", "front", scene=scene)
    root = ET.fromstring(out.read_bytes())
    drawing = root.find(f"{SVG}g[@id='drawing']")
    mm = float(drawing.get("data-mm-per-metre"))
    ox, oy = (float(v) for v in drawing.get("data-origin").split())
    lines = {}
    for path in drawing.find(f"{SVG}g[@id='tout']").iter(SVG + "path"):
        for sub in re.findall(r"M([^L]+)L([^M]+)", path.get("d")):
            (ax, ay), (bx, by) = (tuple(float(v) for v in s.split()) for s in sub)
            key = tuple(round(v, 3) for v in ((ax - ox) / mm, (oy - ay) / mm,
                                              (bx - ox) / mm, (oy - by) / mm))
            lines[key] = path.get("class")
    # the outline: all profile
    assert lines[(0, 0, 4, 0)] == "profile" or lines[(4, 0, 0, 0)] == "profile"
    profile = [k for k, v in lines.items() if v == "profile"]
    assert any(abs(k[1] - 3) < 1e-9 and abs(k[3] - 3) < 1e-9 for k in profile)  # the top
    # the shoulders (z = 2, beside the upper box) are outline too
    assert any(abs(k[1] - 2) < 1e-9 and abs(k[3] - 2) < 1e-9 for k in profile)


def test_sheet_title_block_and_scale_bar(tmp_path):
    out, _ = _draw(tmp_path, "--section", "z=1.2", "--sheet", "A3")
    root = ET.fromstring(out.read_bytes())
    assert (root.get("width"), root.get("height")) == ("420mm", "297mm")
    sheet = ["".join(t.itertext()) for t in root.find(f"{SVG}g[@id='sheet']").iter(SVG + "text")]
    assert "maison" in sheet and "Plan z = 1.20" in sheet and "Scale 1:100" in sheet
    assert f"Date {DAY}" in sheet and any(t.endswith("s.cas:8") for t in sheet)
    assert "N" in sheet  # a plan has its north arrow
    assert ["0", "1", "2", "3", "4", "5 m"] == [t for t in sheet if re.fullmatch(r"\d( m)?", t)]
    # the border, 10 mm in from the paper's edge
    border = [p for p in root.find(f"{SVG}g[@id='sheet']").iter(SVG + "path")
              if p.get("d").startswith("M10 10L410 10L410 287L10 287Z")]
    assert border


def test_section_and_elevation_are_named_in_the_title_block(tmp_path):
    out, _ = _draw(tmp_path, "--section", "x=3", "--title", "Maison Dupont")
    texts = Drawn(out.read_bytes(), 100).texts
    assert "Section x = 3.00" in texts["sheet"] and "Maison Dupont" in texts["sheet"]
    assert "N" not in texts["sheet"]  # no north arrow off a plan
    assert "±0.00" in texts["levels"] and "+3.00" in texts["levels"]
    out, _ = _draw(tmp_path, "--view", "front", "--sheet", "A4-portrait")
    root = ET.fromstring(out.read_bytes())
    assert (root.get("width"), root.get("height")) == ("210mm", "297mm")
    assert "Elevation front" in Drawn(out.read_bytes(), 100).texts["sheet"]


def test_title_with_markup_is_escaped(tmp_path):
    out, _ = _draw(tmp_path, "--section", "z=1.2", "--title", "A <b> & 'c' \"d\"")
    root = ET.fromstring(out.read_bytes())  # still well formed
    texts = ["".join(t.itertext()) for t in root.find(f"{SVG}g[@id='sheet']").iter(SVG + "text")]
    assert "A <b> & 'c' \"d\"" in texts


@pytest.mark.parametrize("suffix", [".svg", ".dxf", ".pdf"])
def test_any_title_gives_a_whole_file(tmp_path, suffix):
    ezdxf = pytest.importorskip("ezdxf")
    title = "Maison \x01 <b>&amp; é\n\t\u2603 " + "x" * 200
    out, _ = _draw(tmp_path, "--section", "z=1.2", "--title", title, name="d" + suffix)
    data = out.read_bytes()
    if suffix == ".svg":
        texts = ["".join(t.itertext()) for t in ET.fromstring(data).iter(SVG + "text")]
        assert any(t.startswith("Maison   <b>&amp; é") and t.endswith("…") for t in texts)
    elif suffix == ".dxf":
        doc = ezdxf.readfile(out)
        assert not doc.audit().has_errors
        assert any(t.dxf.text.startswith("Maison") for t in doc.modelspace().query("TEXT"))
    else:
        assert data.startswith(b"%PDF-") and data.rstrip().endswith(b"%%EOF")


@pytest.mark.parametrize("sheet", ["A5", "a3-sideways", "A3-portraitx", ""])
def test_a_sheet_that_is_no_size_is_a_usage_error(tmp_path, sheet):
    (tmp_path / "s.cas").write_text(BOX_HOUSE)
    code, _, err = run("--section", "z=1.2", "--sheet", sheet, "-o", str(tmp_path / "d.svg"),
                       str(tmp_path / "s.cas"))
    assert code == 2
    assert "--sheet takes A4, A3, A2, A1 or A0" in err and f"'{sheet}'" in err
    assert not (tmp_path / "d.svg").exists()


def test_a_drawing_too_large_for_its_sheet_names_the_scale_that_fits(tmp_path):
    out, err = _draw(tmp_path, "--section", "z=1.2", "--sheet", "A4", "--scale", "1:20",
                     status=1)
    assert "does not fit on A4 at 1:20" in err and "1:100" in err
    assert "s.cas:8:" in err  # at the '>' that made the frame
    assert not out.exists()  # nothing written, not a broken file
    # and at that scale it fits
    _draw(tmp_path, "--section", "z=1.2", "--sheet", "A4", "--scale", "1:100")


def test_date_follows_source_date_epoch(tmp_path, monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "0")
    out, _ = _draw(tmp_path, "--view", "front")
    assert "Date 1970-01-01" in Drawn(out.read_bytes(), 100).texts["sheet"]
    first = out.read_bytes()
    out, _ = _draw(tmp_path, "--view", "front")
    assert out.read_bytes() == first


def test_pdf_is_the_sheet_with_its_text(tmp_path):
    out, _ = _draw(tmp_path, "--section", "z=1.2", "--sheet", "A3", name="plan.pdf")
    data = out.read_bytes()
    assert data.startswith(b"%PDF-")
    box = re.search(rb"/MediaBox \[\s*0 0 ([\d.]+) ([\d.]+)\s*\]", data)
    width, height = (float(v) * 25.4 / 72 for v in box.groups())
    assert width == pytest.approx(420, abs=0.01) and height == pytest.approx(297, abs=0.01)
    again, _ = _draw(tmp_path, "--section", "z=1.2", "--sheet", "A3", name="plan.pdf")
    assert again.read_bytes() == data  # no time stamp nor random id
    if shutil.which("pdftotext") is None:
        pytest.skip("pdftotext is not installed")
    text = subprocess.run(["pdftotext", "-raw", str(out), "-"], capture_output=True, text=True,
                          check=True).stdout
    for value in ("1.50", "1.20", "1.80", "1.00", "10.00", "8.00", "Plan z = 1.20", DAY):
        assert value in text


@pytest.mark.skipif(shutil.which("rsvg-convert") is None, reason="rsvg-convert is not installed")
def test_pdf_draws_what_the_svg_draws(tmp_path):
    from PIL import Image

    if shutil.which("pdftoppm") is None:
        pytest.skip("pdftoppm is not installed")
    svg, _ = _draw(tmp_path, "--section", "z=1.2", "--sheet", "A4", name="p.svg")
    pdf, _ = _draw(tmp_path, "--section", "z=1.2", "--sheet", "A4", name="p.pdf")
    subprocess.run(["rsvg-convert", "-w", "1169", "-b", "white", str(svg), "-o",
                    str(tmp_path / "s.png")], check=True)
    subprocess.run(["pdftoppm", "-r", "100", "-png", "-singlefile", str(pdf),
                    str(tmp_path / "q")], check=True)
    a = np.asarray(Image.open(tmp_path / "s.png").convert("L"), float)
    b = np.asarray(Image.open(tmp_path / "q.png").convert("L"), float)
    assert abs(a.shape[0] - b.shape[0]) <= 1 and abs(a.shape[1] - b.shape[1]) <= 1
    rows, cols = min(a.shape[0], b.shape[0]), min(a.shape[1], b.shape[1])
    a, b = a[:rows, :cols], b[:rows, :cols]
    # the same dark pixels, but for anti-aliasing and the fonts' shapes
    dark_a, dark_b = a < 128, b < 128
    assert abs(dark_a.mean() - dark_b.mean()) < 0.25 * dark_a.mean()
    near_b = dark_b.copy()  # a pixel's worth of rounding either way
    for axis in (0, 1):
        near_b |= np.roll(dark_b, 1, axis) | np.roll(dark_b, -1, axis)
    assert (dark_a & near_b).sum() > 0.8 * dark_a.sum()


def test_an_opening_with_no_glass_shows_what_lies_behind(tmp_path):
    # a wall 6 m long with a window 2 m wide (x = 2 .. 4, z = 1 .. 2); a post
    # 3 m behind it (x = 2.8 .. 3.2): seen only through the window
    scene = ("mur = $D(@h(6, 0.3, 3) !cu(1, 1, 1), @t(2, -1, 1) @h(2, 2, 1) !cu(1, 1, 1));\n"
             "poteau = @t(2.8, 3, 0) @h(0.4, 0.4, 3) !cu(1, 0, 0);\n> mur, poteau;\n")
    out, _ = _draw(tmp_path, "--view", "front", scene=scene)
    drawn = Drawn(out.read_bytes(), 100)
    assert drawn.covered("poteau", (2.8, 0), (2.8, 3)) == pytest.approx(1)
    assert drawn.has_line("poteau", (2.8, 1), (2.8, 2))
    assert drawn.covered("poteau", (3.2, 0), (3.2, 3)) == pytest.approx(1)
    # the post's outline against the room is profile; the window's edges are
    # the wall's outline too (the wall has a hole there), the wall's top as well
    assert drawn.pens["profile"] == {0.35}
    assert drawn.texts["levels"] == ["±0.00", "+1.00", "+2.00", "+3.00"]


def test_sheet_is_warned_about_off_a_drawing(tmp_path):
    out, err = _draw(tmp_path, "--sheet", "A3", name="d.stl")
    assert "--sheet has no effect on stl output (it acts on drawings); it is ignored" in err
