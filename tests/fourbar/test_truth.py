"""Truth: results against independent values: a 50-digit mpmath circle intersection
(truth.mp_solve), mpmath derivatives of it, direct geometry, textbook numbers, and
exact rational arithmetic for the Grashof decision."""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import planarkin as pk
import pytest
from truth import (
    SEED_LINKAGE,
    angdiff,
    bound_rad,
    mp_rates,
    mp_solve,
    random_links,
)

MODES = ("open", "crossed")
PREDICTORS = ("quadratic", "tangent", "previous")
DEG = math.pi / 180


def max_err(r, theta2, theta3, theta4, mode):
    """Largest angular distance of (theta3, theta4) from the mpmath truth of ``mode``."""
    worst = 0.0
    for t2, t3, t4 in zip(theta2, theta3, theta4, strict=True):
        tr = mp_solve(r, t2, mode)
        worst = max(worst, angdiff(t3, tr.theta3), angdiff(t4, tr.theta4))
    return worst


# --- the independent truth itself ------------------------------------------------------


def test_mp_truth_closes_the_loop_and_labels_modes():
    rng = np.random.default_rng(11)
    n = 0
    for r in random_links(rng, 30, "grashof"):
        for t2 in rng.uniform(-4, 4, 4):
            for mode, sign in (("open", 1), ("crossed", -1)):
                p = mp_solve(r, t2, mode)
                if p is None:  # a Grashof double-rocker cannot reach every crank angle
                    continue
                n += 1
                with mpmath.workdps(50):
                    r1, r2, r3, r4 = (mpmath.mpf(float(x)) for x in r)
                    t = mpmath.mpf(float(t2))
                    f1 = r2 * mpmath.cos(t) + r3 * mpmath.cos(p.theta3)
                    f1 -= r4 * mpmath.cos(p.theta4) + r1
                    f2 = r2 * mpmath.sin(t) + r3 * mpmath.sin(p.theta3) - r4 * mpmath.sin(p.theta4)
                    assert abs(f1) < 1e-45 and abs(f2) < 1e-45
                    assert mpmath.sign(mpmath.sin(p.theta4 - p.theta3)) == sign
                    assert -mpmath.pi < p.theta3 <= mpmath.pi and -mpmath.pi < p.theta4 <= mpmath.pi
    assert n > 150


def test_mp_truth_design_md_value():
    """DESIGN.md: r=(6,2,5,5) at t2=0, open is t3=66.42 deg, t4=113.58 deg."""
    p = mp_solve(SEED_LINKAGE, 0.0, "open")
    assert round(math.degrees(p.t3), 2) == 66.42
    assert round(math.degrees(p.t4), 2) == 113.58
    # and by hand: A=(2,0), O4=(6,0), r3=r4=5: B=(4, sqrt(21))
    assert p.t3 == pytest.approx(math.atan2(math.sqrt(21), 2), abs=1e-15)
    assert p.t4 == pytest.approx(math.atan2(math.sqrt(21), -2), abs=1e-15)


# --- textbook and seed values --------------------------------------------------------


@pytest.mark.parametrize(
    "mode, t3_deg, t4_deg", [("open", 20.30, 57.32), ("crossed", -60.98, -98.00)]
)
def test_norton_example_4_1(mode, t3_deg, t4_deg):
    """Norton, Design of Machinery, Example 4-1: ground 100, crank 40, coupler 120,
    rocker 80, theta2 = 40 deg."""
    fb = pk.FourBar(100, 40, 120, 80)
    t2 = math.radians(40)
    tr = mp_solve(fb.lengths, t2, mode)
    assert round(math.degrees(tr.t3), 2) == t3_deg  # the truth agrees with the book
    assert round(math.degrees(tr.t4), 2) == t4_deg
    s = fb.solve(t2, mode=mode)
    assert s.status == pk.Status.CONVERGED and s.success
    assert round(math.degrees(s.theta3), 2) == t3_deg
    assert round(math.degrees(s.theta4), 2) == t4_deg
    assert angdiff(s.theta3, tr.theta3) < 1e-13 and angdiff(s.theta4, tr.theta4) < 1e-13
    c3, c4 = pk.reference.closed_form(fb, t2, mode)
    assert angdiff(c3, tr.theta3) < 1e-13 and angdiff(c4, tr.theta4) < 1e-13
    sw = fb.sweep([t2], mode=mode)
    assert angdiff(sw.theta3[0], tr.theta3) < 1e-13


