"""The fallbacks for invalid Blender values (stratum.shaders.fallbacks), the degenerate-transform test
(stratum.export.placement) and StratumError's split of the ABI function from the detail; no Blender
needed."""

from __future__ import annotations

import math

import numpy as np
import pytest
from stratum import native
from stratum.export import placement
from stratum.shaders.fallbacks import (
    COAT_IOR,
    FLT_MAX,
    IOR,
    NON_NEGATIVE,
    UNIT,
    Range,
    clamp,
    clamp_rgb,
    finite_product,
)

NAN = float("nan")


@pytest.mark.parametrize(("value", "valid", "expected"), [
    (NAN, UNIT, 0.0),  # saturatef(NaN) = 0
    (-0.5, UNIT, 0.0),
    (3e38, UNIT, 1.0),
    (NAN, IOR, 1e-5),  # fmaxf(NaN, 1e-5f) = 1e-5
    (0.0, IOR, 1e-5),
    (-2.0, IOR, 1e-5),
    (NAN, COAT_IOR, 1.0),
    (0.5, COAT_IOR, 1.0),
    (NAN, NON_NEGATIVE, 0.0),
    (-1.0, NON_NEGATIVE, 0.0),
    (math.inf, NON_NEGATIVE, FLT_MAX),
    (-math.inf, NON_NEGATIVE, 0.0),
])
def test_invalid_values_take_cycles_clamp(value: float, valid: Range, expected: float) -> None:
    fixed, problem = clamp(value, valid)
    assert fixed == expected
    assert problem is not None and f"using {expected:g}" in problem


@pytest.mark.parametrize(("value", "words"), [
    (NAN, "is not a number"), (math.inf, "is infinite"), (-1.0, "is below 0"),
    (2.0, "is above 1"),
])
def test_messages_say_what_is_wrong(value: float, words: str) -> None:
    _, problem = clamp(value, UNIT)
    assert problem is not None and words in problem


@pytest.mark.parametrize("value", [0.0, 0.25, 1.0])
def test_valid_values_pass_unchanged(value: float) -> None:
    assert clamp(value, UNIT) == (value, None)
    assert clamp_rgb((value, value, value), UNIT) == ((value, value, value), None)


def test_colour_components_are_fixed_one_by_one() -> None:
    fixed, problem = clamp_rgb((NAN, 0.5, 2.0), UNIT)
    assert fixed == (0.0, 0.5, 1.0)
    assert problem is not None and "nan" in problem and "(0, 0.5, 1)" in problem


def test_emission_products_stop_at_the_largest_float() -> None:
    assert finite_product((1.0, 0.5, 0.0), 3e38) == ((3e38, 1.5e38, 0.0), False)
    radiance, limited = finite_product((2.0, 1.0, 0.0), 3e38)
    assert limited and radiance == (FLT_MAX, 3e38, 0.0)


def _transform(linear: np.ndarray) -> np.ndarray:
    m = np.eye(4)
    m[:3, :3] = linear
    m[:3, 3] = (5.0, -2.0, 1.0)
    return m


@pytest.mark.parametrize(("linear", "skipped"), [
    (np.diag([1.0, 0.0, 1.0]), True),  # a linked duplicate flattened to zero
    (np.diag([1e-18] * 3), True),  # det 1e-54: 0 in float32
    (np.array([[1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 1.0]]), True),  # sheared flat
    (np.diag([1.0, 1e-10, 1.0]), True),
    (np.eye(3), False),
    (np.diag([1.0, 1e-8, 1.0]), False),  # thin but traceable: rays stay below 1e8 R
    (np.diag([1e-8] * 3), False),  # a small object: det 1e-24, a normal float32
    (np.diag([1e6, 1e-8, 1e6]), False),
])
def test_degenerate_transforms(linear: np.ndarray, skipped: bool) -> None:
    matrices = np.stack([_transform(linear), _transform(np.eye(3))]).astype(np.float32)
    assert placement.degenerate(matrices).tolist() == [skipped, False]


def test_smallest_scale_is_exact_below_the_threshold_and_a_bound_above() -> None:
    rng = np.random.default_rng(12)
    linear = rng.normal(size=(200, 3, 3))
    linear[:100] *= 1e-10  # all below MIN_SCALE: exact (SVD)
    matrices = np.stack([_transform(m) for m in linear])
    exact = np.linalg.svd(linear, compute_uv=False)[:, -1]
    found = placement.smallest_scales(matrices)
    assert found[:100] == pytest.approx(exact[:100], rel=1e-9)
    assert np.all(found[100:] <= exact[100:] * (1 + 1e-12))  # a lower bound elsewhere


def test_first_non_finite_names_the_row_major_element() -> None:
    m = np.eye(4)
    m[0, 3] = NAN
    assert placement.first_non_finite(m)[0] == 3
    assert placement.first_non_finite(np.eye(4)) is None


def test_stratum_error_keeps_the_function_apart() -> None:
    error = native.StratumError(native.ERROR_INVALID_ARGUMENT,
                                "stratum_scene_add_instance: instance transform element 3 = nan "
                                "is not finite", index=4)
    assert error.function == "stratum_scene_add_instance"
    assert str(error) == "instance transform element 3 = nan is not finite"
    assert error.message.startswith("stratum_scene_add_instance: ") and error.index == 4


@pytest.mark.parametrize("message", ["texture: unknown colour space 'X'",
                                     "Renderer is closed", "mesh vertex 2: (nan, 0, 0)"])
def test_stratum_error_without_a_function_prefix_is_kept_whole(message: str) -> None:
    error = native.StratumError(native.ERROR_INVALID_ARGUMENT, message)
    assert str(error) == message and error.function == ""
