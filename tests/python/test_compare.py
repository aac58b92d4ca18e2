"""`stratum compare`: metrics against independent computations, the cache and resume (with a
fake Blender that writes known EXRs and logs its invocations), bad input, a Dask cluster
against a local run, and the acceptance run through real Blender (which also needs the report,
stratum/compare/report.py, written separately)."""

from __future__ import annotations

import csv
import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from stratum import cli
from stratum.cli import blender_process
from stratum.compare import estimators, exr, metrics, plan

REPO = Path(__file__).resolve().parents[2]
CORNELL = REPO / "scenes" / "cornell_box.blend"
TIMING_COLUMNS = ("seconds", "trace_seconds")
INTEGRATORS = ("path", "direct", "ao", "light")


# ---- metrics -------------------------------------------------------------------------------


def _pair(shape: tuple[int, int] = (24, 32)) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(5)
    ref = rng.uniform(0.0, 2.0, size=(*shape, 3)).astype(np.float32)
    test = np.maximum(ref + rng.normal(0.0, 0.2, size=ref.shape), 0.0).astype(np.float32)
    return test, ref


def test_mse_and_rel_mse_match_numpy() -> None:
    test, ref = _pair()
    t, r = test.astype(np.float64), ref.astype(np.float64)
    total, rel = 0.0, 0.0
    for c in range(3):  # written differently on purpose: per channel, then averaged
        d = t[..., c] - r[..., c]
        total += np.sum(d**2)
        rel += np.sum(d**2 / (r[..., c] ** 2 + 0.01))
    n = t.size
    assert metrics.mse(test, ref) == pytest.approx(total / n, rel=1e-12)
    assert metrics.rel_mse(test, ref) == pytest.approx(rel / n, rel=1e-12)
    # Known values: a constant offset of 0.5 on a reference of 1 everywhere.
    ones = np.ones((4, 4, 3), np.float32)
    assert metrics.mse(ones + 0.5, ones) == pytest.approx(0.25)
    assert metrics.rel_mse(ones + 0.5, ones) == pytest.approx(0.25 / 1.01)


def test_crop_region_is_x_y_from_the_top_left() -> None:
    image = np.arange(6 * 8 * 3).reshape(6, 8, 3)
    region = metrics.crop_region(image, (2, 1, 3, 4))
    assert region.shape == (4, 3, 3)
    assert (region == image[1:5, 2:5]).all()


def _srgb(x: np.ndarray) -> np.ndarray:
    x = np.clip(x.astype(np.float64), 0, 1)
    low = x * 12.92
    high = 1.055 * x ** (1 / 2.4) - 0.055
    return np.where(x > 0.0031308, high, low).astype(np.float32)


def test_flip_equals_flip_evaluator_on_the_same_pair() -> None:
    import flip_evaluator

    test, ref = _pair((40, 40))
    _, ldr, _ = flip_evaluator.evaluate(_srgb(ref), _srgb(test), "LDR")
    _, hdr, _ = flip_evaluator.evaluate(ref, test, "HDR")
    assert metrics.flip_ldr(test, ref) == pytest.approx(ldr, rel=1e-6)
    assert metrics.flip_hdr(test, ref) == pytest.approx(hdr, rel=1e-6)
    assert 0 < ldr < 1 and 0 < hdr < 1
    assert metrics.flip_ldr(ref, ref) == pytest.approx(0.0, abs=1e-7)


def test_slope_recovers_a_power_law() -> None:
    spp = [1, 2, 4, 8, 16, 64]
    assert metrics.loglog_slope(spp, [3.0 * n**-1.5 for n in spp]) == pytest.approx(-1.5)
    assert metrics.loglog_slope(spp, [0.2 * n**-1.0 for n in spp]) == pytest.approx(-1.0)
    # Noisy power law: least squares in log-log space, against np.polyfit.
    rng = np.random.default_rng(2)
    y = [2.0 * n**-1.2 * math.exp(rng.normal(0, 0.05)) for n in spp]
    assert metrics.loglog_slope(spp, y) == pytest.approx(
        np.polyfit(np.log(spp), np.log(y), 1)[0], rel=1e-10)
    assert metrics.loglog_slope([4], [1.0]) is None
    assert metrics.loglog_slope([1, 2], [0.0, 1.0]) is None  # one usable point


def test_ci95_against_a_hand_computation() -> None:
    # 1, 2, 3, 4: mean 2.5, s = sqrt(5/3) = 1.290994, t_{0.975,3} = 3.182446,
    # half width = 3.182446 * 1.290994 / 2 = 2.054260.
    mean, low, high = metrics.mean_ci95([1.0, 2.0, 3.0, 4.0])
    assert mean == 2.5
    assert low == pytest.approx(2.5 - 2.054260, abs=1e-5)
    assert high == pytest.approx(2.5 + 2.054260, abs=1e-5)
    # n = 2: t = 12.706205, s = |a - b| / sqrt(2): half width = 12.706205 * |a - b| / 2.
    mean, low, high = metrics.mean_ci95([1.0, 3.0])
    assert (low, high) == pytest.approx((2.0 - 12.706205, 2.0 + 12.706205))
    assert metrics.mean_ci95([0.7]) == (0.7, 0.7, 0.7)
    assert metrics.t975(30) == pytest.approx(2.042272)
    assert metrics.t975(50) == pytest.approx(2.0086, abs=1e-3)  # table value 2.008559
    assert metrics.t975(10**6) == pytest.approx(1.959964, abs=1e-4)


