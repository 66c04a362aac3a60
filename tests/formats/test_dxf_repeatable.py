"""A DXF is the same bytes at every run for the same scene and options, as the
PDF is (a drawing kept under version control changes only where the drawing
does): no time of writing, no random GUID, and the CLASSES section in one
order whatever Python's hash seed (ezdxf added two classes in an order that
varied from run to run)."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def dxf(tmp_path: Path, name: str, seed: str, *options: str) -> bytes:
    env = dict(os.environ, PYTHONPATH=str(ROOT), PYTHONHASHSEED=seed)
    subprocess.run([sys.executable, "-m", "castor", *options, "-o", str(tmp_path / name)],
                   env=env, check=True, capture_output=True, timeout=300)
    return (tmp_path / name).read_bytes()


def test_a_sheet_and_a_set_are_the_same_bytes_at_every_run(tmp_path):
    house = ["--section", "z=1.2", str(ROOT / "examples" / "house.cas")]
    pavilion = ["--sheets", str(ROOT / "examples" / "pavilion-sheets.toml"),
                str(ROOT / "examples" / "pavilion.cas")]
    for options in (house, pavilion):
        first = dxf(tmp_path, "a.dxf", "1", *options)
        time.sleep(1.1)  # a time of writing would differ by a second
        again = [dxf(tmp_path, f"{seed}.dxf", seed, *options) for seed in ("2", "3", "4")]
        assert all(data == first for data in again)
        assert b"$TDCREATE\n 40\n2451545.0\n" in first  # ezdxf's fixed date, not today
