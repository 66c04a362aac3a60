"""The pipeline as a library: the same function under castor, the live preview and
an editor, called with settings objects, writing nothing unless asked."""

import ast
import io
from pathlib import Path

import pytest

from castor.diagnostics import Reporter
from castor.pipeline import Overtaken, check, evaluate, frames
from castor.settings import (EvaluationSettings, FrameSettings, MeshSettings, OutputSettings,
                             ReadSettings, RunSettings, Source)

PACKAGE = Path(__file__).resolve().parents[2] / "castor"

SCENE = """L = 2;
boite = @h(L, 1, 1) !cu(1, 1, 1);
> boite;
> inconnu;
> @t(3, 0, 0) boite;
"""


def test_check_gives_a_buffers_diagnostics_and_frames_and_writes_nothing(tmp_path,
                                                                          monkeypatch):
    monkeypatch.chdir(tmp_path)
    checked = check(SCENE, str(tmp_path / "buffer.cas"))
    assert [(d.kind, d.location.line, d.location.column) for d in checked.diagnostics] == [
        ("error", 4, 3)]
    assert "'inconnu' is not defined" in checked.diagnostics[0].message
    assert checked.diagnostics[0].text == "> inconnu;"
    assert [tree.number for tree in checked.trees] == [1, 2]
    assert checked.meshes == ()  # evaluated only: no facetizing unless asked
    assert checked.errors == 1
    assert "buffer.cas:4:3: error:" in checked.printed
    assert list(tmp_path.iterdir()) == []


def test_check_with_mesh_settings_facetizes_each_frame():
    checked = check(SCENE, "buffer.cas", mesh=MeshSettings())
    assert [m.polygon_count for m in checked.meshes] == [6, 6]
    low = checked.meshes[1].objects[0].vertices.min(axis=0)
    assert low.tolist() == [3.0, 0.0, 0.0]
    limited = check(SCENE, "buffer.cas", mesh=MeshSettings(max_polygons=3))
    assert limited.meshes == () and limited.errors == 3  # the unknown object, two refusals


def test_the_settings_of_evaluation_and_reading_reach_their_stages():
    checked = check(SCENE.replace("> inconnu;\n", ""), "b.cas",
                    evaluation=EvaluationSettings(overrides={"L": 5.0}), mesh=MeshSettings())
    assert checked.meshes[0].objects[0].vertices.max(axis=0)[0] == 5.0
    text = "L = 1;\n#ifdef LONG\nL = WIDTH;\n#endif\n> @h(L, 1, 1) !cu(1, 1, 1);\n"
    checked = check(text, "d.cas", reading=ReadSettings(defines=("LONG", "WIDTH=7")),
                    mesh=MeshSettings())
    assert checked.errors == 0, checked.printed
    assert checked.meshes[0].objects[0].vertices.max(axis=0)[0] == 7.0


def test_a_file_and_the_same_text_in_memory_give_the_same_trees(tmp_path):
    from castor.csg import tree

    path = tmp_path / "scene.cas"
    path.write_text(SCENE)
    trees = []
    reporter = Reporter(stream=io.StringIO())
    interpreter = evaluate(Source((str(path),)), reporter, trees.append)
    assert interpreter.frames_attempted == 2 and reporter.errors == 1  # one frame refused
    in_memory = check(SCENE, str(path)).trees
    assert [tree.dump(t) for t in trees] == [tree.dump(t) for t in in_memory]


def test_an_unreadable_file_is_a_diagnostic_for_the_preview_and_a_usage_error_for_castor(
        tmp_path):
    from castor.diagnostics import UsageError

    missing = str(tmp_path / "missing.cas")
    checked = frames(Source((missing,)))
    assert [d.message for d in checked.diagnostics] == [
        f"cannot read '{missing}': No such file or directory"]
    with pytest.raises(UsageError, match="cannot read"):
        evaluate(Source((missing,)), Reporter(stream=io.StringIO()), None)


def test_cancelled_stops_the_evaluation():
    asked = []

    def cancelled():
        asked.append(1)
        return len(asked) > 2

    with pytest.raises(Overtaken):
        check(SCENE, "b.cas", mesh=MeshSettings(), cancelled=cancelled)


def test_run_takes_settings_and_writes_the_format_asked(tmp_path):
    import trimesh

    from castor.run import run

    scene = tmp_path / "scene.cas"
    scene.write_text("> @h(2, 3, 4) !cu(1, 1, 1);\n")
    target = tmp_path / "box.stl"
    stream = io.StringIO()
    status = run(Source((str(scene),)), Reporter(stream=stream),
                 settings=FrameSettings(OutputSettings(format="stl", target=str(target))),
                 how=RunSettings())
    assert status == 0, stream.getvalue()
    assert trimesh.load_mesh(str(target)).volume == pytest.approx(24.0)
    assert run(Source((str(scene),)), Reporter(stream=stream),
               settings=FrameSettings(OutputSettings(format="stl", target=str(tmp_path / "c.stl"))),
               how=RunSettings(check=True)) == 0
    assert not (tmp_path / "c.stl").exists()  # --check writes nothing


def _imports(path: Path) -> set[str]:
    names = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.module:
            names.add(node.module)
        elif isinstance(node, ast.Import):
            names.update(a.name for a in node.names)
    return names


def test_no_module_of_the_library_imports_the_command_line():
    importers = sorted(str(path.relative_to(PACKAGE)) for path in PACKAGE.rglob("*.py")
                       if "castor.cli" in _imports(path))
    assert importers == ["__main__.py"]


def test_usage_error_status_and_stack_size_are_defined_once():
    defined: dict[str, list[str]] = {"USAGE_ERROR": [], "STACK_BYTES": [], "Job": []}
    for path in PACKAGE.rglob("*.py"):
        for node in ast.parse(path.read_text()).body:
            names = ([t.id for t in node.targets if isinstance(t, ast.Name)]
                     if isinstance(node, ast.Assign) else
                     [node.name] if isinstance(node, ast.ClassDef) else [])
            for name in names:
                if name.lstrip("_") in defined:
                    defined[name.lstrip("_")].append(str(path.relative_to(PACKAGE)))
    assert defined == {"USAGE_ERROR": ["diagnostics.py"], "STACK_BYTES": ["settings.py"],
                       "Job": ["jobs.py"]}
