"""The package is laid out by stage, and imports run one way: a module never
imports from a later stage (STYLE.md). A newcomer's walk from the command
line to a vertex of the written frame passes through the folders in order."""

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent.parent / "castor"

# stage of each top-level module or folder, in pipeline order
STAGES = {
    "castor": 0, "castor.diagnostics": 0, "castor.options": 0, "castor.progress": 0,
    "castor.language": 1,
    "castor.csg": 2,
    "castor.mesh": 3, "castor.pictures": 3,
    "castor.formats": 4, "castor.drawings": 4, "castor.quantities": 4,
    "castor.jobs": 5, "castor.interpreter": 5,
    "castor.run": 6,
    "castor.cli": 7, "castor.serve": 7, "castor.view": 7, "castor.__main__": 7, "castor.lsp": 7,
}


def _stage(module: str) -> int:
    parts = module.split(".")
    for n in range(len(parts), 0, -1):
        name = ".".join(parts[:n])
        if name in STAGES:
            return STAGES[name]
    raise AssertionError(f"{module} belongs to no stage: add it to STAGES")


def _modules():
    for path in sorted(PACKAGE.rglob("*.py")):
        relative = path.relative_to(PACKAGE.parent).with_suffix("")
        name = ".".join(relative.parts).removesuffix(".__init__")
        yield name, path


def test_every_module_belongs_to_a_stage():
    for name, _ in _modules():
        _stage(name)


def test_imports_never_go_back_up_the_pipeline():
    wrong = []
    for name, path in _modules():
        here = _stage(name)
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                targets = [node.module]
            elif isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            else:
                continue
            for target in targets:
                if target.startswith("castor.") and _stage(target) > here:
                    wrong.append(f"{name} (stage {here}) imports {target} "
                                 f"(stage {_stage(target)})")
    assert wrong == []


def test_only_the_engine_imports_manifold3d():
    users = []
    for name, path in _modules():
        for node in ast.walk(ast.parse(path.read_text())):
            names = ([node.module] if isinstance(node, ast.ImportFrom) and node.module
                     else [a.name for a in node.names] if isinstance(node, ast.Import) else [])
            if any(n.split(".")[0] == "manifold3d" for n in names):
                users.append(name)
    assert sorted(set(users)) == ["castor.mesh.engine"]
