"""Elements, openings, storeys and spaces (LANGUAGE.md §11), measured on scenes
of boxes whose figures are known by hand."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from castor.pipeline import evaluated_frames

ROOT = Path(__file__).resolve().parents[2]

HOUSE = """\
R1 = 3;  // [storey "Etage"]
R0 = 0;  // [storey "Rez"]
porte = @t(4, -1, 0) @h(1, 3, 2) !cu(0,0,1);   // [door hinge=right]
fenetres = $U[I = 0, 1](@t(1 + I * 6, -1, 1) @h(1, 3, 1) !cu(0,0,1)); // [window]
mur = $D(@h(10, 0.2, 2.8) !cu(1,1,1), $U(porte, fenetres)); // [wall]
dalle = @t(0, 0, 2.8) @h(10, 5, 0.2) !cu(1,1,1); // [slab floor]
sejour = @t(0, 0.2, 0) @h(10, 4.8, 2.8) !cu(1,1,1); // [space "Séjour"]
mur2 = @t(0, 0, R1) @h(10, 0.2, 2.5) !cu(1,1,1); // [wall]
maison = $U(mur, dalle, mur2, @t(0, 4.8, 0) @h(10, 0.2, 5.5) !cu(1,0,0), sejour);
> maison;
"""


def castor(*args, cwd: Path):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-m", "castor", *args], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=300)


def summary(tmp_path: Path, text: str, *options) -> dict:
    (tmp_path / "s.cas").write_text(text)
    run = castor("-q", "s.cas", "--summary", "s.json", "-o", "s.off", *options, cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    return json.loads((tmp_path / "s.json").read_text())["frames"][0]


def totals(frame: dict) -> dict:
    return {(c["class"], c["storey"]): (c["count"], pytest.approx(c["volume"]))
            for c in frame["classes"]}


def test_take_off_per_class_and_storey(tmp_path: Path):
    frame = summary(tmp_path, HOUSE)
    assert frame["storeys"] == [{"name": "Rez", "level": 0}, {"name": "Etage", "level": 3}]
    assert totals(frame) == {
        ("IfcWall", "Rez"): (1, 5.6 - 0.4 - 2 * 0.2),  # less the door's and windows' holes
        ("IfcSlab", "Etage"): (1, 10),  # a floor slab is on the storey it carries
        ("IfcWall", "Etage"): (1, 5),
        # the rest of the house: the back wall less what the slab took of it
        ("IfcBuildingElementProxy", "Rez"): (1, 11 - 0.4),
    }
    whole = frame["objects"][0]["volume"]
    assert whole == pytest.approx(sum(c["volume"] for c in frame["classes"]))


def test_openings_are_the_blocks_cut_the_wall_thickness_deep(tmp_path: Path):
    openings = summary(tmp_path, HOUSE)["openings"]
    door, left, right = openings
    assert door == {"class": "IfcDoor", "name": "porte", "host": "mur", "storey": "Rez",
                    "width": 1, "height": 2, "sill": 0, "head": 2, "volume": 0.4,
                    "hinge": "right", "swing": "in"}
    for window in (left, right):  # one object, two pieces: two windows
        assert (window["class"], window["host"], window["width"], window["height"],
                window["sill"], window["head"], window["volume"]) == \
            ("IfcWindow", "mur", 1, 1, 1, 2, 0.2)


def test_spaces_are_rooms_not_solids(tmp_path: Path):
    frame = summary(tmp_path, HOUSE)
    assert frame["spaces"] == [{"name": "Séjour", "object": "sejour", "storey": "Rez",
                                "floor_area": 48, "volume": 134.4}]
    assert frame["objects"][0]["volume"] == pytest.approx(30.4)  # no room in it
    assert frame["objects"][0]["bbox"] == [[0, 0, 0], [10, 5, 5.5]]


def test_a_frame_of_spaces_only_is_not_empty_and_writes_nothing(tmp_path: Path):
    (tmp_path / "s.cas").write_text('r = @h(2, 3, 2.5) !cu(1, 1, 1); // [space "Chambre"]\n'
                                    "> r;\n")
    run = castor("s.cas", "--summary", "s.json", "-f", "off", cwd=tmp_path)
    assert run.returncode == 0 and "empty" not in run.stderr, run.stderr
    frame = json.loads((tmp_path / "s.json").read_text())["frames"][0]
    assert frame["spaces"][0]["floor_area"] == 6 and frame["spaces"][0]["volume"] == 15
    assert frame["objects"] == []


def test_spaces_are_absent_from_pictures(tmp_path: Path):
    """A red room in front of a grey wall: the picture shows no red."""
    from PIL import Image
    import numpy as np

    text = ("mur = @t(-5, 3, 0) @h(10, 0.2, 5) !cu(0.5, 0.5, 0.5);\n"
            'piece = @t(-1, -1, 0) @h(2, 2, 2) !cu(1, 0, 0); // [space "Salon"]\n'
            "> $U(mur, piece);\n")
    (tmp_path / "s.cas").write_text(text)
    run = castor("-q", "s.cas", "-o", "s.png", "--size", "80x60", "--samples", "1",
                 "--view", "-90,10", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    pixels = np.asarray(Image.open(tmp_path / "s.png").convert("RGB")).astype(int)
    red = (pixels[..., 0] > 150) & (pixels[..., 1] < 80) & (pixels[..., 2] < 80)
    assert not red.any()
    grey = (abs(pixels[..., 0] - pixels[..., 1]) < 10) & (pixels[..., 0] > 40)
    assert grey.sum() > 100


def test_storeys_from_floor_slabs_then_level_0(tmp_path: Path):
    text = ("d0 = @h(4, 4, 0.2) !cu(1,1,1); // [slab floor]\n"
            "d1 = @t(0, 0, 2.8) @h(4, 4, 0.2) !cu(1,1,1); // [slab floor]\n"
            "d2 = @t(5, 0, 2.805) @h(4, 4, 0.2) !cu(1,1,1); // [slab floor]\n"
            "c = @t(0, 0, 3.0) @h(1, 1, 2) !cu(1,1,1); // [column]\n"
            "c0 = @t(0, 0, -1) @h(1, 1, 1) !cu(1,1,1); // [footing]\n"
            "> d0, d1, d2, c, c0;\n")
    frame = summary(tmp_path, text)
    assert [s["name"] for s in frame["storeys"]] == ["Level 0", "Level 1"]
    assert [s["level"] for s in frame["storeys"]] == pytest.approx([0.2, 3.0])
    assert totals(frame) == {("IfcSlab", "Level 0"): (1, 3.2), ("IfcSlab", "Level 1"): (2, 6.4),
                             ("IfcColumn", "Level 1"): (1, 2),
                             ("IfcFooting", "Level 0"): (1, 1)}
    frame = summary(tmp_path, "w = @h(1, 1, 1) !cu(1,1,1); // [wall]\n> w;\n")
    assert frame["storeys"] == [{"name": "Level 0", "level": 0}]


def test_nested_classes_share_the_solid_out(tmp_path: Path):
    """A classed beam inside a classed wall, used twice: each use is an element;
    where the two overlap, the first operand of the union has it."""
    text = ("poutre = @t(0, 0, 2.4) @h(4, 0.2, 0.3) !cu(1,1,1); // [beam lintel]\n"
            "mur = $U(@h(4, 0.2, 2.5) !cu(1,1,1), poutre); // [wall]\n"
            "> $U(mur, @t(0, 5, 0) mur);\n")
    frame = summary(tmp_path, text)
    assert totals(frame) == {("IfcWall", "Level 0"): (2, 2 * 2.0),
                             ("IfcBeam", "Level 0"): (2, 2 * 4 * 0.2 * 0.2)}


def test_annotations_never_change_the_tree():
    """Without spaces, the evaluated tree is the same with or without annotations."""
    from castor.csg.tree import dump

    annotated = HOUSE.replace("sejour = ", "// ").replace(", sejour", "")
    plain = "\n".join(line.split("//")[0] for line in annotated.splitlines())
    a, _ = evaluated_frames(annotated)
    b, _ = evaluated_frames(plain)
    assert dump(a[0]) == dump(b[0])
    assert a[0].classes is not None and b[0].classes is None


def test_pavilion_take_off_by_hand(tmp_path: Path):
    """examples/pavilion.cas, figures worked out by hand from its boxes."""
    run = castor("-q", str(ROOT / "examples" / "pavilion.cas"), "--summary", "p.json",
                 "-o", "p.off", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    frame = json.loads((tmp_path / "p.json").read_text())["frames"][0]
    rez, etage = "Rez-de-chaussée", "Étage"
    shell = 8 * 6 * 3 - 7.5 * 5.5 * 3
    assert totals(frame) == {
        ("IfcSlab", rez): (1, 8 * 6 * 0.2),
        ("IfcStair", rez): (1, sum(0.26 * (i + 1) * 3 / 16 for i in range(16))),
        ("IfcWall", rez): (1, shell - 0.9 * 0.25 * 2.1 - 2 * 1.2 * 0.25 * 1.3),
        ("IfcRoof", etage): (1, 8.6 * 6.6 * 0.25),
        ("IfcSlab", etage): (1, 7.5 * 5.5 * 0.2 - 1.1 * 16 * 0.26 * 0.2),
        ("IfcWall", etage): (2, shell - 3 * 1.2 * 0.25 * 1.3 + 0.1 * 5.5 * 2.8 - 0.1 * 0.9 * 2.1),
    }
    doors = [o for o in frame["openings"] if o["class"] == "IfcDoor"]
    assert [(d["name"], d["host"], d["storey"], d["width"], d["height"], d["hinge"], d["swing"])
            for d in doors] == [("porte", "murs_rdc", rez, 0.9, 2.1, "left", "in"),
                                ("porte_chambre", "cloison", etage, 0.9, 2.1, "right", "out")]
    windows = [(o["storey"], o["sill"], o["head"]) for o in frame["openings"]
               if o["class"] == "IfcWindow"]
    assert windows == [(rez, 0.9, 2.2)] * 2 + [(etage, 3.9, 5.2)] * 3
    assert [(s["name"], s["storey"], s["floor_area"], s["volume"]) for s in frame["spaces"]] == [
        ("Séjour", rez, 41.25, pytest.approx(41.25 * 2.8)),
        ("Chambre", etage, 20.625, pytest.approx(20.625 * 2.8)),
        ("Bureau", etage, pytest.approx(3.65 * 5.5), pytest.approx(3.65 * 5.5 * 2.8))]


def test_spaces_are_absent_from_drawings(tmp_path: Path):
    """A plan through a room is the plan without it, byte for byte, but for
    the room's tag (issue 31: its name and area, in the symbols' group)."""
    import re

    wall = "mur = @t(-5, 3, 0) @h(10, 0.2, 3) !cu(0.5, 0.5, 0.5); // [wall]\n"
    room = 'piece = @t(-1, -1, 0) @h(2, 2, 2.5) !cu(1, 0, 0); // [space "Salon"]\n'
    (tmp_path / "a.cas").write_text(wall + room + "> $U(mur, piece);\n")
    (tmp_path / "b.cas").write_text(wall + "\n> $U(mur);\n")
    for name in ("a", "b"):
        run = castor("-q", f"{name}.cas", "-o", f"{name}.svg", "--section", "z=1",
                     "--title", "plan", cwd=tmp_path)
        assert run.returncode == 0, run.stderr
    symbols = re.compile(r'<g id="symbols".*?</g>\n', re.S)
    a = (tmp_path / "a.svg").read_text().replace("a.cas", "X")
    b = (tmp_path / "b.svg").read_text().replace("b.cas", "X")
    assert "Salon" in symbols.search(a).group(0) and "4.00 m²" in a
    assert symbols.sub("", a) == symbols.sub("", b)


def test_an_opening_in_a_wall_at_an_angle_is_as_wide_as_its_window(tmp_path: Path):
    text = ("fenetre = @t(2, -0.5, 1) @h(1.2, 1.25, 1.3) !cu(0, 0, 1); // [window]\n"
            "mur = @rz(30) $D(@h(5, 0.25, 2.5) !cu(1, 1, 1), fenetre); // [wall]\n"
            "> mur;\n")
    (window,) = summary(tmp_path, text)["openings"]
    assert window["width"] == pytest.approx(1.2) and window["height"] == pytest.approx(1.3)
    assert window["volume"] == pytest.approx(1.2 * 0.25 * 1.3)
    assert (window["sill"], window["head"]) == (1, 2.3)


def test_footprint_of_a_turned_block():
    import numpy as np

    from castor.quantities import footprint

    corners = np.array([[x, y, z] for x in (0, 2) for y in (0, 0.3) for z in (0, 1)], float)
    turn = np.radians(40)
    rotation = np.array([[np.cos(turn), -np.sin(turn), 0], [np.sin(turn), np.cos(turn), 0],
                         [0, 0, 1]])
    width, thickness, direction = footprint(corners @ rotation.T)
    assert (width, thickness) == (pytest.approx(2), pytest.approx(0.3))
    assert abs(np.dot(direction, (np.cos(turn), np.sin(turn)))) == pytest.approx(1)
    assert footprint(corners)[:2] == (2, 0.3)


from hypothesis import HealthCheck, given, settings, strategies as st  # noqa: E402

CLASSES = [None, "wall", "door", "window", "space", "slab floor", "column"]


@st.composite
def classed_scenes(draw):
    """Scenes of boxes and booleans of earlier objects, each maybe classed."""
    lines = []
    for k in range(draw(st.integers(2, 6))):
        if k < 2 or draw(st.booleans()):
            x, y, z = (draw(st.integers(0, 3)) * 0.5 for _ in range(3))
            a, b, c = (draw(st.integers(1, 4)) * 0.5 for _ in range(3))
            body = f"@t({x}, {y}, {z}) @h({a}, {b}, {c}) !cu(1, 1, 1)"
        else:
            op = draw(st.sampled_from(["$U", "$D", "$I"]))
            first, second = draw(st.permutations(range(k)))[:2]
            body = f"{op}(o{first}, o{second})"
        mark = draw(st.sampled_from(CLASSES))
        lines.append(f"o{k} = {body};" + (f" // [{mark}]" if mark else ""))
    lines.append(f"> o{len(lines) - 1};")
    return "\n".join(lines) + "\n"


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(classed_scenes())
def test_the_elements_share_the_solid_out_without_overlap(text):
    from castor.mesh.facetize import Facetizer
    from castor.quantities import Takeoff, object_figures

    trees, said = evaluated_frames(text)
    assert "error" not in said
    scene = trees[0]
    facetizer = Facetizer()
    frame = facetizer.frame(scene)
    whole = sum(object_figures(obj, "").volume for obj in frame.objects)
    takeoff = Takeoff(scene, facetizer)
    parts = sum(p.figures.volume for p in takeoff.placed())
    assert parts == pytest.approx(whole, abs=1e-6)
    for block in takeoff.blocks():
        assert block.figures.volume > 0 and block.height > 0
    for room in takeoff.rooms():
        span = room.solid.vertices.max(axis=0) - room.solid.vertices.min(axis=0)
        assert 0 < room.floor_area <= span[0] * span[1] + 1e-9
        assert room.volume <= room.floor_area * span[2] + 1e-9 or \
            room.volume <= span.prod() + 1e-9
