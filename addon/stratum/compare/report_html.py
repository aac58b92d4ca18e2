"""HTML pieces of the `stratum compare` report: escaping, number formatting, image tags and
problem notes (shared by report.py's page and the sections)."""

from __future__ import annotations

import html
import math
import re
from pathlib import Path
from typing import Any


def esc(value: Any) -> str:
    return html.escape(str(value), quote=True)


def safe_name(text: str) -> str:
    """A file-name-safe version of a sampler name or label."""
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", str(text)) or "x"


def fmt(value: Any, digits: int = 3) -> str:
    if value is None:
        return "–"
    try:
        v = float(value)
    except (TypeError, ValueError):
        return esc(value)
    if not math.isfinite(v):
        return "–"
    return f"{v:.{digits}g}"


def img_tag(out_dir: Path, path: Path, alt: str, css_class: str = "") -> str:
    rel = path.relative_to(out_dir).as_posix()
    cls = f' class="{esc(css_class)}"' if css_class else ""
    return f'<img src="{esc(rel)}" alt="{esc(alt)}"{cls}>'


def problem(text: str) -> str:
    return f'<p class="note problem">{esc(text)}</p>'
