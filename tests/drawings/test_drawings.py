"""Drawings: plans, sections and elevations, read back as a reader would."""

from __future__ import annotations

import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from tests.support.cli import run
from tests.support.drawings import draw_svg, Drawn

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

# a room of 4 x 3 m, walls 0.2 m thick, a door 0.9 m wide in the south wall,
# standing on a floor slab 0.5 m wider all round; one object
ROOM = """
murs = $D(@h(4, 3, 2.5) !cu(0.9, 0.9, 0.8),
          $U(@t(0.2, 0.2, -1) @h(3.6, 2.6, 5) !cu(0.9, 0.9, 0.8),
             @t(1, -0.5, 0) @h(0.9, 1, 2.1) !cu(0.2, 0.4, 0.8)));
sol = @t(-0.5, -0.5, -0.1) @h(5, 4, 0.1) !cu(0.5, 0.5, 0.5);
piece = $U(murs, sol);
> piece;
"""

# two boxes seen from the front (looking towards +y): 'devant' hides part of 'derriere'
TWO_BOXES = """
devant = @h(2, 1, 1) !cu(1, 0, 0);
derriere = @t(1, 3, 0) @h(2, 1, 2) !cu(0, 0, 1);
> devant, derriere;
"""


def test_plan_of_a_room_with_a_door(tmp_path):
    svg = draw_svg(tmp_path, ROOM, "--section", "z=1.2")
    drawn = Drawn(svg, 100)
    # the floor slab is the drawing's extent
    assert drawn.extent("piece") == pytest.approx(np.array([[-0.5, -0.5], [4.5, 3.5]]))
    walls = 4 * 3 - 3.6 * 2.6 - 0.9 * 0.2
    assert drawn.cut_area("piece") == pytest.approx(walls, abs=1e-4)
    assert drawn.in_poche("piece", 0.5, 0.1)  # the south wall
    assert not drawn.in_poche("piece", 1.45, 0.1)  # the door's opening: a gap
    assert not drawn.in_poche("piece", 2, 1.5)  # the room
    # the floor, below the plane, is seen: its outline and the threshold
    assert drawn.has_line("piece", (-0.5, -0.5), (4.5, -0.5))
    assert drawn.has_line("piece", (-0.5, -0.5), (-0.5, 3.5))
    # the floor runs on through the door: no line across the opening
    assert drawn.covered("piece", (1, 0.1), (1.9, 0.1)) == 0
    # nothing inside the room but the floor: no line crosses it
    assert drawn.covered("piece", (0.2, 1.5), (3.8, 1.5)) == 0


def test_vertical_section_cuts_the_floor_and_the_walls(tmp_path):
    # x = 1.5 through the door, seen looking towards +x: y goes to the left
    svg = draw_svg(tmp_path, ROOM, "--section", "x=1.5")
    drawn = Drawn(svg, 100)  # page x is -y: the slab spans -3.5 .. 0.5
    section = 4 * 0.1 + 2 * 0.2 * 2.5 - 0.2 * 2.1  # floor, north and south walls, less the door
    assert drawn.cut_area("piece") == pytest.approx(section, abs=1e-4)
    assert not drawn.in_poche("piece", -0.1, 1.0)  # through the door
    assert drawn.in_poche("piece", -0.1, 2.3)  # the wall over the door


def test_elevation_hides_what_is_behind(tmp_path):
    svg = draw_svg(tmp_path, TWO_BOXES, "--view", "front")
    drawn = Drawn(svg, 100)
    assert not drawn.cuts["devant"] and not drawn.cuts["derriere"]
    # the front box: its outline, whole
    assert drawn.covered("devant", (0, 0), (2, 0)) == pytest.approx(2)
    assert drawn.covered("devant", (2, 0), (2, 1)) == pytest.approx(1)
    # the box behind: its top and right side seen whole
    assert drawn.covered("derriere", (1, 2), (3, 2)) == pytest.approx(2)
    assert drawn.covered("derriere", (3, 0), (3, 2)) == pytest.approx(2)
    # its left side seen only above the front box, its bottom only beside it
    assert drawn.covered("derriere", (1, 0), (1, 2)) == pytest.approx(1)
    assert drawn.has_line("derriere", (1, 1), (1, 2))
    assert drawn.covered("derriere", (1, 0), (3, 0)) == pytest.approx(1)
    assert drawn.has_line("derriere", (2, 0), (3, 0))
    # nothing of it where the front box covers it
    assert drawn.covered("derriere", (1, 0.5), (2, 0.5)) == 0


