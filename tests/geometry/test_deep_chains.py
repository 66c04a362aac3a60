"""Whatever ``castor --check`` accepts is written (issue 29): a chain of named
objects tens of thousands deep (``a1 = a0; a2 = a1; ...``) recursed past the
frame thread's recursion limit (50,000 names), past a worker process's
(``--jobs 2``: 2,000), and a picture of one wrote out the path of every level
(3.5 GB for 30,000)."""

from __future__ import annotations

import subprocess
import sys

import pytest

from tests.support.cli import OUTSIDE, run, write


def _chain(tmp_path, depth: int):
    lines = ["a0 = !cu(1, 1, 1);"]
    lines += [f"a{i} = a{i - 1};" for i in range(1, depth + 1)]
    lines.append(f"> a{depth};")
    return write(tmp_path, "chain.cas", "\n".join(lines) + "\n")


def _one_cube(path) -> None:
    import trimesh

    mesh = trimesh.load(str(path), force="mesh")
    assert mesh.is_watertight
    assert abs(mesh.volume - 1.0) < 1e-9
    assert mesh.bounds.tolist() == [[0, 0, 0], [1, 1, 1]]


@pytest.mark.parametrize("depth, jobs", [(50_000, "1"), (2_000, "2")])
def test_a_deep_chain_of_named_objects_is_written(tmp_path, depth, jobs):
    scene = _chain(tmp_path, depth)
    out = tmp_path / "chain.stl"
    status, _, err = run("--jobs", jobs, "-o", str(out), str(scene))
    assert status == 0, err[-2000:]
    assert "error" not in err and "internal" not in err, err[-2000:]
    _one_cube(out)


def test_a_picture_of_a_deep_chain_keeps_to_its_memory(tmp_path):
    scene = _chain(tmp_path, 30_000)
    out = tmp_path / "chain.png"
    # the peak of castor's process alone: a wrapper whose only child it is
    measure = ("import resource, subprocess, sys\n"
               "done = subprocess.run(sys.argv[1:], capture_output=True, text=True)\n"
               "sys.stderr.write(done.stderr)\n"
               "print(done.returncode, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n")
    result = subprocess.run([sys.executable, "-c", measure, sys.executable, "-m", "castor",
                             "-o", str(out), str(scene)], capture_output=True, text=True,
                            cwd=OUTSIDE, timeout=600)
    status, peak_kb = map(int, result.stdout.split())
    assert status == 0, result.stderr[-2000:]
    assert out.stat().st_size > 0
    assert peak_kb < 1_000_000, peak_kb  # 3.5 GB before, 0.17 GB after


def test_a_leafs_path_above_is_written_as_the_joined_path():
    from castor.csg.paths import join
    from castor.pictures.trace import above_text

    chain = ((("", "U2", "(a)"), "D1", "(b)"), "", "(c)")
    assert above_text(chain) == join((join((join(("", "U2", "(a)")), "D1", "(b)")), "", "(c)"))
    assert above_text(chain) == "U2(a).D1(b)(c)"
    assert above_text("") == "" and above_text("U1(x)") == "U1(x)"
