"""The hostile-scene corpus: one test per (case, Blender).

Runs from the project's venv (not inside Blender): `make test-corpus`, or
    .venv/bin/python -m pytest tests/blender/corpus -q
The cases the session selected run once per Blender in worker subprocesses (runner.py), the two
Blenders concurrently; each test then reads its case's outcome. The outcome table is written to
out/corpus/outcomes.md and .json. tests/blender/conftest.py keeps this folder out of the
in-Blender test runs (collect_ignore), which would run the corpus a second and third time.
"""

from __future__ import annotations

import os
import threading
from pathlib import Path

import pytest

from corpus import all_cases, runner, table

CASES = all_cases()
BLENDERS = {b.name: b for b in runner.blenders()}
OUT = Path(os.environ.get("STRATUM_CORPUS_OUT", runner.REPO / "out" / "corpus"))


@pytest.fixture(scope="session")
def outcomes(request: pytest.FixtureRequest) -> dict[tuple[str, str], runner.Outcome]:
    """Outcomes of the cases this session selected, by (Blender, case)."""
    wanted: dict[str, list[str]] = {}
    for item in request.session.items:
        params = getattr(getattr(item, "callspec", None), "params", {})
        if "case" in params and params.get("blender") in BLENDERS:
            names = wanted.setdefault(params["blender"], [])
            if params["case"] not in names:
                names.append(params["case"])
    results: dict[tuple[str, str], runner.Outcome] = {}

    def run(name: str, names: list[str]) -> None:
        for case_name, outcome in runner.run(BLENDERS[name], names, OUT / name).items():
            results[(name, case_name)] = outcome

    threads = [threading.Thread(target=run, args=item) for item in wanted.items()
               if BLENDERS[item[0]].available()]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    markdown = table.write(results, CASES, list(BLENDERS), OUT)
    print(f"\ncorpus outcome table: {markdown}")
    return results


@pytest.mark.parametrize("blender", list(BLENDERS))
@pytest.mark.parametrize("case", list(CASES))
def test_case(case: str, blender: str, outcomes: dict[tuple[str, str], runner.Outcome]) -> None:
    if not BLENDERS[blender].available():
        pytest.skip(f"{BLENDERS[blender].command[0]} not found")
    outcome = outcomes[(blender, case)]
    assert outcome.passed, f"{CASES[case].what}\n{outcome.describe()}"
