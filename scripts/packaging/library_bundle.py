"""The shared libraries a packaged libstratum.so needs, copied beside it under private names.

`make package` (package.py) calls `bundle`: starting from libstratum.so and Open Image
Denoise's files (the roots), it follows every DT_NEEDED entry, as the loader resolves it on
this machine (`ldd` in an empty environment), down to the base system. Each library found is
copied into the package's lib/ under a private name: its soname with ".so" replaced by two hex
digits of its SHA-256 (libtbb.so.12 -> libtbb.2c.12), written in place over every string that
names it (elf_names.py), so no file grows. Auditwheel renames a wheel's libraries for the same
reason: the loader shares an already loaded library by name, and Blender's process has its
own libtbb.so.12, libOpenColorIO.so.2.x and more loaded before Stratum; under a name no real
library has, nothing is shared, so Stratum's Embree, OIIO, OCIO and TBB are the ones it was
built with, whatever the host carries. Two files of one soname (Debian's oneTBB and OIDN's)
get different digits.

How the loader finds them: the roots carry a DT_RPATH of `$ORIGIN` (patchelf; small files).
Unlike DT_RUNPATH, glibc searches a DT_RPATH for the dependencies of dependencies too (the
RPATHs of the loading chain, when the library asking has no RUNPATH; no bundled library has
one, checked), so the copies need no run path of their own.

The base system, never bundled: glibc (libc, libm, libpthread, libdl, librt, libresolv,
libutil, libanl, the loader) and the C++ runtime (libstdc++, libgcc_s), which every Linux that
runs Blender has and whose copies must be the system's (one allocator and one set of threads
per process). What that asks of the system, its newest GLIBC_/GLIBCXX_ symbol versions, is
reported by `required_versions`.

The roots keep their names: the add-on opens lib/libstratum.so by name, and OIDN's core opens
its device libraries by file name from its own directory.
"""

from __future__ import annotations

import hashlib
import os
import re
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

from scripts.packaging.elf_names import library_names, needed, rename_libraries

BASE_SYSTEM = frozenset({
    "libc.so.6", "libm.so.6", "libpthread.so.0", "libdl.so.2", "librt.so.1", "libresolv.so.2",
    "libutil.so.1", "libanl.so.1", "ld-linux-x86-64.so.2", "libstdc++.so.6", "libgcc_s.so.1",
})
# ldd's lines for the kernel's vDSO and the loader itself name no file to bundle.
_LDD_RESOLVED = re.compile(r"^\s*(\S+) => (\S+) \(0x[0-9a-f]+\)$")
_LDD_MISSING = re.compile(r"^\s*(\S+) => not found$")
_CLEAN_ENV = {"PATH": "/usr/bin:/bin", "LC_ALL": "C"}


class BundleError(RuntimeError):
    """A library cannot be bundled: a dependency is missing, or two files claim one name."""


@dataclass(frozen=True)
class BundledLibrary:
    source: Path  # the file copied (symlinks resolved)
    name: str  # its file name and soname in the package


def _ldd(library: Path) -> list[tuple[str, Path | None]]:
    """(soname, file, or None when not found) for every library `library` pulls in, as the
    loader resolves them in an empty environment (no LD_LIBRARY_PATH)."""
    out = subprocess.run(["ldd", str(library)], capture_output=True, text=True, env=_CLEAN_ENV,
                         check=False)
    if out.returncode != 0:
        raise BundleError(f"ldd {library} failed: {out.stderr.strip() or out.stdout.strip()}")
    found: list[tuple[str, Path | None]] = []
    for line in out.stdout.splitlines():
        if missing := _LDD_MISSING.match(line):
            found.append((missing.group(1), None))
        elif resolved := _LDD_RESOLVED.match(line):
            found.append((resolved.group(1), Path(resolved.group(2))))
    return found


def resolve_dependencies(library: Path) -> dict[str, Path]:
    """soname -> file (symlinks resolved) for every library `library` pulls in; BundleError
    naming a dependency not found."""
    found: dict[str, Path] = {}
    for soname, path in _ldd(library):
        if path is None:
            raise BundleError(f"{library}: dependency {soname} not found")
        found[soname] = Path(os.path.realpath(path))
    return found


def private_name(soname: str, source: Path, taken: set[str]) -> str:
    """libtbb.so.12 -> libtbb.<2 hex digits of the file's SHA-256>.12: the same length, so it
    is written in place; the next digits of the hash when a name is taken."""
    stem, dot_so, suffix = soname.partition(".so")
    if not dot_so:
        raise BundleError(f"{soname}: not a shared library name")
    digest = hashlib.sha256(source.read_bytes()).hexdigest()
    for at in range(0, len(digest) - 1, 2):
        name = f"{stem}.{digest[at:at + 2]}{suffix}"
        if name not in taken:
            return name
    raise BundleError(f"{soname}: no free private name")


