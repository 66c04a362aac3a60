"""The checks made of every boolean's result, made for all its triangles at
once: checks.off_faces (the runs' distances to their faces as one array, the
count made run by run only where a distance is near the tolerance) and
regularize.regular (shells' volumes from the triangles, the engine's
decomposition only where a shell may be a sheet) give what they gave run by
run and shell by shell."""

import manifold3d
import numpy as np
import pytest

from castor.mesh import adapter, checks, instances, primitives, regularize


def _cube():
    return instances.template(primitives.build("cu", (), 0.01))


def _with_corner_moved(cube, by: float, at=(0.0, 0.0, 0.0)):
    """The cube's template with its (1, 1, 1) corner moved by ``by``, placed at ``at``."""
    vertices = cube.vertices.copy()
    vertices[int(np.argmax(vertices.sum(axis=1)))] += by
    return manifold3d.Manifold(manifold3d.Mesh64(
        vert_properties=np.ascontiguousarray(vertices),
        tri_verts=cube.triangles.astype(np.uint64),
        run_index=np.array([0, 3 * len(cube.triangles)], np.uint64),
        run_original_id=np.array([cube.id], np.uint32),
        face_id=cube.face_ids.astype(np.uint64))).translate(list(at))


def _run_by_run(monkeypatch, manifold) -> int:
    with monkeypatch.context() as patched:
        patched.setattr(checks, "_suspects", lambda *args: None)
        return checks.off_faces(manifold)


@pytest.mark.parametrize("by", [0.0, 0.4, 0.7, 0.98, 1.02, 2.0, 1e7])
def test_off_faces_counts_as_run_by_run(monkeypatch, by):
    """Corners moved off their faces by less than half the tolerance (10⁻⁹ of
    the coordinates' size, 4 here), by about it, and by more: the same count
    as run by run, among runs that are right."""
    cube = _cube()
    tolerance = 4e-9
    moved = _with_corner_moved(cube, by * tolerance, at=(3.0, 0.0, 0.0))
    right = cube.manifold + cube.manifold.translate([0.5, 0.25, 0.0])
    every = adapter.compose([right, moved])
    counted = checks.off_faces(every)
    assert counted == _run_by_run(monkeypatch, every)
    assert (counted == 0) == (by < 1)
    if by > 1:
        assert 3 <= counted <= 6


def test_off_faces_looks_again_only_at_runs_near_the_tolerance(monkeypatch):
    cube = _cube()
    right = cube.manifold + cube.manifold.translate([0.5, 0.25, 0.0])
    far = adapter.compose([right, _with_corner_moved(cube, 0.01, at=(3.0, 0.0, 0.0))])
    runs = len(adapter.to_arrays(far).run_ids)
    assert runs >= 3
    looked = []
    moved_planes = checks.moved_planes
    monkeypatch.setattr(checks, "moved_planes",
                        lambda *args: looked.append(1) or moved_planes(*args))
    assert checks.off_faces(far) >= 3
    assert len(looked) == 1  # the moved cube's run, not the union's


def _decomposed(monkeypatch):
    calls = []
    decompose = adapter.decompose
    monkeypatch.setattr(adapter, "decompose", lambda m: calls.append(1) or decompose(m))
    return calls


def test_a_union_of_many_shells_with_no_sheet_is_not_decomposed(monkeypatch):
    cube = _cube().manifold
    union = adapter.compose([cube + cube.translate([0.5, 0.25, 0.0])]
                            + [cube.translate([5 + 2 * k, 0, 0]) for k in range(5)])
    calls = _decomposed(monkeypatch)
    assert regularize.regular(union) is union
    assert calls == []
    # a few shells are decomposed, as before (the engine's is the cheaper then)
    few = adapter.compose([cube, cube.translate([5, 0, 0])])
    assert regularize.regular(few) is few and len(calls) == 1


def test_a_sheet_among_many_shells_is_taken_out(monkeypatch):
    """The sheets left by the intersection of solids that only touch, with
    six cubes apart: found, and taken out by the decomposition."""
    from castor.mesh.caches import PROCESS
    from tests.support.cli import frames_of

    PROCESS.new_facetizer()  # the intersection made again, not found made before
    made = []
    regular = regularize.regular
    monkeypatch.setattr("castor.mesh.booleans.regular", lambda m: made.append(m) or regular(m))
    frames_of(f"> $U(@t(3, 0, 0) !cu(0, 0, 1), {TOUCHING});\n")
    (sheet,) = [m for m in made if not m.is_empty()
                and any(regularize._sheet(shell) for shell in adapter.decompose(m))]
    cubes = [_cube().manifold.translate([5 + 2 * k, 0, 0]) for k in range(6)]
    solid = adapter.compose([sheet, *cubes])
    assert regularize._many_shells(solid) and regularize._may_have_sheets(solid)
    assert regularize.regular(solid).num_tri() == 6 * 12


