"""The import structure of every Python file of the repository, read with ast (nothing is
imported, so the Blender-only files are covered too): no file imports itself through a chain of
others; and, in the add-on, only the native binding imports ctypes.

The files: every *.py git tracks or would track (`git ls-files --cached --others
--exclude-standard`): the add-on, scripts/, the tests and their helpers, scenes/' generators,
native/fuzz/tools/; the venv, build trees and out/ are ignored, as git ignores them.

Where an import leads. A file's root is the nearest folder above it that is not a package (has
no __init__.py): the first entry of sys.path when the file runs as a script, the folder pytest
puts first for a test file and its helpers (its "prepend" import mode), the folder a package
hangs from. Every process of the project also has two shared roots on its path: the repository
(the `scripts` package and, as namespace packages, the tests' folders: `python -m` from the
root, pytest.ini's pythonpath, scripts/run_in_blender.py) and addon/ (`stratum`: the venv's
editable install, Blender's add-on folder, the launcher). An absolute import a.b.c is looked for
as a/b/c.py or a/b/c/__init__.py under the file's root, then under the shared roots; a relative
one under the file's root only. A name found nowhere (the standard library, numpy, bpy, ...) is
no edge.

An edge f -> g is any `import`, `from ... import` or relative import in f that reaches g, at
module level or inside a function (a deferred import still closes a cycle; it only hides it
until run time). `from pkg import name` is an edge to pkg/name.py when that is a module, else to
pkg/__init__.py. Parent packages are not edges: importing a.b runs a/__init__.py first, but a
package importing its own submodules is how packages are built, not a cycle.
"""

from __future__ import annotations

import ast
import subprocess
from collections.abc import Iterable, Iterator, Mapping, Sequence
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
ADDON = REPO / "addon"
SHARED_ROOTS = (REPO, ADDON)
PACKAGE = "stratum"
NATIVE = "stratum.native"


def python_files(repo: Path = REPO) -> list[Path]:
    """Every *.py of the checkout that git tracks or would track (not the ignored ones)."""
    listed = subprocess.run(
        ["git", "-C", str(repo), "ls-files", "-z", "--cached", "--others", "--exclude-standard",
         "--", "*.py"], capture_output=True, check=True).stdout.decode()
    return sorted({repo / name for name in listed.split("\0") if name and (repo / name).is_file()})


def import_root(path: Path) -> Path:
    """The nearest folder above `path` without an __init__.py (see the module docstring)."""
    folder = path.parent
    while (folder / "__init__.py").is_file():
        folder = folder.parent
    return folder


def module_parts(path: Path, root: Path) -> list[str]:
    """The dotted name of `path` under `root`, as parts (a package is its folder)."""
    parts = list(path.relative_to(root).with_suffix("").parts)
    return parts[:-1] if parts[-1] == "__init__" else parts


