"""The import structure of the stratum package, read from its source with ast (nothing is
imported, so the Blender-only modules are covered too): no module imports itself through a
chain of others, and only the native binding imports ctypes.

An edge a -> b is any `import`, `from ... import` or relative import in a that names module b of
the package, at module level or inside a function (a deferred import still closes a cycle; it
only hides it until run time). `from pkg import name` is an edge to pkg.name when that is a
module, else to pkg. Parent packages are not edges: importing a.b runs a/__init__.py first,
but a package importing its own submodules is how packages are built, not a cycle.
"""

from __future__ import annotations

import ast
from collections.abc import Iterator, Mapping
from pathlib import Path

ADDON = Path(__file__).resolve().parents[2] / "addon"
PACKAGE = "stratum"
NATIVE = "stratum.native"


def module_name(path: Path) -> str:
    parts = path.relative_to(ADDON).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def package_modules() -> dict[str, Path]:
    return {module_name(path): path for path in sorted((ADDON / PACKAGE).rglob("*.py"))}


def imports(module: str, path: Path) -> Iterator[tuple[str, str | None]]:
    """(absolute module, imported name or None) for every import statement anywhere in the
    file: `import a.b` gives ("a.b", None), `from .x import y` ("<package>.x", "y")."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    for node in ast.walk(tree):  # every node: imports inside functions count too
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name, None
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                parts = package.split(".")
                base = ".".join(parts[:len(parts) - (node.level - 1)])
                if node.module:
                    base = f"{base}.{node.module}"
            else:
                base = node.module or ""
            for alias in node.names:
                yield base, alias.name


def import_graph(modules: Mapping[str, Path]) -> dict[str, set[str]]:
    """module -> the modules of the package it imports (see the module docstring)."""
    graph: dict[str, set[str]] = {}
    for module, path in modules.items():
        targets: set[str] = set()
        for base, name in imports(module, path):
            if name is not None and f"{base}.{name}" in modules:
                targets.add(f"{base}.{name}")
            elif base in modules:
                targets.add(base)
        graph[module] = targets
    return graph


def cycles(graph: Mapping[str, set[str]]) -> list[list[str]]:
    """One cycle [a, b, ..., a] per strongly connected component that has one (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    components: list[set[str]] = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for target in sorted(graph.get(node, ())):
            if target not in index:
                visit(target)
                low[node] = min(low[node], low[target])
            elif target in on_stack:
                low[node] = min(low[node], index[target])
        if low[node] == index[node]:
            component = set()
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.add(member)
                if member == node:
                    break
            components.append(component)

    for node in sorted(graph):
        if node not in index:
            visit(node)
    found = []
    for component in components:
        start = min(component)
        if len(component) > 1 or start in graph.get(start, ()):
            found.append(_path_back(graph, component, start))
    return found


def _path_back(graph: Mapping[str, set[str]], component: set[str], start: str) -> list[str]:
    """A shortest path start -> ... -> start inside the component (breadth first)."""
    previous: dict[str, str] = {}
    frontier = [start]
    while frontier:
        following = []
        for node in frontier:
            for target in sorted(graph.get(node, set()) & component):
                if target == start:
                    path = [node]
                    while path[-1] != start:
                        path.append(previous[path[-1]])
                    return [*reversed(path), start]
                if target not in previous:
                    previous[target] = node
                    following.append(target)
        frontier = following
    raise AssertionError(f"{start} is in a cycle without a path back to itself")


def test_cycle_finder_names_the_cycle() -> None:
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a", "d"}, "d": set(), "e": {"e"}}
    assert cycles(graph) == [["a", "b", "c", "a"], ["e", "e"]]
    assert cycles({"a": {"b"}, "b": set()}) == []


def test_graph_sees_relative_absolute_and_deferred_imports() -> None:
    """Known edges of each kind, so a parser that finds nothing cannot pass the cycle test."""
    graph = import_graph(package_modules())
    assert "stratum.native" in graph["stratum.cli"]  # from . import native
    assert "stratum.native.abi" in graph["stratum.native.library"]  # from .abi import ...
    assert "stratum.compare" in graph["stratum.cli"]  # deferred: from .compare import ...
    assert "stratum.compare.estimators" in graph["stratum.compare.blender_batch"]  # absolute
    assert "stratum.cli.blender_process" in graph["stratum.compare.runner"]  # from ..x import


def test_no_import_cycles() -> None:
    found = cycles(import_graph(package_modules()))
    assert not found, "import cycles in addon/stratum: " + "; ".join(
        " -> ".join(cycle) for cycle in found)


def test_only_the_native_package_imports_ctypes() -> None:
    offenders = sorted(
        module for module, path in package_modules().items()
        if module != NATIVE and not module.startswith(f"{NATIVE}.")
        and any(base == "ctypes" or base.startswith("ctypes.") for base, _ in imports(module, path)))
    assert not offenders, f"ctypes imported outside {NATIVE}: {', '.join(offenders)}"

