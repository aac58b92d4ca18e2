"""The native part of the corpus, under a sanitizer build (issue 12, point 7): every case's
exported scene is captured through Blender (worker.py --capture: stratum_scene_save and the
renderer settings), then rendered by a stratum-native binary, e.g. the ASan/UBSan build's.

    PYTHONPATH=tests/blender .venv/bin/python -m corpus.replay NATIVE [--blender bpy]
        [--out out/corpus-native] [CASE...]

A replay fails on a sanitizer report or an (Embree) assertion, a death by signal, a timeout, a
non-zero exit without the CLI's own message, or a non-finite pixel in the image it wrote. A case
whose export was refused (an ERROR before any native scene existed) has nothing to replay. Writes OUT/replay.md and exits
1 if any replay failed.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from exr_file import read_channels

from . import all_cases, runner

SANITIZER = re.compile(r"(AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer"
                       r"|runtime error:|Assertion .* failed)")
TIMEOUT = 300.0
# Sanitizer defaults unless the caller set its own: stop at the first error, report leaks
# (the CLI frees what it makes), and fail UBSan findings.
SANITIZER_ENV = {
    "ASAN_OPTIONS": "abort_on_error=0:halt_on_error=1:detect_leaks=1",
    "UBSAN_OPTIONS": "halt_on_error=1:print_stacktrace=1",
}


@dataclass
class Replay:
    case: str
    # "ok", "refused" (the CLI's own message), "no scene" (export made none), or a failure:
    # "sanitizer", "assertion", "crash", "timeout", "non-finite", "exit N".
    verdict: str
    detail: str = ""

    @property
    def failed(self) -> bool:
        return self.verdict not in ("ok", "refused", "no scene")


def setting_args(settings: dict[str, int | float | str]) -> list[str]:
    """name=value arguments typed as the CLI reads them: an int as an integer, a float always
    with a point or an exponent (repr), a string as it is."""
    return [f"{name}={value!r}" if isinstance(value, float) else f"{name}={value}"
            for name, value in settings.items()]


def replay(native: Path, scene: Path, out: Path) -> Replay:
    case = scene.stem
    settings_file = scene.with_suffix(".settings.json")
    settings = json.loads(settings_file.read_text()) if settings_file.is_file() else {}
    image = out / f"{case}.exr"
    image.unlink(missing_ok=True)
    env = {**SANITIZER_ENV, **os.environ}
    try:
        proc = subprocess.run([str(native), "render", str(scene), str(image),
                               *setting_args(settings)], capture_output=True, text=True, check=False,
                              errors="replace", timeout=TIMEOUT, env=env)
    except subprocess.TimeoutExpired:
        return Replay(case, "timeout", f"no result after {TIMEOUT:g} s")
    log = proc.stdout + proc.stderr
    (out / f"{case}.log").write_text(log)
    found = SANITIZER.search(log)
    if found:
        line = next(x for x in log.splitlines() if found.group(0) in x)
        kind = "assertion" if found.group(0).startswith("Assertion") else "sanitizer"
        return Replay(case, kind, runner.short_cause(line.strip()))
    if proc.returncode < 0:
        return Replay(case, "crash", f"signal {-proc.returncode}: {log.strip()[-300:]}")
    if proc.returncode != 0:
        # The CLI's own refusal ("stratum-native: load: ...") is an answer, not a crash.
        refused = "stratum-native:" in proc.stderr
        return Replay(case, "refused" if refused else f"exit {proc.returncode}",
                      proc.stderr.strip()[-300:])
    pixels = np.stack(list(read_channels(image).values()), axis=-1)
    bad = int(np.count_nonzero(~np.isfinite(pixels)))
    if bad:
        return Replay(case, "non-finite", f"{bad} non-finite pixel values")
    return Replay(case, "ok")


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="corpus.replay", description=__doc__.split("\n")[0])
    parser.add_argument("native", type=Path, help="the stratum-native binary")
    parser.add_argument("cases", nargs="*", help="cases to replay (default: all)")
    parser.add_argument("--blender", default="bpy", help="Blender that captures (blender|bpy)")
    parser.add_argument("--out", type=Path, default=runner.REPO / "out" / "corpus-native")
    args = parser.parse_args(argv)
    if not os.access(args.native, os.X_OK):
        print(f"corpus.replay: {args.native} is not an executable", file=sys.stderr)
        return 2
    names = args.cases or list(all_cases())
    blender = {b.name: b for b in runner.blenders()}[args.blender]
    captures = args.out / "captures"
    for old in captures.glob("*.json"):
        old.unlink()
    outcomes = runner.run(blender, names, args.out / "capture", capture=captures)
    args.out.mkdir(parents=True, exist_ok=True)
    results: list[Replay] = []
    for name in names:
        scene = captures / f"{name}.json"
        if scene.is_file():
            results.append(replay(args.native, scene, args.out))
        else:
            outcome = outcomes.get(name)
            results.append(Replay(name, "no scene", outcome.message() if outcome else ""))
    lines = ["| case | replay | detail |", "|---|---|---|"]
    lines += [f"| {r.case} | {r.verdict} | {' '.join(r.detail.split())[:200]} |" for r in results]
    failed = [r for r in results if r.failed]
    summary = (f"{len(results)} cases, {sum(r.verdict == 'ok' for r in results)} rendered, "
               f"{sum(not r.failed and r.verdict != 'ok' for r in results)} without a scene or "
               f"refused, {len(failed)} failed "
               f"({args.native})")
    (args.out / "replay.md").write_text(f"# Corpus replay\n\n{summary}\n\n" + "\n".join(lines)
                                        + "\n")
    print(summary)
    for r in failed:
        print(f"FAILED {r.case}: {r.verdict}: {r.detail}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
