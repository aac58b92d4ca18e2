"""Reading and renaming, in place, the library names an ELF64 shared object carries.

A dependency is named three ways inside a library, all strings of its dynamic string table
(.dynstr): DT_NEEDED entries of the .dynamic section, the library's own DT_SONAME, and the
vn_file of each version-needed record (.gnu.version_r), which the loader matches against the
names of the loaded dependencies (glibc's _dl_check_map_versions asserts it finds one). A new
name of the same length is written over the old string, so no section grows or moves: tools
that append a larger string table (patchelf) copy the sections after it, 23 MB more for
Debian's libopenvdb. Renaming means rewriting every one of those strings, including copies the
linker did not merge.

ELF64 little-endian only (x86-64 Linux, the package's one platform); layouts from the System V
gABI (ELF header, section header, Elf64_Dyn) and the LSB's symbol versioning (Elf64_Verneed).
"""

from __future__ import annotations

import struct
from dataclasses import dataclass
from pathlib import Path

SHT_DYNAMIC = 6
SHT_GNU_VERNEED = 0x6FFFFFFE
DT_NULL, DT_NEEDED, DT_SONAME, DT_RPATH, DT_RUNPATH = 0, 1, 14, 15, 29


class ElfError(RuntimeError):
    pass


@dataclass(frozen=True)
class _Section:
    kind: int
    offset: int
    size: int
    link: int


@dataclass(frozen=True)
class NameReference:
    """One string of the dynamic string table that names a library: where (file offset) and
    what (the name), and why ("needed", "soname", "runpath", "version")."""

    role: str
    offset: int
    name: str


def _sections(data: bytes, path: Path) -> list[_Section]:
    if data[:4] != b"\x7fELF" or data[4] != 2 or data[5] != 1:
        raise ElfError(f"{path}: not a little-endian ELF64 file")
    shoff, = struct.unpack_from("<Q", data, 0x28)
    shentsize, shnum = struct.unpack_from("<HH", data, 0x3A)
    if shoff == 0 or shnum == 0:
        raise ElfError(f"{path}: no section headers")
    sections = []
    for i in range(shnum):
        # Elf64_Shdr: name, type, flags, addr, offset, size, link, info, addralign, entsize.
        _, kind, _, _, offset, size, link, _, _, _ = struct.unpack_from(
            "<IIQQQQIIQQ", data, shoff + i * shentsize)
        sections.append(_Section(kind, offset, size, link))
    return sections


def _string(data: bytes, table: _Section, index: int) -> tuple[int, str]:
    start = table.offset + index
    end = data.index(b"\0", start, table.offset + table.size)
    return start, data[start:end].decode("utf-8", "surrogateescape")


def library_names(path: Path) -> list[NameReference]:
    """Every library name in `path`'s dynamic section and version-needed records."""
    data = path.read_bytes()
    sections = _sections(data, path)
    dynamic = [s for s in sections if s.kind == SHT_DYNAMIC]
    if len(dynamic) != 1:
        raise ElfError(f"{path}: {len(dynamic)} dynamic sections")
    strtab = sections[dynamic[0].link]
    roles = {DT_NEEDED: "needed", DT_SONAME: "soname", DT_RPATH: "runpath", DT_RUNPATH: "runpath"}
    found = []
    for at in range(dynamic[0].offset, dynamic[0].offset + dynamic[0].size, 16):
        tag, value = struct.unpack_from("<qQ", data, at)
        if tag == DT_NULL:
            break
        if tag in roles:
            found.append(NameReference(roles[tag], *_string(data, strtab, value)))
    for verneed in (s for s in sections if s.kind == SHT_GNU_VERNEED):
        table = sections[verneed.link]
        at = verneed.offset
        while True:
            _, _, file_index, _, next_offset = struct.unpack_from("<HHIII", data, at)
            found.append(NameReference("version", *_string(data, table, file_index)))
            if next_offset == 0:
                break
            at += next_offset
    return found


def needed(path: Path) -> list[str]:
    return [ref.name for ref in library_names(path) if ref.role == "needed"]


def rename_libraries(path: Path, renames: dict[str, str]) -> None:
    """Writes each new name over every DT_NEEDED, DT_SONAME and vn_file string equal to the old
    one. New names must have the old ones' lengths; ElfError otherwise."""
    for old, new in renames.items():
        if len(old.encode()) != len(new.encode()):
            raise ElfError(f"{old!r} -> {new!r}: an in-place rename keeps the length")
    data = bytearray(path.read_bytes())
    for ref in library_names(path):
        if ref.role != "runpath" and ref.name in renames:
            new = renames[ref.name].encode()
            data[ref.offset:ref.offset + len(new)] = new
    path.write_bytes(bytes(data))
