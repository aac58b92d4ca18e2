"""What a corpus case is and how its outcome is judged. No bpy here: the judging runs in the
worker (which has the pixels) and the names are read by pytest.

Every case, whatever it expects, fails when
  * Blender crashed or hung (judged by the runner, not here),
  * any pixel of the written image is NaN or infinite,
  * a message shown to the user names an ABI function ("stratum_scene_add_instances: ...")
    instead of the object, or is an internal error (a Python exception that reached the user).
On top of that the expectation says which outcome the issue demands:
  CLEAN    the render finishes without an ERROR (warnings allowed unless quiet);
  WARNING  the render finishes, and a WARNING names the culprit;
  ERROR    an ERROR names the culprit (a render that cannot be made);
  CULPRIT  either of the two: an ERROR naming the culprit, or a finished render with a WARNING
           naming it. Used where rejecting and skipping-with-a-warning are both what the issue
           allows ("reject what cannot render with a message naming the object and the field").
  SURVIVE  an ERROR naming the culprit, or a finished render (warnings allowed): for extreme
           values with no single right picture (a lens of 1e9 mm, clip start after clip end),
           where the issue asks only for "a correct image or a clear message".
`names` must all appear in one message ("A|B": either A or B, e.g. an instance or its
instancer); of `words`, at least one must (case-insensitive): the field, socket or kind. `pixels` is an extra check of a finished image, `same_as` builds a scene
that must render to the identical image (e.g. the scene without a skipped object: the same
settings and seed give the same samples, so nothing but the skipped object may differ).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

CLEAN, WARNING, ERROR, CULPRIT, SURVIVE = "clean", "warning", "error", "culprit", "survive"

# Level of the message Blender's render operator raised (RuntimeError) when the engine was never
# reached, e.g. "No camera found in scene": Blender's own error, shown to the user as an ERROR.
BLENDER_ERROR = "BLENDER"

ABI_NAME = re.compile(r"\bstratum_[a-z_]+")

PixelCheck = Callable[[np.ndarray], "str | None"]
Build = Callable[[Any], None]


@dataclass(frozen=True)
class Expect:
    outcome: str
    names: tuple[str, ...] = ()
    words: tuple[str, ...] = ()
    quiet: bool = False  # CLEAN: no warning at all
    pixels: PixelCheck | None = None
    same_as: Build | None = None


@dataclass(frozen=True)
class Case:
    name: str
    area: str
    what: str  # one line: the hostile input
    build: Build
    expect: Expect
    # Size of the image the render writes (width, height); the build sets the resolution when
    # it is not the stage's 16x16.
    size: tuple[int, int] = (16, 16)


CASES: dict[str, Case] = {}


def case(name: str, area: str, what: str, expect: Expect,
         size: tuple[int, int] = (16, 16)) -> Callable[[Build], Build]:
    """Registers the decorated build function as a case."""

    def register(build: Build) -> Build:
        if name in CASES:
            raise ValueError(f"duplicate corpus case {name}")
        CASES[name] = Case(name, area, what, build, expect, size)
        return build

    return register


def clean(quiet: bool = False, pixels: PixelCheck | None = None,
          same_as: Build | None = None) -> Expect:
    return Expect(CLEAN, quiet=quiet, pixels=pixels, same_as=same_as)


def warning(*names: str, words: tuple[str, ...] = (), pixels: PixelCheck | None = None,
            same_as: Build | None = None) -> Expect:
    return Expect(WARNING, names, words, pixels=pixels, same_as=same_as)


def error(*names: str, words: tuple[str, ...] = ()) -> Expect:
    return Expect(ERROR, names, words)


def culprit(*names: str, words: tuple[str, ...] = (), pixels: PixelCheck | None = None) -> Expect:
    return Expect(CULPRIT, names, words, pixels=pixels)


def survive(*names: str, words: tuple[str, ...] = (), pixels: PixelCheck | None = None) -> Expect:
    return Expect(SURVIVE, names, words, pixels=pixels)


# ---- pixel checks ------------------------------------------------------------------------------


def _centre(pixels: np.ndarray) -> np.ndarray:
    """Mean RGB of the middle quarter of the image (where the base scene's cube is)."""
    h, w = pixels.shape[:2]
    block = pixels[h * 3 // 8: max(h * 5 // 8, h * 3 // 8 + 1),
                   w * 3 // 8: max(w * 5 // 8, w * 3 // 8 + 1), :3]
    return block.reshape(-1, 3).mean(axis=0)


def magenta_centre(pixels: np.ndarray) -> str | None:
    """The cube in the middle shows the missing-image magenta (1, 0, 1) under white light."""
    r, g, b = _centre(pixels)
    if r > 2.0 * g and b > 2.0 * g and r > 0.0:
        return None
    return f"the centre is not magenta: mean RGB ({r:.4g}, {g:.4g}, {b:.4g})"


def lit_centre(pixels: np.ndarray) -> str | None:
    """Something with radiance > 0 is seen in the middle of the image."""
    mean = _centre(pixels)
    return None if mean.max() > 0.0 else "the centre of the image is black"


def lit(pixels: np.ndarray) -> str | None:
    """Some pixel has radiance > 0."""
    return None if pixels[..., :3].max() > 0.0 else "the image is black"


def centre_colour(rgb: tuple[float, float, float], ratio: float = 2.0) -> PixelCheck:
    """The centre's dominant channels are those of `rgb`: each channel that is 1 in `rgb` is
    more than `ratio` times each channel that is 0 (a colour check robust to lighting)."""

    def check(pixels: np.ndarray) -> str | None:
        mean = _centre(pixels)
        hi = [mean[i] for i in range(3) if rgb[i] > 0.5]
        lo = [mean[i] for i in range(3) if rgb[i] <= 0.5]
        if hi and min(hi) > 0.0 and (not lo or min(hi) > ratio * max(lo)):
            return None
        return f"the centre is not the colour {rgb}: mean RGB {tuple(round(float(v), 4) for v in mean)}"

    return check


def all_of(*checks: PixelCheck) -> PixelCheck:
    def check(pixels: np.ndarray) -> str | None:
        for c in checks:
            failure = c(pixels)
            if failure:
                return failure
        return None

    return check


# ---- judging -----------------------------------------------------------------------------------


@dataclass
class Render:
    """What one render gave: the messages (level, text) and the image (None: none written)."""

    reports: list[tuple[str, str]] = field(default_factory=list)
    pixels: np.ndarray | None = None

    def messages(self, *levels: str) -> list[str]:
        return [m for lvl, m in self.reports if lvl in levels]


def _names_culprit(message: str, expect: Expect) -> bool:
    if not all(any(alt in message for alt in n.split("|")) for n in expect.names):
        return False
    low = message.lower()
    return not expect.words or any(w.lower() in low for w in expect.words)


def judge(c: Case, render: Render, reference: Render | None) -> list[str]:
    """The failures of a case's render (empty: the case passes)."""
    failures: list[str] = []
    expect = c.expect
    for level, message in render.reports:
        if ABI_NAME.search(message):
            failures.append(f"{level} names an ABI function instead of the culprit: {message}")
        if "internal error" in message.lower() or "Traceback" in message:
            failures.append(f"{level} is an internal error: {message}")
    pixels = render.pixels
    if pixels is not None:
        bad = int(np.count_nonzero(~np.isfinite(pixels)))
        if bad:
            failures.append(f"{bad} non-finite pixel values in the image")
    errors = render.messages("ERROR", BLENDER_ERROR)
    warnings = render.messages("WARNING")
    rendered = not errors and pixels is not None
    naming_errors = [m for m in errors if _names_culprit(m, expect)]
    naming_warnings = [m for m in warnings if _names_culprit(m, expect)]
    culprit_text = f"names {list(expect.names)}" + (
        f" and one of {list(expect.words)}" if expect.words else "")

    if expect.outcome == ERROR:
        if not naming_errors:
            failures.append(f"no ERROR that {culprit_text}")
    elif expect.outcome in (CULPRIT, SURVIVE) and naming_errors:
        pass
    else:
        if errors:
            failures.append(f"ERROR that does not name the culprit: {errors}"
                            if expect.outcome in (CULPRIT, SURVIVE) else f"unexpected ERROR: {errors}")
        elif pixels is None:
            failures.append("no image was written")
        if expect.outcome in (WARNING, CULPRIT) and not naming_warnings:
            failures.append(f"no WARNING (or ERROR) that {culprit_text}")
        if expect.outcome == CLEAN and expect.quiet and warnings:
            failures.append(f"unexpected WARNING: {warnings}")

    if rendered and pixels is not None:
        if pixels.shape[:2] != (c.size[1], c.size[0]):
            failures.append(f"image is {pixels.shape[1]}x{pixels.shape[0]}, expected "
                            f"{c.size[0]}x{c.size[1]}")
        elif expect.pixels is not None:
            failure = expect.pixels(pixels)
            if failure:
                failures.append(failure)
        if expect.same_as is not None:
            failures.extend(_compare(pixels, reference))
    return failures


def _compare(pixels: np.ndarray, reference: Render | None) -> list[str]:
    if reference is None or reference.pixels is None or reference.messages("ERROR"):
        errors = reference.messages("ERROR", BLENDER_ERROR) if reference else []
        return [f"the reference scene did not render: {errors}"]
    ref = reference.pixels
    if ref.shape != pixels.shape:
        return [f"image shape {pixels.shape} differs from the reference's {ref.shape}"]
    if np.array_equal(pixels, ref):
        return []
    diff = np.abs(pixels.astype(np.float64) - ref)
    message = (f"image differs from the scene without the culprit: "
               f"{int(np.count_nonzero(diff))} values, max |difference| {np.nanmax(diff):.4g}")
    return [message]
