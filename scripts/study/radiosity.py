"""The radiosity part of `make study` (issue 17, acceptance 3; the textbook's claim 12:
brightest-first shooting and Gauss-Seidel converge faster than Jacobi): the three solvers on
the diffuse Cornell box, residual and the book's Delta E per iteration and against the solver's
time; out/study/radiosity.json (measured), out/study/radiosity.md and
out/study/figures/radiosity.png (written from it). run.py's summary reads the page.

| solver       | iteration                                                        |
|--------------|------------------------------------------------------------------|
| jacobi       | one sweep: every patch gathers from the previous iterate (threads) |
| gauss_seidel | one sweep in place (one thread)                                  |
| shooting     | K shots, brightest unshot power first (one thread)               |

The box is the one tests/native/helpers/radiosity_scenes.h builds (Lambert walls of the Cornell
reflectances, two white blocks, an emissive 0.5 x 0.5 quad in the ceiling), built here through
the library's Python API: no Blender involved. Each solver runs one 8 x 8 render of one sample
(the solve is all the work) at a tolerance far below the default, so that the curves show the
whole descent; the form factors are the same for the three (fixed ray sets). Times are the
solvers' own (the per-iteration measures are not counted) and machine-dependent: the load
average is recorded beside them.

    .venv/bin/python -m scripts.study.radiosity [--out out/study] [--quick]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
from pathlib import Path
from typing import Any

from scripts import REPO
from scripts.study.plotting import pyplot

SOLVERS = ("jacobi", "gauss_seidel", "shooting")
TOLERANCE = 1e-7
# Relative Delta E levels the page reports the iterations and seconds to reach.
LEVELS = (1e-2, 1e-3, 1e-4, 1e-6)
REFLECTANCES = {"white": (0.73, 0.71, 0.68), "red": (0.63, 0.065, 0.05), "green": (0.14, 0.45, 0.09)}
EMISSION = 12.0


def block(cx: float, cz: float, half: float, height: float, angle: float) -> list[list[float]]:
    """The five faces (no bottom) of a box of half side `half` standing on y = -1 at (cx, cz),
    turned by `angle` about the vertical, as quads of four corners (x, y, z)."""
    c, s = math.cos(angle), math.sin(angle)

    def at(x: float, y: float, z: float) -> list[float]:
        return [cx + c * x + s * z, y, cz - s * x + c * z]

    y0, y1 = -1.0, -1.0 + height
    p = [at(-half, y0, -half), at(half, y0, -half), at(half, y0, half), at(-half, y0, half),
         at(-half, y1, -half), at(half, y1, -half), at(half, y1, half), at(-half, y1, half)]
    faces = ((4, 7, 6, 5), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7))
    return [[v for k in f for v in p[k]] for f in faces]


def cornell_quads() -> list[tuple[list[float], str]]:
    """The box's quads (12 numbers each) and material names, as radiosity_scenes.h lists them."""
    q = 0.25
    quads = [
        ([-1, -1, -1, 1, -1, -1, 1, -1, 1, -1, -1, 1], "white"),  # floor
        ([-1, -1, -1, -1, 1, -1, 1, 1, -1, 1, -1, -1], "white"),  # back wall
        ([-1, -1, -1, -1, -1, 1, -1, 1, 1, -1, 1, -1], "red"),
        ([1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1], "green"),
        ([-1, 1, -1, 1, 1, -1, 1, 1, -q, -1, 1, -q], "white"),  # the ceiling around the light
        ([-1, 1, q, 1, 1, q, 1, 1, 1, -1, 1, 1], "white"),
        ([-1, 1, -q, -q, 1, -q, -q, 1, q, -1, 1, q], "white"),
        ([q, 1, -q, 1, 1, -q, 1, 1, q, q, 1, q], "white"),
        ([-q, 1, -q, q, 1, -q, q, 1, q, -q, 1, q], "light"),
    ]
    quads += [(f, "white") for f in block(0.35, 0.3, 0.3, 0.6, -0.3)]
    quads += [(f, "white") for f in block(-0.35, -0.35, 0.3, 1.2, 0.3)]
    return [([float(v) for v in corners], name) for corners, name in quads]


def cornell_scene(native: Any) -> Any:
    import numpy as np

    scene = native.Scene()
    diffuse = native.closure_model("diffuse")
    ids = {name: scene.add_material({"model": diffuse, "base_color": rgb})
           for name, rgb in REFLECTANCES.items()}
    ids["light"] = scene.add_material({"model": diffuse, "base_color": (0.0, 0.0, 0.0),
                                       "emission": (EMISSION,) * 3})
    triangles = np.array([[0, 1, 2], [0, 2, 3]], dtype=np.uint32)
    for corners, name in cornell_quads():
        positions = np.array(corners, dtype=np.float32).reshape(4, 3)
        mesh = scene.add_mesh(positions, triangles, np.full(2, ids[name], dtype=np.uint32))
        scene.add_instance(mesh, np.eye(4, dtype=np.float32))
    camera = np.eye(4, dtype=np.float32)
    camera[2, 3] = 1.9
    scene.set_camera(native.Camera(lens_mm=18.0, sensor_width_mm=36.0, sensor_height_mm=36.0,
                                   transform=camera))
    return scene