def test_seed_case():
    """r = (6, 2, 5, 5), 361 crank angles: all converge, crank-rocker (GCRR); the angle
    ranges over the grid match the mpmath closed form and the printed 0.01 deg values."""
    fb = pk.FourBar(*SEED_LINKAGE)
    s = fb.sweep()
    assert len(s) == 361
    summ = s.summary()
    assert summ.converged == 361 and summ.points == 361 and summ.success_rate == 1.0
    assert summ.statuses == {"CONVERGED": 361}
    assert s.success.all()
    g = fb.grashof()
    assert (g.condition, g.barker, g.kind, g.is_grashof) == (
        "grashof",
        "GCRR",
        "crank-rocker",
        True,
    )
    assert (g.s, g.l, g.p, g.q) == (2.0, 6.0, 5.0, 5.0)
    truth = [mp_solve(SEED_LINKAGE, t, "open") for t in s.theta2]
    t3 = np.array([p.t3 for p in truth])
    t4 = np.array([p.t4 for p in truth])
    assert max_err(SEED_LINKAGE, s.theta2, s.theta3, s.theta4, "open") < 1e-9
    for got, want in (
        (s.theta4.min(), t4.min()),
        (s.theta4.max(), t4.max()),
        (s.theta3.min(), t3.min()),
        (s.theta3.max(), t3.max()),
    ):
        assert abs(got - want) < 1e-9
    printed = (101.54, 150.07, 29.93, 78.46)
    ours = np.degrees([t4.min(), t4.max(), t3.min(), t3.max()])
    np.testing.assert_allclose(ours, printed, atol=0.005 + 1e-9)


def test_seed_transmission_angle_extremes():
    """Law of cosines: at t2 = 0, |A O4| = 4 and cos mu = (25 + 25 - 16) / 50 = 0.68, the
    smallest transmission angle of this crank-rocker (47.156 deg); at t2 = pi, |A O4| = 8,
    mu = 106.26 deg whose acute value is 73.74 deg."""
    fb = pk.FourBar(*SEED_LINKAGE)
    s = fb.sweep()
    mu = np.asarray(fb.transmission_angle(s.theta3, s.theta4))
    assert mu.shape == (361,)
    assert mu.min() == pytest.approx(math.acos(0.68), abs=1e-12)
    assert np.argmin(mu) in (0, 360)
    assert mu[180] == pytest.approx(math.pi - math.acos(-0.28), abs=1e-12)
    assert ((mu >= 0) & (mu <= math.pi / 2)).all()
    # elementwise against the mpmath truth: acute angle between coupler and rocker
    for k in range(0, 361, 9):
        tr = mp_solve(SEED_LINKAGE, s.theta2[k], "open")
        with mpmath.workdps(50):
            want = float(mpmath.asin(abs(mpmath.sin(tr.theta4 - tr.theta3))))
        assert abs(mu[k] - want) < 1e-9


def test_branch_indicator_matches_truth():
    rng = np.random.default_rng(12)
    for r in random_links(rng, 30, "grashof"):
        fb = pk.FourBar(*r)
        t2 = rng.uniform(-4, 4, 5)
        for mode in MODES:
            t3, t4 = fb.closed_form(t2, mode)
            b = np.asarray(fb.branch_indicator(t3, t4))
            for k in range(5):
                tr = mp_solve(r, t2[k], mode)
                if tr is None:
                    assert np.isnan(b[k])
                    continue
                assert b[k] == pytest.approx(float(tr.sin34), abs=1e-12)
                assert np.sign(b[k]) == (1 if mode == "open" else -1)


# --- sweeps and the closed form against the truth ------------------------------------


