"""`make package`: dist/stratum-<version>-linux-x64.zip, the add-on as users install it.

One zip for both kinds of Blender (docs/packaging.md):
  * Blender 4.2+ installs it as an extension (Get Extensions > Install from Disk, or
    `blender --command extension install-file`): stratum/blender_manifest.toml is its manifest
    (Blender accepts a manifest inside one top-level directory);
  * Blender 3.x installs it as a legacy add-on (Preferences > Add-ons > Install): the top-level
    directory is the module, and bl_info gets its "version" here, from the manifest.

What goes in: the add-on's Python modules (the CLI's own, `stratum compare` and the Dask
runner, stay out: Blender never imports them, and a static check below proves the rest never
does), the manifest, libstratum.so and Open Image Denoise (its CPU device) with every library
they need beyond the base system under private names (library_bundle.py),
libstratum_dependencies.so (native/packaging/), and the licences of the bundled libraries
(licenses/, third_party_notices.py). Nothing else: no tests, no build tree, no byte code.

    python -m scripts.packaging.package [--library build/libstratum.so]
        [--oidn-dir addon/stratum/lib] [--out dist] [--version X.Y.Z]

--version overrides the manifest's version in the package (a release candidate, or the newer
package the upgrade test installs over an older one); the native library reports the version it
was built with.
"""

from __future__ import annotations

import argparse
import ast
import os
import re
import shutil
import sys
import tempfile
import zipfile
from pathlib import Path

from stratum.native.library import DEPENDENCIES
from stratum.version import VERSION_LINE, version_tuple

from scripts import REPO
from scripts.packaging.library_bundle import (
    BundleError,
    bundle,
    foreign_dependencies,
    required_versions,
)
from scripts.packaging.third_party_notices import NoticeError, index, notices

ADDON = REPO / "addon" / "stratum"
MODULE = "stratum"
PLATFORM = "linux-x64"
# Run only from a shell or a Python of the project (stratum compare, its Blender batch script,
# the Dask workers), never by Blender's add-on.
CLI_ONLY = ("cli", "compare")
OIDN_FILES = ("libOpenImageDenoise.so.2", "libOpenImageDenoise_core.so.*",
              "libOpenImageDenoise_device_cpu.so.*")
_SEMVER = re.compile(r"^\d+\.\d+\.\d+(?:-[0-9A-Za-z.-]+)?(?:\+[0-9A-Za-z.-]+)?$")


class PackageError(RuntimeError):
    pass


def add_on_sources() -> list[Path]:
    """The add-on's Python files, relative to addon/stratum/."""
    files = []
    for path in sorted(ADDON.rglob("*.py")):
        relative = path.relative_to(ADDON)
        if "__pycache__" in relative.parts or relative.parts[0] in ("lib", *CLI_ONLY):
            continue
        files.append(relative)
    return files


def check_imports_inside(files: list[Path]) -> None:
    """Every relative import of a packaged module names a packaged module: leaving the CLI's
    modules out cannot break the add-on, even on a code path no test reaches."""
    modules = {f.with_suffix("").as_posix().removesuffix("/__init__") for f in files}
    modules.add("")
    for relative in files:
        package = relative.parent.as_posix() if relative.parent.as_posix() != "." else ""
        tree = ast.parse((ADDON / relative).read_text(encoding="utf-8"), str(relative))
        for node in ast.walk(tree):
            if not isinstance(node, ast.ImportFrom) or node.level == 0:
                continue
            base = package.split("/") if package else []
            base = base[:len(base) - (node.level - 1)] if node.level > 1 else base
            target = "/".join([*base, *(node.module.split(".") if node.module else [])])
            candidates = [target] + [f"{target}/{a.name}".lstrip("/") for a in node.names]
            if not any(c in modules for c in candidates):
                raise PackageError(f"{relative}:{node.lineno}: imports "
                                   f"{'.' * node.level}{node.module or ''}, which is not packaged")


def stamped_init(version: str) -> str:
    """__init__.py with bl_info["version"] written from the manifest's version."""
    text = (ADDON / "__init__.py").read_text(encoding="utf-8")
    numbers = version_tuple(version)
    opening = "bl_info = {\n"
    if text.count(opening) != 1 or '"version"' in text.split(opening, 1)[1].split("}", 1)[0]:
        raise PackageError("addon/stratum/__init__.py: expected one `bl_info = {` without a "
                           "version (the manifest holds it)")
    stamped = text.replace(opening, f'{opening}    "version": {numbers!r},\n')
    info = next(node for node in ast.parse(stamped).body if isinstance(node, ast.Assign)
                and getattr(node.targets[0], "id", "") == "bl_info")
    if ast.literal_eval(info.value)["version"] != numbers:
        raise PackageError("bl_info stamping failed")
    return stamped


def manifest_text(version: str | None) -> tuple[str, str]:
    """(manifest text, version), the version replaced when given."""
    text = (ADDON / "blender_manifest.toml").read_text(encoding="utf-8")
    match = VERSION_LINE.search(text)
    if match is None:
        raise PackageError("addon/stratum/blender_manifest.toml has no version line")
    if version is None:
        return text, match.group(1)
    if not _SEMVER.match(version):
        raise PackageError(f"--version {version!r} is not a semantic version (X.Y.Z)")
    return text[:match.start(1)] + version + text[match.end(1):], version


