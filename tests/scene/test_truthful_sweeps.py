"""Issue 32's forms of silent wrong answers, each checked against geometry or a closed form:
a value's pose does not depend on the rest of the array (any order, any start), an angle is
reached the other way round where one way meets a dead point, a cylinder's stroke ends are
dead points, a group keeps its branch through a change point, a crank pin in a slot of a
group's link is planned, and a closed-form step is CONVERGED only where rounding keeps it
within 1e-9 of the size."""

import mpmath as mp
import numpy as np
import planarkin as pk
import pytest


def unit(v):
    v = np.asarray(v, float)
    return v / np.hypot(*v)


def circle_circle(p, r1, q, r2, side):
    """The point at r1 from p and r2 from q, on `side` of p -> q (NaN where none)."""
    p, q = np.asarray(p, float), np.asarray(q, float)
    d = np.hypot(*(q - p).T)
    a = (r1**2 - r2**2 + d**2) / (2 * d)
    with np.errstate(invalid="ignore"):
        h = np.sqrt(r1**2 - a**2)
    e = ((q - p).T / d).T
    n = np.stack([-e[..., 1], e[..., 0]], -1)
    return p + (a * e.T).T + (side * h * n.T).T


def cross(u, v):
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def scene(points, links, **rest):
    return pk.Scene.from_dict(
        {
            "name": "case",
            "points": {k: [float(x) for x in v] for k, v in points.items()},
            "links": links,
            "ground": "ground",
            **rest,
        }
    )


# --- a cylinder driving a four-bar: no turning back at the stroke's end ------------------


def cylinder_fourbar():
    o2, o4, k = np.array([0.0, 0.0]), np.array([4.0, 0.0]), np.array([-2.0, -1.0])
    a = 1.5 * np.array([np.cos(np.radians(60)), np.sin(np.radians(60))])
    b = circle_circle(a, 4.0, o4, 3.0, 1.0)
    u = unit(a - k)
    pts = {"O2": o2, "O4": o4, "K": k, "A": a, "B": b, "C2": k + 0.3 * u, "R": k + 0.6 * u}
    links = {
        "ground": ["O2", "O4", "K"],
        "crank": ["O2", "A"],
        "coupler": ["A", "B"],
        "rocker": ["O4", "B"],
        "barrel": ["K", "C2"],
        "rod": ["R", "A"],
    }
    return scene(
        pts,
        links,
        input={"prismatic": "cyl"},
        prismatic={"cyl": {"link": "rod", "guide": "barrel", "line": ["K", "C2"]}},
    )


def test_a_cylinder_driven_fourbar_follows_its_closed_form_over_the_whole_stroke():
    sc = cylinder_fourbar()
    p = {n: np.asarray(v) for n, v in sc.points.items()}
    ka = np.hypot(*(p["A"] - p["K"]))
    side_a = np.sign(cross(p["O2"] - p["K"], p["A"] - p["K"]))
    side_b = np.sign(cross(p["O4"] - p["A"], p["B"] - p["A"]))
    sw = sc.sweep(outputs="all", rate=1.0)
    s = sw.theta
    # the stroke's ends: |KA| = |KO2| -+ r, where the crank and the cylinder fall in line
    ko2 = np.hypot(*(p["O2"] - p["K"]))
    np.testing.assert_allclose(ka + s[[0, -1]], [ko2 - 1.5, ko2 + 1.5], rtol=0, atol=1e-9)
    assert (sw.status[[0, -1]] == pk.Status.SINGULAR).all()
    assert np.isnan(sw.velocities["B"][[0, -1]]).all()
    inner = slice(1, -1)
    a = circle_circle(np.broadcast_to(p["K"], (len(s), 2)), ka + s, p["O2"], 1.5, side_a)
    b = circle_circle(a, 4.0, np.broadcast_to(p["O4"], (len(s), 2)), 3.0, side_b)
    assert sw.success[inner].all()
    np.testing.assert_allclose(sw.points["A"][inner], a[inner], rtol=0, atol=1e-9)
    np.testing.assert_allclose(sw.points["B"][inner], b[inner], rtol=0, atol=1e-9)
    # the same values without the ends: the same poses (the old sweep turned back there)
    again = sc.sweep(s[inner], outputs="all")
    np.testing.assert_array_equal(again.points["B"], sw.points["B"][inner])


# --- any order, any start ------------------------------------------------------------------


