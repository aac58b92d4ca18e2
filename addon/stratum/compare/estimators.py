"""Estimator specs of `stratum compare --integrator`: which integrator and which estimator
settings (issue 6) one configuration renders with, and the short label tables and plots use.

| setting           | label part                         |
|-------------------|------------------------------------|
| light_sampling    | path: bsdf / nee / mis-<heuristic> |
| mis_heuristic     | (in mis-<heuristic>)               |
| light_selection   | sel-<value>                        |
| light_tree_splits | split<value>                       |
| triangle_sampling | tri-<value>                        |
| rr_mode           | rr-<value>                         |
| rr_min_depth      | rrmin<value>                       |
| control_variate   | cv<value>                          |
| use_adaptive_sampling | adaptive<value> (0 or 1)       |
| adaptive_threshold    | thr<value>                     |
| adaptive_min_samples  | min<value>                     |
| adaptive_metric       | metric-<value> (relative, mse) |
| radiosity_patch_size  | patch<value>                   |
| radiosity_solver      | <value> (shooting, gauss_seidel, jacobi) |
| radiosity_tolerance   | tol<value>                     |
| radiosity_rays        | rays<value>                    |
| use_guiding           | guided<value> (0 or 1)         |
| guiding_training_samples | train<value>                |
| guiding_bsdf_fraction | bf<value>                      |
| guiding_split         | split-<value> (binary, full)   |

The names are render settings of the library, and their values, ranges and defaults are the
library's (native.settings(), read on first use: importing this module loads nothing); the
Blender properties scene.stratum.<name> carry the same names.

Spec syntax: `INTEGRATOR[:NAME=VALUE[,NAME=VALUE...]]`, INTEGRATOR a name of the native
integrator registry (path, direct, ao, light, radiosity). In the comma-separated --integrator
list an item of the form NAME=VALUE (no colon) continues the settings of the spec before it, so
`path:light_sampling=mis,mis_heuristic=balance,direct` is two specs.

Resolution of one configuration's settings: the spec's value, else --set's, else the scene's
(read by the probe when the property exists), else the library's default. Every configuration
carries all of them, so its cache key and its render do not depend on what the scene stored.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..native import Setting

Value = str | int | float

# The settings an estimator spec may name, in the order every Estimator carries them.
SETTING_NAMES: tuple[str, ...] = ("light_sampling", "mis_heuristic", "light_selection",
                                  "light_tree_splits",
                                  "triangle_sampling", "rr_mode", "rr_min_depth",
                                  "control_variate", "use_adaptive_sampling",
                                  "adaptive_threshold", "adaptive_min_samples",
                                  "adaptive_metric", "radiosity_patch_size", "radiosity_solver",
                                  "radiosity_tolerance", "radiosity_rays", "use_guiding",
                                  "guiding_training_samples", "guiding_bsdf_fraction",
                                  "guiding_split")
PATH = "path"  # the integrator whose label names its light-sampling strategy
_SUFFIX = {"light_selection": "sel-", "light_tree_splits": "split", "triangle_sampling": "tri-",
           "rr_mode": "rr-", "rr_min_depth": "rrmin", "control_variate": "cv",
           "use_adaptive_sampling": "adaptive", "adaptive_threshold": "thr",
           "adaptive_min_samples": "min", "adaptive_metric": "metric-",
           "radiosity_patch_size": "patch", "radiosity_solver": "", "radiosity_tolerance": "tol",
           "radiosity_rays": "rays", "use_guiding": "guided",
           "guiding_training_samples": "train", "guiding_bsdf_fraction": "bf",
           "guiding_split": "split-"}


class SpecError(ValueError):
    """A bad estimator spec or setting; the message names the bad part."""


@dataclass(frozen=True)
class Estimator:
    """One resolved estimator: integrator, every setting of SETTING_NAMES, and its label."""

    integrator: str
    settings: tuple[tuple[str, Value], ...]
    label: str
    spec: str  # as written (or as made up for the scene's default)

    def setting(self, name: str) -> Value:
        return dict(self.settings)[name]


@dataclass(frozen=True)
class Spec:
    """A parsed spec before resolution: the integrator and the settings it names."""

    integrator: str
    given: tuple[tuple[str, Value], ...]
    text: str


def _setting(name: str) -> Setting:
    """The library's description of estimator setting `name`."""
    from .. import native

    return native.setting(name)


def _is_int(setting: Setting) -> bool:
    from .. import native

    return setting.kind == native.SettingKind.INT


def defaults() -> dict[str, Value]:
    """The library's default of every estimator setting."""
    return {name: _setting(name).default for name in SETTING_NAMES}


def value_syntax(name: str) -> str:
    """What setting `name` takes, for help and messages: "mis|nee|bsdf", "0..1024" or
    "a number in [0, 3.40282e+38]"."""
    setting = _setting(name)
    if setting.choices:
        return "|".join(setting.choice_names())
    if _is_int(setting):
        return f"{setting.minimum}..{setting.maximum}"
    opening = "(" if setting.open_minimum else "["
    return f"a number in {opening}{setting.minimum:g}, {setting.maximum:g}]"