@pytest.mark.parametrize("mode", MODES)
def test_seed_sweep_default_within_1e9(mode):
    """Default (quadratic) predictor: every point within 1e-9 rad of the truth, and of
    the kernel's closed form of the same mode."""
    fb = pk.FourBar(*SEED_LINKAGE)
    s = fb.sweep(mode=mode)
    assert s.success.all()
    err = max_err(SEED_LINKAGE, s.theta2, s.theta3, s.theta4, mode)
    assert err < 1e-9, err
    c3, c4 = fb.closed_form(s.theta2, mode)
    assert np.abs(np.angle(np.exp(1j * (s.theta3 - c3)))).max() < 1e-9
    assert np.abs(np.angle(np.exp(1j * (s.theta4 - c4)))).max() < 1e-9


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("predictor", PREDICTORS)
def test_seed_sweep_within_residual_bound(mode, predictor):
    """Every predictor: the error is within the first-order residual bound
    sqrt(2) * residual * L / (r_other * |sin(t4 - t3)|) of each point."""
    fb = pk.FourBar(*SEED_LINKAGE)
    s = fb.sweep(mode=mode, predictor=predictor)
    assert s.success.all()
    assert (s.residual < 1e-9).all()
    for k in range(361):
        tr = mp_solve(SEED_LINKAGE, s.theta2[k], mode)
        assert angdiff(s.theta3[k], tr.theta3) <= bound_rad(
            SEED_LINKAGE, s.residual[k], tr.sin34, 3
        )
        assert angdiff(s.theta4[k], tr.theta4) <= bound_rad(
            SEED_LINKAGE, s.residual[k], tr.sin34, 4
        )
    # and in absolute terms the seed's printed accuracy (a few 1e-9 rad at most)
    assert max_err(SEED_LINKAGE, s.theta2, s.theta3, s.theta4, mode) < 5e-9


# about 0.8 s a predictor; every predictor is checked on the seed linkage above
@pytest.mark.parametrize(
    "predictor",
    ["quadratic", *(pytest.param(p, marks=pytest.mark.slow) for p in ("tangent", "previous"))],
)
def test_random_sweeps_within_residual_bound(predictor):
    """Random Grashof and non-Grashof linkages: each converged point within the residual
    bound of the mpmath truth of its mode; each NOT_ASSEMBLABLE point has no real
    solution in mpmath either."""
    rng = np.random.default_rng(13)
    links = np.vstack([random_links(rng, 25, "grashof"), random_links(rng, 15, "non-grashof")])
    t2 = np.arange(0, 361, 3) * DEG
    for r in links:
        fb = pk.FourBar(*r)
        for mode in MODES:
            s = fb.sweep(t2, mode=mode, predictor=predictor)
            for k in range(0, len(t2), 2):
                tr = mp_solve(r, t2[k], mode)
                st = s.status[k]
                if tr is None:
                    assert st == pk.Status.NOT_ASSEMBLABLE
                    continue
                if st != pk.Status.CONVERGED:  # only next to a dead point
                    assert st in (pk.Status.SINGULAR, pk.Status.NOT_ASSEMBLABLE)
                    assert abs(float(tr.sin34)) < 1e-6
                    continue
                assert s.residual[k] < 1e-9
                assert angdiff(s.theta3[k], tr.theta3) <= bound_rad(r, s.residual[k], tr.sin34, 3)
                assert angdiff(s.theta4[k], tr.theta4) <= bound_rad(r, s.residual[k], tr.sin34, 4)


def test_closed_form_against_mpmath():
    """The closed form within 1e-13 rad of the 50-digit truth wherever the problem is
    well-conditioned (4e-15 L / (r_other |sin(t4-t3)|) <= 1e-13: 99% of random points),
    and within that conditioning bound elsewhere; NaN exactly where mpmath finds no
    real solution."""
    rng = np.random.default_rng(14)
    links = np.vstack([random_links(rng, 60, "grashof"), random_links(rng, 40, "non-grashof")])
    n_checked = n_13 = 0
    for r in links:
        fb = pk.FourBar(*r)
        t2 = np.concatenate([rng.uniform(-math.pi, math.pi, 8), rng.uniform(-50, 50, 2)])
        big = max(r)
        for mode in MODES:
            c3, c4 = fb.closed_form(t2, mode)
            st = fb.closed_form_status(t2, mode)
            for k in range(len(t2)):
                tr = mp_solve(r, t2[k], mode)
                if tr is None:
                    assert math.isnan(c3[k]) and math.isnan(c4[k])
                    assert st[k] == pk.Status.NOT_ASSEMBLABLE
                    continue
                n_checked += 1
                s34 = abs(float(tr.sin34))
                for got, want, other in ((c3[k], tr.theta3, r[2]), (c4[k], tr.theta4, r[3])):
                    cond = 4e-15 * big / (other * s34)
                    if cond <= 1e-13:
                        n_13 += 1
                        assert angdiff(got, want) < 1e-13
                    else:
                        assert angdiff(got, want) < cond
                assert st[k] == (pk.Status.CONVERGED if s34 > 1e-6 else st[k])
    assert n_checked > 600
    assert n_13 > 0.95 * 2 * n_checked


