"""Slots and prismatic pairs inside Newton groups, and traces and circuits of slider
scenes (DESIGN.md, "Prismatic joints"): what no closed form peels goes to the generic
Newton solver with the displacements as unknowns; tracing follows the whole linkage
through its dead points, a linear input's turning points being the ends of its stroke.

Truth: the NumPy reference (one Newton system of every link, no plan), the constraints
themselves, central differences of positions, and closed forms written here."""

import math

import numpy as np
import planarkin as pk
import pytest
from planarkin.reference import scene_sweep


def slot_triad(**edit):
    """A six-bar whose ternary link T (B, C, E) has its pin B in a ground slot, C hung
    from the crank by the link A-C and E from the ground pivot O4 by the link O4-E: no
    dyad and no circle-line reaches T (each of its points is reached by one link or one
    line), so links A-C, T and O4-E with the slot are one Newton group of four unknowns
    (three rotations and the slot's displacement). Dimensions chosen here."""
    t0 = math.radians(60.0)
    d = {
        "name": "slot triad",
        "points": {
            "O2": [0.0, 0.0],
            "A": [math.cos(t0), math.sin(t0)],
            "G1": [-1.0, -1.0],
            "G2": [5.0, -1.0],
            "O4": [4.0, 2.0],
            "B": [2.0, -1.0],
            "C": [1.5, 1.2],
            "E": [3.0, 0.8],
        },
        "links": {
            "ground": ["O2", "G1", "G2", "O4"],
            "crank": ["O2", "A"],
            "rod": ["A", "C"],
            "tri": ["B", "C", "E"],
            "rocker": ["O4", "E"],
        },
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O2"},
        "slots": {"pin": {"point": "B", "guide": "ground", "line": ["G1", "G2"]}},
    }
    d.update(edit)
    return d


def size_of(sc):
    return float(max(np.ptp(np.array(list(sc.points.values())), axis=0)))


def test_a_slot_inside_a_triad_is_one_newton_group():
    sc = pk.Scene(slot_triad())
    plan = sc.plan()
    assert [s.kind for s in plan.steps] == ["group"]
    assert sorted(plan.steps[0].unknowns) == ["rocker", "rod", "tri"]


def test_slot_group_matches_the_numpy_reference_and_keeps_every_constraint():
    d = slot_triad()
    sc = pk.Scene(d)
    sw = sc.sweep(outputs="all")
    ok = sw.success
    assert 30 < ok.sum() < 361  # a rocking crank: LIMIT past its two dead points
    assert set(sw.status[~ok]) == {pk.Status.LIMIT}
    # the reference marches one way only and has no LIMIT (past a dead point it fails):
    # forward from the drawn angle it meets the first dead point, backward (the angles
    # reversed, from the drawn angle + 360 deg) the other
    size = size_of(sc)
    fwd, back = scene_sweep(d, sw.theta), scene_sweep(d, sw.theta[::-1])
    ref_ok = fwd.success | back.success[::-1]
    np.testing.assert_array_equal(ref_ok, ok)
    for ref, idx in [(fwd, np.flatnonzero(fwd.success)), (back, np.flatnonzero(back.success))]:
        mine = idx if ref is fwd else len(sw.theta) - 1 - idx
        for n in sw.points:
            np.testing.assert_allclose(sw.points[n][mine], ref.points[n][idx], atol=1e-10 * size, err_msg=n)
    p = {n: sw.points[n][ok] for n in sw.points}
    drawn = {n: np.asarray(v) for n, v in d["points"].items()}
    for a, b in [("O2", "A"), ("A", "C"), ("B", "C"), ("C", "E"), ("B", "E"), ("O4", "E")]:
        length = np.linalg.norm(drawn[a] - drawn[b])
        np.testing.assert_allclose(np.linalg.norm(p[a] - p[b], axis=1), length, atol=1e-12 * size)
    np.testing.assert_allclose(p["B"][:, 1], -1.0, atol=1e-12 * size)  # on the slot's line


def test_slot_group_velocities_and_accelerations_are_derivatives_of_positions():
    sc = pk.Scene(slot_triad())
    w = 2.0
    sw = sc.sweep()
    # central differences need the motion on both sides: away from the dead points
    theta = sw.theta[sw.success & (np.abs(sw.det) > 0.05)][::5]
    h = 1e-4
    at = sc.sweep(theta, omega=w, outputs="all")
    up, down = sc.sweep(theta + h, outputs="all"), sc.sweep(theta - h, outputs="all")
    for n in at.points:
        v_fd = (up.points[n] - down.points[n]) / (2 * h) * w
        a_fd = (up.points[n] - 2 * at.points[n] + down.points[n]) / h**2 * w**2
        scale = max(np.abs(a_fd).max(), 1.0)
        np.testing.assert_allclose(at.velocities[n], v_fd, atol=1e-6 * scale, err_msg=n)
        np.testing.assert_allclose(at.accelerations[n], a_fd, atol=1e-5 * scale, err_msg=n)


