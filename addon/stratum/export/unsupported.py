"""Objects and features Stratum does not render: one warning per kind, naming the objects.

Stratum renders surfaces (meshes and what converts to them: curves, surfaces, text, metaballs)
and lights. Everything else a depsgraph can hold is either nothing to render (empties,
armatures, lattices, cameras, speakers, light probes: Cycles renders none of them either) or
a kind listed here, reported in one line per kind:

* volume objects (OpenVDB) and point clouds, including those geometry nodes make;
* hair: CURVES objects and hair particle systems drawn as strands (render type Path; hair
  drawn as objects or collections arrives as ordinary instances);
* fluid gas domains (smoke, fire): Cycles syncs a mesh with a Fluid modifier of type Domain
  and domain type Gas as a volume, never as a surface (blender/geometry.cpp,
  object_fluid_gas_domain_find), so without its volume nothing is drawn; the domain's box is
  skipped here too. A liquid domain's mesh is the liquid surface, rendered as Cycles does.
"""

from __future__ import annotations

from typing import Any

from .common import ExportSummary

KIND_MESSAGES = {
    "VOLUME": "volume objects are not rendered (Stratum renders surfaces only)",
    "POINTCLOUD": "point clouds are not rendered",
    "CURVES": "hair curves objects are not rendered",
    "HAIR": "hair particle systems drawn as strands are not rendered",
    "GAS_DOMAIN": "the smoke/fire volumes of fluid gas domains are not rendered, and (as in "
                  "Cycles) neither are the domains' surfaces",
}
MAX_NAMES = 10  # names listed per kind; the rest are counted


def is_gas_domain(ob: Any) -> bool:
    """A mesh with a Fluid modifier of type Domain, domain type Gas (Cycles' test)."""
    for modifier in getattr(ob, "modifiers", ()):
        if modifier.type == "FLUID" and modifier.fluid_type == "DOMAIN":
            settings = modifier.domain_settings
            if settings is not None and settings.domain_type == "GAS":
                return True
    return False


def hair_systems(ob: Any) -> list[str]:
    """Names of the particle systems of `ob` that Cycles draws as hair strands in renders."""
    names = []
    for modifier in getattr(ob, "modifiers", ()):
        if modifier.type != "PARTICLE_SYSTEM" or not modifier.show_render:
            continue
        system = modifier.particle_system
        settings = system.settings
        if settings is not None and settings.type == "HAIR" and settings.render_type == "PATH":
            names.append(system.name)
    return names


class UnsupportedObjects:
    """Collects what is not rendered, per kind, and reports it once per kind."""

    def __init__(self) -> None:
        self._names: dict[str, list[str]] = {}

    def _note(self, kind: str, name: str) -> None:
        names = self._names.setdefault(kind, [])
        if name not in names:
            names.append(name)

    def skip(self, ob: Any) -> bool:
        """True when `ob`'s own geometry is not rendered (noted); notes its hair, if any."""
        kind = ob.type
        if kind in KIND_MESSAGES:
            self._note(kind, ob.name)
            return True
        if kind == "MESH" and is_gas_domain(ob):
            self._note("GAS_DOMAIN", ob.name)
            return True
        if kind == "MESH":
            for system in hair_systems(ob):
                self._note("HAIR", f"{ob.name} ({system})")
        return False

    def report(self, summary: ExportSummary) -> None:
        for kind, names in self._names.items():
            shown = ", ".join(f"'{n}'" for n in names[:MAX_NAMES])
            more = f" and {len(names) - MAX_NAMES} more" if len(names) > MAX_NAMES else ""
            message = KIND_MESSAGES[kind]
            summary.warn(f"{message[0].upper()}{message[1:]}: {shown}{more}")
