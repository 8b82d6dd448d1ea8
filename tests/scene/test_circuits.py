"""Every assembly, every circuit: against the four-bar's closed form and limits, loop
closure by substitution, complex solution counts from the literature, random Newton starts
(completeness), and tracing that must come back to its start."""

from __future__ import annotations

import math

import numpy as np
import planarkin as pk
import pytest

DEG = math.pi / 180


def fourbar_scene(r, theta2=0.0, mode="open"):
    r1, r2, r3, r4 = r
    fb = pk.FourBar(*r)
    t3, _ = fb.closed_form(theta2, mode=mode)
    a = (r2 * math.cos(theta2), r2 * math.sin(theta2))
    b = (a[0] + r3 * math.cos(t3), a[1] + r3 * math.sin(t3))
    return pk.Scene.from_dict(
        {
            "points": {"O2": [0, 0], "O4": [r1, 0], "A": list(a), "B": list(b)},
            "links": {
                "ground": ["O2", "O4"],
                "crank": ["O2", "A"],
                "coupler": ["A", "B"],
                "rocker": ["O4", "B"],
            },
            "ground": "ground",
            "input": {"link": "crank", "pivot": "O2"},
        }
    )


def closure_error(sc, asm):
    """Largest change of a drawn distance between two points of one link."""
    worst = 0.0
    for pts in sc.links.values():
        for i, a in enumerate(pts):
            for b in pts[i + 1 :]:
                d0 = math.dist(sc.points[a], sc.points[b])
                worst = max(worst, abs(math.dist(asm[a], asm[b]) - d0))
    return worst


# --- the four-bar ------------------------------------------------------------------------


@pytest.mark.parametrize("theta", [0.0, 0.7, 2.5, -2.0])
def test_fourbar_assemblies_are_both_closed_form_modes(theta):
    sc = fourbar_scene((6, 2, 5, 5))
    fb = pk.FourBar(6, 2, 5, 5)
    a = sc.assemblies(theta)
    assert len(a) == 2 and a.complex_counts == []
    for mode, sign in (("open", 1), ("crossed", -1)):
        t3, t4 = fb.closed_form(theta, mode=mode)
        b = (2 * math.cos(theta) + 5 * math.cos(t3), 2 * math.sin(theta) + 5 * math.sin(t3))
        hit = [x for x in a if math.dist(x["B"], b) < 1e-12]
        assert len(hit) == 1
        assert np.sign(hit[0].det) == sign
        assert hit[0].label == ("+" if sign > 0 else "-")
        assert set(hit[0]) == set(sc.points)  # ground points too


def test_non_assemblable_angle_has_no_assembly():
    sc = fourbar_scene((4, 3, 1.5, 2))
    fb = pk.FourBar(4, 3, 1.5, 2)
    t = math.pi  # crank pin at (-3, 0): |A O4| = 7 > 3.5
    assert fb.closed_form_status(t) == pk.Status.NOT_ASSEMBLABLE
    assert len(sc.assemblies(t)) == 0


def test_crank_rocker_has_two_circuits_each_turning_fully():
    sc = fourbar_scene((6, 2, 5, 5))
    cs = sc.circuits(0.4)
    assert len(cs) == 2
    for c in cs:
        assert len(c.assemblies) == 1 and c.full_turn and c.trace.closed
        assert len(c.turning_points) == 0
        assert abs(abs(c.net_turn) - 2 * math.pi) < 1e-9


@pytest.mark.parametrize("r", [(4, 3, 1.5, 2), (2, 4, 2.5, 3), (3, 5, 2.5, 2.2)])
def test_non_grashof_circuit_turns_at_the_toggles(r):
    fb = pk.FourBar(*r)
    assert fb.grashof().condition == "non-grashof"
    lim = fb.limits()
    theta = 0.5 * (lim.intervals[0][0] + lim.intervals[0][1])
    sc = fourbar_scene(r, theta)
    cs = sc.circuits(theta)
    # a triple rocker: one circuit through both modes, rocking between the two toggles
    assert len(cs) == 1
    (c,) = cs
    assert len(c.assemblies) == 2 and not c.full_turn and c.trace.closed
    np.testing.assert_allclose(np.sort(c.turning_points), np.sort(lim.toggles), atol=1e-9)
    # the number of turning points is the number of sign changes of det along the trace
    changes = np.count_nonzero(np.diff(np.sign(c.trace.det)) != 0)
    assert changes == len(c.turning_points)


