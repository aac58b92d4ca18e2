"""The installable package (issue 19): `make package`'s zip installs into a fresh Blender user
configuration, in Blender 3.4 (legacy add-on) and under the bpy wheels of 5.0 (the main venv)
and of the 4.2 and 4.5 LTS lines (their venvs, scripts/setup_wheels.sh) as an extension,
renders the Cornell box from the install alone, upgrades while loaded, and uninstalls cleanly.

Built here, twice: the manifest's version and the next patch version (the upgrade). Each
Blender runs blender_install.py, copied out of the checkout, in four processes: install (+
upgrade over it), restart (enabled from the saved preferences; uninstall), removed, and the
checkout's add-on for a reference render. The package's render must equal the checkout's bit
for bit: the same code on the same libraries (private copies of the same files).

The loader's trace (LD_DEBUG=libs) of the install process must show every library the
library's loading initialises coming from the package; `ldd` in an empty environment must find
every dependency of libstratum.so in the package or the base system.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import tomllib
import zipfile
from pathlib import Path

import pytest
from scripts.packaging.elf_names import needed
from scripts.packaging.library_bundle import BASE_SYSTEM

REPO = Path(__file__).resolve().parents[2]

PYTHON = REPO / ".venv" / "bin" / "python"
SITE = next((REPO / ".venv" / "lib").glob("python3*/site-packages"))
# Each wheel kind's venv: the main one (bpy 5.0) and one per LTS line that
# scripts/setup_wheels.sh makes from scripts/requirements-bpy-<line>.txt.
WHEEL_VENVS = {"wheel": REPO / ".venv"} | {
    f"wheel-{path.stem.removeprefix('requirements-bpy-')}":
        REPO / f".venv-bpy-{path.stem.removeprefix('requirements-bpy-')}"
    for path in sorted((REPO / "scripts").glob("requirements-bpy-*.txt"))}
BLENDER = os.environ.get("BLENDER", "blender")
SCRIPT = Path(__file__).resolve().parent / "blender_install.py"
SCENE = REPO / "scenes" / "cornell_box.blend"
MANIFEST = REPO / "addon" / "stratum" / "blender_manifest.toml"
ROOTS = ("libstratum.so", "libstratum_dependencies.so", "libOpenImageDenoise.so.2")
# A bundled library's private name: the soname with ".so" replaced by two hex digits.
PRIVATE = re.compile(r"^(?P<stem>.+?)\.[0-9a-f]{2}(?P<suffix>(\.\d+)*)$")


def _version() -> str:
    return tomllib.loads(MANIFEST.read_text())["version"]


def _next_version(version: str) -> str:
    major, minor, patch = (int(p) for p in version.split("-")[0].split(".")[:3])
    return f"{major}.{minor}.{patch + 1}"


@pytest.fixture(scope="module")
def packages(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    out = tmp_path_factory.mktemp("dist")
    built = {}
    for version in (_version(), _next_version(_version())):
        args = [str(PYTHON), "-m", "scripts.packaging.package", "--out", str(out / version)]
        if version != _version():
            args += ["--version", version]
        run = subprocess.run(args, capture_output=True, text=True, cwd=REPO, check=False)
        assert run.returncode == 0, run.stderr + run.stdout
        print(run.stdout.strip())
        built[version] = out / version / f"stratum-{version}-linux-x64.zip"
        assert built[version].is_file()
    return built


def _closure(lib_dir: Path, root: str) -> set[str]:
    """The files of lib_dir that `root` loads, itself included."""
    found: set[str] = set()
    pending = [root]
    while pending:
        name = pending.pop()
        if name in found or name in BASE_SYSTEM:
            continue
        found.add(name)
        pending += needed(lib_dir / name)
    return found


@pytest.fixture(scope="module")
def unpacked(packages: dict[str, Path], tmp_path_factory: pytest.TempPathFactory) -> Path:
    target = tmp_path_factory.mktemp("unpacked")
    with zipfile.ZipFile(packages[_version()]) as archive:
        archive.extractall(target)
    for library in (target / "stratum" / "lib").iterdir():
        library.chmod(0o755)
    return target / "stratum"


def test_zip_holds_the_add_on_and_its_libraries_only(packages: dict[str, Path],
                                                     unpacked: Path) -> None:
    zip_path = packages[_version()]
    names = zipfile.ZipFile(zip_path).namelist()
    print(f"{zip_path.name}: {zip_path.stat().st_size / 1e6:.1f} MB, {len(names)} entries")
    assert all(n.startswith("stratum/") for n in names), "one top-level folder, the module"
    assert "stratum/" in names, "the top-level folder's own entry (Blender 3.x's overwrite)"
    unwanted = [n for n in names if re.search(r"__pycache__|\.pyc$|(^|/)(tests?|build)/|\.o$", n)
                or n.startswith(("stratum/compare/", "stratum/cli/"))]
    assert not unwanted, unwanted
    manifest = tomllib.loads((unpacked / "blender_manifest.toml").read_text())
    assert manifest["id"] == "stratum" and manifest["version"] == _version()
    assert manifest["platforms"] == ["linux-x64"] and manifest["type"] == "add-on"
    assert manifest["permissions"]["files"], "the files permission states its reason"
    assert tuple(map(int, manifest["blender_version_min"].split("."))) >= (4, 2, 0)
    # Blender's own validator of extension packages (the one `blender --command extension
    # validate` runs), from the bpy wheel.
    validator = next(SITE.glob("bpy/*/scripts/addons_core/bl_pkg/cli/blender_ext.py"))
    check = subprocess.run([str(PYTHON), str(validator), "validate", str(zip_path)],
                           capture_output=True, text=True, check=False)
    assert check.returncode == 0, check.stdout + check.stderr
    init = (unpacked / "__init__.py").read_text()
    numbers = tuple(int(p) for p in _version().split("-")[0].split("."))
    assert f'"version": {numbers!r},' in init, "bl_info carries the manifest's version"
    # Every bundled library is loaded by a root: nothing in lib/ that no render needs.
    lib_dir = unpacked / "lib"
    reached = set().union(*(_closure(lib_dir, root) for root in ROOTS))
    reached |= {p.name for p in lib_dir.glob("libOpenImageDenoise_device_cpu.so.*")}
    reached |= _closure(lib_dir, next(lib_dir.glob("libOpenImageDenoise_device_cpu.so.*")).name)
    present = {p.name for p in lib_dir.iterdir()}
    assert present == reached, f"unreached: {present - reached}, missing: {reached - present}"
    # Each third-party library's origin and licence files
    # (scripts/packaging/third_party_notices.py).
    licences = unpacked / "licenses"
    listed = {}
    for line in (licences / "THIRD_PARTY.txt").read_text().splitlines()[3:]:
        listed[line.split()[0]] = re.search(r"\[(.*)\]$", line)[1].split(", ")
    assert set(listed) == present - {"libstratum.so", "libstratum_dependencies.so"}
    for library, files in listed.items():
        for name in files:
            assert (licences / name).stat().st_size > 0, (library, name)


def test_ldd_finds_every_dependency_in_the_package(unpacked: Path) -> None:
    lib_dir = unpacked / "lib"
    out = subprocess.run(["ldd", str(lib_dir / "libstratum.so")], capture_output=True,
                         text=True, env={"PATH": "/usr/bin:/bin"}, check=True).stdout
    resolved = re.findall(r"^\s*(\S+) => (\S+) \(", out, re.MULTILINE)
    assert "not found" not in out, out
    outside = [(name, path) for name, path in resolved
               if Path(path).parent != lib_dir and name not in BASE_SYSTEM]
    assert not outside, outside
    names = {name for name, _ in resolved}
    for stem in ("libembree3", "libtbb", "libOpenImageIO", "libOpenColorIO", "libOpenEXR-3_1"):
        assert any(PRIVATE.match(n) and PRIVATE.match(n)["stem"] == stem for n in names), stem


def _environment(home: Path) -> dict[str, str]:
    """A fresh, empty user configuration; nothing of the checkout's environment."""
    folders = {"BLENDER_USER_CONFIG": "config", "BLENDER_USER_SCRIPTS": "scripts",
               "BLENDER_USER_EXTENSIONS": "extensions", "BLENDER_USER_DATAFILES": "datafiles"}
    env = {"PATH": "/usr/bin:/bin", "HOME": str(home), "LC_ALL": "C.UTF-8"}
    for variable, folder in folders.items():
        (home / folder).mkdir(parents=True, exist_ok=True)
        env[variable] = str(home / folder)
    if "DISPLAY" in os.environ:
        env["DISPLAY"] = os.environ["DISPLAY"]
    return env


