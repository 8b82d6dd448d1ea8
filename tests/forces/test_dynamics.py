"""Inverse dynamics against independent truths: the energy balance with the energies
computed here from the sweep's velocities and differentiated numerically along a fine
sweep; the effort's part from the input's angular acceleration against the generalised
inertia; virtual work against Newton-Euler on the loaded built-ins; invariance under a
rigid motion of the drawing and the scaling laws; the pendulum's dynamics in closed form."""

from __future__ import annotations

import math

import numpy as np
import planarkin as pk
import pytest
from forces_cases import FOURBAR, pendulum, random_loads

G = 9.81
K, L0, TR = 30.0, 3.0, -1.5
MASSES = {
    "crank": {"mass": 0.4, "center": "G2", "inertia": 0.02},
    "coupler": {"mass": 1.1, "center": "C", "inertia": 0.3},
    "rocker": {"mass": 0.7, "center": "G4", "inertia": 0.08},
}


def loaded_fourbar() -> pk.Scene:
    d = {**FOURBAR, "points": {**FOURBAR["points"], "G2": [0.0, 1.0], "G4": [4.0, 1.5]}}
    d["links"] = {**FOURBAR["links"], "crank": ["O2", "A", "G2"], "rocker": ["O4", "B", "G4"]}
    d["loads"] = {
        "springs": [{"between": ["C", "O4"], "k": K, "free_length": L0}],
        "torques": [{"link": "rocker", "torque": TR}],
        "gravity": [0.0, -G],
        "masses": MASSES,
    }
    return pk.Scene.from_dict(d)


def energy(sw: pk.SceneSweep) -> np.ndarray:
    """Kinetic plus potential energy from the sweep's own velocities (written out here)."""
    e = np.zeros(len(sw.theta))
    for link, m in MASSES.items():
        v = sw.velocities[m["center"]]
        e += (
            0.5 * m["mass"] * (v**2).sum(axis=1)
            + 0.5 * m["inertia"] * sw.angular_velocities[link] ** 2
        )
        e += m["mass"] * G * sw.points[m["center"]][:, 1]
    d = np.hypot(*(sw.points["C"] - sw.points["O4"]).T)
    return e + 0.5 * K * (d - L0) ** 2


def test_energy_balance_along_a_fine_sweep():
    sc = loaded_fourbar()
    w, h = 3.0, 1e-3
    theta = sc.input_angle + 0.3 + h * np.arange(400)
    sw = sc.sweep(theta, outputs="all", rate=w)
    r = sc.dynamics(sw)
    assert r.success.all() and r.check < 1e-12
    e = energy(sw)
    # dE/dt = w dE/dtheta, a fourth-order central difference
    de = w * (e[:-4] - 8 * e[1:-3] + 8 * e[3:-1] - e[4:]) / (12 * h)
    p_in = r.input * w
    p_ext = TR * sw.angular_velocities["rocker"]
    resid = (p_in + p_ext)[2:-2] - de
    scale = np.abs(p_in).max() + np.abs(p_ext).max()
    assert np.abs(resid).max() < 1e-9 * scale
    # and the result's own energies are those written out here
    np.testing.assert_allclose(r.kinetic_energy + r.potential_energy, e, rtol=1e-13, atol=1e-12)


def test_input_acceleration_term_is_the_generalised_inertia():
    """T(w, a) - T(w, 0) = a * J(theta), J = sum m |d r_G / d theta|^2 + I (d phi / d theta)^2."""
    sc = loaded_fourbar()
    sw = sc.sweep(outputs="all", rate=1.0)
    a = 2.5
    t1 = sc.dynamics(sw, omega=4.0, alpha=a).input
    t0 = sc.dynamics(sw, omega=4.0).input
    J = np.zeros(len(sw.theta))
    for link, m in MASSES.items():
        J += m["mass"] * (sw.velocities[m["center"]] ** 2).sum(axis=1)
        J += m["inertia"] * sw.angular_velocities[link] ** 2
    np.testing.assert_allclose(t1 - t0, a * J, rtol=1e-10, atol=1e-12 * np.abs(t1).max())
    # omega as a profile, one value a point, gives the same as a constant
    prof = sc.dynamics(sw, omega=np.full(len(sw.theta), 4.0), alpha=a).input
    np.testing.assert_allclose(prof, t1, rtol=1e-13, atol=1e-12)