# --- groups: counts, closure, completeness -----------------------------------------------


def test_stephenson_group_has_six_complex_solutions():
    sc = pk.scenes.load("stephenson3")
    for t in sc.input_angle + np.array([0.0, 0.3, 1.1, 2.9]):
        a = sc.assemblies(t)
        assert a.complex_counts == [[6]]
        for asm in a:
            assert closure_error(sc, asm) < 1e-12


@pytest.mark.parametrize(
    ("name", "count"), [("double-butterfly-1", 16), ("double-butterfly-2", 18)]
)
def test_double_butterfly_counts_and_closure(name, count):
    # Waldron and Sreenivasan: 18 complex assemblies with the input at a butterfly hinge,
    # 16 with it at a ternary-bar joint
    sc = pk.scenes.load(name)
    for t in sc.input_angle + np.array([0.05, 0.4, -0.3]):
        a = sc.assemblies(t)
        assert a.complex_counts == [[count]], a.complex_counts
        assert a.failed_paths == 0
        for asm in a:
            assert closure_error(sc, asm) < 1e-12


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_double_butterfly_counts_on_random_geometries(seed):
    # random geometry: the same topology drawn at random joint positions
    rng = np.random.default_rng(seed)
    for name, count in (("double-butterfly-1", 16), ("double-butterfly-2", 18)):
        d = pk.scenes.data(name)
        d["points"] = {
            k: (np.array(v) + rng.normal(0, 0.3, 2)).tolist() for k, v in d["points"].items()
        }
        try:
            sc = pk.Scene.from_dict(d)
        except ValueError:
            continue  # drawn at a dead point: another draw tests the count
        a = sc.assemblies()
        assert a.complex_counts == [[count]], (name, a.complex_counts)
        assert len(a) >= 1  # the drawn pose itself
        drawn = [x for x in a if max(math.dist(x[p], sc.points[p]) for p in sc.points) < 1e-9]
        assert len(drawn) == 1


def test_real_count_is_stable_under_small_changes_of_the_input():
    sc = pk.scenes.load("double-butterfly-1")
    t = sc.input_angle + 0.4
    counts = {len(sc.assemblies(t + e)) for e in (-1e-7, 0.0, 1e-7)}
    assert len(counts) == 1


