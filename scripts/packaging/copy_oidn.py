"""Copies Open Image Denoise from the venv's pyoidn wheel into addon/stratum/lib/ (run by `make
build`): the library, its core (which holds the trained weights), its CPU device and the oneTBB
the device links, found beside one another through their $ORIGIN run path. Blender 3.4 runs its
own Python, which does not see the venv, so the add-on looks there first
(stratum/native/oidn.py). The GPU devices are left out: the add-on asks for a CPU device.

Idempotent: a file already copied (same size and time) is left alone; a changed one is copied
to a temporary name and renamed, because overwriting a library in place would crash a process
that has it loaded. OIDN files of another version left from an earlier copy are removed."""

from __future__ import annotations

import importlib.util
import shutil
import sys
from pathlib import Path

PATTERNS = ("libOpenImageDenoise.so.2", "libOpenImageDenoise_core.so.*",
            "libOpenImageDenoise_device_cpu.so.*", "libtbb.so.12")


def wheel_library_dir() -> Path:
    spec = importlib.util.find_spec("pyoidn")
    if spec is None or not spec.submodule_search_locations:
        sys.exit("copy_oidn: pyoidn is not installed in this Python (scripts/requirements.txt)")
    return Path(next(iter(spec.submodule_search_locations))) / "oidn" / "lib"


def same_file(a: Path, b: Path) -> bool:
    if not b.is_file():
        return False
    sa, sb = a.stat(), b.stat()
    return sa.st_size == sb.st_size and int(sa.st_mtime) == int(sb.st_mtime)


def main(dest: Path) -> None:
    source = wheel_library_dir()
    files = sorted({path for pattern in PATTERNS for path in source.glob(pattern)})
    if len(files) != len(PATTERNS):
        sys.exit(f"copy_oidn: expected {len(PATTERNS)} files in {source}, found "
                 f"{[f.name for f in files]}")
    dest.mkdir(parents=True, exist_ok=True)
    names = {f.name for f in files}
    for stale in dest.glob("libOpenImageDenoise*"):
        if stale.name not in names:
            stale.unlink()
    for path in files:
        target = dest / path.name
        if same_file(path, target):
            continue
        temporary = target.with_name(target.name + ".tmp")
        shutil.copy2(path.resolve(), temporary)
        temporary.replace(target)


if __name__ == "__main__":
    main(Path(sys.argv[1]))