def parse_value(name: str, text: str, where: str) -> Value:
    """The typed value of setting `name`; SpecError naming `where`, the name and the value."""
    if name not in SETTING_NAMES:
        raise SpecError(f"{where}: unknown setting {name!r}; settings: {', '.join(SETTING_NAMES)}")
    setting = _setting(name)
    text = text.strip()
    if setting.choices:
        if text not in setting.choice_names():
            raise SpecError(f"{where}: bad value {text!r} for {name}; values: "
                            f"{', '.join(setting.choice_names())}")
        return text
    if _is_int(setting):
        try:
            number: int | float = int(text)
        except ValueError:
            raise SpecError(f"{where}: bad value {text!r} for {name}; expected an "
                            "integer") from None
        if not setting.minimum <= number <= setting.maximum:
            raise SpecError(f"{where}: bad value {number} for {name}; expected "
                            f"{value_syntax(name)}")
        return number
    try:
        number = float(text)
    except ValueError:
        raise SpecError(f"{where}: bad value {text!r} for {name}; expected "
                        f"{value_syntax(name)}") from None
    above = number > setting.minimum if setting.open_minimum else number >= setting.minimum
    if not (above and number <= setting.maximum):  # also rejects nan
        raise SpecError(f"{where}: bad value {text!r} for {name}; expected "
                        f"{value_syntax(name)}")
    return number


def parse_assignment(text: str, where: str) -> tuple[str, Value]:
    name, eq, value = text.partition("=")
    if not eq or not name.strip() or not value.strip():
        raise SpecError(f"{where}: {text!r} is not NAME=VALUE")
    return name.strip(), parse_value(name.strip(), value, where)


def parse_settings(items: Iterable[str], where: str) -> dict[str, Value]:
    """NAME=VALUE items (e.g. the --set options) -> {name: value}; a name given twice with
    different values is an error."""
    out: dict[str, Value] = {}
    for item in items:
        name, value = parse_assignment(item, where)
        if name in out and out[name] != value:
            raise SpecError(f"{where}: {name} given twice ({out[name]!r} and {value!r})")
        out[name] = value
    return out


def split_specs(text: str) -> list[str]:
    """The comma-separated --integrator list -> one string per spec (see the module doc)."""
    specs: list[str] = []
    for item in (t.strip() for t in str(text).split(",")):
        if not item:
            raise SpecError(f"--integrator {text!r}: empty item")
        if "=" in item and ":" not in item:
            if not specs:
                raise SpecError(f"--integrator {text!r}: {item!r} names a setting before any "
                                "integrator (write INTEGRATOR:NAME=VALUE)")
            sep = "," if ":" in specs[-1] else ":"
            specs[-1] += sep + item
        else:
            specs.append(item)
    return specs


def parse_spec(text: str, integrators: Sequence[str]) -> Spec:
    """`INTEGRATOR[:NAME=VALUE,...]` -> Spec; SpecError naming the bad integrator or value."""
    head, colon, rest = text.strip().partition(":")
    integrator = head.strip()
    if integrator not in integrators:
        raise SpecError(f"--integrator: unknown integrator {integrator!r} in {text!r}; "
                        f"available: {', '.join(integrators)}")
    if colon and not rest.strip():
        raise SpecError(f"--integrator: {text!r} has no settings after ':'")
    items = [t for t in rest.split(",")] if colon else []
    if any(not t.strip() for t in items):
        raise SpecError(f"--integrator {text!r}: empty setting")
    given = parse_settings(items, f"--integrator {text!r}")
    return Spec(integrator, tuple(sorted(given.items())), text.strip())


def parse_specs(text: str, integrators: Sequence[str]) -> list[Spec]:
    return [parse_spec(s, integrators) for s in split_specs(text)]


def _fmt(value: Value) -> str:
    return f"{value:g}" if isinstance(value, float) else str(value)


def make_label(integrator: str, values: Mapping[str, Value], given: Iterable[str]) -> str:
    """bsdf / nee / mis-<heuristic> for the path tracer (from its resolved settings), else the
    integrator's name; then `+<part>` for every other setting the spec itself names (a
    setting common to every configuration does not tell them apart)."""
    named = set(given)
    if integrator == PATH:
        strategy = str(values["light_sampling"])
        parts = [f"mis-{values['mis_heuristic']}" if strategy == "mis" else strategy]
        covered = {"light_sampling", "mis_heuristic"}
    else:
        parts, covered = [integrator], set()
    for name in SETTING_NAMES:
        if name in named and name not in covered:
            prefix = _SUFFIX.get(name, f"{name}-")
            parts.append(f"{prefix}{_fmt(values[name])}")
    return "+".join(parts)


def resolve(spec: Spec, common: Mapping[str, Value],
            scene: Mapping[str, Value] | None = None) -> Estimator:
    """The spec's settings over --set's over the scene's over the defaults."""
    values = defaults()
    for name, value in (scene or {}).items():
        if name in values:
            # A checkbox property (use_*) reads as a bool; the library's value is 0 or 1.
            text = str(int(value)) if isinstance(value, bool) else str(value)
            values[name] = parse_value(name, text, "the scene's setting")
    values.update(common)
    values.update(dict(spec.given))
    label = make_label(spec.integrator, values, (n for n, _ in spec.given))
    return Estimator(spec.integrator, tuple((n, values[n]) for n in SETTING_NAMES), label,
                     spec.text)


def resolve_all(specs: Sequence[Spec], common: Mapping[str, Value],
                scene: Mapping[str, Value] | None = None) -> list[Estimator]:
    """Resolved estimators, in order; two specs that resolve to the same estimator, or to the
    same label, are an error (their rows could not be told apart)."""
    out: list[Estimator] = []
    for spec in specs:
        est = resolve(spec, common, scene)
        for other in out:
            if (other.integrator, other.settings) == (est.integrator, est.settings):
                raise SpecError(f"--integrator: {spec.text!r} and {other.spec!r} are the same "
                                "estimator")
            if other.label == est.label:
                raise SpecError(f"--integrator: {spec.text!r} and {other.spec!r} have the same "
                                f"label {est.label!r}")
        out.append(est)
    return out
