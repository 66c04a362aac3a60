"""The IFC's quantities and a door's or window's size are written to what the
solids hold exactly (12 significant digits): a door 0.9 wide reads back 0.9,
not 0.8999999999999995; coordinates are left whole."""

from __future__ import annotations

import pytest

from tests.support.cli import run, write

ifcopenshell = pytest.importorskip("ifcopenshell")

SCENE = """\
porte = @t(4.7, -0.1, 0) @h(0.9, 0.5, 2.1) !cu(0.2, 0.3, 0.8);  // [door]
mur = $D(@h(6, 0.3, 2.5) !cu(0.9, 0.9, 0.8), porte);  // [wall]
cloison = @t(2.9, 0.3, 0) @h(0.1, 3, 2.5) !cu(0.9, 0.9, 0.8);  // [wall]
maison = $U(mur, cloison);
> maison;
"""


def _quantities(element) -> dict:
    found = {}
    for rel in element.IsDefinedBy:
        definition = rel.RelatingPropertyDefinition
        if definition.is_a("IfcElementQuantity"):
            for q in definition.Quantities:
                found[(definition.Name, q.Name)] = q[3]
    return found


def test_sizes_and_quantities_read_back_without_noise(tmp_path):
    scene = write(tmp_path, "noise.cas", SCENE)
    out = tmp_path / "noise.ifc"
    run("-o", str(out), str(scene), check_status=0)
    model = ifcopenshell.open(str(out))
    door, = model.by_type("IfcDoor")
    assert (door.OverallWidth, door.OverallHeight) == (0.9, 2.1)
    assert _quantities(door)[("Qto_DoorBaseQuantities", "Width")] == 0.9
    walls = {w.Name: _quantities(w) for w in model.by_type("IfcWall")}
    assert walls["cloison"][("Qto_WallBaseQuantities", "Width")] == 0.1
    assert walls["cloison"][("Qto_WallBaseQuantities", "Length")] == 3.0
    assert walls["mur"][("Qto_WallBaseQuantities", "Width")] == 0.3
    # the door's body keeps its coordinates as made (4.7 + 0.9 is 5.6000000000000005)
    xs = {c[0] for points in model.by_type("IfcCartesianPointList3D")
          for c in points.CoordList}
    assert {4.7, 4.7 + 0.9} <= xs