def test_noise_floor_is_the_variance_of_the_mean() -> None:
    rng = np.random.default_rng(11)
    parts = [rng.uniform(0, 1, size=(8, 6, 3)) for _ in range(4)]
    mean, floor = metrics.reference_noise_floor(parts)
    stack = np.array(parts)
    expected_mean = (parts[0] + parts[1] + parts[2] + parts[3]) / 4
    var = sum((p - expected_mean) ** 2 for p in parts) / 3  # sample variance, ddof = 1
    np.testing.assert_allclose(mean, expected_mean)
    assert floor["mse"] == pytest.approx(float(np.mean(var / 4)))
    assert floor["rel_mse"] == pytest.approx(float(np.mean(var / 4 / (expected_mean**2 + 0.01))))
    _, cropped = metrics.reference_noise_floor(list(stack), (1, 2, 3, 4))
    assert cropped["mse"] == pytest.approx(float(np.mean(var[2:6, 1:4] / 4)))
    assert metrics.reference_noise_floor(parts[:1])[1] == {"mse": None, "rel_mse": None}


def test_exr_round_trip(tmp_path: Path) -> None:
    image = np.random.default_rng(1).uniform(0, 5, size=(7, 9, 3)).astype(np.float32)
    exr.write_rgb(tmp_path / "a.exr", image)
    np.testing.assert_array_equal(exr.read_rgb(tmp_path / "a.exr"), image)
    assert [p.name for p in tmp_path.iterdir()] == ["a.exr"]  # no temporary left
    (tmp_path / "bad.exr").write_bytes(b"not an exr")
    with pytest.raises(exr.ExrError):
        exr.read_rgb(tmp_path / "bad.exr")


# ---- plan ----------------------------------------------------------------------------------


def _estimator(spec: str = "path", common: dict[str, Any] | None = None) -> Any:
    return estimators.resolve(estimators.parse_spec(spec, INTEGRATORS), common or {})


def test_cache_key_changes_with_every_setting(native: Any) -> None:
    base = plan.SceneSettings("abc", (16, 16), "cosine", 8)
    path = _estimator()
    key = plan.cache_key(base, path, "sobol", 4, 0)
    assert key == plan.cache_key(plan.SceneSettings("abc", (16, 16), "cosine", 8),
                                 _estimator("path:light_sampling=mis"), "sobol", 4, 0)
    others = [plan.cache_key(plan.SceneSettings("abd", (16, 16), "cosine", 8), path, "sobol",
                             4, 0),
              plan.cache_key(plan.SceneSettings("abc", (16, 8), "cosine", 8), path, "sobol",
                             4, 0),
              plan.cache_key(plan.SceneSettings("abc", (16, 16), "uniform", 8), path,
                             "sobol", 4, 0),
              plan.cache_key(plan.SceneSettings("abc", (16, 16), "cosine", 2), path,
                             "sobol", 4, 0),
              plan.cache_key(base, path, "random", 4, 0), plan.cache_key(base, path, "sobol", 8, 0),
              plan.cache_key(base, path, "sobol", 4, 1),
              plan.cache_key(base, _estimator("ao"), "sobol", 4, 0),
              plan.cache_key(base, _estimator("direct"), "sobol", 4, 0)]
    # Every estimator setting is in the key, whether a spec or --set gives it.
    for name, value in (("light_sampling", "nee"), ("mis_heuristic", "balance"),
                        ("light_selection", "power"), ("triangle_sampling", "area"),
                        ("rr_mode", "off"), ("rr_min_depth", 5),
                        ("control_variate", 0.25)):
        others.append(plan.cache_key(base, _estimator(f"path:{name}={value}"), "sobol", 4, 0))
        assert plan.cache_key(base, _estimator("path", {name: value}), "sobol", 4, 0) == \
            others[-1]
    assert len({key, *others}) == len(others) + 1


def test_batches_balance_cost(native: Any) -> None:
    settings = plan.SceneSettings("abc", (16, 16), "cosine", 8)
    path = _estimator()
    tests, refs = plan.plan(settings, [path], ["a", "b", "c"], [1, 4, 16], [0, 1], path,
                            "sobol", 256, [100000, 100001])
    batches = plan.split_batches(refs + tests, 2)
    assert len(batches) == 2
    assert sorted(c.key for b in batches for c in b) == sorted(c.key for c in refs + tests)
    loads = [sum(c.cost for c in b) for b in batches]
    assert max(loads) - min(loads) <= 258  # within one reference render
    assert not {r.seed for r in refs} & {t.seed for t in tests}


# ---- estimator specs ---------------------------------------------------------------------


