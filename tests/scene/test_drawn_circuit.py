"""A sweep follows the drawn assembly (DESIGN.md, "Scenes"): the side of a dyad is carried
along the path, through an exact change point with the smooth tangent, and a fold ends the
reachable range. Angles the drawn circuit does not reach are LIMIT where the linkage has
another assembly and NOT_ASSEMBLABLE where it has none. Checked against closed forms."""

import math

import numpy as np
import planarkin as pk
import pytest


def four_bar(r1, r2, r3, r4, theta, side=1.0, b=None):
    """A four-bar scene drawn at crank angle `theta`, B on `side` of A -> O4 (or at `b`)."""
    a = np.array([r2 * math.cos(theta), r2 * math.sin(theta)])
    o4 = np.array([r1, 0.0])
    d = o4 - a
    dd = math.hypot(*d)
    along = (r3**2 - r4**2 + dd**2) / (2 * dd)
    h = math.sqrt(max(r3**2 - along**2, 0.0))
    if b is None:
        b = a + along * d / dd + side * h * np.array([-d[1], d[0]]) / dd
    b = np.asarray(b, dtype=float)
    return pk.Scene.from_dict(
        {
            "name": f"four-bar {r1, r2, r3, r4}",
            "points": {"O2": [0.0, 0.0], "O4": o4.tolist(), "A": a.tolist(), "B": b.tolist()},
            "links": {"g": ["O2", "O4"], "c": ["O2", "A"], "k": ["A", "B"], "r": ["O4", "B"]},
            "ground": "g",
            "input": {"link": "c", "pivot": "O2"},
        }
    )


@pytest.mark.parametrize("drawn_deg", [60.5, 200.25, -30.0])
@pytest.mark.parametrize("ground, crank", [(4.0, 2.0), (3.0, 5.0)])
def test_a_parallelogram_stays_a_parallelogram_through_its_change_points(drawn_deg, ground, crank):
    # r1 = r3, r2 = r4: at 0 and 180 deg every link is in line (a change point); the smooth
    # continuation is the parallelogram, B = A + (r1, 0), all the way round
    th = math.radians(drawn_deg)
    a = crank * np.array([math.cos(th), math.sin(th)])
    sc = four_bar(ground, crank, ground, crank, th, b=a + [ground, 0.0])
    sw = sc.sweep()
    # exactly at a change point the dyad is SINGULAR (its links in line); everywhere else
    # it is solved, on the parallelogram
    at = np.abs(np.sin(sw.theta)) < 1e-9
    assert (sw.status[at] == pk.Status.SINGULAR).all()
    assert sw.success[~at].all()
    np.testing.assert_allclose(
        sw.points["B"][~at] - sw.points["A"][~at],
        np.tile([ground, 0.0], ((~at).sum(), 1)),
        atol=1e-12 * ground,
    )
    # the dyad's signed conditioning changes sign at each change point (it is smooth)
    assert (np.diff(np.sign(sw.det[~at])) != 0).sum() == 2
    # drawn crossed (the antiparallelogram: B mirrored in the line A O4), it stays crossed:
    # B - A is never (r1, 0) away from the change points
    o4 = np.array([ground, 0.0])
    u = (o4 - a) / np.linalg.norm(o4 - a)
    b = a + [ground, 0.0]
    other = a + 2 * np.dot(b - a, u) * u - (b - a)
    crossed = four_bar(ground, crank, ground, crank, th, b=other).sweep()
    away = np.abs(np.sin(crossed.theta)) > 1e-6
    gap = np.linalg.norm(crossed.points["B"] - crossed.points["A"] - [ground, 0.0], axis=1)
    assert crossed.success[away].all() and (gap[away] > 1e-3).all()


def test_a_parallelogram_swept_exactly_through_its_change_point():
    sc = four_bar(4.0, 2.0, 4.0, 2.0, math.radians(60.5))
    theta = np.radians(np.linspace(170.0, 190.0, 21))  # 180 deg exactly is the change point
    sw = sc.sweep(theta)
    at = np.flatnonzero(np.isclose(theta, math.pi))
    assert sw.status[at] == pk.Status.SINGULAR
    ok = sw.success
    assert ok.sum() == 20
    np.testing.assert_allclose(
        sw.points["B"][ok] - sw.points["A"][ok], np.tile([4.0, 0.0], (20, 1)), atol=1e-12
    )


