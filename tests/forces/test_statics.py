"""Statics against independent truths: the slider-crank's torque T = -f ds/dtheta in
closed form (and its toggle, which holds any piston force), a four-bar worked by hand with
free-body diagrams, a pendulum under gravity, a spring-loaded arm whose equilibrium angle is
known in closed form, and a statically indeterminate scene refused by name."""

from __future__ import annotations

import math

import numpy as np
import planarkin as pk
import pytest
from forces_cases import FOURBAR, pendulum

R, L = 40.0, 160.0  # the built-in slider-crank's crank and rod (mm), centred (e = 0)


def slider_crank(loads: dict, **extra) -> pk.Scene:
    d = pk.scenes.data("slider-crank")
    d.pop("output", None)
    d.update(extra)
    d["loads"] = loads
    return pk.Scene.from_dict(d)


def ds_dtheta(t: np.ndarray, r: float = R, rod: float = L, e: float = 0.0) -> np.ndarray:
    """d x_B / d theta of x_B = r cos t + sqrt(rod^2 - (r sin t - e)^2)."""
    h = r * np.sin(t) - e
    return -r * np.sin(t) - h * r * np.cos(t) / np.sqrt(rod**2 - h**2)


def test_slider_crank_torque_is_f_ds_dtheta():
    f = -2500.0  # a gas force on the piston, towards the crank (N, along the slot's +x)
    sc = slider_crank({"forces": [{"slot": "piston", "force": f}]})
    r = sc.statics()
    t = r.theta
    # virtual work by hand: T dtheta + f ds = 0
    want = -f * ds_dtheta(t)
    assert r.success.all()
    np.testing.assert_allclose(r.input, want, rtol=0, atol=1e-10 * abs(f) * R)
    # the rod is a two-force member: the slot's normal force is f tan(phi), phi the rod's
    # angle to the line (sin phi = -r sin t / l); positive normal is +y, the guide's push
    phi = np.arcsin(-R * np.sin(t) / L)
    np.testing.assert_allclose(r.normal["piston"], f * np.tan(phi), atol=1e-9 * abs(f))
    # the same force given at the pin (a point load) needs the same torque
    p = slider_crank({"forces": [{"point": "B", "force": [f, 0.0]}]}).statics()
    np.testing.assert_allclose(p.input, want, atol=1e-10 * abs(f) * R)
    assert r.check < 1e-12


def test_slider_crank_toggle_holds_any_piston_force():
    for f in (1.0, 1e6):
        sc = slider_crank({"forces": [{"slot": "piston", "force": -f}]})
        r = sc.statics(sc.sweep(np.array([0.0, math.pi]), outputs="all", rate=1.0))
        # at both dead centres the crank needs no torque and every pin carries f
        assert r.success.all()
        np.testing.assert_allclose(r.input, 0.0, atol=1e-12 * f * R)
        for key in (("A", "rod"), ("O2", "crank")):
            np.testing.assert_allclose(np.hypot(*r.reactions[key].T), f, rtol=1e-12)


def test_offset_slider_crank_closed_form():
    d = pk.scenes.data("slider-crank-offset")
    d.pop("output", None)
    d["loads"] = {"forces": [{"slot": d["input"].get("slot", "piston"), "force": 300.0}]}
    pts = d["points"]
    sc = pk.Scene.from_dict(d)
    (q, _, (a, b)) = sc.slots["piston"]
    o2, crank_tip = sc.input[1], sc.links[sc.input[0]][1]
    r = float(np.hypot(*np.subtract(pts[crank_tip], pts[o2])))
    rod = float(np.hypot(*np.subtract(pts[q], pts[crank_tip])))
    e = pts[q][1] - pts[o2][1]
    assert pts[a][1] == pts[b][1] and pts[b][0] > pts[a][0]  # a horizontal slot, +x
    res = sc.statics()
    want = -300.0 * ds_dtheta(res.theta, r, rod, e)
    np.testing.assert_allclose(res.input, want, atol=1e-10 * 300.0 * r)


