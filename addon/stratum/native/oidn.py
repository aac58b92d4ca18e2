"""Intel Open Image Denoise (OIDN 2.x) through its C API, loaded with ctypes.

No Debian package ships OIDN and Debian's Blender is built without it, so the library comes
from PyPI's `pyoidn` wheel (libOpenImageDenoise.so.2 with its core, its CPU device and oneTBB,
found beside one another through their $ORIGIN run path). `make build` copies those four files
into stratum/lib/, so that Blender 3.4, whose Python does not see the project's venv, finds
them next to libstratum.so. Where the library is looked for, in order (`candidate_paths`):
$STRATUM_OIDN_LIBRARY (alone when set, so that a broken override is reported rather than
passed over), stratum/lib/, the pyoidn package (located without importing it: pyoidn imports
cffi, which Debian's Blender lacks), then the system's loader path.

Only the C API functions used here are declared (oidn.h of OIDN 2.x; the same in 2.3.3, which
the bpy 5.0 wheel bundles, and 2.5.1, which pyoidn ships): a CPU device (no GPU probing, no
thread pinning), one "RT" filter per call, shared host images in FLOAT3, `hdr`, and the
device's error after each step. Images are float32 H x W x 3; the denoised image is a new array.

Which copy in the bpy 5.0 wheel: bpy has already mapped its own OIDN 2.3.3 when the add-on
runs; pyoidn's 2.5.1 loads beside it (its core has another soname, so nothing is shared but
oneTBB, whose libtbb.so.12 bpy has loaded and which OIDN's CPU device accepts) and denoises the
same, measured. The same copy is used in both Blenders, so one version of OIDN is tested.
"""

from __future__ import annotations

import ctypes
import importlib.util
import os
import threading
from pathlib import Path

import numpy as np

from .abi import ERROR_INTERNAL
from .library import StratumError

ENV_VAR = "STRATUM_OIDN_LIBRARY"
LIBRARY_FILE = "libOpenImageDenoise.so.2"

# oidn.h enumerations (OIDNDeviceType, OIDNError, OIDNFormat).
_DEVICE_TYPE_CPU = 1
_ERROR_NONE = 0
_ERROR_NAMES = {1: "unknown error", 2: "invalid argument", 3: "invalid operation",
                4: "out of memory", 5: "unsupported hardware", 6: "cancelled"}
_FORMAT_FLOAT3 = 3

_c_void_p = ctypes.c_void_p
_c_char_p = ctypes.c_char_p
_size_t = ctypes.c_size_t
_SIGNATURES: dict[str, tuple[object, list[object]]] = {
    "oidnNewDevice": (_c_void_p, [ctypes.c_int]),
    "oidnSetDeviceBool": (None, [_c_void_p, _c_char_p, ctypes.c_bool]),
    "oidnCommitDevice": (None, [_c_void_p]),
    "oidnReleaseDevice": (None, [_c_void_p]),
    "oidnGetDeviceError": (ctypes.c_int, [_c_void_p, ctypes.POINTER(_c_char_p)]),
    "oidnNewFilter": (_c_void_p, [_c_void_p, _c_char_p]),
    "oidnSetSharedFilterImage": (None, [_c_void_p, _c_char_p, _c_void_p, ctypes.c_int,
                                        _size_t, _size_t, _size_t, _size_t, _size_t]),
    "oidnSetFilterBool": (None, [_c_void_p, _c_char_p, ctypes.c_bool]),
    "oidnCommitFilter": (None, [_c_void_p]),
    "oidnExecuteFilter": (None, [_c_void_p]),
    "oidnReleaseFilter": (None, [_c_void_p]),
}


class DenoiserUnavailable(StratumError):
    """OIDN could not be loaded or failed: names the library path tried and OIDN's own error."""

    def __init__(self, message: str) -> None:
        super().__init__(ERROR_INTERNAL, message)


def _pyoidn_library() -> Path | None:
    """libOpenImageDenoise.so.2 inside the installed pyoidn package, found by the import
    system's finders without running the package (which needs cffi)."""
    try:
        spec = importlib.util.find_spec("pyoidn")
    except (ImportError, ValueError):
        return None
    if spec is None or not spec.submodule_search_locations:
        return None
    for location in spec.submodule_search_locations:
        path = Path(location) / "oidn" / "lib" / LIBRARY_FILE
        if path.is_file():
            return path
    return None


def candidate_paths() -> list[str]:
    """Where the library is looked for, in order: $STRATUM_OIDN_LIBRARY alone when set; else
    stratum/lib/, pyoidn's copy, then the bare file name for the system's loader path."""
    override = os.environ.get(ENV_VAR)
    if override:
        return [override]
    out = []
    bundled = Path(__file__).resolve().parent.parent / "lib" / LIBRARY_FILE
    if bundled.is_file():
        out.append(str(bundled))
    wheel = _pyoidn_library()
    if wheel is not None:
        out.append(str(wheel))
    out.append(LIBRARY_FILE)
    return out


_lib: ctypes.CDLL | None = None
_lib_path = ""
_lib_lock = threading.Lock()