def closed_form_range(r1, r2, r3, r4):
    """Crank angles (cos) where |r3 - r4| <= |A O4| <= r3 + r4, A on the crank."""
    lo = (r1**2 + r2**2 - (r3 + r4) ** 2) / (2 * r1 * r2)
    hi = (r1**2 + r2**2 - (r3 - r4) ** 2) / (2 * r1 * r2)
    return lo, hi


@pytest.mark.parametrize("near", [0.0, 1e-10])
def test_a_grashof_double_rocker_stays_on_its_circuit(near):
    # coupler shortest (GRCR): the input rocks over [acos(21/24), 90] deg on the drawn circuit
    # and over [270, 360 - acos(21/24)] on the other one, which it cannot reach
    r1, r2, r3, r4 = 4.0, 3.0, 1.5, 3.5
    lo, hi = closed_form_range(r1, r2, r3, r4)
    assert pk.FourBar(r1, r2, r3, r4).grashof().barker == "GRCR"
    dead = (math.acos(hi), math.acos(lo))  # 28.96 and 90 deg
    drawn = dead[1] - near if near else math.radians(60.0)
    sc = four_bar(r1, r2, r3, r4, drawn)
    sw = sc.sweep()
    t = np.mod(sw.theta, 2 * math.pi)
    inside = (t > dead[0] + 1e-11) & (t < dead[1] - 1e-11)
    mirror = (t > 2 * math.pi - dead[1] + 1e-9) & (t < 2 * math.pi - dead[0] - 1e-9)
    np.testing.assert_array_equal(sw.success, inside)
    assert (sw.status[mirror] == pk.Status.LIMIT).all()
    outside = ~inside & ~mirror & (np.abs(np.cos(t) - lo) > 1e-9) & (np.abs(np.cos(t) - hi) > 1e-9)
    assert (sw.status[outside] == pk.Status.NOT_ASSEMBLABLE).all()
    # LIMIT angles name the dead point that stops the motion
    lim = np.mod(sw.limit[sw.status == pk.Status.LIMIT], 2 * math.pi)
    assert np.isin(np.round(lim, 6), np.round(dead, 6)).all()
    # on the drawn circuit, B is the closed form on the drawn side
    a = sw.points["A"][inside]
    for (ax, ay), b in zip(a, sw.points["B"][inside], strict=True):
        th = math.atan2(ay, ax)
        expected = four_bar(r1, r2, r3, r4, th).points["B"]
        np.testing.assert_allclose(b, expected, atol=1e-12 * r1)


def test_a_group_drawn_next_to_its_dead_point_sweeps_away_from_it():
    # the double butterfly's group, drawn 1e-10 rad inside its circuit's dead point: every
    # angle of the circuit's range is solved, as from the pose drawn far from it
    sc = pk.scenes.load("double-butterfly-1")
    trace = sc.trace()
    lo, hi = sorted(np.angle(np.exp(1j * trace.turning_points)))
    assert lo < sc.input_angle < hi  # the drawn circuit's range is (lo, hi)
    for end, inward in [(hi, -1.0), (lo, 1.0)]:
        t = end + inward * 1e-10
        k = np.argmin(np.abs(np.angle(np.exp(1j * (trace.theta - end)))))
        pose = min(
            sc.assemblies(t),
            key=lambda a: sum(
                np.hypot(*(np.asarray(a[n]) - trace.points[n][k])) for n in sc.points
            ),
        )
        near = pk.Scene.from_dict(
            {**sc.to_dict(), "points": {n: [float(v) for v in pose[n]] for n in sc.points}}
        )
        sw = near.sweep()
        th = np.angle(np.exp(1j * sw.theta))
        inside = (th > lo + 1e-12) & (th < hi - 1e-12)
        np.testing.assert_array_equal(sw.success, inside)
