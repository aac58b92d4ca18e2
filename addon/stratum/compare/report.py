"""The `stratum compare` report: `write_report(out_dir, results)` writes out_dir/report.html
and its figures under out_dir/figures/ (static HTML, PNG images, no scripts, no external
resources). `results` follows the results.json schema of the compare runner; every field is
read defensively (missing summary or slopes are computed from the renders).

A section that cannot be drawn (a missing EXR, no native library) says why in the page
instead of failing the whole report.

The page is assembled here; each section's body comes from sections.py, which draws with
report_data (Results, read_exr), report_images (display transform, crops) and report_html.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from . import sections
from .report_data import Results, read_exr
from .report_html import esc, problem, safe_name
from .report_images import display_transform

# Headings of the report's sections, in page order (the report test checks every one).
SECTION_TITLES: tuple[str, ...] = (
    "Settings",
    "Convergence",
    "Results",
    "Convergence slopes",
    "Images",
    "Error spectra",
    "Sample points",
    "Blue-noise texture",
    "Hemisphere distributions",
    "Fibonacci lattice on the hemisphere",
)

_CSS = """
body { font-family: sans-serif; margin: 1.5em auto; max-width: 1250px; color: #222; }
h1 { font-size: 1.6em; } h2 { border-bottom: 1px solid #ccc; margin-top: 1.8em; }
table { border-collapse: collapse; margin: 0.6em 0; font-size: 0.85em; }
td, th { border: 1px solid #ccc; padding: 2px 7px; text-align: right; white-space: nowrap; }
th { background: #f0f0f0; } td.name, th.name { text-align: left; }
img { max-width: 100%; }
table.grid td { text-align: center; vertical-align: top; border: none; padding: 3px; }
table.grid img { display: block; width: 220px; }
table.grid img.crop { image-rendering: pixelated; margin-top: 3px; }
p.note { color: #555; font-size: 0.9em; max-width: 70em; }
p.problem { color: #a00; }
"""


SectionBuilder = Callable[[Results, Path], str]


def _section(title: str, builder: SectionBuilder, results: Results, fig_dir: Path) -> str:
    try:
        body = builder(results, fig_dir)
    except Exception as exc:  # noqa: BLE001 - one broken section must not lose the report
        body = problem(f"This section could not be drawn: {type(exc).__name__}: {exc}")
    anchor = safe_name(title.lower())
    return f'<section id="{esc(anchor)}">\n<h2>{esc(title)}</h2>\n{body}\n</section>\n'


def write_report(out_dir: Path, results: dict[str, Any]) -> Path:
    """Writes out_dir/report.html and out_dir/figures/*.png; returns the html path."""
    out_dir = Path(out_dir)
    fig_dir = out_dir / "figures"
    fig_dir.mkdir(parents=True, exist_ok=True)
    res = Results(out_dir, results if isinstance(results, dict) else {})
    builders: dict[str, SectionBuilder] = {
        "Settings": sections.settings,
        "Convergence": sections.convergence,
        "Results": sections.results_table,
        "Convergence slopes": sections.slopes_table,
        "Images": sections.image_grid,
        "Error spectra": sections.error_spectra,
        "Sample points": sections.sample_points,
        "Blue-noise texture": sections.bluenoise,
        "Hemisphere distributions": sections.hemisphere,
        "Fibonacci lattice on the hemisphere": sections.fibonacci,
    }
    scene = res.raw.get("scene") or "scene"
    toc = " · ".join(f'<a href="#{esc(safe_name(t.lower()))}">{esc(t)}</a>'
                     for t in SECTION_TITLES)
    body = "".join(_section(t, builders[t], res, fig_dir) for t in SECTION_TITLES)
    page = (
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        f"<title>Stratum compare: {esc(Path(str(scene)).name)}</title>\n"
        f"<style>{_CSS}</style>\n</head>\n<body>\n"
        f"<h1>Stratum comparison: {esc(Path(str(scene)).name)}</h1>\n"
        f"<p>{toc}</p>\n{body}</body>\n</html>\n"
    )
    path = out_dir / "report.html"
    path.write_text(page, encoding="utf-8")
    return path



# Results, read_exr and display_transform were defined here before report_data.py and
# report_images.py existed; they stay importable from the report.
__all__ = ["SECTION_TITLES", "Results", "display_transform", "read_exr", "write_report"]
