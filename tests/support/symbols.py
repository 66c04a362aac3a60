"""A small classed house (LANGUAGE.md §11) and castor run on it, its drawings
read back: what the drawings' tests of the classes' symbols, chains, levels,
title fields and registers share."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

SVG = "{http://www.w3.org/2000/svg}"
ROOT = Path(__file__).resolve().parents[2]

# 6 x 4 m, walls 0.2 m thick, 2.8 m high; in the south wall (y = 0) a door
# 0.9 m wide at x = 1 .. 1.9 (hinge left, opening in) and a window 1.2 m wide
# at x = 3.5 .. 4.7; a stair of 14 risers of 0.2 m going north at x = 4 .. 5
# from y = 0.5; a flat roof 0.5 m over the walls all round; a room inside
HOUSE = """\
R0 = 0;  // [storey "Rez"]
R1 = 3;  // [storey "Etage"]
porte = @t(1, -0.1, 0) @h(0.9, 0.4, 2.1) !cu(0, 0, 1);  // [door hinge=left swing=in]
fenetre = @t(3.5, -0.1, 0.9) @h(1.2, 0.4, 1.2) !cu(0, 0, 1);  // [window]
murs = $D(@h(6, 4, 2.8) !cu(1, 1, 1), $U(@t(0.2, 0.2, -0.1) @h(5.6, 3.6, 3) !cu(1, 1, 1), porte, fenetre));  // [wall]
marche = @t(4, 0.5 + I * 0.2, 0) @h(1, 0.2, (I + 1) * 0.2) !cu(1, 0, 0);
escalier = $U[I = 0, 13](marche);  // [stair]
toit = @t(-0.5, -0.5, 2.8) @h(7, 5, 0.2) !cu(0.5, 0.5, 0.5);  // [roof]
sol = @t(0, 0, -0.2) @h(6, 4, 0.2) !cu(0.5, 0.5, 0.5);  // [slab floor]
piece = @t(0.2, 0.2, 0) @h(5.6, 3.6, 2.8) !cu(1, 1, 1);  // [space "Sejour"]
maison = $U(murs, escalier, toit, sol, piece);
> maison;
"""


def register(*sheets, **project) -> str:
    """A drawing register's TOML (CLI.md ``--sheets``): ``[project]`` with A3
    paper at 1:50 and any other field given, then a ``[[sheet]]`` per
    ``(number, drawing)`` or ``(number, drawing, scale)``."""
    fields = {**project, "sheet": "A3", "scale": "1:50"}
    lines = ["[project]"] + [f'{key} = "{value}"' for key, value in fields.items()]
    for number, drawing, *scale in sheets:
        lines += ["", "[[sheet]]", f'number = "{number}"', f'drawing = "{drawing}"']
        lines += [f'scale = "{value}"' for value in scale]
    return "\n".join(lines) + "\n"


def castor(tmp_path: Path, scene: str, *options, status: int = 0) -> str:
    (tmp_path / "s.cas").write_text(scene)
    env = dict(os.environ, PYTHONPATH=str(ROOT), SOURCE_DATE_EPOCH="1700000000")
    done = subprocess.run([sys.executable, "-m", "castor", "s.cas", *options], cwd=tmp_path,
                          env=env, capture_output=True, text=True, timeout=300)
    assert done.returncode == status, done.stderr
    return done.stderr


def svg_of(tmp_path: Path, scene: str = HOUSE, *options) -> tuple[ET.Element, callable, str]:
    """The SVG's root, a function from paper mm back to metres, and the messages."""
    said = castor(tmp_path, scene, *options, "-o", "d.svg")
    root = ET.fromstring((tmp_path / "d.svg").read_bytes())
    drawing = root.find(f"{SVG}g[@id='drawing']")
    ox, oy = (float(v) for v in drawing.get("data-origin").split())
    mm = float(drawing.get("data-mm-per-metre"))
    return root, (lambda x, y: ((x - ox) / mm, (oy - y) / mm)), said


def dxf_of(tmp_path: Path, scene: str = HOUSE, *options):
    import ezdxf

    castor(tmp_path, scene, *options, "-o", "d.dxf")
    return ezdxf.readfile(tmp_path / "d.dxf")


def numbers(d: str) -> list[float]:
    return [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?", d)]


def levels(root) -> list[str]:
    """The texts of an SVG drawing's level marks (its ``levels`` group)."""
    group = root.find(f"{SVG}g[@id='levels']")
    return ["".join(t.itertext()) for t in group.iter(SVG + "text")]
