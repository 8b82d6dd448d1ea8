"""The built-in scenes with loads (issue 34): an engine (the centred slider-crank with a gas
force on its piston), the seed four-bar with a coupler load and masses, Jansen's leg with a
ground reaction on its foot, and the hydraulic boom lifting a payload under gravity. Each is
an existing built-in's geometry with loads added; the load values are chosen here (plausible
orders of magnitude, not data from a machine). ``LOADED`` names them."""

from __future__ import annotations

import math

import numpy as np

from .geometry import DEG
from .linkages import fourbar, jansen
from .sliders import hydraulic_boom, slider_crank

SI_MM = {"length": "mm", "force": "N", "mass": "kg"}
SI_CM = {"length": "cm", "force": "N", "mass": "kg"}


def _bar(points, a, b, per_length):
    """A uniform bar a-b: mass per unit length ``per_length``, centre at its middle,
    inertia m l^2 / 12 about it."""
    pa, pb = np.asarray(points[a], float), np.asarray(points[b], float)
    length = float(np.hypot(*(pb - pa)))
    m = per_length * length
    c = (pa + pb) / 2
    return {"mass": round(m, 6), "center": [float(c[0]), float(c[1])],
            "inertia": round(m * length**2 / 12, 6)}  # fmt: skip


def engine():
    sc = slider_crank(0.0)
    bore_area = math.pi * 40.0**2  # an 80 mm bore, mm^2
    # gas pressure over the crank angle (a two-stroke cycle: one per turn): a peak of
    # 5 MPa (N/mm^2) 15 deg after top dead centre (t = 0), a Gaussian of 35 deg width,
    # over a 0.1 MPa floor; the force pushes the piston towards the crank (-x)
    t = np.arange(0, 360, 5) * DEG
    dt = (t - 15 * DEG + math.pi) % (2 * math.pi) - math.pi
    p = 0.1 + 4.9 * np.exp(-((dt / (35 * DEG)) ** 2))
    force = [round(-float(x) * bore_area, 3) for x in p]
    # the piston (0.5 kg) is a point mass at the pin B, lumped with the rod (0.8 kg, centre
    # 1/3 of the way from A): a point mass has no rotational inertia of its own, so the
    # lumped body's kinetic energy is exact
    a, b = np.asarray(sc["points"]["A"], float), np.asarray(sc["points"]["B"], float)
    mr, mp, rod = 0.8, 0.5, 160.0
    cr = a + (b - a) / 3
    c = (mr * cr + mp * b) / (mr + mp)
    inertia = (
        mr * rod**2 / 12 + mr * float(np.sum((cr - c) ** 2)) + mp * float(np.sum((b - c) ** 2))
    )
    sc.update(
        name="engine (slider-crank with gas force)",
        description=(
            "The centred slider-crank (crank 40 mm, rod 160 mm) as a single-cylinder engine: an "
            "80 mm bore, a gas pressure of 0.1 MPa rising to 5 MPa 15 deg after top dead centre "
            "(a Gaussian of 35 deg width, one firing a turn) as a force table on the piston "
            "over the crank angle; crank 2 kg balanced at O2 (inertia 2000 kg mm^2), rod 0.8 kg "
            "with the 0.5 kg piston lumped at its pin B; gravity 9810 mm/s^2 down. Values "
            "chosen here."
        ),
        units=SI_MM,
        loads={
            "forces": [
                {"slot": "piston", "force": force, "input": [round(float(x), 12) for x in t]}
            ],  # fmt: skip
            "gravity": [0.0, -9810.0],
            "masses": {
                "crank": {"mass": 2.0, "center": "O2", "inertia": 2000.0},
                "rod": {
                    "mass": mr + mp,
                    "center": [float(c[0]), float(c[1])],
                    "inertia": round(inertia, 6),
                },  # fmt: skip
            },
        },
    )
    return sc