TOUCHING = "$I(@t(-1,-1,0) !ex(1,0,0, 0,0, 2,0, 2,1, 1,1, 1,2, 0,2), !cu(0,0,1))"
SHEETS = [
    # solids that only touch intersect into sheets (test_regular_booleans.py)
    f"> $U(@t(3, 0, 0) !cu(0, 0, 1), {TOUCHING});\n",
    f"> $U(@t(3, 0, 0) !cu(0, 0, 1), $D(@t(-2, -2, -2) @h(6, 6, 6) !cu(1, 0, 0), {TOUCHING}));\n",
]


@pytest.mark.parametrize("scene", SHEETS)
def test_every_sheet_the_engine_leaves_is_still_found(monkeypatch, scene):
    """Scenes whose booleans leave shells of no volume: every result with a
    sheet among its shells is one that _may_have_sheets lets through to the
    decomposition, and the frame is as regular as before."""
    from tests.support.cli import frames_of
    from castor.mesh.caches import PROCESS
    from tests.support.regularity import regularity_defects

    PROCESS.new_facetizer()  # the booleans made again, not found made before
    seen = []
    sheet = regularize._sheet

    def noted(shell):
        found = sheet(shell)
        seen.append(found)
        return found

    monkeypatch.setattr(regularize, "_sheet", noted)
    skipped = []
    may = regularize._may_have_sheets

    def asked(manifold):
        answer = may(manifold)
        if not answer:
            found = [regularize._sheet(shell) for shell in adapter.decompose(manifold)]
            skipped.append(any(found))
        return answer

    monkeypatch.setattr(regularize, "_may_have_sheets", asked)
    (frame,) = frames_of(scene)
    assert any(seen)  # the scene does leave a sheet, and it is found
    assert not any(skipped)  # no result whose decomposition was skipped had one
    assert regularity_defects(frame) == []


def test_a_cavity_is_still_kept(monkeypatch):
    box = manifold3d.Manifold.cube([2, 2, 2]) - manifold3d.Manifold.cube([0.5] * 3).translate([0.5] * 3)
    solid = adapter.compose([box, *[_cube().manifold.translate([5 + 2 * k, 0, 0]) for k in range(5)]])
    calls = _decomposed(monkeypatch)
    assert regularize.regular(solid).volume() == pytest.approx(7.875 + 5, abs=1e-12)
    assert calls == []  # a cavity is a shell of negative volume, not a sheet
    assert regularize.regular(box).volume() == pytest.approx(7.875, abs=1e-12)


def test_a_slider_step_on_the_bus_shelter_checks_its_unions_at_once(monkeypatch):
    """The live preview's step (castor.serve.evaluation, caches kept): the
    unions whose operands the shelter's length changed go to the engine, each
    checked and regularized without a run looked at alone, the scene's unions
    of many shells (20, 28) without the engine's decomposition (no result of
    the scene has a sheet shell), and the unions it did not change are not
    made again."""
    from pathlib import Path

    from castor.mesh import booleans
    from castor.serve.evaluation import Watched, evaluate
    from castor.settings import EvaluationSettings, Source

    shelter = Path(__file__).resolve().parents[2] / "examples" / "bus_shelter.cas"

    def step(value):
        result = evaluate(Watched(Source((str(shelter),)),
                                  evaluation=EvaluationSettings(overrides={"LA": value}), quiet=True))
        assert result.errors == 0, result.printed

    step(5.0)
    calls = {"decompose": 0, "run by run": 0, "unions": 0}

    def counted(name, function):
        def call(*args):
            calls[name] += 1
            return function(*args)
        return call

    decompose = adapter.decompose
    monkeypatch.setattr(adapter, "decompose",
                        lambda m: calls.__setitem__("decompose", calls["decompose"] + (
                            m.num_tri() > 5000)) or decompose(m))
    monkeypatch.setattr(checks, "moved_planes", counted("run by run", checks.moved_planes))
    monkeypatch.setattr(booleans, "_united", counted("unions", booleans._united))
    step(5.35)
    # the shelter's posts, its frame, the shelter, the scene and the scene with the light
    assert 1 <= calls["unions"] <= 6
    assert calls["decompose"] == 0 and calls["run by run"] == 0