def _wheel_python(kind: str) -> tuple[Path, Path]:
    """The Python and the site-packages of a wheel kind's venv."""
    venv = WHEEL_VENVS[kind]
    if not (venv / "bin" / "python").is_file():
        pytest.fail(f"no {venv.name}: scripts/setup.sh creates it (scripts/setup_wheels.sh)")
    return venv / "bin" / "python", next((venv / "lib").glob("python3*/site-packages"))


def _run_phase(kind: str, phase: str, work: Path, env: dict[str, str], *options: str) -> dict:
    result = work / f"{phase}.json"
    if kind == "blender":
        command = [BLENDER, "-b", "-noaudio", "--python", str(work / SCRIPT.name), "--"]
    else:
        # -I -S: no PYTHON* variables, no user site, and site-packages' .pth files unread (the
        # checkout's editable install of `stratum` is one); the script appends site-packages.
        python, site = _wheel_python(kind)
        command = [str(python), "-I", "-S", str(work / SCRIPT.name), "--"]
        options = (*options, "--site", str(site))
    command += [phase, str(result), "--scene", str(work / SCENE.name), "--work", str(work),
                "--checkout", str(REPO), *options]
    run = subprocess.run(command, capture_output=True, text=True, cwd=work, env=env,
                         timeout=600, check=False)
    assert result.is_file(), f"{kind} {phase}: no result (exit {run.returncode})\n" \
                             f"{run.stdout[-3000:]}\n{run.stderr[-3000:]}"
    outcome = json.loads(result.read_text())
    assert outcome["ok"], f"{kind} {phase}: {outcome.get('traceback')}\n{run.stdout[-3000:]}"
    return outcome


