"""The package's design stays visible: no import cycles between femcheck modules (deferred imports inside
functions count too: a cycle hidden in a function is still a cycle), the mesh builders and shared solvers live
in their own folders, and no module grows above 500 lines without saying why."""
from __future__ import annotations

import ast

from femcheck.provenance import PACKAGE, find_cycle, import_graph

MAX_LINES = 500


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


def long_modules_without_reason(root=PACKAGE, limit: int = MAX_LINES) -> list[str]:
    """Modules above ``limit`` lines whose docstring does not say why (a sentence naming the limit:
    "... above 500 lines because ...")."""
    out = []
    for path in sorted(root.rglob("*.py")):
        text = path.read_text()
        if len(text.splitlines()) > limit:
            doc = ast.get_docstring(ast.parse(text)) or ""
            if f"{limit} lines" not in doc:
                out.append(f"{path.relative_to(root.parent)}: {len(text.splitlines())} lines")
    return out


def test_no_long_module_without_a_reason(tmp_path):
    # the check sees a long module without a reason, and accepts one with a reason
    (tmp_path / "long.py").write_text('"""A module."""\n' + "x = 1\n" * 600)
    (tmp_path / "ok.py").write_text('"""A module: above 500 lines because of X."""\n' + "x = 1\n" * 600)
    assert long_modules_without_reason(tmp_path) == [f"{tmp_path.name}/long.py: 601 lines"]
    assert long_modules_without_reason() == []