def bundle(roots: list[Path], dest: Path, patchelf: str) -> list[BundledLibrary]:
    """Copies `roots` (names kept) and their dependencies (private names) into `dest`, rewired
    to one another. Returns what was copied, roots first."""
    dest.mkdir(parents=True, exist_ok=True)
    root_files = [Path(os.path.realpath(root)) for root in roots]
    names: dict[Path, str] = {path: root.name for path, root in zip(root_files, roots)}
    # The renames each file gets, fixed by the root whose closure reached it first: a file
    # reached again from another root must resolve its dependencies to the same files.
    renames: dict[Path, dict[str, str]] = {}
    order: list[Path] = list(root_files)
    for root, root_file in zip(roots, root_files):
        resolved = resolve_dependencies(root)
        pending = [root_file]
        while pending:
            path = pending.pop()
            mapping: dict[str, str] = {}
            for soname in needed(path):
                if soname in BASE_SYSTEM:
                    continue
                if soname not in resolved:
                    raise BundleError(f"{path}: ldd of {root} does not resolve {soname}")
                source = resolved[soname]
                if source not in names:
                    if any(ref.role == "runpath" for ref in library_names(source)):
                        raise BundleError(f"{source} has a run path of its own, which would "
                                          "hide the roots' DT_RPATH from its dependencies")
                    names[source] = private_name(soname, source, set(names.values()))
                    order.append(source)
                    pending.append(source)
                mapping[soname] = names[source]
            if path not in root_files:
                mapping[soname_of(path)] = names[path]
            if renames.setdefault(path, mapping) != mapping:
                raise BundleError(f"{path} resolves its dependencies to different files from "
                                  f"different roots: {renames[path]} and {mapping}")
    bundled = [BundledLibrary(source, names[source]) for source in order]
    for item in bundled:
        _copy_renamed(item, renames[item.source], dest)
    for root in root_files:
        # Replaces (or adds) the root's run path; a DT_RPATH, for the reason in the docstring.
        subprocess.run([patchelf, "--force-rpath", "--set-rpath", "$ORIGIN",
                        str(dest / names[root])], check=True)
    return bundled


def soname_of(path: Path) -> str:
    sonames = [ref.name for ref in library_names(path) if ref.role == "soname"]
    if len(sonames) != 1:
        raise BundleError(f"{path}: {len(sonames)} sonames")
    return sonames[0]


def _copy_renamed(item: BundledLibrary, renames: dict[str, str], dest: Path) -> None:
    # A new file each time (copy to a temporary name, then rename): a library of an earlier
    # package may be mapped by a running process.
    scratch = dest / f".{item.name}.tmp"
    shutil.copyfile(item.source, scratch)
    scratch.chmod(0o755)
    rename_libraries(scratch, renames)
    scratch.replace(dest / item.name)


def foreign_dependencies(directory: Path, roots: list[str]) -> dict[str, list[str]]:
    """For each root library in `directory`, what `ldd` (empty environment) resolves outside
    both the directory and the base system, or does not resolve at all; empty when the bundle
    is self-contained. (The copies are found through the roots' run path, so ldd of a copy
    alone would not find its neighbours.)"""
    problems: dict[str, list[str]] = {}
    inside = directory.resolve()
    for root in roots:
        for soname, path in _ldd(directory / root):
            if path is None:
                problems.setdefault(root, []).append(f"{soname} not found")
            elif soname not in BASE_SYSTEM and path.resolve().parent != inside:
                problems.setdefault(root, []).append(f"{soname} => {path}")
    return problems


def required_versions(directory: Path) -> dict[str, str]:
    """The newest GLIBC_ and GLIBCXX_ symbol versions the libraries in `directory` need: the
    oldest glibc and libstdc++ (GCC) a system may have to load the package."""
    newest: dict[str, tuple[int, ...]] = {}
    pattern = re.compile(r"Name: (GLIBC|GLIBCXX)_([0-9.]+)")
    for library in directory.iterdir():
        out = subprocess.run(["readelf", "-V", "--wide", str(library)], capture_output=True,
                             text=True, check=True, env=_CLEAN_ENV)
        for family, number in pattern.findall(out.stdout):
            version = tuple(int(part) for part in number.split("."))
            newest[family] = max(newest.get(family, version), version)
    return {family: ".".join(map(str, version)) for family, version in sorted(newest.items())}
