"""Limit positions (toggles, intervals, rocker extremes) against independent truth:
mpmath at 50 digits, and dense sampling of an mpmath-free NumPy closed form."""

import math

import mpmath as mp
import numpy as np
import planarkin as pk
import pytest
from planarkin.reference import closed_form_vectorized

mp.mp.dps = 50

SEED = (6.0, 2.0, 5.0, 5.0)


def mp_toggles(r1, r2, r3, r4):
    """All crank angles with d = r3 + r4 or |r3 - r4| (det J = 0), by mpmath acos."""
    out = []
    for e in (mp.mpf(r3) + r4, abs(mp.mpf(r3) - r4)):
        c = (mp.mpf(r1) ** 2 + mp.mpf(r2) ** 2 - e**2) / (2 * mp.mpf(r1) * r2)
        if -1 <= c <= 1:
            t = mp.acos(c)
            out += [t, -t]
    return sorted({float(t) for t in out})


def mp_theta4(r, t2, mode):
    """Rocker angle of `mode` at crank angle t2 by mpmath circle intersection."""
    r1, r2, r3, r4 = (mp.mpf(x) for x in r)
    ax, ay = r2 * mp.cos(t2), r2 * mp.sin(t2)
    ux, uy = r1 - ax, -ay
    d = mp.sqrt(ux**2 + uy**2)
    a = (r3**2 - r4**2 + d**2) / (2 * d)
    h = mp.sqrt(r3**2 - a**2)
    s = 1 if mode == "open" else -1
    bx = ax + a * ux / d - s * h * uy / d
    by = ay + a * uy / d + s * h * ux / d
    return mp.atan2(by, bx - r1)


def test_seed_turns_fully_with_the_rocker_range_of_the_closed_form():
    lim = pk.FourBar(*SEED).limits()
    assert lim.full_rotation and lim.toggles.size == 0 and lim.dead_points.size == 0
    assert lim.intervals == ((-math.pi, math.pi),)
    # the printed seed range, to the 0.01 deg given
    assert math.degrees(lim.rocker_min) == pytest.approx(101.54, abs=5e-3)
    assert math.degrees(lim.rocker_max) == pytest.approx(150.07, abs=5e-3)
    # extremes are maxima of the mpmath theta4(theta2): check stationarity and value
    for t2, t4 in (
        (lim.rocker_min_theta2, lim.rocker_min),
        (lim.rocker_max_theta2, lim.rocker_max),
    ):
        assert float(mp_theta4(SEED, mp.mpf(t2), "open")) == pytest.approx(t4, abs=1e-12)
        slope = mp.diff(lambda t: mp_theta4(SEED, t, "open"), mp.mpf(t2))
        assert abs(slope) < 1e-7


@pytest.mark.parametrize(
    "r",
    [
        (2.0, 5.0, 2.5, 2.0),  # triple rocker: outer toggles
        (4.0, 3.0, 1.0, 4.5),  # Grashof double rocker (coupler shortest)
        (5.0, 6.0, 2.0, 4.5),  # non-Grashof with both kinds of toggle
        (3.0, 4.0, 4.0, 1.0),  # rocker-crank
    ],
)
def test_toggles_match_mpmath_and_bound_the_assemblable_set(r):
    fb = pk.FourBar(*r)
    lim = fb.limits()
    want = mp_toggles(*r)
    np.testing.assert_allclose(lim.dead_points, want, atol=1e-13)
    assert not lim.full_rotation
    assert set(np.round(lim.toggles, 12)) <= set(np.round(want, 12))
    # the mask agrees with where the closed form exists, away from the boundaries
    t = np.linspace(-math.pi, math.pi, 20001)
    t = t[np.min(np.abs(t[:, None] - np.asarray(want)[None, :]), axis=1) > 1e-9]
    t3, _ = closed_form_vectorized(*r, t)
    np.testing.assert_array_equal(lim.assemblable(t), ~np.isnan(t3))
    # 1e-9 rad inside each toggle the linkage assembles, 1e-6 outside it does not
    for tog in lim.toggles:
        inside = [tog + s for s in (1e-9, -1e-9) if lim.assemblable(tog + 2 * s)]
        outside = [tog + s for s in (1e-6, -1e-6) if not lim.assemblable(tog + s)]
        assert inside and outside
        for a in inside:
            assert fb.closed_form_status(a) in (pk.Status.CONVERGED, pk.Status.SINGULAR)
        for a in outside:
            assert fb.closed_form_status(a) == pk.Status.NOT_ASSEMBLABLE


