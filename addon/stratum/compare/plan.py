"""What `stratum compare` renders: the configurations (estimator x sampler x spp x seed, plus
the reference renders), their cache keys and file names, and which of them are already done.

Cache key = sha256 of the scene file's bytes (its sha256) and every setting that changes the
image: resolution, hemisphere, max_bounces, the estimator (integrator and every estimator
setting, resolved: estimators.py), sampler, spp, seed (threads do not: the renderer is
bit-identical for any thread count). A configuration is done when its JSON
sidecar exists, names the same key, and the EXR it describes exists with the recorded size and
sha256. Renders write the EXR first and the sidecar last, each under a temporary name renamed
into place, so a crash leaves nothing a resume would trust.
"""

from __future__ import annotations

import hashlib
import json
import os
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from .estimators import Estimator

# 2: the estimator (integrator + its settings) moved from the shared settings into each
# configuration.
CACHE_VERSION = 2
RENDERS_DIR = "renders"
REFERENCE_DIR = "renders/reference_parts"
REFERENCE_PATH = "renders/reference.exr"
# Reference seeds start here; tested seeds are 0..K-1 with K below it, so they are disjoint.
REFERENCE_SEED_BASE = 100_000


@dataclass(frozen=True)
class SceneSettings:
    """Settings shared by every configuration of one comparison."""

    scene_sha256: str
    resolution: tuple[int, int]
    hemisphere: str
    max_bounces: int | None


@dataclass(frozen=True)
class Config:
    """One render: an estimator and a sampler at spp samples per pixel with one seed."""

    estimator: Estimator
    sampler: str
    spp: int
    seed: int
    role: str  # "test" or "reference"
    key: str
    exr: str  # relative to the output dir
    sidecar: str

    @property
    def label(self) -> str:
        prefix = "reference " if self.role == "reference" else ""
        return f"{prefix}{self.estimator.label} {self.sampler} spp={self.spp} seed={self.seed}"

    @property
    def cost(self) -> float:
        """Relative cost for load balancing and the ETA: samples plus a fixed overhead."""
        return float(self.spp) + 2.0


def sha256_file(path: str | os.PathLike[str]) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def cache_key(settings: SceneSettings, estimator: Estimator, sampler: str, spp: int,
              seed: int) -> str:
    """The label is not part of the key: it is derived from the settings, which are."""
    payload = {"version": CACHE_VERSION, **asdict(settings),
               "resolution": list(settings.resolution), "integrator": estimator.integrator,
               "estimator_settings": dict(estimator.settings), "sampler": sampler, "spp": spp,
               "seed": seed}
    return hashlib.sha256(json.dumps(payload, sort_keys=True).encode()).hexdigest()


def file_safe(text: str) -> str:
    return "".join(c if c.isalnum() or c in "-_." else "_" for c in text)


def make_config(settings: SceneSettings, estimator: Estimator, sampler: str, spp: int,
                seed: int, role: str) -> Config:
    key = cache_key(settings, estimator, sampler, spp, seed)
    folder = REFERENCE_DIR if role == "reference" else RENDERS_DIR
    stem = f"{folder}/{file_safe(estimator.label)}_{sampler}_spp{spp}_seed{seed}_{key[:16]}"
    return Config(estimator=estimator, sampler=sampler, spp=spp, seed=seed, role=role, key=key,
                  exr=f"{stem}.exr", sidecar=f"{stem}.json")


def plan(settings: SceneSettings, estimators: list[Estimator], samplers: list[str],
         spps: list[int], seeds: list[int], reference_estimator: Estimator | None,
         reference_sampler: str | None, reference_spp: int | None,
         reference_seeds: list[int]) -> tuple[list[Config], list[Config]]:
    """(test configurations, reference configurations); no reference renders when
    reference_sampler or reference_estimator is None (a reference file was given)."""
    tests = [make_config(settings, e, s, n, seed, "test")
             for e in estimators for s in samplers for n in spps for seed in seeds]
    refs: list[Config] = []
    if (reference_estimator is not None and reference_sampler is not None
            and reference_spp is not None):
        refs = [make_config(settings, reference_estimator, reference_sampler, reference_spp,
                            seed, "reference") for seed in reference_seeds]
    return tests, refs


def read_sidecar(out_dir: Path, config: Config) -> dict[str, Any] | None:
    """The sidecar of a finished configuration, or None when it is not (validly) done."""
    sidecar = out_dir / config.sidecar
    exr = out_dir / config.exr
    try:
        data = json.loads(sidecar.read_text())
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("key") != config.key:
        return None
    try:
        if exr.stat().st_size != data.get("exr_size"):
            return None
    except OSError:
        return None
    if sha256_file(exr) != data.get("exr_sha256"):
        return None
    return data


def batch_entry(config: Config, settings: SceneSettings) -> dict[str, Any]:
    """What the Blender batch script needs to render one configuration."""
    return {"key": config.key, "label": config.label, "exr": config.exr,
            "sidecar": config.sidecar, "sampler": config.sampler, "samples": config.spp,
            "seed": config.seed, "integrator": config.estimator.integrator,
            "estimator_settings": dict(config.estimator.settings),
            "hemisphere": settings.hemisphere, "max_bounces": settings.max_bounces,
            "resolution": list(settings.resolution)}


def split_batches(configs: list[Config], count: int) -> list[list[Config]]:
    """Splits configurations into at most `count` batches of similar total cost (longest
    first onto the lightest batch); each batch is then ordered cheap first."""
    count = max(1, min(count, len(configs)))
    batches: list[list[Config]] = [[] for _ in range(count)]
    loads = [0.0] * count
    for config in sorted(configs, key=lambda c: -c.cost):
        i = loads.index(min(loads))
        batches[i].append(config)
        loads[i] += config.cost
    return [sorted(b, key=lambda c: c.cost) for b in batches if b]
