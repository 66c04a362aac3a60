"""The package is laid out by stage, and imports run one way: a module never
imports from a later stage (STYLE.md). A newcomer's walk from the command
line to a vertex of the written frame passes through the folders in order."""

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "castor"

# stage of each top-level module or folder, in pipeline order
STAGES = {
    "castor": 0, "castor.diagnostics": 0, "castor.progress": 0,
    "castor.settings": 0,
    "castor.language": 1, "castor.primitives": 1, "castor.transformations": 1, "castor.booleans": 1,
    "castor.csg": 2,
    "castor.mesh": 3, "castor.pictures": 3,
    "castor.formats": 4, "castor.drawings": 4, "castor.quantities": 4, "castor.bim": 4,
    "castor.jobs": 5, "castor.interpreter": 5,
    "castor.pipeline": 6, "castor.run": 6, "castor.failures": 6, "castor.editing": 6,
    # the command lines: castor.options parses their text into castor.settings' records
    "castor.cli": 7, "castor.options": 7, "castor.serve": 7, "castor.view": 7,
    "castor.__main__": 7, "castor.lsp": 7, "castor.supervisor": 7,
    "castor.analysis": 7,
}


# An import up the pipeline made on purpose, inside the one function that needs
# it: an extrusion's caps are triangulated by the engine's adapter (the only
# module that calls manifold3d), and its mesh is built only by the facetizer.
LATE_IMPORTS = {("castor.primitives.extrusion", "castor.mesh.adapter")}


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
                if target.startswith("castor.") and _stage(target) > here \
                        and (name, target) not in LATE_IMPORTS:
                    wrong.append(f"{name} (stage {here}) imports {target} "
                                 f"(stage {_stage(target)})")
    assert wrong == []


def _imported(name: str, path: Path, node) -> list[str]:
    """The castor modules an import statement names (a name imported from a
    package is its submodule if there is one, else the package)."""
    if isinstance(node, ast.Import):
        return [a.name for a in node.names if a.name.split(".")[0] == "castor"]
    base = node.module or ""
    if node.level:  # relative: from the module's own package
        package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
        for _ in range(node.level - 1):
            package = package.rsplit(".", 1)[0]
        base = f"{package}.{base}" if base else package
    if base.split(".")[0] != "castor":
        return []
    modules = {m for m, _ in _modules()}
    return [f"{base}.{a.name}" if f"{base}.{a.name}" in modules else base for a in node.names]


def _import_graph() -> dict[str, set[str]]:
    """Each castor module -> the castor modules it imports, at module level or
    inside a function (both run, and a cycle through either is a cycle)."""
    modules = dict(_modules())
    graph = {}
    for name, path in modules.items():
        targets = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, (ast.Import, ast.ImportFrom)):
                for target in _imported(name, path, node):
                    while target not in modules and "." in target:
                        target = target.rsplit(".", 1)[0]
                    if target != name and target in modules:
                        targets.add(target)
        graph[name] = targets
    return graph


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected groups of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            group = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                group.append(w)
                if w == v:
                    break
            if len(group) > 1:
                found.append(sorted(group))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found





def test_no_import_cycle():
    cycles = _cycles(_import_graph())
    assert cycles == []


def test_a_cycle_is_seen():
    """The check itself can fail: a cycle through a function-level import."""
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert _cycles(graph) == [["a", "b", "c"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []


def test_the_mesh_stage_imports_its_primitives_without_a_cycle():
    graph = _import_graph()
    assert "castor.mesh.adapter" in graph["castor.primitives.extrusion"]  # its caps
    assert graph["castor.mesh.adapter"] == set()  # the adapter depends on nothing of castor


def test_only_the_adapter_imports_manifold3d():
    users = []
    for name, path in _modules():
        for node in ast.walk(ast.parse(path.read_text())):
            names = ([node.module] if isinstance(node, ast.ImportFrom) and node.module
                     else [a.name for a in node.names] if isinstance(node, ast.Import) else [])
            if any(n.split(".")[0] == "manifold3d" for n in names):
                users.append(name)
    assert sorted(set(users)) == ["castor.mesh.adapter"]


# Lines a module may hold: one concept per module, a file one can hold in
# one's head (STYLE.md). EXCEPTIONS would list a module that must stay larger,
# and why; none must.
MAX_LINES = 600
CHECKED_FOR_SIZE = ["castor"]
EXCEPTIONS: dict[str, str] = {}


def test_no_module_is_over_600_lines():
    large = []
    for name, path in _modules():
        if not any(name == p or name.startswith(p + ".") for p in CHECKED_FOR_SIZE):
            continue
        lines = len(path.read_text().splitlines())
        if lines > MAX_LINES and name not in EXCEPTIONS:
            large.append(f"{name}: {lines} lines")
    assert large == []


def test_the_mesh_stage_has_one_module_per_concept():
    """The modules issue 17 names, each where a newcomer looks for it."""
    names = {name for name, _ in _modules()}
    for concept in ["adapter", "instances", "provenance", "broadphase", "booleans",
                    "regularize", "merge", "arrays", "caches", "facetize"]:
        assert f"castor.mesh.{concept}" in names
    assert "castor.mesh.engine" not in names and "castor.mesh.polygons" not in names
