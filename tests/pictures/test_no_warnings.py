"""No numpy warning reaches the user (issue 29, item 6).

A picture of a scene with '!rv' printed a RuntimeWarning from its ray
intersections (a ray parallel to a disc: 0 * inf): every primitive, drawn in
pictures and drawings from views that graze its faces, with numpy's warnings
turned into errors and with the usual ones on standard error.
"""

import subprocess
import sys
from pathlib import Path

import pytest

from castor.primitives import PRIMITIVES

REPO = Path(__file__).resolve().parents[2]
FIRST = {"to": 0.3, "pr": 6, "py": 5}  # arguments that are no length
PROFILE = (0, 0, 1, 0, 1, 0.5, 0.5, 1, 0, 1)


def every_primitive() -> str:
    """One of each primitive of the vocabulary, side by side."""
    uses = []
    for k, (name, declared) in enumerate(PRIMITIVES.items()):
        args = [FIRST.get(name, 0.5)] * len(declared.arguments)
        if declared.pair_names:
            args += PROFILE
        text = ", ".join(str(a) for a in (0.8, 0.7, 0.6, *args))
        uses.append(f"@t({2 * k}, 0, 0) !{name}({text})")
    return "> " + ", ".join(uses) + ";\n"


@pytest.mark.parametrize("output, args", [
    ("p.png", ["--size", "160x120", "--view", "-60,25"]),
    ("p.png", ["--size", "160x120", "--view", "front", "--edges"]),  # rays along the discs
    ("p.png", ["--size", "160x120", "--view", "top", "--sun", "0,90"]),
    ("d.svg", ["--section", "z=0.5"]),
    ("d.svg", ["--view", "front"]),
], ids=["perspective", "front", "top", "plan", "elevation"])
def test_pictures_and_drawings_of_every_primitive_warn_of_nothing(tmp_path, output, args):
    (tmp_path / "all.cas").write_text(every_primitive())
    for warnings in (["-W", "error::RuntimeWarning"], []):
        done = subprocess.run([sys.executable, *warnings, "-m", "castor", "-o", output, *args, "all.cas"], cwd=tmp_path,
                              capture_output=True, text=True, timeout=300,
                              env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"})
        assert done.returncode == 0, done.stderr
        assert done.stderr == "", done.stderr
        assert (tmp_path / output).stat().st_size > 0