@pytest.mark.parametrize(("text", "expected"), [
    ("path", [("path", "mis-power", {})]),
    ("path:light_sampling=bsdf,path:light_sampling=nee,direct",
     [("path", "bsdf", {"light_sampling": "bsdf"}), ("path", "nee", {"light_sampling": "nee"}),
      ("direct", "direct", {})]),
    ("path:light_sampling=mis,mis_heuristic=balance,path:mis_heuristic=max",
     [("path", "mis-balance", {"light_sampling": "mis", "mis_heuristic": "balance"}),
      ("path", "mis-max", {"mis_heuristic": "max"})]),
    (" light , path:rr_mode=off,rr_min_depth=0,control_variate=0.5 ",
     [("light", "light", {}),
      ("path", "mis-power+rr-off+rrmin0+cv0.5",
       {"rr_mode": "off", "rr_min_depth": 0, "control_variate": 0.5})]),
    ("direct:light_selection=uniform,ao",
     [("direct", "direct+sel-uniform", {"light_selection": "uniform"}), ("ao", "ao", {})]),
    ("path:light_sampling=nee,triangle_sampling=area,path:light_sampling=nee",
     [("path", "nee+tri-area", {"light_sampling": "nee", "triangle_sampling": "area"}),
      ("path", "nee", {"light_sampling": "nee"})]),
    ("path,path:use_adaptive_sampling=1,adaptive_threshold=0.02",
     [("path", "mis-power", {}),
      ("path", "mis-power+adaptive1+thr0.02",
       {"use_adaptive_sampling": 1, "adaptive_threshold": 0.02})]),
    # Path guiding (issue 17, acceptance 6): `path:use_guiding=1` and its two settings.
    (("path,path:use_guiding=1,path:use_guiding=1,guiding_training_samples=8,"
      "guiding_bsdf_fraction=0.25"),
     [("path", "mis-power", {}),
      ("path", "mis-power+guided1", {"use_guiding": 1}),
      ("path", "mis-power+guided1+train8+bf0.25",
       {"use_guiding": 1, "guiding_training_samples": 8, "guiding_bsdf_fraction": 0.25})]),
])
def test_estimator_specs_parse_resolve_and_label(native: Any, text: str,
                                                  expected: list[Any]) -> None:
    resolved = estimators.resolve_all(estimators.parse_specs(text, INTEGRATORS), {})
    assert [(e.integrator, e.label) for e, _ in zip(resolved, expected, strict=True)] == [
        (i, label) for i, label, _ in expected]
    for est, (_, _, given) in zip(resolved, expected, strict=True):
        assert dict(est.settings) == {**estimators.defaults(), **given}
        assert [n for n, _ in est.settings] == list(estimators.SETTING_NAMES)


def test_common_settings_apply_under_the_specs_own(native: Any) -> None:
    common = estimators.parse_settings(["rr_mode=albedo", "light_sampling=nee"], "--set")
    specs = estimators.parse_specs("path,path:light_sampling=bsdf", INTEGRATORS)
    scene = {"rr_mode": "off", "rr_min_depth": 7}  # the scene's own values, under --set
    nee, bsdf = estimators.resolve_all(specs, common, scene)
    assert (nee.label, nee.setting("light_sampling"), nee.setting("rr_mode")) == (
        "nee", "nee", "albedo")
    assert (bsdf.label, bsdf.setting("light_sampling"), bsdf.setting("rr_min_depth")) == (
        "bsdf", "bsdf", 7)


@pytest.mark.parametrize(("text", "named"), [
    ("bogus", "'bogus'"),
    ("path,pathh", "'pathh'"),
    ("path:light_sampling=sometimes", "'sometimes'"),
    ("path:mis_heuristic=cubic", "'cubic'"),
    ("path:light_selection=random", "'random'"),
    ("path:rr_mode=never", "'never'"),
    ("path:rr_min_depth=two", "'two'"),
    ("path:rr_min_depth=-1", "-1"),
    ("path:rr_min_depth=5000", "5000"),
    ("path:control_variate=-0.5", "'-0.5'"),
    ("path:control_variate=nan", "'nan'"),
    ("path:control_variate=much", "'much'"),
    ("path:use_guiding=2", "2"),
    ("path:guiding_bsdf_fraction=0.01", "0.01"),
    ("path:max_bouncez=3", "'max_bouncez'"),
    ("path:light_sampling", "'light_sampling'"),
    ("path:", "'path:'"),
    ("light_sampling=nee", "'light_sampling=nee'"),
    ("path,,direct", "empty item"),
    ("path:light_sampling=nee,light_sampling=bsdf", "light_sampling given twice"),
    ("path,path:light_sampling=mis", "same estimator"),
    ("path:light_sampling=nee,path:light_sampling=nee,mis_heuristic=max", "same label"),
])
def test_bad_estimator_specs_name_the_bad_part(native: Any, text: str, named: str) -> None:
    with pytest.raises(estimators.SpecError) as info:
        estimators.resolve_all(estimators.parse_specs(text, INTEGRATORS), {})
    assert named in str(info.value)


def test_a_scenes_checkbox_resolves_to_the_librarys_0_or_1(native: Any) -> None:
    """The probe reads scene.stratum.use_adaptive_sampling, a checkbox, as a bool."""
    [est] = estimators.resolve_all(estimators.parse_specs("path", INTEGRATORS), {},
                                   {"use_adaptive_sampling": True, "adaptive_threshold": 0.05})
    assert est.setting("use_adaptive_sampling") == 1
    assert est.setting("adaptive_threshold") == 0.05


def test_setting_values_are_the_native_renderers(native: Any, tiny_scene: Any) -> None:
    """The spec parser takes what the renderer takes, as the library lists it: every choice
    and both ends of every range parse and render, and one step past a range or a name that
    is no choice is a SpecError naming the value."""
    for name in estimators.SETTING_NAMES:
        setting = native.setting(name)
        # An open minimum (radiosity_tolerance's 0) is itself rejected: the next float32 (the
        # renderer stores a float) is the end.
        lowest = (float(np.nextafter(np.float32(setting.minimum), np.float32(math.inf)))
                  if setting.open_minimum else setting.minimum)
        accepted = setting.choice_names() or [lowest, setting.maximum]
        for value in accepted:
            parsed = estimators.parse_value(name, str(value), "test")
            with native.Renderer(tiny_scene, **{name: parsed}):
                pass
        if setting.choices:
            rejected = [f"{accepted[0]}x"]
        elif setting.kind == native.SettingKind.INT:
            rejected = [setting.minimum - 1, setting.maximum + 1]
        else:
            rejected = [setting.minimum - 0.5, setting.maximum * 2, float("nan")]
        for value in rejected:
            with pytest.raises(estimators.SpecError, match=name):
                estimators.parse_value(name, str(value), "test")
            with pytest.raises(native.StratumError):
                native.Renderer(tiny_scene, **{name: value})
    assert estimators.defaults() == {n: native.setting(n).default
                                     for n in estimators.SETTING_NAMES}