def imports(path: Path) -> Iterator[tuple[int, str, str | None]]:
    """(level, module, imported name or None) for every import statement anywhere in the file:
    `import a.b` gives (0, "a.b", None), `from ..x import y` (2, "x", "y"), `from . import z`
    (1, "", "z")."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    for node in ast.walk(tree):  # every node: imports inside functions count too
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield 0, alias.name, None
        elif isinstance(node, ast.ImportFrom):
            for alias in node.names:
                yield node.level, node.module or "", alias.name


def resolve(name: str, roots: Iterable[Path], files: set[Path]) -> Path | None:
    """The file the dotted `name` is under the first root that has it, if one does."""
    if not name:
        return None
    for root in roots:
        base = root.joinpath(*name.split("."))
        for candidate in (base.with_name(base.name + ".py"), base / "__init__.py"):
            if candidate in files:
                return candidate
    return None


def import_graph(files: Sequence[Path], shared_roots: Sequence[Path] = SHARED_ROOTS,
                 top: Path = REPO) -> dict[str, set[str]]:
    """file -> the files it imports (see the module docstring), each named by its path under
    `top`."""
    known = set(files)
    graph: dict[str, set[str]] = {}
    for path in files:
        root = import_root(path)
        own = module_parts(path, root)
        package = own if path.name == "__init__.py" else own[:-1]
        targets: set[str] = set()
        for level, module, name in imports(path):
            if level:
                if level - 1 > len(package):
                    continue  # above the top package: Python refuses it, nothing is imported
                base = ".".join(package[:len(package) - (level - 1)] + ([module] if module else []))
                roots: Sequence[Path] = (root,)
            else:
                base, roots = module, (root, *shared_roots)
            target = None
            if name is not None and name != "*":
                target = resolve(f"{base}.{name}" if base else name, roots, known)
            if target is None:
                target = resolve(base, roots, known)
            if target is not None:
                targets.add(target.relative_to(top).as_posix())
        graph[path.relative_to(top).as_posix()] = targets
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


def _write(top: Path, files: Mapping[str, str]) -> list[Path]:
    for name, text in files.items():
        (top / name).parent.mkdir(parents=True, exist_ok=True)
        (top / name).write_text(text)
    return sorted(top / name for name in files)


def test_cycle_finder_names_the_cycle() -> None:
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a", "d"}, "d": set(), "e": {"e"}}
    assert cycles(graph) == [["a", "b", "c", "a"], ["e", "e"]]
    assert cycles({"a": {"b"}, "b": set()}) == []


def test_graph_follows_every_kind_of_import(tmp_path: Path) -> None:
    """Known edges of each kind on a synthetic tree, so a parser or resolver that finds
    nothing cannot pass the cycle test: relative, absolute, deferred, `from pkg import module`
    and `from pkg import name`, a script's own folder, a shared root, namespace packages."""
    files = _write(tmp_path, {
        "app/pkg/__init__.py": "from . import sub\n",
        "app/pkg/sub.py": "def f():\n    from .deep import thing\n    return thing\n",
        "app/pkg/deep.py": "import json\nimport os\nthing = 1\n",
        "app/runner.py": "import pkg.sub\nfrom helper import x\n",
        "app/helper.py": "from pkg import sub\nfrom pkg import __doc__ as x\n",
        "lib/shared/__init__.py": "VALUE = 1\n",
        "app/uses_shared.py": "from shared import VALUE\nimport numpy\n",
        "tools/ns/inner/mod.py": "y = 2\n",
        "tools/run.py": "from tools.ns.inner.mod import y\n",
    })
    graph = import_graph(files, shared_roots=(tmp_path, tmp_path / "lib"), top=tmp_path)
    assert graph == {
        "app/pkg/__init__.py": {"app/pkg/sub.py"},
        "app/pkg/sub.py": {"app/pkg/deep.py"},
        "app/pkg/deep.py": set(),
        "app/runner.py": {"app/pkg/sub.py", "app/helper.py"},
        "app/helper.py": {"app/pkg/sub.py", "app/pkg/__init__.py"},
        "lib/shared/__init__.py": set(),
        "app/uses_shared.py": {"lib/shared/__init__.py"},
        "tools/ns/inner/mod.py": set(),
        "tools/run.py": {"tools/ns/inner/mod.py"},
    }


def test_a_deferred_circle_across_folders_is_found(tmp_path: Path) -> None:
    """The shape of the circle study/figures -> summary -> radiosity -> figures once had, one of
    its imports deferred into a function: found, and named."""
    files = _write(tmp_path, {
        "scripts/__init__.py": "",
        "scripts/study/__init__.py": "",
        "scripts/study/figures.py": "from scripts.study.summary import fmt\n",
        "scripts/study/summary.py": "import scripts.study.radiosity\n",
        "scripts/study/radiosity.py": "def figure():\n    from scripts.study.figures import x\n",
    })
    found = cycles(import_graph(files, shared_roots=(tmp_path,), top=tmp_path))
    assert found == [["scripts/study/figures.py", "scripts/study/summary.py",
                      "scripts/study/radiosity.py", "scripts/study/figures.py"]]


def test_every_part_of_the_repository_is_read() -> None:
    """The files found reach into each part that holds Python, and each part's imports of its
    own modules are followed (so a part the resolver misses cannot pass for circle-free)."""
    graph = import_graph(python_files())
    for part in ("addon/stratum/", "scripts/", "tests/", "scenes/", "native/fuzz/"):
        files = [name for name in graph if name.startswith(part)]
        assert files, f"no Python file found under {part}"
        assert any(graph[name] for name in files), f"no import followed under {part}"


def test_no_import_cycles() -> None:
    found = cycles(import_graph(python_files()))
    assert not found, "import cycles: " + "; ".join(" -> ".join(cycle) for cycle in found)


def package_modules() -> dict[str, Path]:
    """The add-on's modules by dotted name."""
    return {".".join(module_parts(path, ADDON)): path
            for path in sorted((ADDON / PACKAGE).rglob("*.py"))}


def test_only_the_native_package_imports_ctypes() -> None:
    offenders = sorted(
        module for module, path in package_modules().items()
        if module != NATIVE and not module.startswith(f"{NATIVE}.")
        and any(level == 0 and (name == "ctypes" or name.startswith("ctypes."))
                for level, name, _ in imports(path)))
    assert not offenders, f"ctypes imported outside {NATIVE}: {', '.join(offenders)}"