def test_jansen_at_shuffled_and_shifted_angles_is_the_ordered_sweep_row_by_row():
    sc = pk.scenes.load("jansen")
    theta = sc.input_angle + np.radians(np.arange(30.0, 390.0, 1.0))
    ref = pk.reference.scene_sweep(sc.to_dict(), theta)
    rng = np.random.default_rng(7)
    order = rng.permutation(len(theta))
    sw = sc.sweep(theta[order], outputs="all")
    assert sw.success.all()
    for name in sc.points:
        np.testing.assert_allclose(sw.points[name], ref.points[name][order], rtol=0, atol=1e-9)


def offset_slider_crank(theta_deg, r=1.0, big_l=1.2, e=0.5):
    t = np.radians(theta_deg)
    a = r * np.array([np.cos(t), np.sin(t)])
    x = a[0] + np.sqrt(big_l**2 - (e - a[1]) ** 2)
    pts = {"O": [0, 0], "A": a, "B": [x, e], "G1": [-5, e], "G2": [5, e]}
    links = {"ground": ["O", "G1", "G2"], "crank": ["O", "A"], "rod": ["A", "B"]}
    return scene(
        pts,
        links,
        input={"link": "crank", "pivot": "O"},
        slots={"piston": {"point": "B", "guide": "ground", "line": ["G1", "G2"]}},
    )


@pytest.mark.parametrize("extra", [[], [200.0], [100.0, 0.0]])
def test_an_angle_one_way_past_a_dead_point_is_reached_the_other_way(extra):
    # r = 1, l = 1.2, e = 0.5: the crank rocks between its dead points sin(theta) = -0.7;
    # drawn at 30 deg, 220 deg is past one the short way round and reached going up
    sc = offset_slider_crank(30.0)
    theta = np.radians(np.array(extra + [220.0]))
    sw = sc.sweep(theta, outputs="all")
    t = np.radians(220.0)
    a = np.array([np.cos(t), np.sin(t)])
    x = a[0] + np.sqrt(1.2**2 - (0.5 - a[1]) ** 2)
    assert sw.status[-1] == pk.Status.CONVERGED
    np.testing.assert_allclose(sw.points["B"][-1], [x, 0.5], rtol=0, atol=1e-12)


def test_an_angle_past_dead_points_both_ways_names_the_one_on_the_shorter_way():
    # the double butterfly's drawn circuit rocks between two turning points (the trace's,
    # refined to about 1e-9 rad): an unsolved angle names the one met going the shorter way
    sc = pk.scenes.load("double-butterfly-1")
    lo, hi = sorted(np.angle(np.exp(1j * sc.trace().turning_points)))
    sw = sc.sweep()
    stopped = sw.status == pk.Status.LIMIT
    assert stopped.sum() > 10
    up = np.angle(np.exp(1j * (sw.theta - sc.input_angle))) >= 0  # the shorter way is up
    named = np.angle(np.exp(1j * sw.limit))
    np.testing.assert_allclose(named[stopped & up], hi, rtol=0, atol=1e-8)
    np.testing.assert_allclose(named[stopped & ~up], lo, rtol=0, atol=1e-8)
    assert (stopped & up).any() and (stopped & ~up).any()


def test_an_angle_with_no_assembly_names_no_dead_point():
    sc = offset_slider_crank(30.0)
    sw = sc.sweep(np.radians([270.0, -60.0, 200.0]))  # sin < -0.7: the rod cannot reach
    np.testing.assert_array_equal(sw.status[:2], pk.Status.NOT_ASSEMBLABLE)
    assert np.isnan(sw.limit[:2]).all()
    assert sw.status[2] == pk.Status.CONVERGED


# --- a group through a change point --------------------------------------------------------


def parallelogram_triad(direction_deg):
    """A triad (ternary C-D-B, binaries O4-C, O6-D, A-B) whose loop O4-C-D-O6 is an exact
    parallelogram: B = C + (1, 1.5) moves on a circle of radius 2 about V = (1, 1.5), so
    B and A make a four-bar O2-A-B-V with crank 1, coupler 3 and rocker 2."""
    v = np.array([1.0, 1.5])
    o2 = v + 3.354 * np.array(
        [np.cos(np.radians(direction_deg)), np.sin(np.radians(direction_deg))]
    )
    a = o2 + np.array([1.0, 0.0])
    b = circle_circle(a, 3.0, v, 2.0, 1.0)
    u = (b - v) / 2.0
    pts = {"O2": o2, "O4": [0, 0], "O6": [3, 0], "A": a, "B": b, "C": 2 * u, "D": [3, 0] + 2 * u}
    links = {
        "ground": ["O2", "O4", "O6"],
        "crank": ["O2", "A"],
        "ab": ["A", "B"],
        "tern": ["C", "D", "B"],
        "r4": ["O4", "C"],
        "r6": ["O6", "D"],
    }
    return scene(pts, links, input={"link": "crank", "pivot": "O2"}), o2, v


