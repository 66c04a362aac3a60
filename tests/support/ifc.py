"""castor run on a scene to write an IFC file, the file read back with
ifcopenshell: what the IFC tests of the coordinator's model and of its reissue share."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def ifc_of(tmp_path: Path, text: str, *options: str, name: str = "s.ifc"):
    """castor run on ``text`` (written as s.cas in ``tmp_path``) with ``options``:
    the IFC file ``name`` read back, and what castor said (the test is skipped
    where ifcopenshell is not installed)."""
    ifcopenshell = pytest.importorskip("ifcopenshell")
    (tmp_path / "s.cas").write_text(text)
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    run = subprocess.run([sys.executable, "-m", "castor", "s.cas", "-o", name, *options],
                         cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0 and "Traceback" not in run.stderr, run.stderr
    return ifcopenshell.open(str(tmp_path / name)), run.stderr