def test_closed_form_scalar_and_reference_against_mpmath():
    fb = pk.FourBar(*SEED_LINKAGE)
    for t2 in (0.0, 0.3, -2.0, math.pi, 100.0):
        for mode in MODES:
            tr = mp_solve(SEED_LINKAGE, t2, mode)
            c3, c4 = pk.reference.closed_form(fb, t2, mode)
            assert angdiff(c3, tr.theta3) < 1e-14 and angdiff(c4, tr.theta4) < 1e-14


# --- velocity and acceleration ---------------------------------------------------------


@pytest.mark.parametrize("mode", MODES)
def test_seed_sweep_rates_against_mpmath_derivatives(mode):
    """omega = x'(t2) w2 and alpha = x'' w2^2 + x' a2, x'(t2) and x'' by mpmath.diff of
    the 50-digit closed form."""
    fb = pk.FourBar(*SEED_LINKAGE)
    w2, a2 = 10.0, -3.0
    s = fb.sweep(mode=mode, omega2=w2, alpha2=a2)
    for k in range(0, 361, 15):
        w3, w4, al3, al4 = mp_rates(SEED_LINKAGE, s.theta2[k], mode, w2, a2)
        assert s.omega3[k] == pytest.approx(w3, rel=1e-9, abs=1e-9)
        assert s.omega4[k] == pytest.approx(w4, rel=1e-9, abs=1e-9)
        assert s.alpha3[k] == pytest.approx(al3, rel=1e-8, abs=1e-8)
        assert s.alpha4[k] == pytest.approx(al4, rel=1e-8, abs=1e-8)


def test_velocity_acceleration_against_mpmath_derivatives():
    """fb.velocity/acceleration at the (accurate) closed-form positions of random
    linkages, away from dead points, against mpmath.diff of the mpmath closed form."""
    rng = np.random.default_rng(15)
    n = 0
    for r in random_links(rng, 16, "grashof", lo=0.5, hi=5.0):
        fb = pk.FourBar(*r)
        for mode in MODES:
            t2 = rng.uniform(-math.pi, math.pi, 3)
            t3, t4 = fb.closed_form(t2, mode)
            w2 = rng.uniform(-5, 5, 3)
            a2 = rng.uniform(-5, 5, 3)
            w3, w4 = fb.velocity(t2, t3, t4, w2)
            al3, al4 = fb.acceleration(t2, t3, t4, w2, a2)
            for k in range(3):
                if np.isnan(t3[k]):
                    continue
                tr = mp_solve(r, t2[k], mode)
                if abs(float(tr.sin34)) < 0.05:
                    continue
                n += 1
                want = mp_rates(r, t2[k], mode, w2[k], a2[k])
                scale_w = abs(w2[k]) * max(r) / min(r) + 1.0
                scale_a = (w2[k] ** 2 + abs(a2[k])) * (max(r) / min(r)) ** 2 + 1.0
                tol_w, tol_a = 1e-10 * scale_w, 1e-9 * scale_a
                assert abs(w3[k] - want[0]) < tol_w and abs(w4[k] - want[1]) < tol_w
                assert abs(al3[k] - want[2]) < tol_a and abs(al4[k] - want[3]) < tol_a
    assert n >= 30


def test_velocity_textbook_relation():
    """Kennedy's theorem-free check: the velocity of B computed along the crank and
    coupler equals the velocity of B along the rocker (loop-closure derivative), in
    mpmath from the kernel's omega3, omega4."""
    fb = pk.FourBar(100, 40, 120, 80)
    t2 = math.radians(40)
    s = fb.sweep([t2], omega2=25.0, alpha2=15.0, mode="open")
    with mpmath.workdps(50):
        t2m, t3, t4 = (mpmath.mpf(float(x)) for x in (t2, s.theta3[0], s.theta4[0]))
        w3, w4 = mpmath.mpf(float(s.omega3[0])), mpmath.mpf(float(s.omega4[0]))
        vb_a = (-40 * 25 * mpmath.sin(t2m) - 120 * w3 * mpmath.sin(t3),
                40 * 25 * mpmath.cos(t2m) + 120 * w3 * mpmath.cos(t3))  # fmt: skip
        vb_b = (-80 * w4 * mpmath.sin(t4), 80 * w4 * mpmath.cos(t4))
        assert abs(vb_a[0] - vb_b[0]) < 1e-9 and abs(vb_a[1] - vb_b[1]) < 1e-9