def fourbar_loaded():
    sc = fourbar()
    pts = sc["points"]
    sc.update(
        name="four-bar with coupler load and masses",
        description=(
            "The seed four-bar (6, 2, 5, 5), lengths in cm, lifting a 50 N load hung at its "
            "coupler point P, its links uniform steel-like bars of 0.05 kg/cm (centres at "
            "their middles, inertia m l^2 / 12; the coupler's centre between A and B), under "
            "gravity 981 cm/s^2. Values chosen here. The crank turns fully."
        ),
        units=SI_CM,
        loads={
            "forces": [{"point": "P", "force": [0.0, -50.0]}],
            "gravity": [0.0, -981.0],
            "masses": {
                "crank": _bar(pts, "O2", "A", 0.05),
                "coupler": _bar(pts, "A", "B", 0.05),
                "rocker": _bar(pts, "O4", "B", 0.05),
            },
        },
    )
    return sc


def jansen_loaded():
    """Jansen's leg carrying 100 N on its foot while the foot is on the ground: the stance
    is where the foot is within 2 units of its lowest point, with a 1-unit ramp."""
    import planarkin as pk

    sc = jansen()
    pts = {k: [float(v[0]), float(v[1])] for k, v in sc["points"].items()}
    probe = pk.Scene.from_dict({**sc, "points": pts})
    t = probe.input_angle + np.arange(0, 360, 5) * DEG
    y = probe.sweep(t, outputs=["foot"]).points["foot"][:, 1]
    ground_y = float(y.min())
    w = np.clip((ground_y + 2.0 - y) / 1.0, 0.0, 1.0)
    order = np.argsort(t % (2 * math.pi))
    ts = (t % (2 * math.pi))[order]
    fy = (100.0 * w)[order]
    per_cm = 0.02
    masses = {}
    for link, names in sc["links"].items():
        if link in ("ground",):
            continue
        masses[link] = _bar(pts, names[0], names[1], per_cm)
    sc.update(
        name="Jansen's leg with a foot ground reaction",
        description=(
            "Jansen's Strandbeest leg (lengths as published, read as cm) walking: the ground "
            "pushes its foot up with 100 N while the foot is within 2 cm of its lowest point "
            "(ramped over 1 cm), a table over the crank angle; each link a bar of 0.02 kg/cm "
            "between its first two points (the triangles' centres on their first side); "
            "gravity 981 cm/s^2. Values chosen here. The crank turns fully."
        ),
        units=SI_CM,
        loads={
            "forces": [
                {
                    "point": "foot",
                    "force": [[0.0, round(float(f), 9)] for f in fy],
                    "input": [round(float(x), 12) for x in ts],
                }
            ],  # fmt: skip
            "gravity": [0.0, -981.0],
            "masses": masses,
        },
    )
    return sc


def boom_loaded():
    sc = hydraulic_boom()
    pts = {k: [float(v[0]), float(v[1])] for k, v in sc["points"].items()}
    sc.update(
        name="hydraulic boom lifting a payload",
        description=(
            "The hydraulic-cylinder boom (boom 2000 mm, cylinder pinned 800 mm from O) lifting a "
            "500 kg payload hung at its tip T (4905 N down) under gravity 9810 mm/s^2; boom "
            "120 kg with its centre at the middle of O-T (inertia m l^2 / 12), barrel 15 kg and "
            "rod 8 kg at their middles. The input effort is the cylinder's force (positive "
            "extends it). Values chosen here."
        ),
        units=SI_MM,
        loads={
            "forces": [{"point": "T", "force": [0.0, -4905.0]}],
            "gravity": [0.0, -9810.0],
            "masses": {
                "boom": {**_bar(pts, "O", "T", 120.0 / 2000.0)},
                "barrel": _bar(pts, "C1", "C2", 15.0 / 400.0),
                "rod": _bar(pts, "R", "E", 8.0 / 400.0),
            },
        },
    )
    return sc


LOADED = {
    "engine": engine,
    "fourbar-loaded": fourbar_loaded,
    "jansen-loaded": jansen_loaded,
    "hydraulic-boom-loaded": boom_loaded,
}