def test_pendulum_dynamics_closed_form():
    m, lg, ig = 3.0, 0.5, 0.04
    sc = pendulum(gravity=[0.0, -G], masses={"arm": {"mass": m, "center": "G", "inertia": ig}})
    w, a = 2.0, 1.5
    r = sc.dynamics(omega=w, alpha=a)
    t = r.theta
    np.testing.assert_allclose(r.input, (ig + m * lg**2) * a + m * G * lg * np.cos(t), atol=1e-12)
    # the pin: ground on arm = m a_G - m g, a_G = -w^2 r + a k x r
    rg = lg * np.stack((np.cos(t), np.sin(t)), axis=1)
    ag = -(w**2) * rg + a * np.stack((-rg[:, 1], rg[:, 0]), axis=1)
    np.testing.assert_allclose(
        r.reactions[("O", "arm")], m * ag - m * np.array([0, -G]), atol=1e-12
    )
    np.testing.assert_allclose(r.kinetic_energy, 0.5 * (ig + m * lg**2) * w**2, rtol=1e-13)
    # the shaking force is what the arm puts on the ground: minus the pin's force on the arm
    np.testing.assert_allclose(r.shaking_force, -r.reactions[("O", "arm")], atol=1e-12)


@pytest.mark.parametrize(
    "name", ["engine", "fourbar-loaded", "jansen-loaded", "hydraulic-boom-loaded"]
)
def test_virtual_work_equals_newton_euler_on_the_loaded_builtins(name):
    sc = pk.scenes.load(name)
    sw = sc.sweep(outputs="all", rate=3.0)
    for r in (sc.statics(sw), sc.dynamics(sw)):
        ok = r.success
        assert ok.sum() > 300
        scale = np.abs(r.input[ok]).max()
        assert np.abs(r.input - r.input_virtual_work)[ok].max() < 1e-10 * scale
        assert r.check < 1e-10
        assert "checks" in r.summary()


def _rigid(d: dict, beta: float, shift: np.ndarray) -> dict:
    c, s = math.cos(beta), math.sin(beta)
    rot = np.array([[c, -s], [s, c]])
    out = {
        **d,
        "points": {k: list(rot @ np.asarray(v, float) + shift) for k, v in d["points"].items()},
    }
    loads = dict(d["loads"])
    loads["gravity"] = list(rot @ np.asarray(loads["gravity"]))
    loads["forces"] = [
        {**f, "force": list(rot @ np.asarray(f["force"]))} for f in loads.get("forces", [])
    ]
    masses = {}
    for k, m in loads["masses"].items():
        c_ = m["center"]
        masses[k] = {
            **m,
            "center": c_ if isinstance(c_, str) else list(rot @ np.asarray(c_) + shift),
        }
    loads["masses"] = masses
    out["loads"] = loads
    return out


def test_rotation_and_translation_of_the_drawing():
    base = pk.scenes.data("fourbar-loaded")
    beta, shift = 0.7, np.array([123.0, -45.0])
    a, b = pk.Scene.from_dict(base), pk.Scene.from_dict(_rigid(base, beta, shift))
    ra, rb = a.dynamics(omega=5.0), b.dynamics(omega=5.0)
    np.testing.assert_allclose(rb.theta, ra.theta + beta, atol=1e-12)
    scale = np.abs(ra.input).max()
    np.testing.assert_allclose(rb.input, ra.input, rtol=0, atol=1e-10 * scale)
    c, s = math.cos(beta), math.sin(beta)
    rot = np.array([[c, -s], [s, c]])
    for key, f in ra.reactions.items():
        np.testing.assert_allclose(rb.reactions[key], f @ rot.T, atol=1e-10 * np.abs(f).max())
    np.testing.assert_allclose(rb.kinetic_energy, ra.kinetic_energy, rtol=1e-10)