# --- coupler point -----------------------------------------------------------------------


def test_coupler_point_direct_geometry():
    """P = A + p (cos(t3 + delta), sin(t3 + delta)), A = r2 (cos t2, sin t2), in mpmath;
    also: the point at p = r3, delta = 0 is the rocker pin B = O4 + r4 (cos t4, sin t4)."""
    rng = np.random.default_rng(16)
    for r in random_links(rng, 20, "grashof"):
        fb = pk.FourBar(*r)
        t2 = rng.uniform(-4, 4, 6)
        t3, t4 = fb.closed_form(t2, "open")
        p, delta = float(rng.uniform(0.1, 5)), float(rng.uniform(-4, 4))
        x, y = fb.coupler_point(t2, t3, p, delta)
        for k in range(6):
            if np.isnan(t3[k]):
                assert np.isnan(x[k]) and np.isnan(y[k])
                continue
            with mpmath.workdps(50):
                a2, a3 = mpmath.mpf(float(t2[k])), mpmath.mpf(float(t3[k]))
                ax, ay = r[1] * mpmath.cos(a2), r[1] * mpmath.sin(a2)
                px = ax + p * mpmath.cos(a3 + delta)
                py = ay + p * mpmath.sin(a3 + delta)
            scale = r[1] + p
            assert abs(x[k] - float(px)) < 1e-14 * scale
            assert abs(y[k] - float(py)) < 1e-14 * scale
        bx, by = fb.coupler_point(t2, t3, float(r[2]), 0.0)
        for k in range(6):
            tr = mp_solve(r, t2[k], "open")
            if tr is None:
                continue
            with mpmath.workdps(50):
                ex = r[0] + r[3] * mpmath.cos(tr.theta4)
                ey = r[3] * mpmath.sin(tr.theta4)
            assert abs(bx[k] - float(ex)) < 1e-12 * max(r)
            assert abs(by[k] - float(ey)) < 1e-12 * max(r)


def test_coupler_curve_follows_sweep():
    """The curve is the coupler point at each swept (theta2, theta3), and so within the
    sweep's angle error (times p) of the curve through the mpmath truth."""
    fb = pk.FourBar(*SEED_LINKAGE)
    s = fb.sweep(np.arange(0, 361, 30) * DEG)  # coarse: residuals up to tol
    x, y = fb.coupler_curve(s, 3.0, 0.5)
    for k in range(len(s)):
        tr = mp_solve(SEED_LINKAGE, s.theta2[k], "open")
        bound = 3.0 * bound_rad(SEED_LINKAGE, s.residual[k], tr.sin34, 3) + 1e-14
        with mpmath.workdps(50):
            t2 = mpmath.mpf(float(s.theta2[k]))
            for t3, tol in ((mpmath.mpf(float(s.theta3[k])), 1e-14), (tr.theta3, bound)):
                px = 2 * mpmath.cos(t2) + 3 * mpmath.cos(t3 + mpmath.mpf(0.5))
                py = 2 * mpmath.sin(t2) + 3 * mpmath.sin(t3 + mpmath.mpf(0.5))
                assert abs(x[k] - float(px)) < tol and abs(y[k] - float(py)) < tol


# --- Grashof / Barker ----------------------------------------------------------------------