@pytest.mark.parametrize("direction", [40, 45, 50, 55, 60, 65, 70, 225, 240])
def test_a_parallelogram_inside_a_group_never_turns_into_the_antiparallelogram(direction):
    sc, o2, v = parallelogram_triad(direction)
    assert [s.kind for s in sc.plan("all").steps] == ["group"]
    theta = np.radians(np.arange(0.0, 360.5, 0.5))
    for th in (theta, theta[::-1]):
        sw = sc.sweep(th, outputs="all")
        ok = sw.success
        pt = sw.points
        # the parallelogram: D - C = O6 - O4; and B on its four-bar's closed form
        gap = np.hypot(*((pt["D"] - pt["C"]) - [3.0, 0.0]).T)
        assert (gap[ok] < 1e-9).all()
        a = o2 + np.stack([np.cos(th), np.sin(th)], -1)
        b = circle_circle(a, 3.0, np.broadcast_to(v, a.shape), 2.0, 1.0)
        np.testing.assert_allclose(pt["B"][ok], b[ok], rtol=0, atol=1e-9)
        if direction != 60:  # drawn 0.5 deg from the change point there: it may stop
            assert ok.sum() >= len(th) - 2


def test_a_group_crosses_its_change_point_from_every_direction_with_or_without_rates():
    # The step across the crossing extrapolates the tangent with its curvature; the last
    # solutions before it are splits a hair apart at a conditioning near 1e-6, whose
    # tangents are off by about 1e-4: the curvature comes from solutions far enough apart.
    # Without rates the tangents come from the Newton check's Jacobian (one correction from
    # the solution's), with rates from the solution's: both cross, to the same points.
    theta = np.radians(np.arange(0.0, 360.5, 0.5))
    for direction in range(0, 360, 10):
        sc, o2, v = parallelogram_triad(direction)
        if [s.kind for s in sc.plan("all").steps] != ["group"]:
            continue
        a = o2 + np.stack([np.cos(theta), np.sin(theta)], -1)
        b = circle_circle(a, 3.0, np.broadcast_to(v, a.shape), 2.0, 1.0)
        for th, bb in ((theta, b), (theta[::-1], b[::-1])):
            plain, rated = sc.sweep(th, outputs="all"), sc.sweep(th, outputs="all", rate=1.0)
            for sw in (plain, rated):
                ok = sw.success
                assert ok.sum() >= len(th) - 2, direction
                np.testing.assert_allclose(sw.points["B"][ok], bb[ok], rtol=0, atol=1e-9)
            np.testing.assert_array_equal(plain.status, rated.status)


# --- a crank pin in a slot of a group's link -----------------------------------------------


def test_a_crank_pin_in_a_slot_of_a_three_link_group_is_solved():
    c, d = np.array([-2.5, 3.0]), np.array([2.0, 3.5])
    pts = {"O2": [0, 0], "O4": [-3, 0], "O6": [3, 0], "C": c, "D": d, "A": c + 0.45 * (d - c)}
    links = {
        "ground": ["O2", "O4", "O6"],
        "crank": ["O2", "A"],
        "l1": ["O4", "C"],
        "coupler": ["C", "D"],
        "l3": ["O6", "D"],
    }
    sc = scene(
        pts,
        links,
        input={"link": "crank", "pivot": "O2"},
        slots={"s": {"point": "A", "guide": "coupler", "line": ["C", "D"]}},
    )
    assert [s.kind for s in sc.plan("all").steps] == ["group"]
    theta = sc.input_angle + np.radians(np.arange(-40.0, 40.5, 0.5))
    sw = sc.sweep(theta, outputs="all")
    ok = sw.success
    assert ok.sum() > 100
    p = {n: sw.points[n][ok] for n in ("A", "C", "D")}
    r = np.hypot(*(np.asarray(pts["A"]))).item()
    np.testing.assert_allclose(np.hypot(*p["A"].T), r, rtol=0, atol=1e-12)
    np.testing.assert_allclose(
        np.hypot(*(p["C"] - [-3, 0]).T), np.hypot(*(c - [-3, 0])), atol=1e-12
    )
    np.testing.assert_allclose(np.hypot(*(p["D"] - [3, 0]).T), np.hypot(*(d - [3, 0])), atol=1e-12)
    np.testing.assert_allclose(np.hypot(*(p["D"] - p["C"]).T), np.hypot(*(d - c)), atol=1e-12)
    # A on the line C-D (the slot), and C moving continuously (one branch)
    line = cross(unit_rows(p["D"] - p["C"]), p["A"] - p["C"])
    assert np.abs(line).max() < 1e-12
    assert np.hypot(*np.diff(p["C"], axis=0).T).max() < 0.2