def oidn_files(directory: Path) -> list[Path]:
    found = [sorted(directory.glob(pattern)) for pattern in OIDN_FILES]
    if not all(len(f) == 1 for f in found):
        raise PackageError(f"{directory}: expected one each of {OIDN_FILES} (make build copies "
                           f"them), found {[p.name for f in found for p in f]}")
    return [f[0] for f in found]


def write_zip(target: Path, entries: list[tuple[str, Path | str | bytes]]) -> None:
    """Entries (name in the zip, file or text) with fixed times, so that the same inputs give
    the same zip; written beside `target` and renamed over it. Each directory has its entry,
    as zip tools write them: Blender 3.x's add-on installer removes an installed add-on before
    extracting a new one over it only for the zip's top-level entries (userpref.py,
    _zipfile_root_namelist), and without a `stratum/` entry it would rewrite the installed
    files in place, libstratum.so included while Blender has it mapped."""
    directories = sorted({"/".join(name.split("/")[:depth]) + "/" for name, _ in entries
                          for depth in range(1, name.count("/") + 1)})
    scratch = target.with_name(f".{target.name}.tmp")
    with zipfile.ZipFile(scratch, "w", compression=zipfile.ZIP_DEFLATED) as archive:
        for directory in directories:
            info = zipfile.ZipInfo(directory, date_time=(2020, 1, 1, 0, 0, 0))
            info.external_attr = (0o40755 << 16) | 0x10  # a directory (MS-DOS flag too)
            archive.writestr(info, b"")
        for name, content in entries:
            info = zipfile.ZipInfo(name, date_time=(2020, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            executable = isinstance(content, Path) and ".so" in content.name
            info.external_attr = (0o100755 if executable else 0o100644) << 16
            if isinstance(content, Path):
                with content.open("rb") as src, archive.open(info, "w") as dst:
                    shutil.copyfileobj(src, dst, 1 << 20)
            else:
                archive.writestr(info, content)
    scratch.replace(target)


def build_package(library: Path, oidn_dir: Path, out: Path, version: str | None,
                  patchelf: str) -> Path:
    if not library.is_file():
        raise PackageError(f"{library}: no such library (make build)")
    manifest, version = manifest_text(version)
    sources = add_on_sources()
    check_imports_inside(sources)
    with tempfile.TemporaryDirectory(prefix="stratum-package-") as scratch:
        lib_dir = Path(scratch) / "lib"
        dependencies = library.with_name(DEPENDENCIES)
        if not dependencies.is_file():
            raise PackageError(f"{dependencies}: no such library (make build)")
        roots = [library, dependencies, *oidn_files(oidn_dir)]
        bundled = bundle(roots, lib_dir, patchelf)
        if problems := foreign_dependencies(lib_dir, [root.name for root in roots]):
            raise PackageError(f"the bundle is not self-contained: {problems}")
        entries: list[tuple[str, Path | str | bytes]] = [(f"{MODULE}/blender_manifest.toml", manifest)]
        for relative in sources:
            name = f"{MODULE}/{relative.as_posix()}"
            if relative == Path("__init__.py"):
                entries.append((name, stamped_init(version)))
            else:
                entries.append((name, ADDON / relative))
        entries += [(f"{MODULE}/lib/{item.name}", lib_dir / item.name) for item in bundled]
        own = {library.name, DEPENDENCIES}
        origins, licence_files = notices([(item.name, item.source) for item in bundled
                                          if item.name not in own])
        entries += [(f"{MODULE}/licenses/{name}", content)
                    for name, content in sorted(licence_files.items())]
        entries.append((f"{MODULE}/licenses/THIRD_PARTY.txt", index(origins)))
        out.mkdir(parents=True, exist_ok=True)
        target = out / f"{MODULE}-{version}-{PLATFORM}.zip"
        write_zip(target, entries)
        needs = required_versions(lib_dir)
        unpacked = sum((lib_dir / item.name).stat().st_size for item in bundled)
    print(f"package: {target} ({target.stat().st_size / 1e6:.1f} MB; {len(sources)} Python "
          f"files, {len(bundled)} libraries, {unpacked / 1e6:.0f} MB unpacked); needs "
          + ", ".join(f"{k} >= {v}" for k, v in needs.items()))
    return target


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--library", type=Path, default=REPO / "build" / "libstratum.so")
    parser.add_argument("--oidn-dir", type=Path, default=ADDON / "lib")
    parser.add_argument("--out", type=Path, default=REPO / "dist")
    parser.add_argument("--version", default=None)
    parser.add_argument("--patchelf", default=shutil.which("patchelf", path=os.pathsep.join(
        [str(Path(sys.executable).parent), os.environ.get("PATH", "")])))
    args = parser.parse_args(argv)
    if not args.patchelf:
        print("package: patchelf not found (scripts/requirements.txt installs it)", file=sys.stderr)
        return 2
    try:
        build_package(args.library, args.oidn_dir, args.out, args.version, args.patchelf)
    except (PackageError, BundleError, NoticeError) as exc:
        print(f"package: {exc}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
