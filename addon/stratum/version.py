"""Stratum's version, read from blender_manifest.toml beside this file (the one place it is
written). A regular expression, not tomllib: Blender 3.4's Python (3.10) has no tomllib, and
the manifest's `version` line is a plain string by the extension format's rules."""

from __future__ import annotations

import re
from pathlib import Path

MANIFEST = Path(__file__).resolve().parent / "blender_manifest.toml"
# The manifest's `version = "X.Y.Z"` line; group 1 is the version (make package rewrites it).
VERSION_LINE = re.compile(r'^version\s*=\s*"([^"]+)"\s*$', re.MULTILINE)


def read_manifest_version(manifest: Path = MANIFEST) -> str:
    """The `version` of a blender_manifest.toml; ValueError naming the file when it has none."""
    match = VERSION_LINE.search(manifest.read_text(encoding="utf-8"))
    if match is None:
        raise ValueError(f"{manifest}: no `version = \"...\"` line")
    return match.group(1)


def version_tuple(version: str) -> tuple[int, ...]:
    """"1.2.3" -> (1, 2, 3), the form of bl_info["version"]; a pre-release or build suffix
    ("1.2.3-rc1", "1.2.3+local") is dropped, as Blender's add-on list shows numbers only."""
    core = re.split(r"[-+]", version, maxsplit=1)[0]
    return tuple(int(part) for part in core.split("."))


__version__ = read_manifest_version()
