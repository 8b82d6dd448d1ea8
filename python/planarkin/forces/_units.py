"""The unit system of a scene's loads: which factor turns mass times acceleration (and
kinetic energy) into the scene's force (and force times length) units. A leaf: names only."""

from __future__ import annotations

from collections.abc import Mapping

__all__ = ["inertia_factor", "unit_names"]

#: Each known unit in SI (metres, newtons, kilograms).
LENGTH = {"m": 1.0, "mm": 1e-3, "cm": 1e-2, "km": 1e3, "um": 1e-6, "in": 0.0254, "ft": 0.3048}
FORCE = {"N": 1.0, "kN": 1e3, "mN": 1e-3, "MN": 1e6, "lbf": 4.4482216152605}
MASS = {"kg": 1.0, "g": 1e-3, "t": 1e3, "lb": 0.45359237}


def unit_names(length: str | None, table: Mapping[str, str] | None) -> dict[str, str | None]:
    """The scene's length, force and mass units (force N and mass kg unless named; the
    length unit None where the scene names none)."""
    t = dict(table or {})
    return {
        "length": t.get("length", length),
        "force": t.get("force", "N"),
        "mass": t.get("mass", "kg"),
    }


def inertia_factor(units: Mapping[str, str | None]) -> float:
    """mass x length / time^2 in force units: 1 where the units are consistent SI or any
    is not a unit known here (then the scene is taken to be stated in consistent units)."""
    length, force, mass = units["length"], units["force"], units["mass"]
    if length is None:
        length = "m"
    if length not in LENGTH or force not in FORCE or mass not in MASS:
        return 1.0
    return MASS[mass] * LENGTH[length] / FORCE[force]
