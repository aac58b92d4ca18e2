"""scripts/packaging/elf_names.py and library_bundle's names, which `make package` relies on: a
rename is written over every string that names the library (DT_NEEDED, DT_SONAME, the
version-needed records), the file keeps its size, and readelf and the loader read the new
names."""

from __future__ import annotations

import hashlib
import re
import shutil
import subprocess
from pathlib import Path

import pytest
from scripts.packaging.elf_names import ElfError, library_names, needed, rename_libraries
from scripts.packaging.library_bundle import BundleError, private_name

# Debian's libtiff: it needs libjpeg.so.62 and has a version-needed record naming it (readelf
# -V), which the rename must follow.
LIBTIFF = Path("/lib/x86_64-linux-gnu/libtiff.so.6")


def _readelf(*args: str) -> str:
    return subprocess.run(["readelf", *args], capture_output=True, text=True, check=True).stdout


@pytest.fixture
def libtiff(tmp_path: Path) -> Path:
    if not LIBTIFF.exists():
        pytest.fail(f"{LIBTIFF} missing: scripts/setup.sh installs libopenimageio-dev")
    copy = tmp_path / "libtiff.so.6"
    shutil.copyfile(LIBTIFF.resolve(), copy)
    return copy


def test_names_are_read_as_readelf_reads_them(libtiff: Path) -> None:
    dynamic = _readelf("-d", str(libtiff))
    assert needed(libtiff) == re.findall(r"\(NEEDED\)\s+Shared library: \[(.+)\]", dynamic)
    versions = re.findall(r"File: (\S+)", _readelf("-V", "--wide", str(libtiff)))
    assert sorted(r.name for r in library_names(libtiff) if r.role == "version") == \
        sorted(versions)
    assert [r.name for r in library_names(libtiff) if r.role == "soname"] == ["libtiff.so.6"]


def test_rename_in_place_reaches_every_reference(libtiff: Path) -> None:
    size = libtiff.stat().st_size
    rename_libraries(libtiff, {"libjpeg.so.62": "libjpeg.7f.62", "libtiff.so.6": "libtiff.ab.6"})
    assert libtiff.stat().st_size == size
    dynamic = _readelf("-d", str(libtiff))
    assert "[libjpeg.7f.62]" in dynamic and "[libjpeg.so.62]" not in dynamic
    assert "Library soname: [libtiff.ab.6]" in dynamic
    versions = _readelf("-V", "--wide", str(libtiff))
    assert "File: libjpeg.7f.62" in versions and "File: libjpeg.so.62" not in versions
    # Other names are untouched.
    assert "libc.so.6" in needed(libtiff) and "libz.so.1" in needed(libtiff)


def test_a_rename_must_keep_the_length(libtiff: Path) -> None:
    before = hashlib.sha256(libtiff.read_bytes()).hexdigest()
    with pytest.raises(ElfError, match="keeps the length"):
        rename_libraries(libtiff, {"libz.so.1": "libz-private.so.1"})
    assert hashlib.sha256(libtiff.read_bytes()).hexdigest() == before


def test_not_an_elf_file(tmp_path: Path) -> None:
    text = tmp_path / "notes.so"
    text.write_text("not a library")
    with pytest.raises(ElfError, match="not a little-endian ELF64"):
        library_names(text)


def test_private_names(libtiff: Path) -> None:
    digest = hashlib.sha256(libtiff.read_bytes()).hexdigest()
    first = private_name("libtiff.so.6", libtiff, set())
    assert first == f"libtiff.{digest[:2]}.6" and len(first) == len("libtiff.so.6")
    # A taken name moves on to the next digits of the hash.
    assert private_name("libtiff.so.6", libtiff, {first}) == f"libtiff.{digest[2:4]}.6"
    with pytest.raises(BundleError, match="not a shared library name"):
        private_name("libtiff", libtiff, set())
