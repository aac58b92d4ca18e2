"""Installs, uses and uninstalls the packaged add-on inside one Blender process (one phase per
process), as a user does; run by test_package.py in Blender 3.4 (`blender -b --python`) and
under the bpy wheel (`python -I -S`, the wheel's site-packages appended here, so that the
checkout's editable install of `stratum` is not importable). It is copied out of the checkout
first: nothing of the checkout is on sys.path or mapped while it runs, which it asserts.

    ... blender_install.py -- PHASE RESULT.json [--zip Z] [--scene S] [--site DIR]
                                                [--checkout DIR] [--addon-dir DIR]

Phases:
  load       install --zip, enable it and load the native library (for a trace of the loader)
  install    install --zip (Blender 3.x: Preferences > Add-ons > Install; 4.2+: Install from
             Disk into the user_default repository), enable, render --scene; then, when
             --upgrade-zip is given, install it over the first while the library is loaded,
             check the loaded file was replaced rather than overwritten, render again; save
             the preferences
  restart    a new session: the add-on is enabled from the saved preferences (the bpy 4.2
             wheel: by its module name, READS_PREFERENCES); render, then uninstall through
             Blender while it is loaded; save the preferences
  removed    a new session: no Stratum anywhere
  checkout   the reference: the checkout's add-on (--addon-dir) renders --scene
The result (digests of the renders' float pixels, versions, paths) goes to RESULT.json.
"""

from __future__ import annotations

import hashlib
import importlib
import importlib.util
import json
import os
import sys
from pathlib import Path
from typing import Any

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
PHASE, RESULT = argv[0], Path(argv[1])
OPTIONS = dict(zip(argv[2::2], argv[3::2]))
if "--site" in OPTIONS:
    sys.path.append(OPTIONS["--site"])

import bpy
import numpy as np

EXTENSIONS = bpy.app.version >= (4, 2, 0)
REPOSITORY = "user_default"
# The bpy module starts with factory preferences (Blender's startup reads the user's), so a new
# session reads them itself; but bpy 4.2.23's module crashes in wm.read_userpref (a segfault in
# UI_icons_reload_internal_textures, which makes GPU textures in a module that has no GPU
# context; no add-on involved: it crashes from an empty configuration too). 4.5 and 5.0 read
# them. In 4.2 the restart enables the installed extension by its module name instead.
READS_PREFERENCES = "--site" in OPTIONS and bpy.app.version >= (4, 5, 0)
result: dict[str, Any] = {"blender": list(bpy.app.version), "phase": PHASE}


def addon_module() -> str | None:
    names = [a.module for a in bpy.context.preferences.addons
             if a.module.split(".")[-1] == "stratum"]
    return names[0] if names else None


def install_root() -> Path:
    if EXTENSIONS:
        return Path(bpy.utils.user_resource("EXTENSIONS", path=REPOSITORY))
    return Path(bpy.utils.user_resource("SCRIPTS", path="addons"))


def install(zip_path: str) -> None:
    if EXTENSIONS:
        outcome = bpy.ops.extensions.package_install_files(
            filepath=zip_path, repo=REPOSITORY, enable_on_install=True)
    else:
        outcome = bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
        if outcome == {"FINISHED"}:
            outcome = bpy.ops.preferences.addon_enable(module="stratum")
    assert outcome == {"FINISHED"}, f"installing {zip_path}: {outcome}"
    assert addon_module() is not None, f"{zip_path} installed but not enabled"


