"""What determines a computed result: the femcheck source it runs and the library versions under it.

Cache and reference keys (:mod:`femcheck.cache`, :mod:`femcheck.references`) and the mesh cache
(:mod:`femcheck.meshes.cache`) hash the source of every femcheck module a model imports, *transitively*, found
by reading the import statements of the package (absolute and relative, at module level and inside functions),
plus the versions of the numerical libraries. Nothing is listed by hand, so a module added to a model's imports,
or a change anywhere below it, changes the key. The graph is static: a module loaded by name at run time
(``importlib.import_module``) is not seen; femcheck uses that only to pick a problem kind, whose module is a
root of every key anyway. The root package ``femcheck/__init__.py`` is not followed: it is the public facade
(``femcheck.run`` imports the runner, hence everything) and holds no numerics.
"""
from __future__ import annotations

import ast
import hashlib
import io
import tokenize
from functools import lru_cache
from importlib import metadata
from pathlib import Path
from typing import Iterable

PACKAGE = Path(__file__).resolve().parent
ROOT = PACKAGE.name
# Libraries whose numerics enter FE/mesh results (the key changes with their version).
LIBRARIES = ("numpy", "scipy", "scikit-fem", "gmsh", "pyamg", "meshio")


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def module_files() -> dict[str, Path]:
    """femcheck module name -> source file."""
    return {_module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def _imports(name: str, path: Path, modules: dict[str, Path]) -> set[str]:
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text())):
        targets: list[str] = []
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = package.split(".")
                anchor = parts[: len(parts) - (node.level - 1)]
                base = ".".join(anchor + ([base] if base else []))
            targets = [base] + [f"{base}.{a.name}" for a in node.names]
        for t in targets:
            # importing a.b.c runs a/__init__ and a/b/__init__ too
            pieces = t.split(".")
            for i in range(1, len(pieces) + 1):
                mod = ".".join(pieces[:i])
                if mod in modules and mod != name and mod != ROOT:
                    found.add(mod)
    return found


def import_graph() -> dict[str, set[str]]:
    """Edges module -> the femcheck modules it imports (parent packages included, as Python runs them)."""
    modules = module_files()
    return {name: _imports(name, path, modules) for name, path in modules.items()}


def closure(roots: Iterable[str]) -> list[str]:
    """Every femcheck module reachable from ``roots`` through imports, the roots included, sorted."""
    return sorted(_closure(tuple(sorted(set(roots)))))


@lru_cache(maxsize=None)
def _closure(roots: tuple[str, ...]) -> frozenset[str]:
    graph = _graph_cached()
    unknown = [r for r in roots if r not in graph]
    if unknown:
        raise KeyError(f"not femcheck modules: {unknown}")
    seen: set[str] = set()
    todo = list(roots)
    while todo:
        m = todo.pop()
        if m not in seen:
            seen.add(m)
            todo.extend(graph[m] - seen)
            parent = m.rpartition(".")[0]           # a module's packages run before it
            if parent and parent != ROOT:
                todo.append(parent)
    return frozenset(seen)


@lru_cache(maxsize=1)
def _graph_cached() -> dict[str, set[str]]:
    return import_graph()


def library_versions() -> dict[str, str]:
    out = {}
    for lib in LIBRARIES:
        try:
            out[lib] = metadata.version(lib)
        except metadata.PackageNotFoundError:
            out[lib] = "absent"
    return out


def code_text(source: str) -> str:
    """The part of a module's source that can change what it computes: the source with its docstrings (module,
    class and function), comments, trailing blanks and blank lines removed. Keys hash this, so editing
    documentation does not make stored references stale; a change to any statement, name or literal does.
    Docstring positions come from :mod:`ast` and comments from :mod:`tokenize`, both stable across Python
    versions (the text hashed is the source itself, not a version-dependent AST dump)."""
    lines = source.splitlines()
    blank: dict[int, list[tuple[int, int]]] = {}        # 0-based line -> character ranges to drop

    def drop(r0: int, c0: int, r1: int, c1: int) -> None:       # 1-based rows, character columns
        for r in range(r0, r1 + 1):
            blank.setdefault(r - 1, []).append((c0 if r == r0 else 0, c1 if r == r1 else len(lines[r - 1])))

    def chars(row: int, byte_col: int) -> int:          # ast columns are UTF-8 byte offsets
        return len(lines[row - 1].encode()[:byte_col].decode(errors="ignore"))

    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and node.body:
            d = node.body[0]
            if isinstance(d, ast.Expr) and isinstance(d.value, ast.Constant) and isinstance(d.value.value, str):
                drop(d.lineno, chars(d.lineno, d.col_offset), d.end_lineno, chars(d.end_lineno, d.end_col_offset))
    for tok in tokenize.generate_tokens(io.StringIO(source).readline):
        if tok.type == tokenize.COMMENT:
            drop(tok.start[0], tok.start[1], tok.end[0], tok.end[1])
    out = []
    for i, line in enumerate(lines):
        for c0, c1 in sorted(blank.get(i, []), reverse=True):
            line = line[:c0] + line[c1:]
        if line.strip():
            out.append(line.rstrip())
    return "\n".join(out)


@lru_cache(maxsize=None)
def _code_text_of(path: str, mtime_ns: int, size: int) -> str:
    """:func:`code_text` of a file, cached while the file is unchanged (stat in the key)."""
    return code_text(Path(path).read_text(encoding="utf-8"))


def code_digest(roots: Iterable[str]) -> str:
    """sha256 over the module names and :func:`code_text` of ``closure(roots)`` and the library versions."""
    files = module_files()
    h = hashlib.sha256()
    for m in closure(roots):
        h.update(m.encode())
        st = files[m].stat()
        h.update(_code_text_of(str(files[m]), st.st_mtime_ns, st.st_size).encode())
    for lib, version in sorted(library_versions().items()):
        h.update(f"{lib}={version}".encode())
    return h.hexdigest()


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One import cycle of ``graph`` as [a, b, ..., a], or None (depth-first search)."""
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