def _group_newton_starts(sc, theta, starts, rng):
    """Random Newton starts on the loop-closure equations, vectorised over starts, with the
    drawn links' lengths: the input link rotated to theta, every other link's rotation
    unknown, joints coinciding. Returns the converged poses (starts, P, 2)."""
    names = list(sc.points)
    idx = {n: i for i, n in enumerate(names)}
    d = sc.to_dict()
    links = [k for k in d["links"] if k not in (d["ground"], d["input"]["link"])]
    xy = np.array([d["points"][n] for n in names], dtype=float)
    piv = idx[d["input"]["pivot"]]
    rot = theta - sc.input_angle
    c, s = math.cos(rot), math.sin(rot)
    known = {idx[p]: xy[idx[p]] for p in d["links"][d["ground"]]}
    for p in d["links"][d["input"]["link"]]:
        v = xy[idx[p]] - xy[piv]
        known[idx[p]] = xy[piv] + np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])
    # unknowns per link: translation of its first point and its rotation
    n = len(links)
    first = [idx[d["links"][k][0]] for k in links]

    def pos(x, k, p):  # x: (S, 3n)
        t, phi = x[:, 3 * k : 3 * k + 2], x[:, 3 * k + 2]
        v = xy[p] - xy[first[k]]
        return t + np.stack([np.cos(phi) * v[0] - np.sin(phi) * v[1],
                             np.sin(phi) * v[0] + np.cos(phi) * v[1]], -1)  # fmt: skip

    on = {}
    for k, name in enumerate(links):
        for p in d["links"][name]:
            on.setdefault(idx[p], []).append(k)

    def residual(x):
        r = []
        for p, ks in on.items():
            if p in known:
                r += [pos(x, k, p) - known[p] for k in ks]
            else:
                r += [pos(x, k, p) - pos(x, ks[0], p) for k in ks[1:]]
        return np.concatenate(r, axis=1)

    size = np.ptp(xy, axis=0).max()
    x = np.empty((starts, 3 * n))
    for k in range(n):
        x[:, 3 * k : 3 * k + 2] = xy[first[k]] + rng.normal(0, size, (starts, 2))
        x[:, 3 * k + 2] = rng.uniform(-math.pi, math.pi, starts)
    h = 1e-7
    for it in range(40):
        f = residual(x)
        if it == 20:  # drop the starts that are going nowhere
            keep = np.abs(f).max(axis=1) < 1e-2 * size
            x, f = x[keep], f[keep]
        jac = np.stack([(residual(x + h * e) - f) / h for e in np.eye(3 * n)], -1)
        step = np.linalg.solve(jac + 1e-14 * np.eye(3 * n), -f[..., None])[..., 0]
        x = x + np.clip(step, -1.0, 1.0)
    ok = np.abs(residual(x)).max(axis=1) < 1e-9 * size
    starts = len(x)
    poses = np.repeat(xy[None], starts, 0)
    for p, v in known.items():
        poses[:, p] = v
    for p, ks in on.items():
        if p not in known:
            poses[:, p] = pos(x, ks[0], p)
    return poses[ok]


@pytest.mark.parametrize(
    "name",
    [
        # 10 000 Newton starts in numpy: 3 s on 2 cores for stephenson3, 7 s for each
        # double butterfly, so all three are left out of the inner loop
        pytest.param("stephenson3", marks=pytest.mark.slow),
        pytest.param("double-butterfly-1", marks=pytest.mark.slow),
        pytest.param("double-butterfly-2", marks=pytest.mark.slow),
    ],
)
def test_every_newton_solution_is_among_the_assemblies(name):
    # completeness: what random Newton starts find, the homotopy found too
    sc = pk.scenes.load(name)
    theta = sc.input_angle + 0.2
    found = np.array([[a[p] for p in sc.points] for a in sc.assemblies(theta)])
    newton = _group_newton_starts(sc, theta, 10_000, np.random.default_rng(7))
    assert len(newton) > 100
    size = np.ptp(np.array(list(sc.points.values())), axis=0).max()
    gap = np.abs(newton[:, None] - found[None]).max(axis=(2, 3)).min(axis=1)
    assert (gap < 1e-6 * size).all(), gap.max()


# --- tracing and circuits ------------------------------------------------------------------