def test_batch_sets_every_estimator_setting_or_fails_naming_it() -> None:
    from types import SimpleNamespace

    from stratum.compare.blender_batch import set_estimator_settings

    props = SimpleNamespace(light_sampling="mis", rr_mode="throughput")
    set_estimator_settings(props, {"light_sampling": "nee", "rr_mode": "off"})
    assert (props.light_sampling, props.rr_mode) == ("nee", "off")
    with pytest.raises(RuntimeError, match="no property 'control_variate'.*control_variate=0.5"):
        set_estimator_settings(props, {"control_variate": 0.5})


# ---- a fake Blender: writes known EXRs, logs what it renders -------------------------------

FAKE_BLENDER = r'''#!{python}
"""Stands in for `blender -b SCENE --python blender_batch.py -- BATCH.json`."""
import json, os, sys, zlib
from pathlib import Path
import numpy as np

script = Path(sys.argv[sys.argv.index("--python") + 1])
payload = json.loads(Path(sys.argv[sys.argv.index("--") + 1]).read_text())
log = Path(os.environ["FAKE_BLENDER_LOG"])
with open(log, "a") as f:
    f.write(json.dumps({{"mode": payload["mode"],
                        "keys": [c["key"] for c in payload.get("configs", [])]}}) + "\n")
sys.path.insert(0, str(script.parent))
import blender_batch  # only the standard library: no bpy needed for run_batch
if payload["mode"] == "probe":
    blender_batch.write_json_atomic(Path(payload["probe_output"]), {{
        "resolution": [12, 10], "integrator": "path", "hemisphere": "cosine",
        "max_bounces": 4, "sampler": "random", "samples": 16}})
    os._exit(0)
sys.path.insert(0, payload["addon_parent"])
from stratum.compare.exr import write_rgb

def render(entry, path):
    if os.environ.get("FAKE_BLENDER_FAIL") == entry["sampler"]:
        raise RuntimeError("fake failure of " + entry["label"])
    w, h = entry["resolution"]
    y, x = np.mgrid[0:h, 0:w]
    truth = np.stack([(x + 1) / w, (y + 1) / h, np.full((h, w), 0.5)], -1)
    settings = json.dumps(entry["estimator_settings"], sort_keys=True)
    seed = zlib.crc32(f"{{entry['integrator']}}{{settings}}{{entry['sampler']}}"
                      f"{{entry['seed']}}{{entry['samples']}}".encode())
    noise = np.random.default_rng(seed).normal(0, 0.3, truth.shape)
    write_rgb(path.with_suffix(".exr"), truth + noise / np.sqrt(entry["samples"]))
    return {{"seconds": 0.001 * entry["samples"], "trace_seconds": 0.0005 * entry["samples"]}}

try:
    blender_batch.run_batch(payload, render)
except Exception as exc:
    print(f"stratum compare: {{exc}}", file=sys.stderr)
    os._exit(1)
os._exit(0)
'''


