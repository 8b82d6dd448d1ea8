"""Extremes: scale, huge crank angles, extreme length ratios, non-Grashof sweeps,
toggles and dead points, branch jumps, change-point linkages, NaN crank angles.
Every number is checked against the 50-digit mpmath truth (truth.mp_solve)."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import planarkin as pk
import pytest
from numpy.testing import assert_array_equal
from truth import (
    SEED_LINKAGE,
    angdiff,
    bound_rad,
    mp_solve,
    mp_toggles,
    near_toggle,
    random_links,
    resolvable,
)

MODES = ("open", "crossed")
DEG = math.pi / 180
S = pk.Status


def wrapped_diff(a, b):
    """|a - b| reduced to [0, pi], elementwise (float64)."""
    return np.abs(np.angle(np.exp(1j * (np.asarray(a) - np.asarray(b)))))


def in_range(a):
    a = np.asarray(a)
    a = a[~np.isnan(a)]
    return bool(((a > -math.pi) & (a <= math.pi)).all())


@pytest.fixture(scope="module")
def mixed_links():
    rng = np.random.default_rng(31)
    return np.vstack(
        [
            [SEED_LINKAGE],
            random_links(rng, 60, "grashof"),
            random_links(rng, 40, "non-grashof"),
        ]
    )


# --- scale -----------------------------------------------------------------------------


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("k", [-30, -20, -7, -1, 1, 5, 20, 30])
def test_power_of_two_scale_is_bit_identical(mixed_links, mode, k):
    """Every length times 2**k: the same angles, iteration counts, statuses and
    residuals, bit for bit (scaling by a power of two is exact in binary)."""
    t2 = np.concatenate([np.arange(361) * DEG, np.linspace(-13, 13, 50), [np.nan, 1e12]])
    base = pk.sweep_batch(mixed_links, t2, mode=mode)
    scaled = pk.sweep_batch(mixed_links * 2.0**k, t2, mode=mode)
    for f in ("theta3", "theta4", "status", "nit", "residual"):
        assert_array_equal(getattr(scaled, f), getattr(base, f), err_msg=f)
    c3, c4 = pk.closed_form_batch(mixed_links, t2, mode)
    d3, d4 = pk.closed_form_batch(mixed_links * 2.0**k, t2, mode)
    assert_array_equal(c3, d3)
    assert_array_equal(c4, d4)
    fb, fbs = pk.FourBar(*SEED_LINKAGE), pk.FourBar(*(x * 2.0**k for x in SEED_LINKAGE))
    for t in (0.0, 1.0, -2.5):
        a, b = fb.solve(t, mode=mode, history=True), fbs.solve(t, mode=mode, history=True)
        assert (a.theta3, a.theta4, a.status, a.nit, a.residual) == (
            b.theta3, b.theta4, b.status, b.nit, b.residual)  # fmt: skip
        assert_array_equal(a.history, b.history)


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("scale", [1e-9, 1e-6, 1e6, 1e9])
def test_decimal_scale_same_angles_and_statuses(mixed_links, mode, scale):
    """Every length times 1e-9 .. 1e9 (the scaled lengths are rounded, so not exact):
    identical statuses and the same angles within 1e-12 rad. Each answer carries its last
    Newton correction (errors ~1e-15), so the only difference left is the exact solution
    moving with the rounded data, ~8e-15 L / (r_other |sin(t4 - t3)|): at the rare point
    where that exceeds 1e-12, the difference is held to it instead."""
    base = pk.sweep_batch(mixed_links, mode=mode)
    sc = pk.sweep_batch(mixed_links * scale, mode=mode)
    assert_array_equal(sc.status, base.status)
    ok = base.status == S.CONVERGED
    assert ok.sum() > 0.25 * ok.size
    r = mixed_links
    big = r.max(axis=1)[:, None]
    sin34 = np.abs(np.sin(base.theta4 - base.theta3))
    n_strict = 0
    for which, col in ((3, 2), (4, 3)):
        d = wrapped_diff(getattr(sc, f"theta{which}"), getattr(base, f"theta{which}"))[ok]
        data = (8e-15 * big / (r[:, col][:, None] * sin34))[ok]
        strict = data <= 1e-12
        n_strict += strict.sum()
        assert (d[strict] <= 1e-12).all(), d[strict].max()
        assert (d[~strict] <= 2 * data[~strict]).all()
    assert n_strict > 0.99 * 2 * ok.sum()


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("scale", [1e-9, 1e-6, 1e6, 1e9])
def test_decimal_scale_seed_within_1e12(mode, scale):
    fb = pk.FourBar(*SEED_LINKAGE)
    a = fb.sweep(mode=mode)
    b = pk.FourBar(*(x * scale for x in SEED_LINKAGE)).sweep(mode=mode)
    assert_array_equal(a.status, b.status)
    assert wrapped_diff(a.theta3, b.theta3).max() < 1e-12
    assert wrapped_diff(a.theta4, b.theta4).max() < 1e-12


# --- huge and special crank angles ---------------------------------------------------------

HUGE = [1e3, -1e3, 1e10, 1e16, 1e300, -1e300, 1.7976931348623157e308, 5e-324, -0.0, math.pi,
        -math.pi, 2 * math.pi, 7 * math.pi, -1e-300]  # fmt: skip


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("t2", HUGE)
def test_any_finite_crank_angle(mode, t2):
    """However large, a finite crank angle is reduced correctly: results in (-pi, pi]
    and equal to the mpmath solution at the same angle (mpmath reduces it exactly)."""
    fb = pk.FourBar(*SEED_LINKAGE)
    tr = mp_solve(SEED_LINKAGE, t2, mode)
    s = fb.solve(t2, mode=mode)
    assert s.status == S.CONVERGED
    assert in_range([s.theta3, s.theta4])
    assert angdiff(s.theta3, tr.theta3) < 1e-12 and angdiff(s.theta4, tr.theta4) < 1e-12
    sw = fb.sweep([t2, t2, 0.5, t2], mode=mode)
    assert (sw.status == S.CONVERGED).all()
    assert in_range(sw.theta3) and in_range(sw.theta4)
    for k in (0, 1, 3):
        assert angdiff(sw.theta3[k], tr.theta3) < 1e-9 and angdiff(sw.theta4[k], tr.theta4) < 1e-9
    c3, c4 = fb.closed_form(np.array([t2]), mode)
    assert angdiff(c3[0], tr.theta3) < 1e-12 and angdiff(c4[0], tr.theta4) < 1e-12
    r3, r4 = pk.reference.closed_form(fb, t2, mode)
    assert angdiff(r3, tr.theta3) < 1e-12 and angdiff(r4, tr.theta4) < 1e-12


@pytest.mark.parametrize("t2", [math.nan, math.inf, -math.inf])
def test_non_finite_crank_angle_is_a_status(t2):
    fb = pk.FourBar(*SEED_LINKAGE)
    for mode in MODES:
        s = fb.solve(t2, mode=mode, history=True)
        assert s.status == S.NON_FINITE and not s.success and s.nit == 0
        assert math.isnan(s.theta3) and math.isnan(s.theta4)
        r = pk.reference.solve(fb, t2, mode=mode)
        assert r.status == S.NON_FINITE
        c3, c4 = fb.closed_form(np.array([t2]), mode)
        assert np.isnan(c3).all() and np.isnan(c4).all()
        assert fb.closed_form_status(np.array([t2]), mode)[0] == S.NON_FINITE


def test_all_returned_angles_in_half_open_range(mixed_links):
    rng = np.random.default_rng(32)
    t2 = np.concatenate([rng.uniform(-1e6, 1e6, 100), np.arange(-720, 721, 5) * DEG])
    for mode in MODES:
        for pred in ("quadratic", "tangent", "previous"):
            b = pk.sweep_batch(mixed_links, t2, mode=mode, predictor=pred)
            assert in_range(b.theta3) and in_range(b.theta4)
            assert not np.isnan(b.theta3[b.status == S.CONVERGED]).any()
            assert np.isnan(b.theta3[b.status != S.CONVERGED]).all()
            assert np.isnan(b.theta4[b.status != S.CONVERGED]).all()


# --- extreme ratios ------------------------------------------------------------------------

RATIOS = [
    (1.0, 1e-6, 1.0, 1.0),  # crank 1e-6 of the others
    (5.0, 5e-6, 4.0, 3.0),
    (3.0, 2e-6, 7.0, 5.0),
    (1e4, 1.0, 1e4, 1e4),  # coupler 1e4 times the crank
    (1e4, 1.0, 1e4, 1.5e4),
    (7e3, 1.0, 1e4, 8e3),
]


@pytest.mark.parametrize("r", RATIOS)
@pytest.mark.parametrize("mode", MODES)
def test_extreme_ratios(r, mode):
    """solve() and the closed form within 1e-9 rad of the truth (measured ~4e-16); the
    default sweep within its residual bound and within 1e-9 rad (measured 9.95e-10: the
    Newton correction, an estimate of the angle error, must be below tol), and at
    tol = 1e-11 within 1e-9 rad with room (measured 1e-11)."""
    fb = pk.FourBar(*r)
    assert fb.grashof().barker == "GCRR"
    s = fb.sweep(mode=mode)
    tight = fb.sweep(mode=mode, tol=1e-11)
    assert s.success.all() and tight.success.all()
    for k in range(0, 361, 4):
        t2 = s.theta2[k]
        tr = mp_solve(r, t2, mode)
        p = fb.solve(t2, mode=mode)
        assert p.status == S.CONVERGED
        assert angdiff(p.theta3, tr.theta3) < 1e-9 and angdiff(p.theta4, tr.theta4) < 1e-9
        c3, c4 = pk.reference.closed_form(fb, t2, mode)
        assert angdiff(c3, tr.theta3) < 1e-9 and angdiff(c4, tr.theta4) < 1e-9
        assert angdiff(s.theta3[k], tr.theta3) <= bound_rad(r, s.residual[k], tr.sin34, 3)
        assert angdiff(s.theta4[k], tr.theta4) <= bound_rad(r, s.residual[k], tr.sin34, 4)
        assert angdiff(s.theta3[k], tr.theta3) < 1e-9 and angdiff(s.theta4[k], tr.theta4) < 1e-9
        assert angdiff(tight.theta3[k], tr.theta3) < 1e-9
        assert angdiff(tight.theta4[k], tr.theta4) < 1e-9


# --- non-Grashof sweeps, toggles and dead points ---------------------------------------------

NON_GRASHOF = [
    (5.0, 3.0, 4.0, 3.0),
    (3.0, 4.0, 9.0, 5.0),
    (2.0, 6.0, 3.0, 4.5),
    (7.0, 4.0, 2.5, 3.0),
    (2.0, 9.0, 3.0, 4.0),
]


@pytest.mark.parametrize("r", NON_GRASHOF)
@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("predictor", ["quadratic", "tangent", "previous"])
def test_non_grashof_full_turn(r, mode, predictor):
    """0..360 deg: unreachable crank angles are NOT_ASSEMBLABLE with nit == 0 and NaN
    angles; reachable ones are solved on the requested mode, also after an unreachable
    span (the sweep carries on)."""
    fb = pk.FourBar(*r)
    assert fb.grashof().condition == "non-grashof"
    t2 = np.arange(0, 721, 1) * DEG  # two turns: the sweep re-enters reachable spans
    s = fb.sweep(t2, mode=mode, predictor=predictor)
    n_na = n_ok = 0
    after_gap = False
    sign = 1 if mode == "open" else -1
    for k in range(len(t2)):
        tr = mp_solve(r, t2[k], mode)
        if tr is None and s.status[k] == S.SINGULAR:
            # e.g. (2, 9, 3, 4) at t2 = 360 deg: cos(float(2 pi)) rounds to 1, and the
            # kernel sees the toggle |A O4| = r3 + r4 exactly; the exact float angle is
            # 2.4e-16 rad off it, out of reach. Flagged either way.
            assert near_toggle(r, t2[k], 1e-12)
            continue
        if tr is None:
            assert s.status[k] == S.NOT_ASSEMBLABLE and s.nit[k] == 0
            assert np.isnan(s.theta3[k]) and np.isnan(s.theta4[k])
            n_na += 1
            after_gap = True
            continue
        if s.status[k] != S.CONVERGED:
            # only right at a limit: |sin(t4 - t3)| tiny there
            assert s.status[k] in (S.SINGULAR, S.NOT_ASSEMBLABLE)
            assert abs(float(tr.sin34)) < 1e-6
            continue
        n_ok += 1
        assert np.sign(math.sin(s.theta4[k] - s.theta3[k])) == sign
        assert angdiff(s.theta3[k], tr.theta3) <= bound_rad(r, s.residual[k], tr.sin34, 3)
        assert angdiff(s.theta4[k], tr.theta4) <= bound_rad(r, s.residual[k], tr.sin34, 4)
        if after_gap:
            after_gap = False  # first point solved past an unreachable span
    assert n_na > 20
    if r != (2.0, 9.0, 3.0, 4.0):  # (2, 9, 3, 4) reaches only t2 = 0 (a toggle)
        assert n_ok > 20


def _inside(r, toggle, distance, mode="open"):
    """The float crank angle ``distance`` rad from the mpmath ``toggle`` on the side where
    the linkage assembles, or None."""
    for side in (1, -1):
        with mpmath.workdps(50):
            probe = float(toggle + side * mpmath.mpf("1e-4"))
            t = float(toggle + side * mpmath.mpf(distance))
        if mp_solve(r, probe, mode) is not None:
            return t
    return None


def _toggle_cases(rng, n):
    links = np.vstack(
        [random_links(rng, n, "non-grashof"), random_links(rng, n, "grashof", lo=0.5, hi=5)]
    )
    for r in links:
        for tg in mp_toggles(r):
            yield r, tg


def test_one_nanorad_inside_toggle():
    """1e-9 rad inside a toggle limit: solve() (from the closed form), the reference and
    the closed form are CONVERGED within 1e-9 rad of mpmath, or SINGULAR; never a wrong
    number, never NOT_ASSEMBLABLE (the point assembles by ~1e-9 rad). So is a sweep that
    reaches the point by continuation (see also test_sweep_into_toggle_within_1e9)."""
    rng = np.random.default_rng(33)
    n = 0
    for r, tg in _toggle_cases(rng, 40):
        t = _inside(r, tg, "1e-9")
        if t is None:
            continue
        fb = pk.FourBar(*r)
        for mode in MODES:
            tr = mp_solve(r, t, mode)
            assert tr is not None
            for s in (fb.solve(t, mode=mode), pk.reference.solve(fb, t, mode=mode)):
                n += 1
                assert s.status in (S.CONVERGED, S.SINGULAR), s
                if s.status == S.CONVERGED:
                    assert angdiff(s.theta3, tr.theta3) < 1e-9
                    assert angdiff(s.theta4, tr.theta4) < 1e-9
            c3, c4 = fb.closed_form(np.array([t]), mode)
            assert angdiff(c3[0], tr.theta3) < 1e-9 and angdiff(c4[0], tr.theta4) < 1e-9
            # a sweep that approaches from 1e-3 rad away, by continuation
            pts = [_inside(r, tg, "1e-3"), _inside(r, tg, "1e-6"), t]
            sw = fb.sweep(pts, mode=mode)
            assert sw.status[-1] in (S.CONVERGED, S.SINGULAR)
            if sw.status[-1] == S.CONVERGED:
                assert angdiff(sw.theta3[-1], tr.theta3) < 1e-9
                assert angdiff(sw.theta4[-1], tr.theta4) < 1e-9
    assert n > 150


@pytest.mark.parametrize("predictor", ["quadratic", "tangent", "previous"])
@pytest.mark.parametrize("mode", MODES)
def test_sweep_into_toggle_within_1e9(predictor, mode):
    """(5, 3, 4, 3): toggle at t2 = 120 deg exactly (cos t2 = (25 + 9 - 49) / 30 = -1/2).
    Sweep 117, 118, 119 deg, then 120 deg - 1e-9 rad: CONVERGED within 1e-9 rad, or
    SINGULAR. A residual below tol is not enough there (one of 7.0e-10 comes with theta3
    1.48e-5 rad off): the Newton correction must be below tol too."""
    r = (5.0, 3.0, 4.0, 3.0)
    (tg,) = mp_toggles(r)
    assert abs(float(tg) - 2 * math.pi / 3) < 1e-15
    with mpmath.workdps(50):
        pts = [float(tg - k * mpmath.pi / 180) for k in (3, 2, 1)] + [
            float(tg - mpmath.mpf("1e-9"))
        ]
    sw = pk.FourBar(*r).sweep(pts, mode=mode, predictor=predictor)
    tr = mp_solve(r, pts[-1], mode)
    assert sw.status[-1] in (S.CONVERGED, S.SINGULAR)
    if sw.status[-1] == S.CONVERGED:
        assert angdiff(sw.theta3[-1], tr.theta3) < 1e-9
        assert angdiff(sw.theta4[-1], tr.theta4) < 1e-9


APPROACH = [
    (5.0, 3.0, 4.0, 3.0),
    (4.0, 3.0, 2.0, 3.5),
    # 1e-14 rad from its toggle at 0.9014 rad: CONVERGED 1.32e-9 rad off unless the
    # singular threshold weighs |sin(t4 - t3)| by min(r3, r4) / L
    (7.0, 4.0, 2.5, 3.0),
]


@pytest.mark.parametrize("r", APPROACH)
def test_approach_toggle_decades(r):
    """Distances 1e-3 .. 1e-15 rad from each toggle: every point within 1e-9 rad of the
    truth or flagged (SINGULAR; NOT_ASSEMBLABLE only where rounding the crank angle's
    cosine can cross the limit, |sin(t4 - t3)| < 1e-7). Down to 1e-11 rad everything
    converges."""
    fb = pk.FourBar(*r)
    switch = []
    for tg in mp_toggles(r):
        for mode in MODES:
            first_flag = None
            for k in range(3, 16):
                t = _inside(r, tg, f"1e-{k}", mode)
                tr = mp_solve(r, t, mode)
                s = fb.solve(t, mode=mode)
                sw = fb.sweep([t], mode=mode)
                assert sw.status[0] == s.status
                if s.status == S.CONVERGED:
                    assert angdiff(s.theta3, tr.theta3) < 1e-9, (k, mode)
                    assert angdiff(s.theta4, tr.theta4) < 1e-9, (k, mode)
                else:
                    assert s.status in (S.SINGULAR, S.NOT_ASSEMBLABLE)
                    if s.status == S.NOT_ASSEMBLABLE:
                        assert abs(float(tr.sin34)) < 1e-7
                    assert k > 11
                    first_flag = first_flag or k
            switch.append(first_flag)
    assert all(f is not None for f in switch)  # a dead point is flagged at last


# Points a plain |sin(t4 - t3)| < 1e-7 threshold passes as CONVERGED 1.5e-9 and 1.3e-8 rad
# off; the documented threshold is on the conditioning |sin(t4 - t3)| min(r3, r4) / L.
@pytest.mark.parametrize(
    "r, t2, mode",
    [
        # moderate lengths: theta4 1.5e-9 rad off, true |sin(t4 - t3)| = 1.04e-7
        ((2.1380925639877404, 2.1260325858823386, 2.127963575963852, 1.1708255678882284),
         1.7690448232681408, "open"),
        # coupler 0.05 of the longest link: theta3 1.3e-8 rad off, true |sin| = 1.74e-7
        ((5.2157316877200985, 5.615220283347213, 0.2467538740723595, 9.17999780292001),
         2.1110669232618955, "open"),
    ],
)  # fmt: skip
def test_near_toggle_never_silently_wrong(r, t2, mode):
    tr = mp_solve(r, t2, mode)
    tr100 = mp_solve(r, t2, mode, dps=100)  # the truth is settled
    assert angdiff(tr.theta3, tr100.theta3) < 1e-40
    s = pk.FourBar(*r).solve(t2, mode=mode)
    if s.status == S.CONVERGED:
        assert angdiff(s.theta3, tr.theta3) < 1e-9
        assert angdiff(s.theta4, tr.theta4) < 1e-9
    else:
        assert s.status == S.SINGULAR


def test_near_toggle_random_approach_is_flagged_or_right():
    """Random linkages approached at random distances 1e-15.5 .. 1e-12.5 rad from a toggle:
    never a status other than CONVERGED / SINGULAR / NOT_ASSEMBLABLE-within-rounding, and
    every CONVERGED point within 1e-9 rad of the truth (docs/site/fourbar.rst's claim)."""
    rng = np.random.default_rng(34)
    for r, tg in _toggle_cases(rng, 25):
        fb = pk.FourBar(*r)
        for e in rng.uniform(12.5, 15.5, 3):
            t = _inside(r, tg, mpmath.mpf(10) ** (-e))
            if t is None:
                continue
            for mode in MODES:
                tr = mp_solve(r, t, mode)
                s = fb.solve(t, mode=mode)
                if s.status == S.CONVERGED:
                    assert angdiff(s.theta3, tr.theta3) < 1e-9
                    assert angdiff(s.theta4, tr.theta4) < 1e-9
                else:
                    assert s.status in (S.SINGULAR, S.NOT_ASSEMBLABLE)
                    assert not resolvable(r, tr.sin34, 1e-9)


# --- branch jumps and mode labels --------------------------------------------------------


def test_other_mode_guess_is_branch_jump():
    rng = np.random.default_rng(35)
    n = 0
    for r in random_links(rng, 60, "grashof"):
        fb = pk.FourBar(*r)
        for t2 in rng.uniform(-math.pi, math.pi, 3):
            for mode, other in (("open", "crossed"), ("crossed", "open")):
                g = mp_solve(r, t2, other)
                if g is None or abs(float(g.sin34)) < 1e-3:
                    continue
                n += 1
                for s in (fb.solve(t2, mode=mode, guess=(g.t3, g.t4)),
                          pk.reference.solve(fb, t2, mode=mode, guess=(g.t3, g.t4))):  # fmt: skip
                    assert s.status == S.BRANCH_JUMP and not s.success
                    assert math.isnan(s.theta3) and math.isnan(s.theta4)
                    assert s.residual < 1e-9  # it did converge, on the other mode
                # a sweep seeded with the other mode's guess still follows the mode asked
                sw = fb.sweep([t2], mode=mode, guess=(g.t3, g.t4))
                assert sw.status[0] == S.CONVERGED
                tr = mp_solve(r, t2, mode)
                assert angdiff(sw.theta3[0], tr.theta3) < 1e-9
    assert n > 150


@pytest.mark.parametrize("predictor", ["quadratic", "tangent", "previous"])
def test_converged_points_carry_their_mode(mixed_links, predictor):
    rng = np.random.default_rng(36)
    t2 = np.concatenate([np.arange(361) * DEG, rng.uniform(-10, 10, 60)])
    for mode, sign in (("open", 1.0), ("crossed", -1.0)):
        b = pk.sweep_batch(mixed_links, t2, mode=mode, predictor=predictor)
        ok = b.status == S.CONVERGED
        assert ok.sum() > 0.25 * ok.size
        assert (np.sign(np.sin(b.theta4 - b.theta3))[ok] == sign).all()
        # against the truth's label on a sample
        idx = np.argwhere(ok)
        for i, j in idx[rng.choice(len(idx), 150, replace=False)]:
            tr = mp_solve(mixed_links[i], t2[j], mode)
            assert np.sign(float(tr.sin34)) == sign
            assert angdiff(b.theta3[i, j], tr.theta3) <= bound_rad(
                mixed_links[i], b.residual[i, j], tr.sin34, 3)  # fmt: skip


# --- change-point linkages -----------------------------------------------------------------

CHANGE_POINT = {
    # lengths: crank angles of the change points, and whether the crank pin lands on O4
    (6.0, 2.0, 6.0, 2.0): [0.0, math.pi],  # parallelogram
    (2.0, 6.0, 2.0, 6.0): [0.0, math.pi],  # parallelogram, long crank
    (6.0, 2.0, 2.0, 6.0): [0.0, math.pi],  # kite / deltoid
    (2.0, 2.0, 6.0, 6.0): [0.0],  # kite: crank pin on O4 at t2 = 0 (r3 = r4: any t3)
}


@pytest.mark.parametrize("r", list(CHANGE_POINT))
@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("predictor", ["quadratic", "tangent", "previous"])
def test_change_point_linkages(r, mode, predictor):
    """At the bifurcation crank angles the result is flagged (SINGULAR, NaN angles), not
    a number; everywhere else every point is CONVERGED and equals mpmath's solution of
    THAT mode."""
    fb = pk.FourBar(*r)
    g = fb.grashof()
    assert g.condition == "change-point" and g.barker == "S2X"
    t2 = np.arange(361) * DEG
    s = fb.sweep(t2, mode=mode, predictor=predictor)
    bif = CHANGE_POINT[r]
    at_bif = np.zeros(361, dtype=bool)
    for b in bif:
        at_bif |= wrapped_diff(t2, b) < 1e-12
    assert at_bif.sum() == (3 if math.pi in bif else 2)  # 0, 180 and 360 deg
    assert (s.status[at_bif] == S.SINGULAR).all()
    assert np.isnan(s.theta3[at_bif]).all() and np.isnan(s.theta4[at_bif]).all()
    for b in bif:
        for t in (b, -b, b + 2 * math.pi):
            p = fb.solve(t, mode=mode)
            assert p.status == S.SINGULAR and math.isnan(p.theta3)
            assert fb.closed_form_status(np.array([t]), mode)[0] == S.SINGULAR
    assert (s.status[~at_bif] == S.CONVERGED).all()
    sign = 1 if mode == "open" else -1
    for k in np.flatnonzero(~at_bif):
        tr = mp_solve(r, t2[k], mode)
        assert np.sign(float(tr.sin34)) == sign
        assert angdiff(s.theta3[k], tr.theta3) <= bound_rad(r, s.residual[k], tr.sin34, 3)
        assert angdiff(s.theta4[k], tr.theta4) <= bound_rad(r, s.residual[k], tr.sin34, 4)
        if predictor == "quadratic":  # the others stop at a residual up to tol
            assert angdiff(s.theta3[k], tr.theta3) < 1e-8


@pytest.mark.parametrize(
    "grid, mode, predictor",
    [
        # (10, 1, 1, 10) at t2 = 0: A = (1, 0), |A O4| = 9 = r4 - r3, all links collinear.
        # unflagged, this ends CONVERGED: theta3 = 3.14147058 (truth pi), 1.2e-4 rad off, nit 6
        ([14.375, 0.0078125, 0.0], "open", "previous"),
        # unflagged: CONVERGED, 9.6e-7 rad off, residual 4.1e-14, |sin| 8.6e-7
        ([14.375, 0.0078125, 0.0], "open", "tangent"),
        # 3 deg steps; unflagged: CONVERGED 1.5e-4 rad off at t2 = 0
        (list(np.arange(-30, 1, 3) * DEG), "crossed", "tangent"),
    ],
)
def test_change_point_reached_by_continuation(grid, mode, predictor):
    """The exact change point of (10, 1, 1, 10) at t2 = 0 (all links collinear: sin(t4 - t3)
    is 0 in mpmath), reached by continuation on grids that end there, is SINGULAR, as
    solve() from the closed form says."""
    r = (10.0, 1.0, 1.0, 10.0)
    fb = pk.FourBar(*r)
    assert fb.grashof().barker == "S2X"
    tr = mp_solve(r, 0.0, mode)
    assert tr.sin34 == 0  # exactly collinear: the two modes meet
    assert fb.solve(0.0, mode=mode).status == S.SINGULAR  # from the closed form: flagged
    s = fb.sweep(grid, mode=mode, predictor=predictor)
    assert s.theta2[-1] == 0.0
    assert s.status[-1] == S.SINGULAR, (s.status, s.nit, s.residual, s.theta3)


def test_kite_crank_pin_on_o4():
    """(2, 2, 6, 6) at t2 = 0: A = O4 and r3 = r4, every coupler angle closes the loop:
    indeterminate, flagged SINGULAR with NaN, also by the closed form (NaN)."""
    fb = pk.FourBar(2.0, 2.0, 6.0, 6.0)
    assert mp_solve(fb.lengths, 0.0, "open") is None  # no single answer
    for mode in MODES:
        s = fb.solve(0.0, mode=mode)
        assert s.status == S.SINGULAR and s.nit == 0 and math.isnan(s.theta3)
        c3, c4 = fb.closed_form(np.array([0.0]), mode)
        assert np.isnan(c3[0]) and np.isnan(c4[0])
        assert math.isnan(pk.reference.closed_form(fb, 0.0, mode)[0])
        # with an explicit guess Newton starts, but the Jacobian is singular there
        g = fb.solve(0.0, mode=mode, guess=(1.0, 1.0))
        assert g.status != S.CONVERGED or abs(math.sin(g.theta4 - g.theta3)) >= 1e-7
    # t2 = pi is no change point: ordinary, both modes
    for mode in MODES:
        tr = mp_solve(fb.lengths, math.pi, mode)
        s = fb.solve(math.pi, mode=mode)
        assert s.status == S.CONVERGED and angdiff(s.theta3, tr.theta3) < 1e-12


def test_parallelogram_branch_labels():
    """(6, 2, 6, 2): DESIGN.md: the label is a property of each point. Open mode follows
    t3 = 0, t4 = t2 on (0, pi) and the antiparallelogram on (pi, 2 pi); crossed the other
    way round. The antiparallelogram B is the mirror of the parallelogram's B about the
    line A-O4 (computed in mpmath here)."""
    r = (6.0, 2.0, 6.0, 2.0)
    fb = pk.FourBar(*r)
    t2 = np.arange(361) * DEG
    op, cr = fb.sweep(t2, mode="open"), fb.sweep(t2, mode="crossed")
    upper = (t2 > 0) & (t2 < math.pi)
    lower = (t2 > math.pi) & (t2 < 2 * math.pi)
    for s, para, anti in ((op, upper, lower), (cr, lower, upper)):
        assert (s.status[para | anti] == S.CONVERGED).all()
        assert np.abs(s.theta3[para]).max() < 1e-9
        assert wrapped_diff(s.theta4[para], t2[para]).max() < 1e-9
        assert np.abs(s.theta3[anti]).min() > 1e-3  # not the parallelogram
        for k in np.flatnonzero(anti):
            with mpmath.workdps(50):
                t = mpmath.mpf(float(t2[k]))
                ax, ay = 2 * mpmath.cos(t), 2 * mpmath.sin(t)
                bx, by = ax + 6, ay  # parallelogram B
                ux, uy = 6 - ax, -ay  # line A -> O4
                n2 = ux * ux + uy * uy
                vx, vy = bx - ax, by - ay
                dot = (vx * ux + vy * uy) / n2
                mx, my = 2 * (ax + dot * ux) - bx, 2 * (ay + dot * uy) - by  # mirror of B
                t3 = mpmath.atan2(my - ay, mx - ax)
                t4 = mpmath.atan2(my, mx - 6)
            assert angdiff(s.theta3[k], t3) < 1e-9 and angdiff(s.theta4[k], t4) < 1e-9
    # the labels: open has sin(t4 - t3) > 0 at every converged point, crossed < 0
    assert (np.sin(op.theta4 - op.theta3)[op.success] > 0).all()
    assert (np.sin(cr.theta4 - cr.theta3)[cr.success] < 0).all()


# --- NaN inside an array -------------------------------------------------------------------


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("predictor", ["quadratic", "tangent", "previous"])
def test_nan_crank_angle_inside_array(mode, predictor):
    """A NaN crank angle is NON_FINITE for that point only (nit 0, NaN angles); the others
    are solved: before it identical to a sweep without the NaN, after it within 1e-9 rad
    of it (the next point restarts from the closed form) and of the truth."""
    fb = pk.FourBar(*SEED_LINKAGE)
    t2 = np.arange(0, 361, 2) * DEG
    holes = t2.copy()
    holes[[10, 60, 61, 150]] = np.nan
    a = fb.sweep(holes, mode=mode, predictor=predictor)
    b = fb.sweep(t2, mode=mode, predictor=predictor)
    nan = np.isnan(holes)
    assert (a.status[nan] == S.NON_FINITE).all() and (a.nit[nan] == 0).all()
    assert np.isnan(a.theta3[nan]).all() and np.isnan(a.theta4[nan]).all()
    assert (a.status[~nan] == S.CONVERGED).all()
    assert_array_equal(a.theta3[:10], b.theta3[:10])
    assert_array_equal(a.theta4[:10], b.theta4[:10])
    assert wrapped_diff(a.theta3[~nan], b.theta3[~nan]).max() < 1e-9
    assert wrapped_diff(a.theta4[~nan], b.theta4[~nan]).max() < 1e-9
    for k in (11, 62, 151):  # restarted from the closed form
        tr = mp_solve(SEED_LINKAGE, holes[k], mode)
        assert angdiff(a.theta3[k], tr.theta3) < 1e-12 and angdiff(a.theta4[k], tr.theta4) < 1e-12
    summ = a.summary()
    assert summ.statuses == {"NON_FINITE": 4, "CONVERGED": len(t2) - 4}


# --- any finite scale ---------------------------------------------------------------------------

#: Scales across the whole double range, including those where arithmetic in the given
#: units (not scaled to a unit longest link) breaks down: every point SINGULAR at 1e-100,
#: NON_FINITE at 2^340, NOT_ASSEMBLABLE at 1e160 and above, and a crank that seems unable
#: to turn fully at 1e-300.
EXTREME_SCALES = [2.0**-1070, 1e-300, 1e-100, 2.0**-340, 1e-9, 1e100, 1e160, 2.0**340, 1e300]


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("scale", EXTREME_SCALES, ids=lambda s: f"{s:.3g}")
def test_any_finite_scale_gives_the_seed_answer(mode, scale, scalar_path):
    """The seed linkage times any finite scale: the statuses and angles of the 50-digit
    mpmath truth of the unscaled linkage (the problem is scale-free), the same limits, and
    the NumPy reference bit for bit; a power-of-two scale is bit-identical to the seed."""
    r = tuple(x * scale for x in SEED_LINKAGE)
    fb, seed = pk.FourBar(*r), pk.FourBar(*SEED_LINKAGE)
    s = fb.sweep(mode=mode, omega2=1.0, alpha2=0.5)
    assert (s.status == S.CONVERGED).all(), s.summary()
    for k in range(0, 361, 15):
        tr = mp_solve(SEED_LINKAGE, s.theta2[k], mode)
        assert angdiff(s.theta3[k], tr.theta3) < 1e-12
        assert angdiff(s.theta4[k], tr.theta4) < 1e-12
    base = seed.sweep(mode=mode, omega2=1.0, alpha2=0.5)
    assert np.allclose(s.omega4, base.omega4, rtol=1e-9, atol=1e-12)
    assert np.allclose(s.alpha4, base.alpha4, rtol=1e-9, atol=1e-12)
    lim, lim0 = fb.limits(mode), seed.limits(mode)
    assert lim.full_rotation and lim.dead_points.size == 0 and lim.toggles.size == 0
    assert abs(lim.rocker_min - lim0.rocker_min) < 1e-12
    assert abs(lim.rocker_max - lim0.rocker_max) < 1e-12
    b = pk.sweep_batch(np.array([r]), mode=mode)
    assert_array_equal(b.status[0], s.status)
    rs = pk.reference.sweep(fb, mode=mode)
    for f in ("theta3", "theta4", "status", "nit", "residual"):
        assert_array_equal(getattr(rs, f), getattr(s, f), err_msg=f)
    assert rs.lengths == fb.lengths == r
    if math.frexp(scale)[0] == 0.5:  # a power of two: bit-identical
        for f in ("theta3", "theta4", "status", "nit", "residual"):
            assert_array_equal(getattr(s, f), getattr(base, f), err_msg=f)


def test_lengths_beyond_the_unit_problem_are_rejected():
    """A link shorter than the smallest normal double times the longest has no place in
    the scale-free problem: ValueError naming it, in the kernel, the batch and the
    reference alike."""
    r = (1e300, 1e-300, 1e300, 1e300)
    with pytest.raises(ValueError, match=r"^r2 is too short"):
        pk.FourBar(*r)
    with pytest.raises(ValueError, match=r"^links\[0, 1\] is too short"):
        pk.sweep_batch(np.array([r]))

    class Lengths:
        r1, r2, r3, r4 = r

    with pytest.raises(ValueError, match=r"^r2 is too short"):
        pk.reference.sweep(Lengths())
