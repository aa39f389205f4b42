"""Keys of cached results and stored references are derived from the imports (femcheck.provenance), so they
change whenever any code under a model changes, and only then."""
from __future__ import annotations

import json
import shutil
import subprocess
import sys

import pytest

from femcheck import provenance
from femcheck.problems import KINDS, problem
from femcheck.runner import model_modules
from femcheck.scene import load_scene


@pytest.fixture
def package_copy(tmp_path, monkeypatch):
    """A private copy of the package source that provenance reads instead of the installed one."""
    root = tmp_path / "femcheck"
    shutil.copytree(provenance.PACKAGE, root, ignore=shutil.ignore_patterns("__pycache__"))
    monkeypatch.setattr(provenance, "PACKAGE", root)
    provenance._closure.cache_clear()
    provenance._graph_cached.cache_clear()
    yield root
    provenance._closure.cache_clear()
    provenance._graph_cached.cache_clear()


def test_closure_follows_relative_deferred_and_parent_imports():
    c = provenance.closure(["femcheck.fem.srb_conformal"])
    # the modules the hand-written list of the conformal SRB reference missed (issue 12, finding 1)
    assert {"femcheck.meshes.block", "femcheck.meshes.plane", "femcheck.meshes.srb_segments",
            "femcheck.solvers.two_body", "femcheck.geometry.srb", "femcheck.fem"} <= set(c)
    assert "femcheck" not in c and "femcheck.runner" not in c and "femcheck.report.html" not in c
    # imports inside functions (the kinds load their heavy models lazily) are part of the closure too
    assert "femcheck.ehl.adapter" in provenance.closure(["femcheck.problems.ehl_contact"])
    assert {"femcheck.fem.bearing2d", "femcheck.bem.bearing_condensed"} <= \
        set(provenance.closure(["femcheck.problems.bearing_load"]))


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_every_stored_model_keys_its_adapter_and_scene_code(kind):
    prob = problem(kind)
    for name in prob.DEPENDS:
        c = set(provenance.closure(model_modules(type("S", (), {"kind": kind})(), name)))
        assert prob.__name__ in c and "femcheck.scene" in c and "femcheck.result" in c


@pytest.mark.slow
def test_key_changes_with_code_below_the_model_and_only_there(package_copy):
    roots = ("femcheck.fem.srb_conformal",)
    before = provenance.code_digest(roots)
    report = package_copy / "report" / "html.py"
    report.write_text(report.read_text() + "\n# unrelated\n")
    provenance._closure.cache_clear(); provenance._graph_cached.cache_clear()
    assert provenance.code_digest(roots) == before
    plane = package_copy / "meshes" / "plane.py"             # two imports below the model
    src = plane.read_text()
    # documentation is not code: a docstring and a comment edited leave the key alone
    doc = src.replace('"""', '"""Edited. ', 1).replace("# ", "# edited ", 1)
    assert doc != src
    plane.write_text(doc)
    assert provenance.code_digest(roots) == before
    plane.write_text(src.replace("import gmsh", "import gmsh as gmsh", 1))      # a statement changed
    assert provenance.code_digest(roots) != before


def test_code_text_drops_documentation_only():
    src = ('"""Module doc."""\nimport numpy as np  # why\n\n\nclass A:\n    """Class doc,\n    two lines."""\n'
           '    x = "not a docstring"  # trailing\n\n    def f(self):\n        """f doc."""\n        return 1\n')
    assert provenance.code_text(src) == ('import numpy as np\nclass A:\n    x = "not a docstring"\n'
                                         '    def f(self):\n        return 1')
    assert provenance.code_text(src.replace("return 1", "return 2")) != provenance.code_text(src)


@pytest.mark.slow
def test_key_changes_with_a_new_import(package_copy):
    roots = ("femcheck.fem.point_contact",)
    before = set(provenance.closure(roots))
    assert "femcheck.bem.layered" not in before
    f = package_copy / "fem" / "point_contact.py"
    f.write_text(f.read_text().replace("from __future__ import annotations\n",
                                       "from __future__ import annotations\n\nfrom ..bem import layered\n", 1))
    provenance._closure.cache_clear(); provenance._graph_cached.cache_clear()
    assert "femcheck.bem.layered" in provenance.closure(roots)


def test_key_changes_with_library_versions(monkeypatch):
    roots = ("femcheck.meshes.block",)
    before = provenance.code_digest(roots)
    real = provenance.library_versions()
    monkeypatch.setattr(provenance, "library_versions", lambda: {**real, "gmsh": "0.0.0"})
    assert provenance.code_digest(roots) != before


@pytest.mark.slow
def test_static_closure_covers_every_module_a_model_loads():
    """Run the hertz-line FE model (coarse levels) in a fresh interpreter and list the femcheck modules it loaded:
    each must be in the static closure its key hashes."""
    code = (
        "import json, sys\n"
        "from femcheck.scene import load_scene\n"
        "from femcheck.problems import problem\n"
        "sc = load_scene('hertz-line', {'numerics.fem_levels': 2})\n"
        "problem(sc.kind).MODELS['fem'](sc, None)\n"
        "print(json.dumps(sorted(m for m in sys.modules if m.startswith('femcheck'))))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    loaded = set(json.loads(out.stdout.strip().splitlines()[-1])) - {"femcheck"}
    sc = load_scene("hertz-line")
    static = set(provenance.closure(model_modules(sc, "fem")))
    assert loaded <= static, sorted(loaded - static)


def test_mesh_cache_reads_back_and_rebuild_bypasses_it(tmp_path, monkeypatch):
    from dataclasses import dataclass

    from femcheck.meshes import cache as mesh_cache

    monkeypatch.setenv("FEMCHECK_CACHE", str(tmp_path))

    @dataclass
    class Spec:
        h: float

    builds = []

    def build():
        builds.append(1)
        return f"mesh {len(builds)}"

    def read(path):
        return path.read_text()

    def write(mesh, path):
        with open(path, "w") as fh:
            fh.write(mesh)

    args = ("toy", Spec(0.1), "femcheck.meshes.plane", ".txt", build, read, write)
    assert mesh_cache.cached(*args) == "mesh 1"
    assert mesh_cache.cached(*args) == "mesh 1" and len(builds) == 1          # read back
    with mesh_cache.rebuilding():
        assert mesh_cache.cached(*args) == "mesh 2"                           # --rebuild meshes again
    assert mesh_cache.cached(*args) == "mesh 2" and len(builds) == 2          # and stores the new one
    assert mesh_cache.mesh_key("toy", Spec(0.1), "femcheck.meshes.plane") != \
        mesh_cache.mesh_key("toy", Spec(0.1), "femcheck.meshes.block")        # the builder's code is in the key