@pytest.mark.parametrize(
    "name", ["double-butterfly-1", "double-butterfly-2", "stephenson3", "jansen"]
)
def test_circuits_partition_the_assemblies_and_traces_close(name):
    sc = pk.scenes.load(name)
    theta = sc.input_angle
    a = sc.assemblies(theta)
    cs = sc.circuits(theta)
    on = [id(x) for c in cs for x in c.assemblies]
    assert sorted(on) == sorted(id(x) for x in cs_assemblies(cs))
    assert len(on) == len(set(on)) == len(a)  # each assembly once, on exactly one circuit
    for c in cs:
        tr = c.trace
        assert tr.closed
        np.testing.assert_allclose(tr.coords[-1], tr.coords[0], atol=1e-9)
        changes = np.count_nonzero(np.diff(np.sign(tr.det)) != 0)
        assert changes == len(tr.turning_points) == len(c.turning_points)
        # every pose on the path is an assembly
        for i in range(0, len(tr), max(1, len(tr) // 20)):
            assert closure_error(sc, {n: tr.points[n][i] for n in sc.points}) < 1e-9
        if not c.full_turn:
            assert len(c.turning_points) >= 2 and len(c.turning_points) % 2 == 0


def cs_assemblies(cs):
    return [x for c in cs for x in c.assemblies]


def test_trace_from_the_drawn_pose_matches_the_sweep():
    sc = pk.scenes.load("double-butterfly-1")
    tr = sc.trace()
    assert tr.closed
    sw = sc.sweep(outputs="all")
    # the trace passes every angle the sweep solved, on the same poses
    ok = np.flatnonzero(sw.success)
    for k in ok[::30]:
        t = sw.theta[k]
        i = np.argmin(np.abs(np.angle(np.exp(1j * (tr.theta - t)))))
        # nearest traced point within one step: compare loosely, then exactly on a re-solve
        assert abs(np.angle(np.exp(1j * (tr.theta[i] - t)))) < 0.05
    # the sweep stops at the first turning point the trace finds beyond the drawn angle
    lim = sw.limit[np.isfinite(sw.limit)]
    assert len(lim)
    tps = np.angle(np.exp(1j * tr.turning_points))
    for v in np.unique(np.round(lim, 6)):
        assert np.min(np.abs(np.angle(np.exp(1j * (tps - v))))) < 1e-5


def test_at_draws_the_scene_in_another_assembly():
    sc = pk.scenes.load("fourbar")
    crossed = [a for a in sc.assemblies() if a.det < 0][0]
    other = sc.at(crossed)
    assert other.points["B"] == crossed["B"]
    fb = pk.FourBar(6, 2, 5, 5)
    sw = other.sweep(outputs=["rocker"])
    _, t4 = fb.closed_form(sw.theta, mode="crossed")
    np.testing.assert_allclose(sw.angles["rocker"], t4, atol=1e-12)
    bad = dict(crossed)
    bad["B"] = (bad["B"][0] + 0.1, bad["B"][1])
    with pytest.raises(ValueError, match="is not an assembly of this scene"):
        sc.at(bad)


def test_sweep_reports_limit_with_the_dead_point():
    sc = pk.scenes.load("double-butterfly-2")
    sw = sc.sweep()
    lim = sw.status == pk.Status.LIMIT
    assert lim.any() and sw.success.any()
    assert np.isfinite(sw.limit[lim]).all() and np.isnan(sw.limit[~lim]).all()
    assert (sw.status != pk.Status.MAX_ITERATIONS).all()
    # the dead points are where the conditioning vanishes: re-solve just short of each
    for v in np.unique(sw.limit[lim]):
        side = np.angle(np.exp(1j * (v - sc.input_angle)))  # the way round from the drawing
        toward = v - 1e-4 * np.sign(side)
        near = sc.sweep(np.array([toward]))
        assert near.success[0] and abs(near.det[0]) < 0.05


def test_bad_arguments():
    sc = pk.scenes.load("fourbar")
    with pytest.raises(ValueError, match="theta"):
        sc.assemblies(math.nan)
    with pytest.raises(ValueError, match="runs"):
        sc.assemblies(0.0, runs=0)
    with pytest.raises(ValueError, match="step"):
        sc.trace(step=-1)
    with pytest.raises(ValueError, match="start"):
        sc.trace({"A": (0, 0)})


def test_labels_follow_an_assembly_as_the_input_moves():
    # a label is the joints' elbow signs: along a sweep (one assembly followed by
    # continuation) the label of the assembly nearest the sweep's pose stays the same
    sc = pk.scenes.load("stephenson3")
    t = sc.input_angle + np.linspace(0, 0.3, 7)
    sw = sc.sweep(t, outputs="all")
    labels = []
    for k, th in enumerate(t):
        a = sc.assemblies(th)
        gap = [max(math.dist(x[p], sw.points[p][k]) for p in sc.points) for x in a]
        labels.append(a[int(np.argmin(gap))].label)
        assert min(gap) < 1e-9
    assert len(set(labels)) == 1
    assert len({x.label for x in sc.assemblies()}) == len(sc.assemblies())