def _open(path: str) -> ctypes.CDLL:
    lib = ctypes.CDLL(path, mode=os.RTLD_LOCAL)
    for name, (restype, argtypes) in _SIGNATURES.items():
        fn = getattr(lib, name)  # AttributeError: not an OIDN 2.x library
        fn.restype = restype
        fn.argtypes = argtypes
    return lib


def load_library() -> tuple[ctypes.CDLL, str]:
    """Loads OIDN once per process and returns it with the path it came from; raises
    DenoiserUnavailable naming every path tried and why each failed. A failure is not kept,
    so that installing the library (or fixing the override) works without a restart."""
    global _lib, _lib_path
    with _lib_lock:
        if _lib is not None:
            return _lib, _lib_path
        failures = []
        for path in candidate_paths():
            try:
                lib = _open(path)
            except (OSError, AttributeError) as exc:
                failures.append(f"{path}: {exc}")
                continue
            _lib, _lib_path = lib, path
            return lib, path
        raise DenoiserUnavailable(
            "Open Image Denoise could not be loaded (install pyoidn with `make build`, or set "
            f"{ENV_VAR}); tried " + "; ".join(failures))


def available() -> bool:
    try:
        load_library()
    except DenoiserUnavailable:
        return False
    return True


def _image(array: np.ndarray | None, what: str, shape: tuple[int, ...] | None) -> np.ndarray | None:
    if array is None:
        return None
    image = np.ascontiguousarray(array, dtype=np.float32)
    if image.ndim != 3 or image.shape[2] != 3 or image.shape[0] < 1 or image.shape[1] < 1:
        raise ValueError(f"denoise: {what} must be an H x W x 3 array, got shape {array.shape}")
    if shape is not None and image.shape != shape:
        raise ValueError(f"denoise: {what} has shape {image.shape}, color has {shape}")
    if not np.isfinite(image).all():
        raise ValueError(f"denoise: {what} has values that are not finite")
    return image


def _raise_on_error(lib: ctypes.CDLL, device: int | None, path: str, step: str) -> None:
    message = _c_char_p()
    code = lib.oidnGetDeviceError(device, ctypes.byref(message))
    if code != _ERROR_NONE:
        text = message.value.decode("utf-8", "replace") if message.value else ""
        raise DenoiserUnavailable(
            f"Open Image Denoise ({path}) failed at {step}: "
            f"{text or _ERROR_NAMES.get(code, f'error {code}')}")


def denoise(color: np.ndarray, albedo: np.ndarray | None = None,
            normal: np.ndarray | None = None, hdr: bool = True) -> np.ndarray:
    """The RT filter's denoised `color` (H x W x 3 float32, linear; `hdr` False for values in
    [0, 1]), guided by first-hit `albedo` in [0, 1] and `normal` in [-1, 1] when given. OIDN
    takes a normal only together with an albedo. Raises ValueError for bad images and
    DenoiserUnavailable when the library is missing or fails."""
    noisy = _image(color, "color", None)
    assert noisy is not None
    guide_albedo = _image(albedo, "albedo", noisy.shape)
    guide_normal = _image(normal, "normal", noisy.shape)
    if guide_normal is not None and guide_albedo is None:
        raise ValueError("denoise: OIDN uses a normal guide only together with an albedo guide")
    lib, path = load_library()
    height, width = noisy.shape[:2]
    output = np.empty_like(noisy)
    device = lib.oidnNewDevice(_DEVICE_TYPE_CPU)
    if not device:
        _raise_on_error(lib, None, path, "creating a CPU device")
        raise DenoiserUnavailable(f"Open Image Denoise ({path}) could not create a CPU device")
    try:
        # No thread pinning: it asks oneTBB for the CPU's core types, which loads tbbbind and
        # hwloc, and in Debian's Blender 3.4 (jemalloc) hwloc then aborts the process with
        # "free(): invalid size" (measured). A renderer inside Blender should not pin threads
        # of the host anyway.
        lib.oidnSetDeviceBool(device, b"setAffinity", False)
        lib.oidnCommitDevice(device)
        _raise_on_error(lib, device, path, "committing the CPU device")
        oidn_filter = lib.oidnNewFilter(device, b"RT")
        _raise_on_error(lib, device, path, "creating the RT filter")
        try:
            images = {b"color": noisy, b"albedo": guide_albedo, b"normal": guide_normal,
                      b"output": output}
            for name, image in images.items():
                if image is not None:
                    lib.oidnSetSharedFilterImage(oidn_filter, name, image.ctypes.data,
                                                 _FORMAT_FLOAT3, width, height, 0, 0, 0)
            lib.oidnSetFilterBool(oidn_filter, b"hdr", bool(hdr))
            lib.oidnCommitFilter(oidn_filter)
            _raise_on_error(lib, device, path, "setting up the RT filter")
            lib.oidnExecuteFilter(oidn_filter)
            _raise_on_error(lib, device, path, "denoising")
        finally:
            if oidn_filter:
                lib.oidnReleaseFilter(oidn_filter)
    finally:
        lib.oidnReleaseDevice(device)
    return output
