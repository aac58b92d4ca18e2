"""Loading libstratum.so, the errors every native call can raise, and the library's version.

The library is loaded lazily (first use), from $STRATUM_LIBRARY or stratum/lib/libstratum.so,
with RTLD_LOCAL | RTLD_DEEPBIND on Linux: Blender (and the bpy wheel) carry their own Embree,
OIIO and TBB, and deep binding keeps our library bound to the copies it was linked with.

In the packaged add-on (`make package`, docs/packaging.md) lib/ also holds every library
libstratum.so needs, under private names, and libstratum_dependencies.so, which has no code and
names libstratum.so's dependencies. That one is opened first, without deep binding, so that the
dependencies bind malloc and free as the host process does: Blender links jemalloc, and a
library opened with RTLD_DEEPBIND binds free() to libc's while libc's own allocations (strdup,
getline) come from the host's malloc, which aborted Blender 3.4 in libselinux's constructor
(measured). libstratum.so is opened next with RTLD_DEEPBIND, so its own references (Embree's C
API, OIIO, OCIO, TBB) bind to the package's copies ahead of any the host exports.

Every native call goes through `_check`, so a non-OK status becomes a `StratumError` carrying
stratum_last_error()'s text.
"""

from __future__ import annotations

import ctypes
import os
import sys
import threading
from dataclasses import dataclass
from pathlib import Path

from .abi import (
    ERROR_INTERNAL,
    ERROR_INVALID_STATE,
    OK,
    STATUS_NAMES,
    function_signatures,
)


class StratumError(RuntimeError):
    """A native call failed (status != OK) or the library could not be loaded.

    stratum_last_error() reads "stratum_function: detail"; the function is kept apart
    (`function`) so that what a user sees, str(error), is the detail alone: Blender's messages
    name the object and field, not the ABI entry point. `message` is the whole text. `index`
    is the failing element of a batched call (add_instances), else None."""

    def __init__(self, status: int, message: str, index: int | None = None) -> None:
        self.status = status
        self.message = message
        self.index = index
        head, sep, rest = message.partition(": ")
        is_function = sep and head.startswith("stratum_") and head.isidentifier()
        self.function = head if is_function else ""
        self.detail = rest if is_function else message
        super().__init__(self.detail or STATUS_NAMES.get(status, f"status {status}"))


class LibraryLoadError(StratumError):
    """libstratum.so is missing or cannot be loaded."""

    def __init__(self, message: str) -> None:
        super().__init__(ERROR_INTERNAL, message)


# ---- library loading ------------------------------------------------------------------------

DEPENDENCIES = "libstratum_dependencies.so"
_lib: ctypes.CDLL | None = None
_lib_path: Path | None = None
_lib_lock = threading.Lock()


@dataclass(frozen=True)
class LibraryStatus:
    """What the add-on's preferences and `stratum --version` show: the library file, and its
    version when it loads, else why it does not (the text of the LibraryLoadError)."""

    path: Path
    version: str | None
    error: str | None


def default_library_path() -> Path:
    """$STRATUM_LIBRARY, else lib/libstratum.so in the stratum package (beside native/)."""
    env = os.environ.get("STRATUM_LIBRARY")
    if env:
        return Path(env)
    return Path(__file__).resolve().parent.parent / "lib" / "libstratum.so"


def _declare(lib: ctypes.CDLL) -> None:
    for name, (restype, argtypes) in function_signatures().items():
        try:
            fn = getattr(lib, name)
        except AttributeError as exc:
            raise LibraryLoadError(f"{lib._name}: missing symbol {name}") from exc
        fn.restype = restype
        fn.argtypes = argtypes


def load_library(path: str | os.PathLike[str] | None = None) -> ctypes.CDLL:
    """Loads (once) and returns the library; raises LibraryLoadError with the reason."""
    global _lib, _lib_path
    with _lib_lock:
        if _lib is not None:
            return _lib
        lib_path = Path(path) if path is not None else default_library_path()
        if not lib_path.is_file():
            raise LibraryLoadError(
                f"Stratum native library not found at {lib_path} "
                "(build it with `make build`, or set STRATUM_LIBRARY)"
            )
        mode = ctypes.RTLD_LOCAL
        if sys.platform.startswith("linux"):
            mode = os.RTLD_LOCAL | os.RTLD_DEEPBIND
        try:
            _open_packaged_dependencies(lib_path)
            lib = ctypes.CDLL(str(lib_path), mode=mode)
        except OSError as exc:
            raise LibraryLoadError(f"cannot load Stratum native library {lib_path}: {exc}") from exc
        _declare(lib)
        _lib = lib
        _lib_path = lib_path.resolve()
        return lib


def _open_packaged_dependencies(lib_path: Path) -> None:
    """Opens a package's libstratum_dependencies.so (none in a checkout, where the system's
    libraries are used as they are). ctypes never closes a library, so no handle is kept."""
    dependencies = lib_path.with_name(DEPENDENCIES)
    if dependencies.is_file():
        ctypes.CDLL(str(dependencies), mode=os.RTLD_LOCAL)


def library_status() -> LibraryStatus:
    """Loads the library if it is not yet loaded; never raises."""
    try:
        found = version()
    except StratumError as exc:
        return LibraryStatus(default_library_path(), None, str(exc))
    return LibraryStatus(_lib_path or default_library_path(), found, None)


def library_available() -> bool:
    try:
        load_library()
    except StratumError:
        return False
    return True


def _last_error(lib: ctypes.CDLL) -> str:
    raw = lib.stratum_last_error()
    return raw.decode("utf-8", "replace") if raw else ""


def _check(lib: ctypes.CDLL, status: int, what: str) -> None:
    if status != OK:
        message = _last_error(lib) or f"{what} failed: {STATUS_NAMES.get(status, status)}"
        raise StratumError(int(status), message)


def version() -> str:
    lib = load_library()
    raw = lib.stratum_version()
    return raw.decode("utf-8", "replace") if raw else ""


# ---- native handles --------------------------------------------------------------------------


class _Handle:
    """Owns one native handle and frees it exactly once (close / context manager / __del__)."""

    _destroy_name = ""

    def __init__(self) -> None:
        self._lib = load_library()
        self._ptr = ctypes.c_void_p()

    @property
    def handle(self) -> ctypes.c_void_p:
        if not self._ptr:
            raise StratumError(ERROR_INVALID_STATE, f"{type(self).__name__} is closed")
        return self._ptr

    def close(self) -> None:
        ptr = getattr(self, "_ptr", None)
        if ptr:
            getattr(self._lib, self._destroy_name)(ptr)
            self._ptr = ctypes.c_void_p()

    @property
    def closed(self) -> bool:
        return not self._ptr

    def __enter__(self):  # noqa: ANN204 - returns the concrete subclass
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __del__(self) -> None:
        try:
            self.close()
        except Exception:  # noqa: BLE001 - never raise from a finalizer
            pass