def test_scaling_laws():
    """Lengths x s: with the same forces, torques scale by s and forces stay; inertia alone
    (masses kept, inertias x s^2, same rate) scales forces by s and torques by s^2."""
    s = 1e3
    base = pk.scenes.data("fourbar-loaded")

    def scaled(d: dict, loads: dict) -> dict:
        return {
            **d,
            "points": {k: [s * v[0], s * v[1]] for k, v in d["points"].items()},
            "loads": loads,
        }

    statics = {"forces": base["loads"]["forces"], "torques": []}
    a, b = pk.Scene.from_dict({**base, "loads": statics}), pk.Scene.from_dict(scaled(base, statics))
    ra, rb = a.statics(), b.statics()
    np.testing.assert_allclose(
        rb.input, s * ra.input, rtol=0, atol=1e-10 * s * np.abs(ra.input).max()
    )
    for key, f in ra.reactions.items():
        np.testing.assert_allclose(rb.reactions[key], f, atol=1e-10 * np.abs(f).max())
    inertia = {"masses": {k: {**m, "center": [s * m["center"][0], s * m["center"][1]],
                              "inertia": s * s * m["inertia"]}
                          for k, m in base["loads"]["masses"].items()}}  # fmt: skip
    small = {"masses": base["loads"]["masses"]}
    da = pk.Scene.from_dict({**base, "loads": small}).dynamics(omega=7.0)
    db = pk.Scene.from_dict(scaled(base, inertia)).dynamics(omega=7.0)
    np.testing.assert_allclose(
        db.input, s * s * da.input, rtol=0, atol=1e-9 * s * s * np.abs(da.input).max()
    )
    np.testing.assert_allclose(
        db.shaking_force, s * da.shaking_force, atol=1e-9 * s * np.abs(da.shaking_force).max()
    )


def test_units_make_inertia_consistent():
    # the same pendulum stated in mm (gravity 9810 mm/s^2): torques in N mm, 1000 x those in N m
    m = 3.0
    si = pendulum(gravity=[0.0, -G], masses={"arm": {"mass": m, "center": "G", "inertia": 0.04}})
    d = si.to_dict()
    mm = {**d, "units": {"length": "mm", "force": "N", "mass": "kg"},
          "points": {k: [1e3 * v[0], 1e3 * v[1]] for k, v in d["points"].items()},
          "loads": {"gravity": [0.0, -G * 1e3],
                    "masses": {"arm": {"mass": m, "center": "G", "inertia": 0.04e6}}}}  # fmt: skip
    a, b = si.dynamics(omega=3.0, alpha=1.0), pk.Scene.from_dict(mm).dynamics(omega=3.0, alpha=1.0)
    np.testing.assert_allclose(b.input, 1e3 * a.input, rtol=1e-12)
    np.testing.assert_allclose(
        b.reactions[("O", "arm")], a.reactions[("O", "arm")], rtol=1e-12, atol=1e-12
    )


def test_dynamics_needs_a_rate():
    sc = pendulum(masses={"arm": {"mass": 1.0, "center": "G"}})
    with pytest.raises(ValueError, match="omega"):
        sc.dynamics(sc.sweep(outputs="all"))
    with pytest.raises(ValueError, match=r"omega must be a number or one value per sweep point"):
        sc.dynamics(omega=[1.0, 2.0])


@pytest.mark.parametrize("name", pk.scenes.names())
def test_every_builtin_closes_its_checks_under_every_kind_of_load(name):
    rng = np.random.default_rng(sum(map(ord, name)))
    sc = pk.scenes.load(name)
    loaded = pk.Scene.from_dict({**sc.to_dict(), "loads": random_loads(sc, rng)})
    sw = loaded.sweep(outputs="all", rate=1.7)
    for r in (loaded.statics(sw), loaded.dynamics(sw, alpha=0.4)):
        # every point the sweep solved, but those within 1e-5 of a dead point
        assert r.success.sum() >= 0.9 * sw.success.sum() > 0, r.summary()
        assert r.checks["virtual_work"] < 1e-10, (name, r.checks)
        assert r.checks.get("energy", 0.0) < 1e-10, (name, r.checks)