def test_fourbar_worked_by_hand():
    """Crank O2-A vertical (A = (0, 2)), coupler A-B-C (B = (4, 3), C = (2, 2.5) its
    midpoint), rocker O4-B vertical (O4 = (4, 0)). Loads: P = 10 to the right at B, a weight
    W = 4 down at C.

    Free-body diagrams. The rocker carries no load: a two-force member along O4-B, so the
    rocker pushes the coupler at B with (0, R). Coupler, moments about A:
    (B - A) x (P, R) + (C - A) x (0, -W) = (4, 1) x (P, R) + (2, 0.5) x (0, -W)
    = 4 R - P - 2 W = 0, so R = (P + 2 W) / 4 = 4.5. Coupler, forces: the crank's force at
    A is F_A = -(P, R) - (0, -W) = (-P, W - R) = (-10, -0.5). Crank: the coupler pushes it
    at A with -F_A = (P, R - W); moments about O2: T + (0, 2) x (P, R - W) = T - 2 P = 0,
    so T = 2 P = 20. Ground on crank at O2: -(P, R - W) = (-10, -0.5); the coupler on the
    rocker at B: (0, -R); ground on rocker at O4: (0, R).
    """
    d = dict(FOURBAR, loads={"forces": [{"point": "B", "force": [10.0, 0.0]},
                                        {"point": "C", "force": [0.0, -4.0]}]})  # fmt: skip
    sc = pk.Scene.from_dict(d)
    r = sc.statics(sc.sweep(np.array([math.pi / 2]), outputs="all", rate=1.0))
    P, W = 10.0, 4.0
    R_ = (P + 2 * W) / 4
    tol = dict(rtol=0, atol=1e-12)
    np.testing.assert_allclose(r.input, [2 * P], **tol)
    np.testing.assert_allclose(r.reactions[("A", "coupler")][0], [-P, W - R_], **tol)
    np.testing.assert_allclose(r.reactions[("O2", "crank")][0], [-P, W - R_], **tol)
    np.testing.assert_allclose(r.reactions[("B", "rocker")][0], [0.0, -R_], **tol)
    np.testing.assert_allclose(r.reactions[("O4", "rocker")][0], [0.0, R_], **tol)
    # the rocker's velocity ratio by hand: v_B = v_A = (-2, 0) at unit crank rate, so
    # omega_4 = 2/3 and the mechanical advantage d theta_2 / d theta_4 = 3/2
    np.testing.assert_allclose(r.mechanical_advantage, [1.5], **tol)
    # the ground receives the loads through O2 and O4: (P, -W) in all
    np.testing.assert_allclose(r.shaking_force[0], [P, -W], **tol)


def test_pendulum_under_gravity():
    m, g, lg = 3.0, 9.81, 0.5  # G at half the arm's length 1
    sc = pendulum(gravity=[0.0, -g], masses={"arm": {"mass": m, "center": "G"}})
    r = sc.statics()
    np.testing.assert_allclose(r.input, m * g * lg * np.cos(r.theta), atol=1e-12 * m * g)
    # the pin carries the weight: ground on arm (0, m g)
    np.testing.assert_allclose(r.reactions[("O", "arm")], np.tile([0.0, m * g], (361, 1)),
                               atol=1e-12 * m * g)  # fmt: skip
    np.testing.assert_allclose(r.potential_energy, m * g * lg * np.sin(r.theta), atol=1e-12)
    # the centre given as coordinates of the drawing is the same centre
    c = pendulum(gravity=[0.0, -g], masses={"arm": {"mass": m, "center": [0.4, 0.3]}})
    np.testing.assert_allclose(c.statics().input, r.input, atol=1e-12)


def test_spring_loaded_arm_equilibrium():
    """A weight m g at the arm's tip P (arm length l) and a zero-free-length spring k from P
    to S = (d, 0) on the ground: V = k/2 (l^2 + d^2 - 2 l d cos t) + m g l sin t, so the
    holding torque is V'(t) = k l d sin t + m g l cos t, zero at tan t = -m g / (k d)."""
    m, g, k, dd = 2.0, 9.81, 50.0, 1.5
    sc = pk.Scene.from_dict(
        {
            "points": {"O": [0.0, 0.0], "S": [dd, 0.0], "P": [0.8, 0.6]},
            "links": {"ground": ["O", "S"], "arm": ["O", "P"]},
            "ground": "ground",
            "input": {"link": "arm", "pivot": "O"},
            "loads": {
                "springs": [{"between": ["P", "S"], "k": k, "free_length": 0.0}],
                "gravity": [0.0, -g],
                "masses": {"arm": {"mass": m, "center": "P"}},
            },
        }
    )
    r = sc.statics()
    t = r.theta
    np.testing.assert_allclose(r.input, k * dd * np.sin(t) + m * g * np.cos(t), atol=1e-11 * k)
    star = math.atan2(-m * g, k * dd)
    at = sc.statics(sc.sweep(np.array([star, star + math.pi]), outputs="all", rate=1.0))
    np.testing.assert_allclose(at.input, 0.0, atol=1e-12 * k * dd)
    # a preload P0 adds P0 dd' / dt to the torque (dd'/dt of the spring's length)
    spring = {"between": ["P", "S"], "k": 0.0, "free_length": 0.0, "preload": 7.0}
    pre = pk.Scene.from_dict({**sc.to_dict(), "loads": {"springs": [spring]}})
    length = np.sqrt(1 + dd**2 - 2 * dd * np.cos(t))
    np.testing.assert_allclose(pre.statics().input, 7.0 * dd * np.sin(t) / length, atol=1e-11)


