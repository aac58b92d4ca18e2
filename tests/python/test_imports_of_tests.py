"""What the tests import, read with ast from every Python file under tests/: no file imports
from a test module (test_*.py: helpers two tests share live in a helper module, such as
tests/blender/agreement.py), and none imports a private name (_name) of the stratum package
(a test calls what the module offers)."""

from __future__ import annotations

import ast
from pathlib import Path

TESTS = Path(__file__).resolve().parents[1]


def _imports(path: Path) -> list[tuple[int, str, list[str]]]:
    """(line, module, imported names) of every import statement, anywhere in the file."""
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), filename=str(path))):
        if isinstance(node, ast.Import):
            found += [(node.lineno, alias.name, []) for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            found.append((node.lineno, node.module, [alias.name for alias in node.names]))
    return found


def test_no_test_imports_a_test_module_or_a_private_name() -> None:
    offences = []
    for path in sorted(TESTS.rglob("*.py")):
        where = path.relative_to(TESTS.parent)
        for line, module, names in _imports(path):
            last = module.split(".")[-1]
            if last.startswith("test_") or module.split(".")[0] == "tests":
                offences.append(f"{where}:{line} imports the test module {module}")
            private = [n for n in names if n.startswith("_") and not n.startswith("__")]
            if module.split(".")[0] == "stratum" and private:
                offences.append(f"{where}:{line} imports {', '.join(private)} from {module}")
    assert not offences, "\n".join(offences)
