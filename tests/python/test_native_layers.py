"""The native library's folders form one-way layers (docs/architecture.md): a file may include
files of its own folder and of lower layers only, never of a higher layer or of a peer in its
own layer, and only the C ABI folder (`api`) includes the public header. This test reads every
`#include "..."` of native/src and fails naming each include that runs against the order, so
the picture in docs/architecture.md stays true."""

from __future__ import annotations

import re
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
SOURCES = REPO / "native" / "src"
NATIVE_TESTS = REPO / "tests" / "native"
TEST_HELPERS = "helpers"  # tests/native/helpers: the headers the native tests share
ARCHITECTURE = REPO / "docs" / "architecture.md"

# Lowest first; folders on one line are peers (neither includes the other).
LAYERS: list[tuple[str, ...]] = [
    ("core",),
    ("sampling", "texture", "accel", "guiding"),
    ("shading",),
    ("scene",),
    ("bsdf", "lights"),
    ("render_scene",),
    ("film", "radiosity"),
    ("integrators",),
    ("render",),
    ("api",),
]
PUBLIC_HEADER = "stratum"  # native/include/stratum/stratum.h
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)


def _layer_of() -> dict[str, int]:
    return {folder: rank for rank, peers in enumerate(LAYERS) for folder in peers}


def _includes() -> list[tuple[Path, str]]:
    found = []
    for path in sorted(SOURCES.rglob("*")):
        if path.suffix in (".h", ".cpp"):
            found += [(path, include) for include in INCLUDE.findall(path.read_text())]
    return found


def test_every_native_folder_has_a_layer() -> None:
    folders = {p.name for p in SOURCES.iterdir() if p.is_dir()}
    assert folders == set(_layer_of()), (
        f"folders without a layer: {sorted(folders - set(_layer_of()))}; "
        f"layers without a folder: {sorted(set(_layer_of()) - folders)}")


def test_no_include_runs_against_the_layers() -> None:
    rank = _layer_of()
    back_edges = []
    for path, include in _includes():
        source = path.relative_to(SOURCES).parts[0]
        target = include.split("/")[0]
        if target == source:
            continue
        if target == PUBLIC_HEADER:
            if source != "api":
                back_edges.append(f"{path.relative_to(REPO)} includes the public header {include}")
            continue
        assert target in rank, f"{path.relative_to(REPO)} includes {include} outside native/src"
        if rank[target] >= rank[source]:
            kind = "a peer" if rank[target] == rank[source] else "a higher layer"
            back_edges.append(f"{path.relative_to(REPO)} includes {include} ({kind})")
    assert not back_edges, "includes against the layers:\n" + "\n".join(back_edges)


def test_the_architecture_page_draws_these_layers() -> None:
    """docs/architecture.md's layer line lists the same order (so the two change together)."""
    text = ARCHITECTURE.read_text()
    expected = " → ".join(", ".join(peers) for peers in LAYERS)
    assert expected in text, f"docs/architecture.md does not show the layer order: {expected}"


def test_native_tests_are_filed_under_the_layers() -> None:
    """tests/native mirrors native/src: each test file sits in the folder of the layer whose
    code it tests (tests/native/<layer>/test_*.cpp), the headers they share in helpers/."""
    layers = set(_layer_of())
    misplaced = []
    for path in sorted(NATIVE_TESTS.rglob("*")):
        if path.is_dir():
            continue
        parts = path.relative_to(NATIVE_TESTS).parts
        folder = parts[0] if len(parts) == 2 else None
        if path.suffix == ".cpp" and folder not in layers:
            misplaced.append(f"{path.relative_to(REPO)}: not in a folder named after a layer")
        elif path.suffix == ".h" and folder != TEST_HELPERS:
            misplaced.append(f"{path.relative_to(REPO)}: a shared header outside {TEST_HELPERS}/")
    assert not misplaced, "native tests out of place:\n" + "\n".join(misplaced)