def _trace_of_loading(trace_dir: Path, lib_dir: str) -> list[str]:
    """The files whose initialisers ran while the add-on loaded libstratum.so: from the first
    trace line naming the package's lib/ to libstratum.so's own initialiser."""
    for trace in trace_dir.glob("ld.*"):
        lines = trace.read_text(errors="replace").splitlines()
        end = next((i for i, line in enumerate(lines)
                    if line.endswith(f"calling init: {lib_dir}/libstratum.so")), None)
        if end is None:
            continue
        start = next(i for i, line in enumerate(lines) if lib_dir in line)
        return [line.split("calling init: ", 1)[1] for line in lines[start:end + 1]
                if "calling init: " in line]
    raise AssertionError(f"no trace in {trace_dir} shows {lib_dir}/libstratum.so loading")


@pytest.mark.parametrize("kind", ["blender", *WHEEL_VENVS])
def test_install_render_upgrade_uninstall(kind: str, packages: dict[str, Path],
                                          unpacked: Path, tmp_path: Path) -> None:
    if kind == "blender" and shutil.which(BLENDER) is None:
        pytest.fail(f"{BLENDER} not found (scripts/setup.sh installs Debian's Blender 3.4)")
    work = tmp_path / "work"
    work.mkdir()
    shutil.copy(SCRIPT, work)
    shutil.copy(SCENE, work)
    env = _environment(tmp_path / "home")
    old, new = packages.values()
    traces = tmp_path / "ld"
    traces.mkdir()
    traced = {**env, "LD_DEBUG": "libs", "LD_DEBUG_OUTPUT": str(traces / "ld")}
    installed = _run_phase(kind, "install", work, traced, "--zip", str(old),
                           "--upgrade-zip", str(new))
    assert installed["version"] == _version() and installed["library_version"] == _version()
    assert installed["version_on_disk"] == _next_version(_version())
    assert installed["digest_after_upgrade"] == installed["digest"]
    assert installed["denoised_digest"] != installed["digest"], "the denoiser changed nothing"

    lib_dir = str(Path(installed["library"]).parent)
    initialised = _trace_of_loading(traces, lib_dir)
    foreign = [path for path in initialised if Path(path).parent != Path(lib_dir)
               and Path(path).name not in BASE_SYSTEM]
    assert not foreign, f"loaded from outside the package: {foreign}"
    expected = _closure(unpacked / "lib", "libstratum.so") | \
        _closure(unpacked / "lib", "libstratum_dependencies.so")
    from_package = {Path(p).name for p in initialised if Path(p).parent == Path(lib_dir)}
    assert from_package == expected, f"not loaded: {expected - from_package}"

    restarted = _run_phase(kind, "restart", work, env)
    assert restarted["version"] == _next_version(_version())
    assert restarted["digest"] == installed["digest"]
    _run_phase(kind, "removed", work, env)

    reference_env = {**env, "PATH": os.environ.get("PATH", "/usr/bin:/bin")}
    if kind != "blender":
        checkout = subprocess.run(
            [str(_wheel_python(kind)[0]), str(work / SCRIPT.name), "--", "checkout", str(work / "ref.json"),
             "--scene", str(work / SCENE.name), "--work", str(work), "--addon-dir",
             str(REPO / "addon")], capture_output=True, text=True, env=reference_env, cwd=work,
            check=False)
        reference = json.loads((work / "ref.json").read_text())
        assert reference["ok"], reference.get("traceback", "") + checkout.stderr[-2000:]
    else:
        reference = _run_phase(kind, "checkout", work, reference_env, "--addon-dir",
                               str(REPO / "addon"))
    assert installed["digest"] == reference["digest"], "the package renders unlike the checkout"