def unit_rows(v):
    return (v.T / np.hypot(*v.T)).T


# --- the closed-form conditioning floor ----------------------------------------------------


def fourbar_near_toggle(eps):
    a, b, c, d = 2.0, 3.0, 2.5, 6.0  # non-Grashof: the crank rocks between toggles
    toggle = np.arccos((a * a + d * d - (b + c) ** 2) / (2 * a * d))
    t = toggle - 0.3
    pa = a * np.array([np.cos(t), np.sin(t)])
    pb = circle_circle(pa, b, np.array([d, 0.0]), c, 1.0)
    links = {
        "ground": ["O2", "O4"],
        "crank": ["O2", "A"],
        "coupler": ["A", "B"],
        "rocker": ["O4", "B"],
    }
    sc = scene(
        {"O2": [0, 0], "O4": [d, 0], "A": pa, "B": pb},
        links,
        input={"link": "crank", "pivot": "O2"},
    )
    return sc, (a, b, c, d), toggle


def exact_b(dims, theta):
    a, b, c, d = (mp.mpf(x) for x in dims)
    ax, ay = a * mp.cos(theta), a * mp.sin(theta)
    dx, dy = d - ax, -ay
    dist = mp.sqrt(dx * dx + dy * dy)
    along = (b * b - c * c + dist * dist) / (2 * dist)
    h = mp.sqrt(b * b - along * along)
    return [ax + (along * dx + h * dy) / dist, ay + (along * dy - h * dx) / dist], [
        ax + (along * dx - h * dy) / dist,
        ay + (along * dy + h * dx) / dist,
    ]


@pytest.mark.parametrize("eps", [1e-13, 1e-12, 1e-11, 1e-10, 1e-9, 1e-8, 1e-6])
def test_a_dyad_near_its_dead_point_is_converged_only_within_1e9_of_the_size(eps):
    mp.mp.dps = 40
    sc, dims, toggle = fourbar_near_toggle(eps)
    sw = sc.sweep(np.array([toggle - eps]), outputs="all")
    if sw.status[0] != pk.Status.CONVERGED:
        assert sw.status[0] == pk.Status.SINGULAR
        assert eps <= 1e-10  # conditioning ~ sqrt(eps): below the floor only this close
        return
    got = sw.points["B"][0]
    theta = mp.mpf(toggle) - mp.mpf(eps)
    err = min(
        max(abs(float(x) - g) for x, g in zip(side, got, strict=True))
        for side in exact_b(dims, theta)
    )
    assert err <= 1e-9 * 6.0


@pytest.mark.parametrize("name", ["jansen", "double-butterfly-1", "stephenson3", "hydraulic-boom"])
def test_a_rows_answer_does_not_depend_on_the_rest_of_the_array(name):
    # issue 32: a row changed from LIMIT to CONVERGED when one more angle was appended;
    # any subset, order or start gives each value the same status and pose
    sc = pk.scenes.load(name)
    full = sc.sweep(outputs="all")
    size = float(np.ptp(np.array(list(sc.points.values())), axis=0).max())
    rng = np.random.default_rng(11)
    for _ in range(3):
        pick = rng.permutation(len(full.theta))[: rng.integers(5, 60)]
        part = sc.sweep(full.theta[pick], outputs="all")
        np.testing.assert_array_equal(part.status, full.status[pick])
        ok = part.success
        np.testing.assert_allclose(part.coords[ok], full.coords[pick][ok], rtol=0, atol=1e-9 * size)


def reflect(p, a, b):
    d = (b - a) / np.hypot(*(b - a))
    v = p - a
    return a + 2 * (v @ d) * d - v


