"""Writes the README's render-settings tables from the library's own lists (native.settings()
and native.passes()) and from stratum/blender_settings.py (where each setting comes from in
Blender), between the lines <!-- settings:begin --> and <!-- settings:end -->, so that the
README cannot drift from the library.

    .venv/bin/python -m scripts.settings_table          # rewrites README.md
    .venv/bin/python -m scripts.settings_table --check  # exit 1 when README.md differs

tests/python/test_settings.py fails while README.md differs from what this writes.
"""

from __future__ import annotations

import argparse
import math
import sys

from stratum import blender_settings, native

from scripts import REPO

README = REPO / "README.md"
BEGIN = "<!-- settings:begin -->"
END = "<!-- settings:end -->"
CHOICES_INTRO = ("The choices, in menu order (Blender stores a choice as its position; the "
                 "library only appends):")
PASSES_INTRO = ("Passes (`passes` names those a render holds besides Combined; "
                "`native.Renderer.read_pass` reads one):")


def _number(value: float) -> str:
    return "∞" if math.isinf(value) else f"{value:g}"


def _values(setting: native.Setting) -> str:
    if setting.kind == native.SettingKind.INT:
        text = f"integer {setting.minimum} … {setting.maximum}"
    elif setting.kind == native.SettingKind.FLOAT:
        opening = "(" if setting.open_minimum else "["
        text = f"number in {opening}{_number(setting.minimum)}, {_number(setting.maximum)}]"
    else:
        names = ", ".join(f"`{name}`" for name in setting.choice_names())
        text = f"one of {names}" if setting.kind == native.SettingKind.CHOICE else (
            f"comma-separated, of {names}")
    return f"{text} {setting.unit}".rstrip()


def _default(setting: native.Setting) -> str:
    if setting.default == "":
        return "none"
    return f"`{setting.default}`"


def _in_blender(setting: native.Setting) -> str:
    name = setting.name
    if name in blender_settings.PROPERTIES:
        text = f"`scene.stratum.{name}`"
        if blender_settings.is_switch(setting):
            text += " (a checkbox)"
        if name in blender_settings.UI_DEFAULTS:
            text += f" (default `{blender_settings.UI_DEFAULTS[name]}`)"
        viewport = [prop for prop, stands_for in blender_settings.VIEWPORT_SETTINGS.items()
                    if stands_for == name]
        for prop in viewport:
            default = blender_settings.VIEWPORT_DEFAULTS[prop]
            shown = ("on" if default else "off") if isinstance(default, bool) else f"`{default}`"
            text += f"; the Rendered viewport's: `scene.stratum.{prop}` (default {shown})"
        if name in blender_settings.CYCLES_LIGHT_PATHS:
            text += (f", or Cycles' `scene.cycles.{blender_settings.CYCLES_LIGHT_PATHS[name]}` "
                     "where the scene takes Cycles' Light Paths (below the table)")
        return text
    if name in blender_settings.FROM_BLENDER:
        return blender_settings.FROM_BLENDER[name]
    return f"not set: {blender_settings.NOT_IN_BLENDER[name]}"


def _cell(text: str) -> str:
    return text.replace("|", "\\|")


def settings_markdown() -> str:
    """The generated part of the README: settings, their choices, the passes."""
    settings = native.settings()
    lines = [
        "| setting | meaning | values | default | in Blender |",
        "|---|---|---|---|---|",
    ]
    lines += [f"| `{s.name}` | {_cell(s.description)} | {_cell(_values(s))} | "
              f"{_default(s)} | {_cell(_in_blender(s))} |" for s in settings]
    lines += ["", CHOICES_INTRO, ""]
    for s in settings:
        if s.kind != native.SettingKind.CHOICE:
            continue
        lines.append(f"* `{s.name}`:")
        for choice in s.choices:
            lines.append(f"  * `{choice.name}` ({choice.label}): {choice.description}")
    lines += ["", PASSES_INTRO, "", "| pass | channels | holds |", "|---|---|---|"]
    lines += [f"| `{p.name}` | {p.channels} | {_cell(p.description)} |" for p in native.passes()]
    return "\n".join(lines)


def with_tables(readme: str) -> str:
    """`readme` with the text between the markers replaced by settings_markdown()."""
    head, begin, rest = readme.partition(BEGIN)
    _, end, tail = rest.partition(END)
    if not begin or not end:
        raise ValueError(f"README.md lacks the lines {BEGIN} and {END}")
    return f"{head}{BEGIN}\n{settings_markdown()}\n{END}{tail}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true",
                        help="only report whether README.md is up to date (exit 1 if not)")
    args = parser.parse_args(argv)
    current = README.read_text(encoding="utf-8")
    updated = with_tables(current)
    if args.check:
        if updated != current:
            print("README.md's settings tables are out of date: run "
                  "`python -m scripts.settings_table`", file=sys.stderr)
            return 1
        return 0
    if updated != current:
        README.write_text(updated, encoding="utf-8")
        print(f"settings_table: wrote {README}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