def test_slot_group_is_bit_stable_under_power_of_two_scaling():
    d = slot_triad()
    big = dict(d, points={n: [4.0 * x, 4.0 * y] for n, (x, y) in d["points"].items()})
    a, b = pk.Scene(d).sweep(outputs="all"), pk.Scene(big).sweep(outputs="all")
    np.testing.assert_array_equal(a.status, b.status)
    for n in a.points:
        np.testing.assert_array_equal(4.0 * a.points[n], b.points[n])


def test_slot_group_trace_keeps_the_constraints_and_finds_its_dead_points():
    sc = pk.Scene(slot_triad())
    tr = sc.trace()
    assert tr.closed
    size = size_of(sc)
    pts = {n: tr.points[n] for n in tr.points}
    np.testing.assert_allclose(pts["B"][:, 1], -1.0, atol=1e-9 * size)
    np.testing.assert_allclose(np.linalg.norm(pts["A"] - pts["C"], axis=1), math.dist((0.5, 3**0.5 / 2), (1.5, 1.2)), atol=1e-9 * size)
    # at each turning point the plan's conditioning vanishes: a sweep just inside it is
    # nearly singular
    for t in tr.turning_points:
        sw = sc.sweep(np.array([t]))
        assert not sw.success[0] or abs(sw.det[0]) < 1e-3


def test_slider_crank_circuits_are_the_two_blocks_each_a_full_turn():
    # crank r = 40 < rod l = 100: the crank turns fully on each of the two assemblies
    # (block right or left of the crank pivot), and they never meet
    sc = pk.scenes.load("slider-crank")
    cs = sc.circuits()
    assert len(cs) == 2
    for c in cs:
        assert c.full_turn and len(c.assemblies) == 1 and len(c.turning_points) == 0


def test_hydraulic_boom_is_one_circuit_whose_turning_points_are_the_stroke_ends():
    # the triangle O-C1-E with |C1 E| = drawn + s: it flattens (a dead point) when
    # |C1 E| = |O C1| + |O E| or |O E| - |O C1|; between them the boom is above or below
    # the line O-C1, the two assemblies of one circuit joined at those two dead points
    sc = pk.scenes.load("hydraulic-boom")
    p = {n: np.asarray(v) for n, v in sc.points.items()}
    oc, oe, ce = (np.linalg.norm(p["C1"] - p["O"]), np.linalg.norm(p["E"] - p["O"]), np.linalg.norm(p["E"] - p["C1"]))
    hi, lo = oc + oe - ce, abs(oe - oc) - ce
    (c,) = sc.circuits()
    assert len(c.assemblies) == 2 and not c.full_turn
    np.testing.assert_allclose(sorted(c.turning_points), [lo, hi], rtol=0, atol=1e-9 * 2000)
    np.testing.assert_allclose(sc.stroke(), (lo, hi), rtol=0, atol=1e-9 * 2000)
    sw = sc.sweep()
    assert sw.success.all()
    np.testing.assert_allclose(sw.theta[[0, -1]], (lo, hi), rtol=0, atol=1e-9 * 2000)


def test_elliptic_trammel_circuit_turns_at_the_slots_ends():
    # the trammel's blocks A (on x) and B (on y), |AB| = L: the block on x travels
    # between -L and +L; its stroke from the drawn pose ends where the bar lies on the
    # x axis
    sc = pk.scenes.load("elliptic-trammel")
    lo, hi = sc.stroke()
    (c,) = sc.circuits()
    np.testing.assert_allclose(sorted(c.turning_points), [lo, hi], atol=1e-9 * size_of(sc))


def test_every_slider_built_in_traces_closed_keeping_its_slots():
    for name in [n for n in pk.scenes.names() if {"slots", "prismatic"} & set(pk.scenes.data(n))]:
        sc = pk.scenes.load(name)
        tr = sc.trace()
        assert tr.closed, name
        # every traced pose solves: a sweep at the traced inputs away from turning points
        # gives the same points on the same circuit where it is the drawn one
        d = pk.scenes.data(name)
        for s in d.get("slots", {}).values():
            q, (a, b) = s["point"], s["line"]
            if s["guide"] == d["ground"]:
                pa, pb = np.asarray(d["points"][a]), np.asarray(d["points"][b])
                u = (pb - pa) / np.linalg.norm(pb - pa)
                off = u[0] * (tr.points[q] - pa)[:, 1] - u[1] * (tr.points[q] - pa)[:, 0]
                np.testing.assert_allclose(off, off[0], atol=1e-9 * size_of(sc), err_msg=name)


@pytest.mark.parametrize("name", ["whitworth", "scotch-yoke", "inverted-slider-crank"])
def test_slider_assemblies_lie_on_their_circuits(name):
    sc = pk.scenes.load(name)
    a = sc.assemblies()
    cs = sc.circuits()
    assert sum(len(c.assemblies) for c in cs) == len(a)
