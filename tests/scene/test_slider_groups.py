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


@pytest.mark.slow  # the numpy reference marches 361 angles twice: about 5 s on 2 cores
def test_slot_group_matches_the_numpy_reference_and_keeps_every_constraint():
    d = slot_triad()
    sc = pk.Scene(d)
    sw = sc.sweep(outputs="all")
    ok = sw.success
    assert 30 < ok.sum() < 361  # a rocking crank: LIMIT past its two dead points
    # past its dead points the crank finds no assembly at all (the independent scan below
    # agrees): NOT_ASSEMBLABLE, not LIMIT
    assert set(sw.status[~ok]) == {pk.Status.NOT_ASSEMBLABLE}
    for t in sw.theta[~ok][::20]:
        assert triad_assemblies_by_scanning(d, t) == []
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
            np.testing.assert_allclose(
                sw.points[n][mine], ref.points[n][idx], atol=1e-10 * size, err_msg=n
            )
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
    np.testing.assert_allclose(
        np.linalg.norm(pts["A"] - pts["C"], axis=1),
        math.dist((0.5, 3**0.5 / 2), (1.5, 1.2)),
        atol=1e-9 * size,
    )
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
    d = pk.scenes.load("hydraulic-boom").to_dict()
    d.pop("limits")  # the linkage itself, its cylinder free to pass through zero length
    sc = pk.Scene.from_dict(d)
    p = {n: np.asarray(v) for n, v in sc.points.items()}
    oc, oe, ce = (
        np.linalg.norm(p["C1"] - p["O"]),
        np.linalg.norm(p["E"] - p["O"]),
        np.linalg.norm(p["E"] - p["C1"]),
    )
    hi, lo = oc + oe - ce, abs(oe - oc) - ce
    (c,) = sc.circuits()
    assert len(c.assemblies) == 2 and not c.full_turn
    np.testing.assert_allclose(sorted(c.turning_points), [lo, hi], rtol=0, atol=1e-9 * 2000)
    np.testing.assert_allclose(sc.stroke(), (lo, hi), rtol=0, atol=1e-9 * 2000)
    sw = sc.sweep()
    # the default sweep spans the stroke: its ends are the dead points (SINGULAR there)
    assert sw.success[1:-1].all()
    assert (sw.status[[0, -1]] == pk.Status.SINGULAR).all()
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
        # closed, or an arc between the scene's travel limits
        assert tr.closed or len(tr.limits) == 2, name
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


def triad_assemblies_by_scanning(d, theta):
    """Every assembly of the slot triad at crank angle ``theta``, independently: for a
    slot position b (B = (b, -1)), C is on the circle about A (radius |AC|) at |BC| from
    B (two intersections), E follows rigidly from B and C, and |O4 E| must equal the
    rocker's length: one scalar equation per branch in b, whose roots are found by a
    dense scan and bisection."""
    p = {n: np.asarray(v, dtype=float) for n, v in d["points"].items()}
    a = np.array([math.cos(theta), math.sin(theta)])
    r_ac, r_bc = np.linalg.norm(p["C"] - p["A"]), np.linalg.norm(p["C"] - p["B"])
    r4 = np.linalg.norm(p["E"] - p["O4"])
    # E in T's frame (origin B, x axis towards C)
    u0 = (p["C"] - p["B"]) / r_bc
    be = p["E"] - p["B"]
    e_local = np.array([np.dot(be, u0), u0[0] * be[1] - u0[1] * be[0]])

    def residual(b, side):
        bb = np.array([b, -1.0])
        d_ab = np.linalg.norm(a - bb)
        x = (d_ab**2 + r_bc**2 - r_ac**2) / (2 * d_ab)
        h2 = r_bc**2 - x**2
        if h2 < 0:
            return math.nan
        w = (a - bb) / d_ab
        c = bb + x * w + side * math.sqrt(h2) * np.array([-w[1], w[0]])
        u = (c - bb) / r_bc
        e = bb + e_local[0] * u + e_local[1] * np.array([-u[1], u[0]])
        return np.linalg.norm(e - p["O4"]) - r4

    roots = []
    grid = np.linspace(-20.0, 20.0, 40001)
    for side in (1.0, -1.0):
        f = np.array([residual(b, side) for b in grid])
        for k in np.flatnonzero(np.isfinite(f[:-1]) & np.isfinite(f[1:]) & (f[:-1] * f[1:] < 0)):
            lo, hi = grid[k], grid[k + 1]
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                if residual(lo, side) * residual(mid, side) <= 0:
                    hi = mid
                else:
                    lo = mid
            roots.append(0.5 * (lo + hi))
    return sorted(roots)


