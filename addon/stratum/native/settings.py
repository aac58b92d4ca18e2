"""What the library lists once for every host: its render settings (name, label, description,
kind, range, unit, default, choices in menu order) and the passes a render can hold. The add-on's
properties, `stratum compare`'s choices and help, and the README's settings table are built
from these lists, so none of them can disagree with the library.

Both lists are static in the library: they are read once (on first use) and kept.
"""

from __future__ import annotations

import ctypes
import functools
from dataclasses import dataclass
from typing import NamedTuple

from .abi import SettingKind, _SettingInfo
from .library import _check, load_library


class RegistryEntry(NamedTuple):
    """(name, label, description) of a registry entry or of a setting's choice."""

    name: str
    label: str
    description: str


@dataclass(frozen=True)
class Setting:
    """One render setting as the library describes it. INT and FLOAT settings accept
    [minimum, maximum] (minimum excluded when open_minimum; a FLOAT maximum may be inf); CHOICE
    takes one name of `choices`, LIST a comma-separated list of them ("" = none). `choices`
    are in menu order, which only grows at the end: a host may store a choice's position."""

    name: str
    label: str
    description: str
    kind: SettingKind
    minimum: int | float
    maximum: int | float
    open_minimum: bool
    unit: str
    default: int | float | str
    choices: tuple[RegistryEntry, ...]

    def choice_names(self) -> list[str]:
        return [choice.name for choice in self.choices]


class Pass(NamedTuple):
    """A pass (AOV) a render can hold: Cycles' name, floats per pixel, what it holds."""

    name: str
    channels: int
    description: str


# registry(kind): the choices of these settings, by the names `stratum compare` and the tests use.
REGISTRY_SETTINGS: dict[str, str] = {
    "sampler": "sampler",
    "filter": "filter_type",
    "integrator": "integrator",
    "hemisphere": "hemisphere",
}


def _text(raw: bytes | None) -> str:
    return (raw or b"").decode("utf-8", "replace")


def _typed(kind: SettingKind, text: str) -> int | float | str:
    """A value the library wrote as text ("16", "1.5", "inf", "mis") as the Python type that
    sets it."""
    if kind == SettingKind.INT:
        return int(text)
    if kind == SettingKind.FLOAT:
        return float(text)
    return text


def _range_end(kind: SettingKind, value: float) -> int | float:
    return int(value) if kind == SettingKind.INT else float(value)


def _choices(lib: ctypes.CDLL, setting: int, count: int) -> tuple[RegistryEntry, ...]:
    entries = []
    for choice in range(count):
        name, label, description = ctypes.c_char_p(), ctypes.c_char_p(), ctypes.c_char_p()
        _check(lib, lib.stratum_setting_choice(setting, choice, ctypes.byref(name),
                                               ctypes.byref(label), ctypes.byref(description)),
               "stratum_setting_choice")
        entries.append(RegistryEntry(_text(name.value), _text(label.value),
                                     _text(description.value)))
    return tuple(entries)


@functools.cache
def settings() -> tuple[Setting, ...]:
    """Every render setting, in the library's order (raises LibraryLoadError when the library
    cannot be loaded; a later call tries again)."""
    lib = load_library()
    out = []
    for index in range(lib.stratum_setting_count()):
        info = _SettingInfo()
        _check(lib, lib.stratum_setting_info(index, ctypes.byref(info)), "stratum_setting_info")
        kind = SettingKind(info.kind)
        out.append(Setting(
            name=_text(info.name),
            label=_text(info.label),
            description=_text(info.description),
            kind=kind,
            minimum=_range_end(kind, info.minimum),
            maximum=_range_end(kind, info.maximum),
            open_minimum=bool(info.open_minimum),
            unit=_text(info.unit),
            default=_typed(kind, _text(info.default_value)),
            choices=_choices(lib, index, info.choice_count),
        ))
    return tuple(out)


def setting(name: str) -> Setting:
    """The render setting `name`; KeyError naming the known ones."""
    for candidate in settings():
        if candidate.name == name:
            return candidate
    known = ", ".join(s.name for s in settings())
    raise KeyError(f"unknown render setting {name!r}; known: {known}")


def registry(kind: str) -> list[RegistryEntry]:
    """Entries of the 'sampler', 'filter', 'integrator' or 'hemisphere' registry, as
    (name, label, description): the choices of the setting that picks one."""
    if kind not in REGISTRY_SETTINGS:
        raise ValueError(f"unknown registry {kind!r}; expected one of {sorted(REGISTRY_SETTINGS)}")
    return list(setting(REGISTRY_SETTINGS[kind]).choices)


@functools.cache
def passes() -> tuple[Pass, ...]:
    """Every pass a render can hold; the first is Combined (the image, always held), the
    others are held when the setting `passes` names them."""
    lib = load_library()
    out = []
    for index in range(lib.stratum_pass_count()):
        name, description = ctypes.c_char_p(), ctypes.c_char_p()
        channels = ctypes.c_int32()
        _check(lib, lib.stratum_pass_info(index, ctypes.byref(name), ctypes.byref(channels),
                                          ctypes.byref(description)), "stratum_pass_info")
        out.append(Pass(_text(name.value), int(channels.value), _text(description.value)))
    return tuple(out)