@pytest.fixture
def fake_blender(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    exe = tmp_path / "fake_blender"
    exe.write_text(FAKE_BLENDER.format(python=sys.executable))
    exe.chmod(0o755)
    log = tmp_path / "blender.log"
    log.write_text("")
    monkeypatch.setenv("STRATUM_BLENDER", str(exe))
    monkeypatch.setenv("FAKE_BLENDER_LOG", str(log))
    return log


def _calls(log: Path) -> list[dict[str, Any]]:
    return [json.loads(line) for line in log.read_text().splitlines()]


@pytest.fixture
def no_report(monkeypatch: pytest.MonkeyPatch) -> list[dict[str, Any]]:
    """Replaces the report step (tested on its own) by a recorder."""
    from stratum.compare import command

    seen: list[dict[str, Any]] = []
    monkeypatch.setattr(command, "_report", lambda out, results: seen.append(results) or 0)
    return seen


def _compare(out: Path, *extra: str, scene: Path = CORNELL) -> int:
    return cli.main(["compare", str(scene), "--samplers", "random,sobol", "--spp", "1,4",
                     "--seeds", "3", "--reference-spp", "64", "--out", str(out), *extra])


def test_results_json_schema_and_values(native: Any, fake_blender: Path, tmp_path: Path,
                                        no_report: list[dict[str, Any]]) -> None:
    out = tmp_path / "out"
    assert _compare(out, "--crop", "2,1,8,6") == 0
    results = json.loads((out / "results.json").read_text())
    assert results == no_report[0]
    assert results["resolution"] == [12, 10] and results["crop"] == [2, 1, 8, 6]
    assert (results["integrator"], results["hemisphere"], results["max_bounces"]) == (
        "path", "cosine", 4)
    assert results["samplers"] == ["random", "sobol"] and results["spp"] == [1, 4]
    assert results["seeds"] == [0, 1, 2]
    ref = results["reference"]
    assert ref["source"] == "rendered" and ref["spp"] == 64 and len(ref["seeds"]) == 4
    assert not set(ref["seeds"]) & set(results["seeds"])
    parts = [exr.read_rgb(out / p) for p in ref["parts"]]
    mean = np.mean(np.array(parts, dtype=np.float64), axis=0)
    np.testing.assert_allclose(exr.read_rgb(out / ref["path"]), mean, rtol=1e-6)
    var = np.var(np.array(parts, dtype=np.float64), axis=0, ddof=1)[1:7, 2:10] / 4
    assert ref["noise_floor"]["mse"] == pytest.approx(float(var.mean()), rel=1e-5)
    assert len(results["renders"]) == 2 * 2 * 3
    for r in results["renders"]:
        image = exr.read_rgb(out / r["path"])[1:7, 2:10].astype(np.float64)
        refc = exr.read_rgb(out / ref["path"])[1:7, 2:10].astype(np.float64)
        assert r["mse"] == pytest.approx(float(np.mean((image - refc) ** 2)), rel=1e-6)
        assert r["seconds"] == pytest.approx(0.001 * r["spp"])
        assert r["below_noise_floor"] == (r["mse"] <= 3 * ref["noise_floor"]["mse"]
                                          or r["rel_mse"] <= 3 * ref["noise_floor"]["rel_mse"])
        assert set(r) >= {"sampler", "spp", "seed", "path", "seconds", "mse", "rel_mse",
                          "flip_ldr", "flip_hdr", "below_noise_floor"}
    rows = [s for s in results["summary"] if s["sampler"] == "sobol" and s["spp"] == 4
            and s["metric"] == "mse"]
    assert len(rows) == 1 and rows[0]["n"] == 3
    values = [r["mse"] for r in results["renders"] if r["sampler"] == "sobol" and r["spp"] == 4]
    mean_, low, high = metrics.mean_ci95(values)
    assert (rows[0]["mean"], rows[0]["ci95_low"], rows[0]["ci95_high"]) == pytest.approx(
        (mean_, low, high))
    assert {s["metric"] for s in results["summary"]} == {"mse", "rel_mse", "flip_ldr",
                                                         "flip_hdr", "seconds",
                                                         "trace_seconds"}
    # The fake's noise falls as 1/sqrt(spp): MSE ~ spp^-1 (plus the reference's floor).
    for sampler in ("random", "sobol"):
        slopes = results["slopes"][sampler]
        assert set(slopes) >= {"mse", "rel_mse", "flip_ldr", "flip_hdr", "mse_vs_seconds"}
        assert -1.1 < slopes["mse"] < -0.8, slopes
    with open(out / "results.csv") as f:
        assert len(list(csv.DictReader(f))) == 12


def test_two_estimators_are_an_axis_like_samplers(native: Any, fake_blender: Path,
                                                 tmp_path: Path,
                                                 no_report: list[dict[str, Any]]) -> None:
    out = tmp_path / "out"
    specs = "path:light_sampling=bsdf,path:light_sampling=nee"
    assert cli.main(["compare", str(CORNELL), "--samplers", "random", "--integrator", specs,
                     "--set", "rr_mode=off", "--spp", "1,4", "--seeds", "2",
                     "--reference-spp", "16", "--reference-renders", "2",
                     "--out", str(out)]) == 0
    results = json.loads((out / "results.json").read_text())
    assert results["series"] == ["bsdf", "nee"] and results["samplers"] == ["random"]
    assert [e["label"] for e in results["estimators"]] == ["bsdf", "nee"]
    assert results["common_settings"] == {"rr_mode": "off"}
    ref = results["reference"]["estimator"]
    assert (ref["label"], ref["integrator"]) == ("mis-power", "path")
    assert ref["settings"]["rr_mode"] == "off"  # --set applies to the reference too
    assert len(results["renders"]) == 2 * 2 * 2
    for r in results["renders"]:
        assert r["series"] == r["estimator"] and r["integrator"] == "path"
        assert r["estimator_settings"]["light_sampling"] == r["estimator"]
        assert r["estimator_settings"]["rr_mode"] == "off"
    assert {(s["series"], s["spp"]) for s in results["summary"]} == {
        (e, n) for e in ("bsdf", "nee") for n in (1, 4)}
    assert set(results["slopes"]) == {"bsdf", "nee"}
    with open(out / "results.csv") as f:
        rows = list(csv.DictReader(f))
    assert {r["estimator"] for r in rows} == {"bsdf", "nee"}
    assert json.loads(rows[0]["estimator_settings"])["rr_mode"] == "off"
    # Every configuration rendered once, all keys distinct; the same estimators again
    # (in the other order) render nothing.
    keys = [k for c in _calls(fake_blender) for k in c["keys"]]
    assert len(keys) == len(set(keys)) == 8 + 2
    fake_blender.write_text("")
    assert cli.main(["compare", str(CORNELL), "--samplers", "random", "--integrator",
                     "path:light_sampling=nee,path:light_sampling=bsdf", "--set",
                     "rr_mode=off", "--spp", "1,4", "--seeds", "2", "--reference-spp", "16",
                     "--reference-renders", "2", "--out", str(out)]) == 0
    assert [c["mode"] for c in _calls(fake_blender)] == ["probe"]
    # Several estimators and several samplers: series label/sampler.
    assert cli.main(["compare", str(CORNELL), "--samplers", "random,sobol", "--integrator",
                     specs, "--spp", "1", "--seeds", "2", "--reference-spp", "16",
                     "--reference-renders", "2", "--out", str(tmp_path / "both")]) == 0
    assert no_report[-1]["series"] == ["bsdf/random", "bsdf/sobol", "nee/random", "nee/sobol"]


@pytest.mark.parametrize(("args", "named"), [
    (["--integrator", "path,bogus_integrator"], "bogus_integrator"),
    (["--integrator", "path:light_sampling=sometimes"], "sometimes"),
    (["--set", "rr_mode=never"], "never"),
    (["--set", "no_such_setting=1"], "no_such_setting"),
    (["--reference-integrator", "path:mis_heuristic=cubic"], "cubic"),
    (["--max-bounces", "2000"], "2000"),
])
def test_bad_estimator_options_exit_non_zero_naming_the_value(
        native: Any, fake_blender: Path, tmp_path: Path, args: list[str], named: str) -> None:
    out = tmp_path / "out"
    proc = subprocess.run([sys.executable, "-m", "stratum.cli", "compare", str(CORNELL),
                           "--out", str(out), *args], check=False, capture_output=True,
                          text=True, timeout=120, env=dict(os.environ))
    assert proc.returncode == 2
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("stratum compare:") and named in lines[0]
    assert not out.exists()
    assert _calls(fake_blender) == []


def test_resume_skips_finished_configurations(native: Any, fake_blender: Path, tmp_path: Path,
                                              no_report: list[dict[str, Any]]) -> None:
    out = tmp_path / "out"
    assert _compare(out, "--jobs", "2") == 0
    first = _calls(fake_blender)
    rendered = [k for c in first for k in c["keys"]]
    assert [c["mode"] for c in first].count("probe") == 1
    assert len(rendered) == len(set(rendered)) == 12 + 4
    assert sum(c["mode"] == "render" for c in first) == 2  # one Blender per job
    csv_first = (out / "results.csv").read_text()

    fake_blender.write_text("")
    assert _compare(out, "--jobs", "2") == 0
    assert [c["mode"] for c in _calls(fake_blender)] == ["probe"]  # nothing re-rendered
    assert (out / "results.csv").read_text() == csv_first

    # A crash after the EXR but before the sidecar, a truncated EXR, a temporary left behind:
    # exactly those two configurations are rendered again.
    sidecars = sorted((out / "renders").glob("*_random_spp4_*.json"))
    sidecars[0].unlink()
    damaged = json.loads(sidecars[1].read_text())
    (out / damaged["exr"]).write_bytes((out / damaged["exr"]).read_bytes()[:100])
    (out / "renders" / ".tmp-999-x.exr").write_bytes(b"partial")
    fake_blender.write_text("")
    assert _compare(out, "--jobs", "2") == 0
    again = [k for c in _calls(fake_blender) for k in c["keys"]]
    assert len(again) == 2 and damaged["key"] in again
    assert (out / "results.csv").read_text() == csv_first
    assert not list((out / "renders").glob(".tmp-*"))

    # Another spp only renders the new configurations.
    fake_blender.write_text("")
    assert cli.main(["compare", str(CORNELL), "--samplers", "random,sobol", "--spp", "1,4,2",
                     "--seeds", "3", "--reference-spp", "64", "--out", str(out)]) == 0
    assert len([k for c in _calls(fake_blender) for k in c["keys"]]) == 2 * 3


def test_a_failing_render_leaves_the_others_and_no_trusted_file(
        native: Any, fake_blender: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
        capsys: pytest.CaptureFixture[str], no_report: list[dict[str, Any]]) -> None:
    out = tmp_path / "out"
    monkeypatch.setenv("FAKE_BLENDER_FAIL", "sobol")
    assert _compare(out, "--reference-sampler", "random") == 1
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert "fake failure of mis-power sobol" in err and "6 of 16 renders failed" in err
    assert not (out / "results.json").exists()
    assert not list((out / "renders").glob("*_sobol_*"))
    assert len(list((out / "renders").glob("*_random_*.json"))) == 6  # the others went on
    monkeypatch.delenv("FAKE_BLENDER_FAIL")
    fake_blender.write_text("")
    assert _compare(out, "--reference-sampler", "random") == 0
    keys = [k for c in _calls(fake_blender) for k in c["keys"]]
    assert len(keys) == 6  # only sobol's 2 spp x 3 seeds


def test_reference_file(native: Any, fake_blender: Path, tmp_path: Path,
                        no_report: list[dict[str, Any]]) -> None:
    ref = np.full((10, 12, 3), 0.5, np.float32)
    exr.write_rgb(tmp_path / "ref.exr", ref)
    out = tmp_path / "out"
    with pytest.raises(SystemExit):  # --reference-spp and --reference are exclusive
        _compare(out, "--reference", str(tmp_path / "ref.exr"))
    assert cli.main(["compare", str(CORNELL), "--samplers", "random", "--spp", "1",
                     "--seeds", "2", "--reference", str(tmp_path / "ref.exr"),
                     "--out", str(out)]) == 0
    results = no_report[-1]
    assert results["reference"]["source"] == "file"
    assert results["reference"]["noise_floor"] == {"mse": None, "rel_mse": None}
    assert not any(r["below_noise_floor"] for r in results["renders"])
    assert all(c["mode"] == "probe" or all("reference" not in k for k in c["keys"])
               for c in _calls(fake_blender))
    assert sum(len(c["keys"]) for c in _calls(fake_blender)) == 2


def test_missing_report_module_is_a_clear_error(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    from stratum.compare import command

    monkeypatch.setitem(sys.modules, "stratum.compare.report", None)
    assert command._report(tmp_path, {}) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "report" in err[0]


# ---- bad input -----------------------------------------------------------------------------


@pytest.mark.parametrize("case", ["missing_blend", "unknown_sampler", "unreadable_reference",
                                  "zero_resolution", "zero_spp", "negative_spp"])
def test_bad_input_is_one_line_and_writes_nothing(native: Any, fake_blender: Path,
                                                  tmp_path: Path, case: str) -> None:
    garbage = tmp_path / "garbage.exr"
    garbage.write_bytes(b"\x76\x2f\x31\x01 truncated")
    scene = str(tmp_path / "none.blend") if case == "missing_blend" else str(CORNELL)
    args = {"missing_blend": [],
            "unknown_sampler": ["--samplers", "random,bogus_sampler"],
            "unreadable_reference": ["--reference", str(garbage)],
            "zero_resolution": ["--resolution", "0x16"],
            "zero_spp": ["--spp", "1,0"],
            "negative_spp": ["--spp", "-4"]}[case]
    out = tmp_path / "out"
    proc = subprocess.run([sys.executable, "-m", "stratum.cli", "compare", scene, "--out",
                           str(out), *args], check=False, capture_output=True, text=True,
                          timeout=120,                          env=dict(os.environ))
    assert proc.returncode != 0
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith("stratum compare:")
    assert not out.exists()
    assert _calls(fake_blender) == []  # validated before Blender ran at all


# ---- real Blender --------------------------------------------------------------------------


def _need_blender(native: Any) -> None:
    if blender_process.blender_executable() is None or os.environ.get("STRATUM_BLENDER", "").endswith(
            "fake_blender"):
        pytest.skip("Blender not found (set STRATUM_BLENDER)")
    if not CORNELL.is_file():
        pytest.skip(f"{CORNELL} is missing")


def _rows_without_timing(path: Path) -> list[dict[str, str]]:
    with open(path) as f:
        return [{k: v for k, v in row.items() if k not in TIMING_COLUMNS}
                for row in csv.DictReader(f)]


def test_dask_cluster_gives_the_results_of_a_local_run(native: Any, tmp_path: Path,
                                                        no_report: list[dict[str, Any]]) -> None:
    _need_blender(native)
    from distributed import LocalCluster

    started = time.perf_counter()
    args = ["--samplers", "random,sobol", "--spp", "1,2", "--seeds", "1", "--reference-spp",
            "16", "--resolution", "16x16", "--threads", "1"]
    assert cli.main(["compare", str(CORNELL), *args, "--out", str(tmp_path / "local")]) == 0
    local_done = time.perf_counter()
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster:
        assert cli.main(["compare", str(CORNELL), *args, "--out", str(tmp_path / "dask"),
                         "--scheduler", cluster.scheduler_address]) == 0
    local = _rows_without_timing(tmp_path / "local" / "results.csv")
    dask = _rows_without_timing(tmp_path / "dask" / "results.csv")
    assert len(local) == 2 * 2 and local == dask
    np.testing.assert_array_equal(exr.read_rgb(tmp_path / "local/renders/reference.exr"),
                                  exr.read_rgb(tmp_path / "dask/renders/reference.exr"))
    print(f"local run {local_done - started:.1f} s, Dask run "
          f"{time.perf_counter() - local_done:.1f} s")


@pytest.mark.long
def test_acceptance_cornell_64(native: Any, tmp_path: Path) -> None:
    """Acceptance 2: the documented command, all samplers, through real Blender, including the
    report. Needs stratum/compare/report.py (the report engineer's part of issue 4)."""
    _need_blender(native)
    if not (REPO / "addon" / "stratum" / "compare" / "report.py").is_file():
        pytest.skip("needs stratum/compare/report.py (the report, written separately)")
    from stratum.compare.report import SECTION_TITLES

    cmd = [sys.executable, "-m", "stratum.cli", "compare", str(CORNELL), "--spp", "1,4,16",
           "--seeds", "2", "--reference-spp", "256", "--resolution", "64x64"]
    started = time.perf_counter()
    proc = subprocess.run(cmd, check=False, cwd=tmp_path, capture_output=True, text=True,
                          timeout=900)
    seconds = time.perf_counter() - started
    print(f"acceptance 2: {seconds:.1f} s")
    assert proc.returncode == 0, proc.stderr[-3000:]
    out = tmp_path / "compare-cornell_box"
    results = json.loads((out / "results.json").read_text())
    n_samplers = len(native.registry("sampler"))
    assert len(results["samplers"]) == n_samplers
    assert len(results["renders"]) == n_samplers * 3 * 2
    assert results["reference"]["noise_floor"]["mse"] > 0
    page = (out / "report.html").read_text()
    for title in SECTION_TITLES:
        assert f"<h2>{title}</h2>" in page, title
    assert 'class="problem"' not in page
    assert seconds < 300, f"acceptance run took {seconds:.0f} s"


def test_crop_outside_the_image_is_rejected_before_rendering(
        native: Any, fake_blender: Path, tmp_path: Path,
        capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "out"
    # The fake scene is 12x10: known only after Blender opened it (the probe).
    assert cli.main(["compare", str(CORNELL), "--crop", "4,4,10,4", "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "outside the 12x10 image" in err[0]
    assert [c["mode"] for c in _calls(fake_blender)] == ["probe"]
    assert not out.exists()


def test_progress_bar_without_a_tty() -> None:
    import io

    from stratum.compare.runner import ProgressBar

    settings = plan.SceneSettings("abc", (16, 16), "cosine", 8)
    tests, _ = plan.plan(settings, [_estimator()], ["random"], [1, 4], [0], None, None, None,
                         [])
    stream = io.StringIO()
    bar = ProgressBar(tests, stream=stream, already_done=1)
    bar.event("start", {"key": tests[0].key})
    bar.event("done", {"key": tests[0].key})
    bar.event("done", {"key": tests[0].key})  # reported twice: counted once
    bar.event("start", {"key": tests[1].key})
    bar.event("done", {"key": tests[1].key})
    lines = stream.getvalue().splitlines()
    assert len(lines) == 2 and "\r" not in stream.getvalue()
    assert "2/3 configurations" in lines[0] and "ETA" in lines[0]
    assert "now: mis-power random spp=1 seed=0" in lines[0]
    assert "3/3 configurations" in lines[1] and "ETA 0:00" in lines[1]


# ---- the estimator study (scripts/study/run.py, scripts/study/estimators.py) ------------------


def _study_estimators() -> Any:
    from scripts.study import estimators

    return estimators


def _synthetic_results(costs: dict[str, tuple[float, float]]) -> dict[str, Any]:
    """results.json rows where series s has MSE = v/spp and trace time = c·spp for
    costs[s] = (v, c): MSE·time = v·c at every spp."""
    spps = [1, 4, 16]
    summary = [{"series": s, "spp": n, "metric": metric, "mean": value}
               for s, (v, c) in costs.items() for n in spps
               for metric, value in (("mse", v / n), ("trace_seconds", c * n))]
    return {"series": list(costs), "spp": spps, "summary": summary}


def test_study_equal_time_interpolates_the_mse_time_curve() -> None:
    """On MSE = v/N, t = c·N the MSE at time T is exactly v·c/T (a line of slope -1 in
    log-log), whether T falls between measured points or below an estimator's cheapest."""
    study = _study_estimators()
    nee_area = study.BOOK_NEE
    costs = {"bsdf": (4.0, 0.5), nee_area: (1.0, 1.0), "mis-power": (1.5, 1.2),
             "direct": (0.5, 0.1)}
    budget, at = study.equal_time(_synthetic_results(costs))
    assert budget == pytest.approx(0.5 * 16)  # bsdf is the cheapest unbiased at 16 spp
    for series, (v, c) in costs.items():
        assert at[series][0] == pytest.approx(v * c / budget)
    assert not at["bsdf"][1] and not at[nee_area][1] and at["direct"][1]  # direct ends at 1.6 s
    # Median pixel errors a tenth of the MSE, except the NEE's, which a hundredth: the ratios
    # to mis-power follow.
    medians = {(s, n): v / n / (100.0 if s == nee_area else 10.0)
               for s, (v, _) in costs.items() for n in (1, 4, 16)}
    text, numbers = study.table(_synthetic_results(costs), medians)
    nee = numbers["series"][nee_area]
    assert nee["ratio_equal_spp"] == pytest.approx(1.0 / 1.5)
    assert nee["median_ratio_equal_spp"] == pytest.approx(0.1 / 1.5)
    assert nee["median_ratio_equal_time"] == pytest.approx(0.1 * 1.0 / 1.8)
    assert numbers["series"]["bsdf"]["ratio_equal_time"] == pytest.approx(2.0 / 1.8)
    assert f"| {nee_area} |" in text
    lines = study.verdicts({"est_small": numbers})
    small = next(line for line in lines if line.startswith("- NEE wins for small lights"))
    assert f"{nee_area}/bsdf = 0.25 (MSE, equal spp: shown)" in small
    assert f"{nee_area}/bsdf = 0.5 (MSE, equal time: shown)" in small
    assert f"{nee_area}/bsdf = 0.025 (median px error, equal spp: shown)" in small
    assert any("not measured" in line for line in lines)  # est_large was not given


@pytest.mark.long
def test_study_quick_runs_the_estimator_ladder(native: Any, tmp_path: Path) -> None:
    """`python -m scripts.study.run --quick` on the estimator runs: the pipeline end to end
    through real Blender at toy sizes (32x32, 1 and 4 spp, 2 seeds) into estimators.md."""
    _need_blender(native)
    out = tmp_path / "study"
    started = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "scripts.study.run", "--quick",
                           "--only", "est_small,est_large,est_glossy", "--out", str(out)],
                          cwd=REPO, check=False, capture_output=True, text=True, timeout=900)
    print(f"study --quick (estimators): {time.perf_counter() - started:.0f} s")
    assert proc.returncode == 0, proc.stderr[-3000:]
    page = (out / "estimators.md").read_text()
    labels = ["bsdf", "nee+tri-area", "nee", "mis-balance", "mis-power", "mis-max",
              "mis-power+tri-area", "direct"]
    if "light" in {e.name for e in native.registry("integrator")}:
        labels.append("light")
    for run in ("est_small", "est_large", "est_glossy"):
        assert f"## {run}:" in page
        results = json.loads((out / run / "results.json").read_text())
        assert sorted(results["series"]) == sorted(labels)
        assert (out / run / "report.html").is_file()
    assert page.count("(MSE, equal spp: ") >= 9
    assert not [line for line in page.splitlines()
                if "not measured" in line and "light tracing" not in line]
    assert (out / "figures" / "estimators_mse.png").is_file()
    assert "## Estimators (issue 6)" in (out / "summary.md").read_text()
