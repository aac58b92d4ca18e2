"""docs/architecture.md names every module and folder of the add-on: its listing (the code
block of "## The add-on") holds one line per path under addon/stratum/, and no path that is
not there, so a module added, moved or removed without its line fails here."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "addon" / "stratum"
DOC = ROOT / "docs" / "architecture.md"
# Built or generated, not source: the libraries (make build) and byte code.
NOT_SOURCE = {"lib", "__pycache__"}


def listed_paths(text: str) -> list[str]:
    """The first word of every line of the code block under "## The add-on"."""
    section = text.split("\n## The add-on\n", 1)[1].split("\n## ", 1)[0]
    block = re.search(r"^```\n(.*?)^```", section, re.DOTALL | re.MULTILINE)
    assert block is not None, "docs/architecture.md: no listing under '## The add-on'"
    return [line.split()[0] for line in block.group(1).splitlines() if line.strip()]


def source_paths() -> set[str]:
    """Every module, the manifest and every folder of the package, as paths under it
    (folders with a trailing slash)."""
    paths = {"lib/"}  # listed as the place the built libraries go
    for path in PACKAGE.rglob("*"):
        relative = path.relative_to(PACKAGE)
        if NOT_SOURCE & set(relative.parts):
            continue
        if path.is_dir():
            paths.add(f"{relative.as_posix()}/")
        elif path.suffix == ".py" or path.name == "blender_manifest.toml":
            paths.add(relative.as_posix())
    return paths


def test_listing_is_read() -> None:
    listed = listed_paths(DOC.read_text(encoding="utf-8"))
    assert "__init__.py" in listed and "shaders/nodes/compiler.py" in listed


def test_every_module_and_folder_is_listed_once() -> None:
    listed = listed_paths(DOC.read_text(encoding="utf-8"))
    repeated = sorted({p for p in listed if listed.count(p) > 1})
    assert not repeated, f"listed twice in docs/architecture.md: {repeated}"
    missing = sorted(source_paths() - set(listed))
    assert not missing, f"add a line to docs/architecture.md's add-on listing for: {missing}"
    stale = sorted(set(listed) - source_paths())
    assert not stale, f"docs/architecture.md lists paths addon/stratum/ does not have: {stale}"