def test_libstratum_binds_to_the_package_beside_blenders_own_copies(
        packages: dict[str, Path], tmp_path: Path) -> None:
    """Debian's Blender 3.4 has loaded Embree 3, OIIO 2.4, OCIO 2.1 and oneTBB under the very
    symbol names libstratum.so uses. Under LD_DEBUG=bindings every reference of libstratum.so
    must bind to the package, to the base system, or be one of its STB_GNU_UNIQUE symbols
    (inline statics of libstdc++'s headers), which the loader gives one instance per process
    whatever the scope: deep binding and the private names keep Blender's copies out."""
    if shutil.which(BLENDER) is None:
        pytest.fail(f"{BLENDER} not found (scripts/setup.sh installs Debian's Blender 3.4)")
    work = tmp_path / "work"
    work.mkdir()
    shutil.copy(SCRIPT, work)
    shutil.copy(SCENE, work)
    traces = tmp_path / "ld"
    traces.mkdir()
    env = {**_environment(tmp_path / "home"), "LD_DEBUG": "bindings",
           "LD_DEBUG_OUTPUT": str(traces / "ld")}
    loaded = _run_phase("blender", "load", work, env, "--zip", str(packages[_version()]))
    library = Path(loaded["library"])
    symbols = subprocess.run(["nm", "-D", "--defined-only", str(library)], capture_output=True,
                             text=True, check=True).stdout.splitlines()
    unique = {line.split()[-1] for line in symbols if line.split()[1:2] == ["u"]}
    prefix = f"binding file {library} [0] to "
    targets: dict[str, int] = {}
    elsewhere = []
    for trace in traces.glob("ld.*"):
        with trace.open(errors="replace") as stream:
            for line in stream:
                if prefix not in line:
                    continue
                target = line.split(prefix, 1)[1].split(" [", 1)[0]
                symbol = line.rsplit("`", 1)[1].rstrip("'\n")
                targets[Path(target).name] = targets.get(Path(target).name, 0) + 1
                if Path(target).parent != library.parent and \
                        Path(target).name not in BASE_SYSTEM and symbol not in unique:
                    elsewhere.append((symbol, target))
    print(f"libstratum.so's bindings by target: {sorted(targets.items())}")
    assert not elsewhere, f"bound outside the package: {elsewhere[:20]}"
    for stem in ("libembree3", "libOpenImageIO", "libOpenColorIO", "libtbb"):
        assert any(PRIVATE.match(t) and PRIVATE.match(t)["stem"] == stem for t in targets), stem