def measure(out: Path, quick: bool) -> dict[str, Any]:
    """Solves the box with each solver; writes and returns out/radiosity.json."""
    from stratum import native

    patch_size, rays = (0.5, 64) if quick else (0.125, 256)
    scene = cornell_scene(native)
    result: dict[str, Any] = {"patch_size": patch_size, "rays": rays, "tolerance": TOLERANCE,
                              "load_average": os.getloadavg()[0], "solvers": {}}
    try:
        for solver in SOLVERS:
            with native.Renderer(scene, width=8, height=8, samples=1, integrator="radiosity",
                                 radiosity_patch_size=patch_size, radiosity_rays=rays,
                                 radiosity_solver=solver, radiosity_tolerance=TOLERANCE) as r:
                r.start()
                while not r.wait(1000):
                    pass
                p = r.progress()
                history = r.radiosity_iterations()
            result["patches"] = p.counter("radiosity.patches")
            result["solvers"][solver] = {
                "bytes": p.counter("radiosity.bytes"), "seconds": p.counter("radiosity.seconds"),
                "delta_e": history[:, 0].tolist(), "relative": history[:, 1].tolist(),
                "residual": history[:, 2].tolist(), "solver_seconds": history[:, 3].tolist()}
            print(f"study.radiosity: {solver}: {len(history)} iterations, "
                  f"{history[-1, 3]:.3f} s solving", flush=True)
    finally:
        scene.close()
    out.mkdir(parents=True, exist_ok=True)
    (out / "radiosity.json").write_text(json.dumps(result, indent=1))
    return result


def first_reaching(values: list[float], level: float) -> int | None:
    """The 0-based index of the first value <= level, or None."""
    return next((k for k, v in enumerate(values) if v <= level), None)


def figure(result: dict[str, Any], path: Path) -> None:
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for solver, r in result["solvers"].items():
        iterations = list(range(1, len(r["residual"]) + 1))
        axes[0].semilogy(iterations, r["residual"], marker=".", label=solver)
        axes[1].loglog(r["solver_seconds"], r["residual"], marker=".", label=solver)
    axes[0].set_xlabel("iteration (a sweep; K shots for shooting)")
    axes[1].set_xlabel("solver seconds")
    for ax in axes:
        ax.set_ylabel("residual (radiance)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle(f"Diffuse Cornell box, K = {result['patches']:.0f} patches, "
                 f"{result['rays']} rays per patch")
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=100)
    plt.close(fig)


def write_page(out: Path, load: Any = None) -> tuple[str, dict[str, Any]]:
    """out/radiosity.md (and the figure) from out/radiosity.json; its text and the numbers for
    headline.json. `load` is the summary's results loader, unused: this part has no compare
    run."""
    del load
    parts = ["# Radiosity solvers (issue 17, claim 12)", "",
             ("Generated by `scripts/study/radiosity.py` (`make study`). Residual "
              "Σ A_i |b_i + κ_i (GM)_i − M_i| / (π Σ A_i) and the book's ΔE per iteration; "
              "seconds are the solver's own."), ""]
    path = out / "radiosity.json"
    if not path.is_file():
        parts += ["Not measured yet: run `make study`.", ""]
        text = "\n".join(parts)
        (out / "radiosity.md").write_text(text)
        return text, {}
    result = json.loads(path.read_text())
    parts += [(f"Diffuse Cornell box, patch size {result['patch_size']}: K = "
               f"{result['patches']:.0f} patches, {result['rays']} form-factor rays per patch, "
               f"tolerance {result['tolerance']:g}; load average {result['load_average']:.2f}."),
              "", "| solver | iterations | solver ms | final residual | " + " | ".join(
                  f"iterations / ms to ΔE/L̄ ≤ {level:g}" for level in LEVELS) + " | memory MB |",
              "|---|---|---|---|" + "---|" * len(LEVELS) + "---|"]
    numbers: dict[str, Any] = {"patches": result["patches"], "solvers": {}}
    for solver, r in result["solvers"].items():
        cells = []
        reached: dict[str, Any] = {}
        for level in LEVELS:
            k = first_reaching(r["relative"], level)
            cells.append("–" if k is None else f"{k + 1} / {1e3 * r['solver_seconds'][k]:.1f}")
            reached[f"{level:g}"] = None if k is None else {"iterations": k + 1,
                                                            "seconds": r["solver_seconds"][k]}
        parts.append(f"| {solver} | {len(r['residual'])} | {1e3 * r['solver_seconds'][-1]:.1f} | "
                     f"{r['residual'][-1]:.2e} | " + " | ".join(cells)
                     + f" | {r['bytes'] / 1e6:.1f} |")
        numbers["solvers"][solver] = reached
    figure(result, out / "figures" / "radiosity.png")
    parts += ["", "![residual against iterations and time](figures/radiosity.png)", ""]
    text = "\n".join(parts)
    (out / "radiosity.md").write_text(text)
    print(f"study: wrote {out / 'radiosity.md'}")
    return text, numbers


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default=str(REPO / "out" / "study"))
    p.add_argument("--quick", action="store_true", help="a coarse patching, to test the script")
    args = p.parse_args(argv)
    out = Path(args.out).resolve()
    measure(out, args.quick)
    write_page(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
