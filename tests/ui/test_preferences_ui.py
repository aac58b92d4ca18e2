"""The add-on's preferences (issue 19) in Blender 3.4's real UI, installed from `make package`'s
zip into an empty user configuration: Blender draws them without an error, and they name the
version of the manifest and the native library loaded from the install. The screenshot
out/ui/preferences/preferences.png is for a reviewer's eye."""

from __future__ import annotations

import subprocess
import sys
import tomllib
from pathlib import Path
from typing import Any

import pytest
from conftest import OUT, REPO, run_scenario

CORNELL = REPO / "scenes" / "cornell_box.blend"
VERSION = tomllib.loads((REPO / "addon" / "stratum" / "blender_manifest.toml").read_text())[
    "version"]


@pytest.fixture(scope="module")
def preferences(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    home = tmp_path_factory.mktemp("blender-user")
    built = subprocess.run([sys.executable, "-m", "scripts.packaging.package", "--out",
                            str(home / "dist")], capture_output=True, text=True, cwd=REPO,
                           check=False)
    assert built.returncode == 0, built.stderr
    package = home / "dist" / f"stratum-{VERSION}-linux-x64.zip"
    env = {"PYTHONPATH": str(REPO / "tests" / "ui"), "HOME": str(home),
           "BLENDER_USER_CONFIG": str(home / "config"),
           "BLENDER_USER_SCRIPTS": str(home / "scripts"), "STRATUM_PACKAGE": str(package)}
    return run_scenario("scenario_preferences.py", CORNELL, "preferences", env=env) | {
        "home": str(home)}


def test_blender_draws_the_preferences_of_the_installed_add_on(
        preferences: dict[str, Any]) -> None:
    assert not preferences.get("draw_errors"), preferences["draw_errors"]
    scripts = Path(preferences["home"]) / "scripts"
    assert Path(preferences["module_file"]).is_relative_to(scripts)
    assert preferences["drawn"] == ["StratumPreferences"]
    drawn = preferences["shown"]
    assert drawn["version"] == VERSION and drawn["library_version"] == VERSION, drawn
    assert Path(drawn["library"]).is_relative_to(scripts / "addons" / "stratum" / "lib"), drawn
    assert (OUT / "preferences" / "preferences.png").stat().st_size > 0