@pytest.mark.parametrize("deg", [60.0, 10.0, 200.0, 300.0])
def test_slot_group_assemblies_are_every_real_solution(deg):
    # the homotopy takes the slot's displacement as one more unknown (linear in the loop
    # equations: the guide here is ground); its real roots, polished, are the assemblies
    d = slot_triad()
    sc = pk.Scene(d)
    theta = math.radians(deg)
    found = sc.assemblies(theta)
    want = triad_assemblies_by_scanning(d, theta)
    got = sorted(float(a["B"][0]) for a in found)
    assert len(got) == len(want)
    np.testing.assert_allclose(got, want, atol=1e-9)
    assert all(c >= len(want) for (c,) in found.complex_counts)


def prismatic_triad():
    """The slot triad with its slot turned into a prismatic pair on a rocking guide: link
    T (B, C, E) translates along the line G1-G2 of link 'arm' pivoted at ground O5, so
    T keeps the arm's rotation: a Newton group whose slide turns with an unknown rotation
    (a bilinear term of the loop equations). Dimensions chosen here."""
    d = slot_triad()
    d["points"].update({"O5": [2.0, -3.0], "G1": [2.0, -1.0], "G2": [3.0, -1.0]})
    d["links"] = {
        "ground": ["O2", "O4", "O5"],
        "crank": ["O2", "A"],
        "rod": ["A", "C"],
        "tri": ["B", "C", "E"],
        "rocker": ["O4", "E"],
        "arm": ["O5", "G1", "G2"],
    }
    del d["slots"]
    d["prismatic"] = {"slide": {"link": "tri", "guide": "arm", "line": ["G1", "G2"]}}
    return d


@pytest.mark.slow  # the numpy reference marches 361 angles twice: about 4 s on 2 cores
def test_prismatic_group_turning_with_its_guide_matches_the_reference():
    d = prismatic_triad()
    sc = pk.Scene(d)
    assert [s.kind for s in sc.plan().steps] == ["group"]
    sw = sc.sweep(outputs="all")
    fwd, back = scene_sweep(d, sw.theta), scene_sweep(d, sw.theta[::-1])
    np.testing.assert_array_equal(fwd.success | back.success[::-1], sw.success)
    size = size_of(sc)
    for ref, idx in [(fwd, np.flatnonzero(fwd.success)), (back, np.flatnonzero(back.success))]:
        mine = idx if ref is fwd else len(sw.theta) - 1 - idx
        for n in sw.points:
            np.testing.assert_allclose(
                sw.points[n][mine], ref.points[n][idx], atol=1e-10 * size, err_msg=n
            )


def test_prismatic_group_assemblies_keep_the_pair_and_lie_on_the_traced_circuit():
    d = prismatic_triad()
    sc = pk.Scene(d)
    theta = math.radians(60.0)
    found = sc.assemblies(theta)
    assert len(found) >= 1
    p0 = {n: np.asarray(v) for n, v in d["points"].items()}
    drawn_turn = p0["C"] - p0["B"]
    for a in found:
        a = {n: np.asarray(v) for n, v in a.items()}
        # T keeps the arm's rotation, and B stays on the arm's line G1-G2
        arm, tri = a["G2"] - a["G1"], a["C"] - a["B"]
        turn_arm = math.atan2(arm[1], arm[0])
        turn_tri = math.atan2(tri[1], tri[0]) - math.atan2(drawn_turn[1], drawn_turn[0])
        assert abs(math.remainder(turn_tri - turn_arm, math.tau)) < 1e-12
        rel_b = a["B"] - a["G1"]
        assert abs(arm[0] * rel_b[1] - arm[1] * rel_b[0]) < 1e-12 * size_of(sc)
    # the drawn pose is one of them
    assert any(max(np.abs(np.asarray(a[n]) - p0[n]).max() for n in p0) < 1e-9 for a in found)
    (c,) = sc.circuits(theta)
    assert len(c.assemblies) == len(found)