def test_indeterminate_scene_is_refused_by_name():
    # a parallelogram with a third parallel bar: one pin more than the equations fix
    data = {
        "points": {"O2": (0, 0), "O4": (2, 0), "O6": (1, 0), "A": (0, 1), "B": (2, 1),
                   "C": (1, 1)},
        "links": {"ground": ("O2", "O4", "O6"), "crank": ("O2", "A"), "coupler": ("A", "B", "C"),
                  "rocker": ("O4", "B"), "extra": ("O6", "C")},
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O2"},
        "slots": {},
        "prismatic": {},
    }  # fmt: skip
    with pytest.raises(ValueError, match=r"statically indeterminate: the pin at joint '\w+'"):
        pk.forces.Structure.of(data)


def test_dead_point_effort_is_nan_with_its_status():
    # driven by the piston, the crank's dead centres end the stroke: a torque on the crank
    # needs an unbounded piston force there
    sc = slider_crank({"torques": [{"link": "crank", "torque": 5.0}]}, input={"slot": "piston"})
    lo, hi = sc.stroke()
    r = sc.statics(sc.sweep(np.array([lo, 0.5 * (lo + hi), hi]), outputs="all", rate=1.0))
    assert np.isnan(r.input[[0, 2]]).all() and np.isfinite(r.input[1])
    assert (r.status[[0, 2]] != pk.Status.CONVERGED).all()
    assert r.status[1] == pk.Status.CONVERGED


def test_bad_loads_name_the_entry():
    with pytest.raises(ValueError, match=r"^loads.forces\[0\].point: 'Z' is not a point"):
        pendulum(forces=[{"point": "Z", "force": [0, 1]}])
    with pytest.raises(ValueError, match=r"^loads.masses.arm.mass: must be >= 0, got -1"):
        pendulum(masses={"arm": {"mass": -1, "center": "G"}})
    sc = pendulum()
    with pytest.raises(ValueError, match=r"^loads.torques\[0\].link: 'rod' is not a link"):
        sc.statics(loads={"torques": [{"link": "rod", "torque": 1.0}]})


def test_units_table_round_trips():
    d = dict(FOURBAR, units={"length": "mm", "force": "kN"})
    sc = pk.Scene.from_dict(d)
    assert sc.units == "mm"
    assert sc.unit_system == {"length": "mm", "force": "kN", "mass": "kg"}
    assert pk.Scene.from_dict(sc.to_dict()).to_dict()["units"] == {"length": "mm", "force": "kN"}
    assert pk.Scene.from_dict(dict(FOURBAR, units="mm")).to_dict()["units"] == "mm"


def test_cylinder_force_lifting_a_boom():
    """The hydraulic boom with a payload W at its tip T only: the cylinder (barrel and rod,
    unloaded) is a two-force member along C1-E, so moments about O give
    F (E - O) x u = W T_x, u the unit direction C1 -> E; the barrel's and rod's pin forces
    are F u along the line, and the prismatic pair carries no moment."""
    d = pk.scenes.data("hydraulic-boom")
    W = 4905.0
    d["loads"] = {"forces": [{"point": "T", "force": [0.0, -W]}]}
    sc = pk.Scene.from_dict(d)
    r = sc.statics()
    sw = sc.sweep(r.theta, outputs="all", rate=1.0)
    ok = r.success
    assert ok.sum() > 300
    e, t, c1 = sw.points["E"][ok], sw.points["T"][ok], sw.points["C1"][ok]
    u = (e - c1) / np.hypot(*(e - c1).T)[:, None]
    f = W * t[:, 0] / (e[:, 0] * u[:, 1] - e[:, 1] * u[:, 0])
    np.testing.assert_allclose(r.input[ok], f, rtol=1e-10)
    np.testing.assert_allclose(r.moment["cylinder"][ok], 0.0, atol=1e-9 * W * 1e3)
    np.testing.assert_allclose(r.normal["cylinder"][ok], 0.0, atol=1e-9 * W)
    # the boom pushes the rod at E: -F u (the cylinder in compression pushes back)
    np.testing.assert_allclose(r.reactions[("E", "rod")][ok], -f[:, None] * u, rtol=1e-9,
                               atol=1e-9 * W)  # fmt: skip


@pytest.mark.parametrize("suffix", [".json", ".toml"])
def test_loads_round_trip_through_files(tmp_path, suffix):
    sc = pk.scenes.load("engine")
    back = pk.Scene.load(sc.save(tmp_path / f"engine{suffix}"))
    assert back.loads == sc.loads and back.unit_system == sc.unit_system
    np.testing.assert_array_equal(back.statics().input, sc.statics().input)


def test_a_redrawn_scene_keeps_its_mass_centres_on_their_links():
    sc = pk.scenes.load("fourbar-loaded")
    sw = sc.sweep(outputs="all")
    i = 100
    other = sc.at({n: sw.points[n][i] for n in sc.points})
    # the same pose: the same gravity torque, as drawn there
    r0 = sc.statics(sc.sweep(sw.theta[i : i + 1], outputs="all", rate=1.0))
    r1 = other.statics(other.sweep(sw.theta[i : i + 1], outputs="all", rate=1.0))
    np.testing.assert_allclose(r1.input, r0.input, rtol=1e-12)
