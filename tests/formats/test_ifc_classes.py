"""The IFC file and the classes of LANGUAGE.md §11: a '>' object takes the class
its annotation gives it, and --ifc-class overrides the annotation."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ifcopenshell = pytest.importorskip("ifcopenshell")

ROOT = Path(__file__).resolve().parents[2]

SCENE = """\
m = @h(4, 0.2, 2.5) !cu(1, 1, 1); // [wall]
s = @h(4, 4, 0.2) !cu(1, 1, 1); // [slab floor]
c = @t(5, 0, 0) @h(0.3, 0.3, 2.5) !cu(1, 1, 1);
> m, s, c;
"""


def classes(tmp_path: Path, *options) -> dict[str, str]:
    (tmp_path / "s.cas").write_text(SCENE)
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    run = subprocess.run([sys.executable, "-m", "castor", "s.cas", "-o", "s.ifc", *options],
                         cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    model = ifcopenshell.open(str(tmp_path / "s.ifc"))
    return {e.Name: e.is_a() for e in model.by_type("IfcElement")}


def test_an_annotated_object_is_an_element_of_its_class(tmp_path: Path):
    assert classes(tmp_path) == {"m": "IfcWall", "s": "IfcSlab", "c": "IfcBuildingElementProxy"}


def test_ifc_class_overrides_the_annotation(tmp_path: Path):
    assert classes(tmp_path, "--ifc-class", "m=IfcColumn", "--ifc-class", "c=IfcColumn") == \
        {"m": "IfcColumn", "s": "IfcSlab", "c": "IfcColumn"}
