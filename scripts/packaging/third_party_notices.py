"""The licences of the libraries `make package` bundles, which their licences ask a
redistributor to pass on (BSD and MIT notices, Apache-2.0's text, the GPL/LGPL terms of FFmpeg's
codecs and others).

Debian's libraries: the package that owns each file (`dpkg -S`) and that package's
/usr/share/doc/<package>/copyright, Debian's machine-readable record of every copyright holder
and licence in it. Open Image Denoise and its oneTBB come from PyPI's pyoidn wheel, which ships
only its own (MIT) licence: OIDN and oneTBB are Apache-2.0 (their projects' LICENSE files), so
Debian's copy of the Apache-2.0 text goes with pyoidn's notice.

The package gets stratum/licenses/<package>.txt per Debian package, and
stratum/licenses/THIRD_PARTY.txt: for each bundled file, where it came from and which licence
file covers it.
"""

from __future__ import annotations

import importlib.metadata
import subprocess
from dataclasses import dataclass
from pathlib import Path

APACHE = Path("/usr/share/common-licenses/Apache-2.0")
# Files of the wheel, by the name they keep in the package (the root names) or their soname.
PYOIDN_FILES = ("libOpenImageDenoise", "libtbb")


class NoticeError(RuntimeError):
    pass


@dataclass(frozen=True)
class Origin:
    """Where one bundled file came from and the licence files (names under licenses/) that
    cover it."""

    library: str
    source: str
    licences: tuple[str, ...]


def _debian_package(path: Path) -> tuple[str, str] | None:
    """(package, version) owning `path`, or None when dpkg knows no package for it."""
    # Debian 12 merges /lib into /usr/lib; dpkg records one of the two spellings.
    candidates = [str(path)]
    if str(path).startswith("/lib/"):
        candidates.append("/usr" + str(path))
    elif str(path).startswith("/usr/lib/"):
        candidates.append(str(path).removeprefix("/usr"))
    for candidate in candidates:
        owner = subprocess.run(["dpkg-query", "-S", candidate], capture_output=True, text=True,
                               check=False)
        if owner.returncode == 0:
            package = owner.stdout.split(":", 1)[0].strip()
            version = subprocess.run(["dpkg-query", "-W", "-f", "${Version}", package],
                                     capture_output=True, text=True, check=True).stdout
            return package, version
    return None


def notices(bundled: list[tuple[str, Path]]) -> tuple[list[Origin], dict[str, bytes]]:
    """For (name in the package, source file) pairs of the third-party libraries: their
    origins, and the licence files to write (name under licenses/ -> content)."""
    origins: list[Origin] = []
    files: dict[str, bytes] = {}
    for name, source in bundled:
        owner = _debian_package(source)
        if owner is not None:
            package, version = owner
            copyright_file = Path("/usr/share/doc") / package / "copyright"
            if not copyright_file.is_file():
                raise NoticeError(f"{source}: Debian package {package} has no {copyright_file}")
            files[f"{package}.txt"] = copyright_file.read_bytes()
            origins.append(Origin(name, f"Debian {package} {version}", (f"{package}.txt",)))
        elif name.startswith(PYOIDN_FILES):
            origins.append(Origin(name, f"PyPI pyoidn {_pyoidn_version()} (Open Image Denoise, "
                                  "oneTBB: Apache-2.0)", ("Apache-2.0.txt", "pyoidn.txt")))
            files["Apache-2.0.txt"] = APACHE.read_bytes()
            files["pyoidn.txt"] = _pyoidn_licence()
        else:
            raise NoticeError(f"{source}: neither a Debian package's nor pyoidn's; its licence "
                              "is unknown")
    return origins, files


def _pyoidn_version() -> str:
    return importlib.metadata.version("pyoidn")


def _pyoidn_licence() -> bytes:
    distribution = importlib.metadata.distribution("pyoidn")
    licences = [f for f in distribution.files or () if "LICENSE" in f.name.upper()]
    if not licences:
        raise NoticeError("the pyoidn wheel lists no LICENSE file")
    return Path(distribution.locate_file(licences[0])).read_bytes()


def index(origins: list[Origin]) -> str:
    """THIRD_PARTY.txt: one line per bundled file."""
    lines = ["Libraries bundled in stratum/lib/ (renamed: the soname's \".so\" replaced by two hex",
             "digits), where each came from, and the licence files in this folder that cover it.",
             ""]
    width = max(len(o.library) for o in origins)
    lines += [f"{o.library:<{width}}  {o.source}  [{', '.join(o.licences)}]" for o in origins]
    return "\n".join(lines) + "\n"