def test_curved_surfaces_are_drawn_by_their_silhouettes(tmp_path):
    svg = draw_svg(tmp_path, "tube = @h(0.5, 0.5, 2) !cy(0.5, 0.5, 0.5);\n> tube;\n", "--view", "front")
    drawn = Drawn(svg, 100)
    # a cylinder seen from the side: a rectangle, not a line per facet
    vertical = [s for s in drawn.lines["tube"] if abs(s[0, 0] - s[-1, 0]) < 1e-6]
    assert len(vertical) == 2
    assert drawn.covered("tube", (-0.5, 0), (-0.5, 2), tol=0.01) == pytest.approx(2, abs=0.01)
    assert drawn.covered("tube", (0.5, 0), (0.5, 2), tol=0.01) == pytest.approx(2, abs=0.01)
    assert drawn.covered("tube", (0, 0), (0, 2), tol=0.4) == 0
    assert drawn.covered("tube", (-0.5, 0), (0.5, 0)) == pytest.approx(1, abs=0.01)
    assert drawn.covered("tube", (-0.5, 2), (0.5, 2)) == pytest.approx(1, abs=0.01)


def test_scale_sets_the_printed_size(tmp_path):
    svg = draw_svg(tmp_path, TWO_BOXES, "--view", "front", "--scale", "1:50")
    drawn = Drawn(svg, 50)  # 20 mm of paper a metre
    assert drawn.extent("devant") == pytest.approx(np.array([[0, 0], [2, 1]]))
    # the sheet holds the drawing (3 x 2 m, 60 x 40 mm) and its title block below it
    assert drawn.width_mm >= 60 + 20 and drawn.height_mm >= 40 + 30 + 20


def test_dxf_in_metres_with_a_layer_per_object(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    draw_svg(tmp_path, ROOM + "lampe = @t(2, 1.5, 0) @h(0.3, 0.3, 1.5) !cu(1, 1, 0);\n> lampe;\n",
          "--section", "z=1.2", name="p%d.dxf")
    doc = ezdxf.readfile(tmp_path / "p1.dxf")
    auditor = doc.audit()
    assert not auditor.has_errors
    layers = {layer.dxf.name for layer in doc.layers}
    assert {"piece"} <= layers
    hatches = doc.modelspace().query("HATCH")
    assert {h.dxf.layer for h in hatches} - {"sheet"} == {"piece"}  # (the scale bar's blocks)
    outline = [p for p in doc.modelspace().query("LWPOLYLINE") if p.dxf.layer == "piece"]
    area = 0.0
    for polyline in outline:
        points = np.array([p[:2] for p in polyline.get_points()])
        x, y = points[:, 0], points[:, 1]
        area += np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) / 2
    assert area == pytest.approx(4 * 3 - 3.6 * 2.6 - 0.9 * 0.2, abs=1e-6)
    xs = [c for line in doc.modelspace().query("LINE") if line.dxf.layer == "piece"
          for c in (line.dxf.start.x, line.dxf.end.x)]
    assert min(xs) == pytest.approx(-0.5) and max(xs) == pytest.approx(4.5)  # metres
    # the second frame's object, another file
    doc2 = ezdxf.readfile(tmp_path / "p2.dxf")
    assert {h.dxf.layer for h in doc2.modelspace().query("HATCH")} - {"sheet"} == {"lampe"}


# a plan, an elevation and a section of each example; the bus shelter, by far the
# heaviest to make, as a plan only (the four others' elevations and sections cover those)
EXAMPLE_DRAWINGS = [
    (name, drawing)
    for name in ("bus_shelter", "car", "door", "house", "staircase")
    for drawing in (("--section", "z=1.2"), ("--view", "front"), ("--section", "x=1"))
    if name != "bus_shelter" or drawing[0] == "--section" and drawing[1] == "z=1.2"
]


@pytest.mark.skipif(shutil.which("rsvg-convert") is None, reason="rsvg-convert is not installed")
@pytest.mark.parametrize("name,drawing", EXAMPLE_DRAWINGS)
def test_every_example_drawn_and_read_back(tmp_path, name, drawing):
    ezdxf = pytest.importorskip("ezdxf")
    from PIL import Image

    source = EXAMPLES / f"{name}.cas"
    defines = ["-D", "ONE_FRAME"] if name in ("bus_shelter", "door") else []
    if name == "door":
        defines += ["--set", "T=0.5"]
    svg = tmp_path / "d.svg"
    run(*defines, *drawing, "-o", str(svg), str(source), check_status=0, cwd=EXAMPLES)
    ET.fromstring(svg.read_bytes())
    png = tmp_path / "d.png"
    subprocess.run(["rsvg-convert", "-w", "600", "-b", "white", str(svg), "-o", str(png)],
                   check=True, capture_output=True)
    pixels = np.asarray(Image.open(png).convert("L"))
    assert (pixels < 128).mean() > 0.002  # something is drawn
    assert (pixels > 200).mean() > 0.3  # on a white page
    dxf = tmp_path / "d.dxf"
    run(*defines, *drawing, "-o", str(dxf), str(source), check_status=0, cwd=EXAMPLES)
    doc = ezdxf.readfile(dxf)
    assert not doc.audit().has_errors
    assert len(doc.modelspace()) > 0