@pytest.mark.parametrize("seed", range(6))
def test_a_kite_inside_a_group_stays_on_the_kite(seed):
    # a triad whose loop O4-C-D-O6 is an exact kite (|O4 C| = |O4 O6| = 3, |C D| = |D O6|
    # = 2): on the kite branch C is O6 reflected in the line O4-D; the folded circuit
    # (C held at O6) crosses it at the kite's change point and must never be taken
    rng = np.random.default_rng(seed)
    o4, o6 = np.zeros(2), np.array([3.0, 0.0])
    phi = np.radians(rng.uniform(5.0, 80.0))
    c = 3.0 * np.array([np.cos(phi), np.sin(phi)])
    d = circle_circle(o6, 2.0, c, 2.0, 1.0)
    b = c + 0.6 * (d - c) + 0.8 * np.array([-(d - c)[1], (d - c)[0]])
    psi, chi, length = rng.uniform(0, 2 * np.pi), rng.uniform(0, 2 * np.pi), rng.uniform(1.5, 4)
    a = b + length * np.array([np.cos(psi), np.sin(psi)])
    o2 = a + np.array([np.cos(chi), np.sin(chi)])
    pts = {"O2": o2, "O4": o4, "O6": o6, "A": a, "B": b, "C": c, "D": d}
    links = {
        "ground": ["O2", "O4", "O6"],
        "crank": ["O2", "A"],
        "ab": ["A", "B"],
        "tern": ["C", "D", "B"],
        "r4": ["O4", "C"],
        "r6": ["O6", "D"],
    }
    sc = scene(pts, links, input={"link": "crank", "pivot": "O2"})
    theta = sc.input_angle + np.radians(np.arange(0.0, 360.5, 0.5))
    sw = sc.sweep(theta, outputs="all")
    ok = np.where(sw.success)[0]
    assert len(ok) > 30
    gap = [np.hypot(*(sw.points["C"][k] - reflect(o6, o4, sw.points["D"][k]))) for k in ok]
    assert max(gap) < 1e-9


# --- a cylinder pushing a point of a group's link (the input's joint in a Newton group) ---


def excavator():
    """A four-bar O2-A-B-O4 whose coupler point E is pushed by a cylinder from ground K:
    no dyad reaches A, B or E; the cylinder's joint must join the group, held at the
    input (issue 32: 'no rigid group of at most 12 links solves them')."""
    o2, o4, k = np.array([0.0, 0.0]), np.array([4.0, 0.0]), np.array([-1.0, -2.0])
    a, b, e = np.array([0.5, 1.8]), np.array([3.5, 2.6]), np.array([2.0, 3.4])
    u = unit(e - k)
    pts = {"O2": o2, "O4": o4, "K": k, "A": a, "B": b, "E": e, "C2": k + 0.4 * u, "R": k + 0.8 * u}
    links = {
        "ground": ["O2", "O4", "K"],
        "crank": ["O2", "A"],
        "coupler": ["A", "B", "E"],
        "rocker": ["O4", "B"],
        "barrel": ["K", "C2"],
        "rod": ["R", "E"],
    }
    return scene(
        pts,
        links,
        input={"prismatic": "cyl"},
        prismatic={"cyl": {"link": "rod", "guide": "barrel", "line": ["K", "C2"]}},
    ), pts