@pytest.mark.slow  # 300 linkages sampled at 40 001 angles: about 2 s on 2 cores per mode
@pytest.mark.parametrize("mode", ["open", "crossed"])
def test_rocker_extremes_contain_every_sampled_angle(mode):
    rng = np.random.default_rng(7)
    t = np.linspace(-math.pi, math.pi, 40001)
    checked = crosses = 0
    for r in rng.uniform(0.2, 5.0, size=(300, 4)):
        lim = pk.FourBar(*r).limits(mode)
        _, t4 = closed_form_vectorized(*r, t, mode)
        t4 = t4[~np.isnan(t4)]
        if lim.rocker_min is None:
            # no extremes: the output turns fully or nothing assembles
            assert t4.size == 0 or np.ptp(np.unwrap(t4)) > 2 * math.pi - 0.05
            continue
        swing = lim.rocker_swing
        rel = np.mod(t4 - lim.rocker_min + 1e-9, 2 * math.pi) - 1e-9
        assert rel.max() <= swing + 1e-9
        # the interval [min, max] is read as it stands: max is never below min, even
        # across +-180 deg (then max > pi), and max - min is the swing
        assert -math.pi < lim.rocker_min <= math.pi
        assert lim.rocker_max >= lim.rocker_min
        assert lim.rocker_max - lim.rocker_min == pytest.approx(swing, abs=1e-12)
        crosses += lim.rocker_max > math.pi
        checked += 1
    assert crosses > 0  # some rocker swings across +-180 deg
    assert checked > 100


def test_change_point_parallelogram_passes_both_dead_points():
    lim = pk.FourBar(6, 2, 6, 2).limits()
    assert lim.full_rotation and lim.toggles.size == 0
    np.testing.assert_allclose(lim.dead_points, [0.0, math.pi])


def _change_point_linkages():
    """Change-point linkages, some with decimal lengths whose distances round (e.g.
    |1.8 - 0.6| and |1.8 - 0.6| computed apart): those that are exact change points."""
    from fractions import Fraction

    bases = [(6, 5, 3, 2), (6, 2, 6, 2), (3, 2, 5, 6), (5, 6, 2, 3), (6, 2, 2, 6), (2, 6, 2, 6)]
    out = []
    for base in bases:
        for k in (1.0, 0.1, 0.3, 0.7, 1.1, 3.3, 1e-3):
            r = tuple(x * k for x in base)
            f = [Fraction(x) for x in r]
            at0 = f[0] + f[3] == f[1] + f[2] or f[0] + f[2] == f[1] + f[3]
            atpi = f[0] + f[1] == f[2] + f[3]
            if at0 or atpi:
                out.append((r, [0.0] * at0 + [math.pi] * atpi))
    return out


@pytest.mark.parametrize("r, folds", _change_point_linkages(), ids=str)
@pytest.mark.parametrize("mode", ["open", "crossed"])
def test_change_point_folds_are_dead_points_where_the_sweep_is_singular(r, folds, mode):
    """A change-point linkage folds flat (all links collinear) at theta2 = 0 when
    r1 + r4 = r2 + r3 or r1 + r3 = r2 + r4, and at pi when r1 + r2 = r3 + r4 (exact
    rational arithmetic here). Those are dead points: limits() lists them, and the sweep
    says SINGULAR there; and every SINGULAR point of a sweep is a listed dead point. The
    decimal scalings (e.g. (6, 2, 6, 2) x 0.3) list their fold at 0 too, however the
    distances at the fold round."""
    fb = pk.FourBar(*r)
    assert fb.grashof().condition == "change-point"
    lim = fb.limits(mode)
    for f in folds:
        assert f in lim.dead_points.tolist(), (lim.dead_points, f)
        assert f not in lim.toggles.tolist()
    assert (fb.sweep(folds, mode=mode).status == pk.Status.SINGULAR).all()
    s = fb.sweep(np.linspace(-math.pi, math.pi, 721), mode=mode)
    sing = s.theta2[s.status == pk.Status.SINGULAR]
    assert sing.size
    for t in sing:
        gap = np.abs(np.angle(np.exp(1j * (lim.dead_points - t))))
        assert gap.min() < 1e-6, (t, lim.dead_points)


def test_never_assemblable_linkage_has_no_interval():
    lim = pk.FourBar(10, 1, 1, 1).limits()
    assert lim.intervals == () and lim.rocker_min is None and not lim.full_rotation
    assert np.all(pk.FourBar(10, 1, 1, 1).sweep().status == pk.Status.NOT_ASSEMBLABLE)
