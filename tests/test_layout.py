"""The package's design stays visible: no import cycles between femcheck modules (deferred imports inside
functions count too: a cycle hidden in a function is still a cycle), and the mesh builders and shared solvers live
in their own folders."""
from __future__ import annotations

from femcheck.provenance import PACKAGE, find_cycle, import_graph


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
