"""The outcome table of a corpus run (case -> outcome -> message per Blender), for the issue's
closing note: Markdown for people, JSON for tools. No bpy here."""

from __future__ import annotations

import json
from dataclasses import asdict
from pathlib import Path

from .case import Case
from .runner import Outcome

MESSAGE_CHARS = 240


def _cell(text: str) -> str:
    one_line = " ".join(text.split())
    if len(one_line) > MESSAGE_CHARS:
        one_line = one_line[: MESSAGE_CHARS - 1] + "…"
    return one_line.replace("|", "\\|")


def write(outcomes: dict[tuple[str, str], Outcome], cases: dict[str, Case],
          blender_names: list[str], folder: Path) -> Path:
    """Writes folder/outcomes.md and folder/outcomes.json (outcomes by (Blender name, case)),
    columns in the order of `blender_names`. Returns the Markdown file."""
    folder.mkdir(parents=True, exist_ok=True)
    names = [n for n in blender_names if any(b == n for b, _ in outcomes)]
    versions = {o.blender: o.version for o in outcomes.values() if o.version}
    header = ["case", "area", "input"]
    for name in names:
        header += [f"{name} {versions.get(name, '')}".strip(), "message"]
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    totals = {name: [0, 0] for name in names}
    for case_name, c in cases.items():
        row = [case_name, c.area, _cell(c.what)]
        present = False
        for name in names:
            outcome = outcomes.get((name, case_name))
            if outcome is None:
                row += ["", ""]
                continue
            present = True
            totals[name][0] += outcome.passed
            totals[name][1] += 1
            row += [outcome.verdict(), _cell(outcome.message())]
        if present:
            lines.append("| " + " | ".join(row) + " |")
    summary = ", ".join(f"{name}: {p}/{n} pass" for name, (p, n) in totals.items())
    markdown = folder / "outcomes.md"
    markdown.write_text(f"# Hostile-scene corpus\n\n{summary}\n\n" + "\n".join(lines) + "\n",
                        encoding="utf-8")
    records = [asdict(o) | {"area": cases[o.case].area if o.case in cases else ""}
               for o in outcomes.values()]
    (folder / "outcomes.json").write_text(json.dumps({"blenders": versions,
                                                      "outcomes": records}, indent=1))
    return markdown