def render_digest(scene_file: str, out: Path, denoise: bool = False) -> str:
    """Renders the scene at 32x32, 8 spp, to a float EXR; SHA-256 of its RGBA pixels."""
    bpy.ops.wm.open_mainfile(filepath=scene_file)
    scene = bpy.context.scene
    scene.render.engine = "STRATUM"
    scene.stratum.use_denoising = denoise
    scene.render.resolution_x = scene.render.resolution_y = 32
    scene.render.resolution_percentage = 100
    scene.stratum.samples = 8
    settings = scene.render.image_settings
    settings.file_format, settings.color_mode, settings.color_depth = "OPEN_EXR", "RGBA", "32"
    scene.render.filepath = str(out)
    scene.render.use_file_extension = False
    out.unlink(missing_ok=True)
    assert bpy.ops.render.render(write_still=True) == {"FINISHED"}
    image = bpy.data.images.load(str(out), check_existing=False)
    pixels = np.empty(image.size[0] * image.size[1] * image.channels, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    assert np.isfinite(pixels).all() and pixels.max() > 0.0, "the render is black or not finite"
    return hashlib.sha256(pixels.tobytes()).hexdigest()


def mapped_files() -> list[tuple[str, int]]:
    """(path, inode) of every file mapped into this process."""
    seen = set()
    for line in Path("/proc/self/maps").read_text().splitlines():
        fields = line.split(maxsplit=5)
        if len(fields) == 6 and fields[5].startswith("/"):
            seen.add((fields[5], int(fields[4])))
    return sorted(seen)


def loaded_library() -> tuple[str, int]:
    found = [(p, i) for p, i in mapped_files() if Path(p.removesuffix(" (deleted)")).name
             == "libstratum.so"]
    assert len(found) == 1, f"libstratum.so mapped {len(found)} times: {found}"
    return found[0]


def check_isolated() -> None:
    """The add-on, its library and everything they load come from the install, not the
    checkout."""
    checkout = Path(OPTIONS["--checkout"]).resolve()

    # Under a bpy wheel, the venv that holds it (.venv, .venv-bpy-<line>: --site is its
    # lib/python3.x/site-packages) is part of the Blender, not of Stratum.
    wheel_venv = Path(OPTIONS["--site"]).resolve().parents[2] if "--site" in OPTIONS else None

    def of_checkout(path: str) -> bool:
        resolved = Path(path.removesuffix(" (deleted)")).resolve()
        return resolved.is_relative_to(checkout) and \
            not (wheel_venv is not None and resolved.is_relative_to(wheel_venv))

    module = addon_module()
    assert module is not None
    root = str(install_root().resolve())
    files = [m.__file__ for n, m in list(sys.modules.items())
             if (n == module or n.startswith(module + ".")) and getattr(m, "__file__", None)]
    assert files and all(str(Path(f).resolve()).startswith(root) for f in files), files
    preferences = bpy.context.preferences.addons[module].preferences
    assert preferences is not None and type(preferences).bl_idname == module, \
        f"add-on preferences: {preferences!r}"
    status = sys.modules[module + ".native"].library_status()
    assert status.version is not None, status.error
    assert str(status.path).startswith(root), status.path
    on_path = [p for p in sys.path if p and of_checkout(p)]
    assert not on_path, f"the checkout is on sys.path: {on_path}"
    mapped = [p for p, _ in mapped_files() if of_checkout(p)]
    assert not mapped, f"files of the checkout are mapped: {mapped}"
    spec = importlib.util.find_spec("stratum")
    assert spec is None or not of_checkout(spec.origin or ""), spec
    result.update(module=module, library=str(status.path), library_version=status.version,
                  version=sys.modules[module].__version__, install_root=root)


def phase_install() -> None:
    out = Path(OPTIONS["--work"])
    install(OPTIONS["--zip"])
    result["digest"] = render_digest(OPTIONS["--scene"], out / "install.exr")
    check_isolated()
    # Open Image Denoise from the package: its library, core and CPU device (which the core
    # opens by name from its own folder) and the oneTBB the device needs.
    result["denoised_digest"] = render_digest(OPTIONS["--scene"], out / "denoised.exr", True)
    oidn = sorted({Path(p).name for p, _ in mapped_files()
                   if "OpenImageDenoise" in p and p.startswith(result["install_root"])})
    assert len(oidn) == 3 and any("device_cpu" in name for name in oidn), oidn
    result["denoiser"] = oidn
    if "--upgrade-zip" in OPTIONS:
        _, inode = loaded_library()
        install(OPTIONS["--upgrade-zip"])
        on_disk = Path(result["library"])
        # The running library was unlinked (Blender 3.4 removes the add-on's folder, 4.2+
        # renames it aside and deletes it) and a new file written (another inode), not
        # rewritten in place, which would change the pages Blender is executing.
        assert on_disk.stat().st_ino != inode, f"{on_disk} was overwritten in place"
        mapped_path, mapped_inode = loaded_library()
        assert mapped_inode == inode and mapped_path.endswith(" (deleted)"), loaded_library()
        result["mapped_after_upgrade"] = mapped_path
        result["digest_after_upgrade"] = render_digest(OPTIONS["--scene"], out / "upgraded.exr")
        manifest = install_root() / "stratum" / "blender_manifest.toml"
        result["version_on_disk"] = next(line.split('"')[1] for line in
                                         manifest.read_text().splitlines()
                                         if line.startswith("version"))
    bpy.ops.wm.save_userpref()


def remove_legacy_addon() -> set[str]:
    """Preferences > Add-ons > Remove (Blender 3.x). The operator ends by redrawing its area,
    which background mode has not: in 3.4 that last line raises after the add-on was disabled
    and its files removed. That one error is accepted; what was removed is checked after."""
    try:
        return bpy.ops.preferences.addon_remove(module="stratum")
    except RuntimeError as exc:
        if "context.area.tag_redraw()" not in str(exc) or bpy.app.background is False:
            raise
        return {"FINISHED"}


def phase_load() -> None:
    """Installs and enables --zip and loads the native library, nothing more (the test traces
    the loader's symbol bindings, a large trace)."""
    install(OPTIONS["--zip"])
    module = addon_module()
    result["library_version"] = sys.modules[module + ".native"].version()
    result["library"] = str(sys.modules[module + ".native"].library_status().path)


def phase_restart() -> None:
    out = Path(OPTIONS["--work"])
    if READS_PREFERENCES:
        bpy.ops.wm.read_userpref()
    elif "--site" in OPTIONS:
        bpy.ops.preferences.addon_enable(module=f"bl_ext.{REPOSITORY}.stratum")
    result["enabled_at_start"] = addon_module()
    assert result["enabled_at_start"] is not None, "not enabled from the saved preferences"
    result["digest"] = render_digest(OPTIONS["--scene"], out / "restart.exr")
    check_isolated()
    installed = install_root() / "stratum"
    assert installed.is_dir()
    if EXTENSIONS:
        outcome = bpy.ops.extensions.package_uninstall(repo_directory=str(install_root()),
                                                       pkg_id="stratum")
    else:
        outcome = remove_legacy_addon()
    assert outcome == {"FINISHED"}, f"uninstall: {outcome}"
    assert not installed.exists(), f"{installed} left after uninstalling"
    assert addon_module() is None
    bpy.ops.wm.save_userpref()


def phase_removed() -> None:
    if READS_PREFERENCES:
        bpy.ops.wm.read_userpref()
    assert addon_module() is None
    assert not (install_root() / "stratum").exists()
    engines = {getattr(cls, "bl_idname", "") for cls in bpy.types.RenderEngine.__subclasses__()}
    assert "STRATUM" not in engines, engines


def phase_checkout() -> None:
    sys.path.insert(0, OPTIONS["--addon-dir"])
    stratum = importlib.import_module("stratum")
    stratum.register()
    result["digest"] = render_digest(OPTIONS["--scene"], Path(OPTIONS["--work"]) / "checkout.exr")
    result["version"] = stratum.__version__


def main() -> None:
    try:
        {"install": phase_install, "load": phase_load, "restart": phase_restart,
         "removed": phase_removed, "checkout": phase_checkout}[PHASE]()
        result["ok"] = True
    except Exception as exc:  # noqa: BLE001 - whatever failed, the test shows it
        import traceback

        result.update(ok=False, error=f"{type(exc).__name__}: {exc}",
                      traceback=traceback.format_exc())
    RESULT.write_text(json.dumps(result, indent=1))
    sys.stdout.flush()
    os._exit(0)


main()
