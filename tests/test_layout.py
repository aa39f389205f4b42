"""The package's design stays visible: no import cycles between femcheck modules (deferred imports inside
functions count too: a cycle hidden in a function is still a cycle), and the mesh builders and shared solvers live
in their own folders."""
from __future__ import annotations

import ast
from pathlib import Path

import femcheck

PACKAGE = Path(femcheck.__file__).parent


def _module_name(path: Path) -> str:
    rel = path.relative_to(PACKAGE.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def import_graph() -> dict[str, set[str]]:
    """Edges module -> femcheck modules it imports (absolute or relative, at any depth of the file)."""
    modules = {_module_name(p): p for p in PACKAGE.rglob("*.py")}
    graph: dict[str, set[str]] = {m: set() for m in modules}
    for name, path in modules.items():
        is_pkg = path.name == "__init__.py"
        package = name if is_pkg else name.rpartition(".")[0]
        for node in ast.walk(ast.parse(path.read_text())):
            targets: list[str] = []
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    anchor = package.split(".")[: len(package.split(".")) - (node.level - 1)]
                    base = ".".join(anchor + ([base] if base else []))
                targets = [base] + [f"{base}.{a.name}" for a in node.names]
            for t in targets:
                if t in modules and t != name and t != package:
                    graph[name].add(t)
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    colour: dict[str, int] = {}
    stack: list[str] = []

    def visit(n: str) -> list[str] | None:
        colour[n] = 1
        stack.append(n)
        for m in sorted(graph[n]):
            if colour.get(m) == 1:
                return stack[stack.index(m):] + [m]
            if m not in colour and (c := visit(m)):
                return c
        stack.pop()
        colour[n] = 2
        return None

    for n in sorted(graph):
        if n not in colour and (c := visit(n)):
            return c
    return None


def test_cycle_finder_sees_a_cycle():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) is None


def test_package_import_graph_has_no_cycle():
    graph = import_graph()
    assert "femcheck.cect.coulomb" in graph["femcheck.cect.exact"]       # the graph sees relative imports
    assert find_cycle(graph) is None, " -> ".join(find_cycle(graph))


def test_meshes_and_solvers_have_their_own_folders():
    fem_files = {p.name for p in (PACKAGE / "fem").glob("*.py")}
    assert not any(n.startswith("mesh") for n in fem_files)
    for name in ("elasticity2d", "elasticity3d", "frictionless", "coulomb", "rigid_indenter", "two_body",
                 "convergence"):
        assert (PACKAGE / "solvers" / f"{name}.py").is_file()
    graph = import_graph()
    for m, deps in graph.items():     # builders and shared solvers never depend on the FE models
        if m.startswith(("femcheck.meshes", "femcheck.solvers")):
            assert not any(d.startswith("femcheck.fem") for d in deps), (m, deps)