# Norton, Design of Machinery, Table 2-4. (r1 ground, r2 input, r3 coupler, r4 output)
BARKER = [
    # Grashof, S + L < P + Q: 2 + 7 < 5 + 6; which link is shortest
    ((5, 2, 7, 6), "GCRR", "crank-rocker", "grashof"),  # shortest = input
    ((2, 5, 7, 6), "GCCC", "double-crank", "grashof"),  # shortest = ground
    ((5, 7, 2, 6), "GRCR", "double-rocker", "grashof"),  # shortest = coupler
    ((5, 7, 6, 2), "GRRC", "rocker-crank", "grashof"),  # shortest = output
    # non-Grashof, S + L > P + Q: 2 + 9 > 3 + 4; which link is longest
    ((9, 2, 3, 4), "RRR1", "triple-rocker", "non-grashof"),  # longest = ground
    ((2, 9, 3, 4), "RRR2", "triple-rocker", "non-grashof"),  # longest = input
    ((2, 3, 9, 4), "RRR3", "triple-rocker", "non-grashof"),  # longest = coupler
    ((2, 3, 4, 9), "RRR4", "triple-rocker", "non-grashof"),  # longest = output
    # change point, S + L = P + Q: 2 + 6 = 3 + 5; which link is shortest
    ((2, 6, 3, 5), "SCCC", "change-point", "change-point"),  # shortest = ground
    ((5, 2, 6, 3), "SCRR", "change-point", "change-point"),  # shortest = input
    ((6, 5, 2, 3), "SRCR", "change-point", "change-point"),  # shortest = coupler
    ((6, 5, 3, 2), "SRRC", "change-point", "change-point"),  # shortest = output
    # two equal pairs: parallelogram and kite (deltoid)
    ((6, 2, 6, 2), "S2X", "change-point", "change-point"),
    ((2, 2, 6, 6), "S2X", "change-point", "change-point"),
    ((2, 6, 2, 6), "S2X", "change-point", "change-point"),
    ((6, 2, 2, 6), "S2X", "change-point", "change-point"),
    # all four equal
    ((3, 3, 3, 3), "S3X", "change-point", "change-point"),
]


def exact_condition(r):
    s = sorted(Fraction(float(x)) for x in r)
    lhs, rhs = s[0] + s[3], s[1] + s[2]
    return "grashof" if lhs < rhs else "non-grashof" if lhs > rhs else "change-point"


@pytest.mark.parametrize("r, barker, kind, condition", BARKER)
def test_barker_class(r, barker, kind, condition):
    assert exact_condition(r) == condition  # the example is what it claims
    g = pk.FourBar(*r).grashof()
    assert (g.barker, g.kind, g.condition) == (barker, kind, condition)
    assert g.is_grashof == (condition == "grashof")
    s = sorted(float(x) for x in r)
    assert (g.s, g.p, g.q, g.l) == tuple(s)
    assert isinstance(g.description, str) and g.description


def test_all_fourteen_barker_classes_covered():
    assert len({b for _, b, _, _ in BARKER}) == 14


@pytest.mark.parametrize("scale", [1.0, 2.0**-40, 2.0**40, 0.1, 1e7])
def test_barker_class_scale_free(scale):
    for r, barker, _, condition in BARKER:
        rr = [x * scale for x in r]
        if exact_condition(rr) != condition:  # a non-binary scale can break an equality
            continue
        assert pk.FourBar(*rr).grashof().barker == barker


def test_change_point_decided_exactly():
    """[0.5, 0.25, 0.375, 0.375]: sums exactly equal in binary -> change point;
    [0.1, 0.4, 0.3, 0.2]: 0.1 + 0.4 and 0.2 + 0.3 both round to 0.5 in floating
    point, but the exact binary sums differ, so it is not a change point."""
    assert Fraction(0.5) + Fraction(0.25) == Fraction(0.375) + Fraction(0.375)
    assert pk.FourBar(0.5, 0.25, 0.375, 0.375).grashof().condition == "change-point"

    assert 0.1 + 0.4 == 0.2 + 0.3  # in floating point they look equal...
    exact = Fraction(0.1) + Fraction(0.4) - (Fraction(0.2) + Fraction(0.3))
    assert exact != 0  # ...but are not
    g = pk.FourBar(0.1, 0.4, 0.3, 0.2).grashof()
    assert g.condition == exact_condition([0.1, 0.4, 0.3, 0.2])
    assert g.condition == ("grashof" if exact < 0 else "non-grashof")
    assert g.condition != "change-point"


def test_grashof_condition_random_exact():
    """The condition agrees with exact rational arithmetic on random lengths, including
    lengths built to sit on or one ulp off the change-point equality."""
    rng = np.random.default_rng(17)
    cases = [list(r) for r in rng.uniform(0.1, 10, (300, 4))]
    for _ in range(200):
        s, big, p = sorted(rng.uniform(0.1, 10, 3))
        q = s + big - p  # often exactly a change point, sometimes a rounding off
        if q <= 0:
            continue
        for qq in (q, np.nextafter(q, 0), np.nextafter(q, 20)):
            r = [s, big, p, float(qq)]
            rng.shuffle(r)
            cases.append(r)
    kinds = set()
    for r in cases:
        want = exact_condition(r)
        kinds.add(want)
        assert pk.FourBar(*r).grashof().condition == want, r
    assert kinds == {"grashof", "non-grashof", "change-point"}