def test_a_cylinder_pushing_a_coupler_point_is_solved_as_a_held_group():
    sc, pts = excavator()
    assert [s.kind for s in sc.plan("all").steps] == ["group"]
    sw = sc.sweep(outputs="all", rate=1.0)
    ok = sw.success
    assert ok.sum() >= 355
    p = {n: sw.points[n][ok] for n in pts}
    drawn = {n: np.asarray(v) for n, v in pts.items()}
    for a, b in [("O2", "A"), ("A", "B"), ("B", "O4"), ("A", "E"), ("B", "E"), ("R", "E")]:
        got = np.hypot(*(p[a] - p[b]).T)
        np.testing.assert_allclose(got, np.hypot(*(drawn[a] - drawn[b])), rtol=0, atol=1e-12)
    # the cylinder: |K E| is its drawn length plus the extension, K, C2, R and E in line
    ke0 = np.hypot(*(drawn["E"] - drawn["K"]))
    np.testing.assert_allclose(np.hypot(*(p["E"] - p["K"]).T), ke0 + sw.theta[ok], atol=1e-12)
    line = unit_rows(p["E"] - p["K"])
    for n in ("C2", "R"):
        assert np.abs(cross(line, p[n] - p["K"])).max() < 1e-12
    # one branch: every point moves continuously with the extension (a switch to the other
    # assembly would jump by a sizeable fraction of the linkage between two rows)
    ds = np.diff(sw.theta[ok])
    for n in ("A", "B", "E"):
        jump = np.hypot(*np.diff(p[n], axis=0).T)
        speed = np.hypot(*sw.velocities[n][ok].T)
        assert (jump <= 2.0 * np.maximum(speed[:-1], speed[1:]) * ds + 1e-9).all()
    # velocities and accelerations against central differences of positions
    k = int(np.flatnonzero(ok)[len(np.flatnonzero(ok)) // 2])
    h = 1e-4
    s = sw.theta[k] + np.array([-h, 0.0, h])
    three = sc.sweep(s, outputs="all", rate=1.0)
    e = three.points["E"]
    np.testing.assert_allclose(sw.velocities["E"][k], (e[2] - e[0]) / (2 * h), atol=1e-7)
    np.testing.assert_allclose(
        sw.accelerations["E"][k], (e[2] - 2 * e[1] + e[0]) / h**2, rtol=0, atol=1e-5
    )


def test_a_cylinder_at_zero_length_is_singular_with_its_conditioning_going_to_zero():
    # a boom whose cylinder pin E can meet the barrel's pivot C1 (|O E| = |O C1|): at zero
    # length the barrel's direction is undefined; the conditioning falls as the length
    c1 = np.array([600.0, -400.0])
    g = np.hypot(*c1)
    e = g * np.array([np.cos(np.radians(30.0)), np.sin(np.radians(30.0))])
    ax = unit(e - c1)
    pts = {"O": [0.0, 0.0], "C1": c1, "E": e, "C2": c1 + 100 * ax, "R": e - 100 * ax}
    links = {"ground": ["O", "C1"], "boom": ["O", "E"], "barrel": ["C1", "C2"], "rod": ["R", "E"]}
    sc = scene(
        pts,
        links,
        input={"prismatic": "cyl"},
        prismatic={"cyl": {"link": "rod", "guide": "barrel", "line": ["C1", "C2"]}},
    )
    rho0 = np.hypot(*(e - c1))
    gaps = np.array([1.0, 1e-1, 1e-2, 1e-9, 0.0])
    sw = sc.sweep(-rho0 + gaps, outputs="all")
    det = np.abs(sw.step_det[:, 0])
    # proportional to the length left (the dyad itself stays well conditioned)
    np.testing.assert_allclose(det[:3] / gaps[:3], det[0] / gaps[0], rtol=1e-3)
    assert (sw.status[:2] == pk.Status.CONVERGED).all()
    assert (sw.status[3:] == pk.Status.SINGULAR).all()
    # where solved, E is at the cylinder's length from C1 and at |O C1| from O
    ok = sw.success
    np.testing.assert_allclose(np.hypot(*(sw.points["E"][ok] - c1).T), gaps[ok], atol=1e-9)


@pytest.mark.parametrize("drawn", [20.0, 90.0])
def test_a_pose_does_not_depend_on_the_outputs_at_an_exact_kite_change_point(drawn):
    # a kite four-bar (crank = ground = 2, coupler = rocker = 3) whose crank pin meets the
    # rocker's pivot at theta = 0 (sampled exactly), driving a dyad to E
    a, b = 2.0, 3.0
    t = np.radians(drawn)
    pa = a * np.array([np.cos(t), np.sin(t)])
    pb = circle_circle(pa, b, np.array([a, 0.0]), b, 1.0)
    o6 = np.array([a + 2.5, 3.5])
    pe = circle_circle(pb, 2.0, o6, 2.5, 1.0)
    pts = {"O2": [0, 0], "O4": [a, 0], "O6": o6, "A": pa, "B": pb, "E": pe}
    links = {
        "ground": ["O2", "O4", "O6"],
        "crank": ["O2", "A"],
        "coupler": ["A", "B"],
        "rocker": ["O4", "B"],
        "be": ["B", "E"],
        "ge": ["O6", "E"],
    }
    sc = scene(pts, links, input={"link": "crank", "pivot": "O2"})
    theta = np.radians(np.arange(0.0, 360.5, 1.0))
    every, one = sc.sweep(theta, outputs="all"), sc.sweep(theta, outputs=["E"])
    np.testing.assert_array_equal(every.status, one.status)
    ok = every.success
    np.testing.assert_array_equal(every.points["E"][ok], one.points["E"][ok])
    # and E where solved satisfies its two links exactly
    np.testing.assert_allclose(np.hypot(*(every.points["E"][ok] - o6).T), 2.5, atol=1e-12)
