"""Property tests (hypothesis) over random linkages and crank angles, each checked against
the mpmath truth (truth.mp_solve); plus thread-safety of the kernel."""

from __future__ import annotations

import math
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import planarkin as pk
import pytest
from _support import examples
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_array_equal
from truth import (
    DOCUMENTED_SINGULAR_THRESHOLD,
    angdiff,
    below_singular_threshold,
    bound_rad,
    mp_residual,
    mp_solve,
    near_toggle,
    random_links,
    resolvable,
)

S = pk.Status
MODES = ("open", "crossed")
PREDICTORS = ("quadratic", "tangent", "previous")

# log-uniform lengths over 0.1 .. 10 (two decades each way of the unit)
length = st.floats(-1.0, 1.0).map(lambda e: float(10.0**e))
lengths = st.tuples(length, length, length, length)
angle = st.floats(-50.0, 50.0, allow_nan=False, allow_infinity=False)
any_float = st.floats(allow_nan=True, allow_infinity=True, allow_subnormal=True)
mode_st = st.sampled_from(MODES)
predictor_st = st.sampled_from(PREDICTORS)
tol_st = st.sampled_from([1e-9, 1e-6, 1e-12, 1e-14])

SETTINGS = settings(
    max_examples=examples(400),
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
    derandomize=True,
)


def check_point(r, t2, mode, t3, t4, status, residual, tol):
    """One solved point against the truth of its mode."""
    tr = mp_solve(r, t2, mode)
    if tr is not None and tr.sin34 == 0:
        # exactly on a dead or change point (e.g. a kite at t2 = 0): never a number, also for
        # a sweep arriving by continuation (whose residual alone can pass ~1e-4 rad off)
        assert status != S.CONVERGED
        return
    if status == S.CONVERGED:
        assert tr is not None
        assert -math.pi < t3 <= math.pi and -math.pi < t4 <= math.pi
        # the loop closes to tol (mpmath residual of the returned, wrapped angles)
        assert mp_residual(r, t2, t3, t4) < tol + 8e-16
        assert residual < tol
        assert math.copysign(1.0, math.sin(t4 - t3)) == (1.0 if mode == "open" else -1.0)
        assert angdiff(t3, tr.theta3) <= bound_rad(r, residual, tr.sin34, 3)
        assert angdiff(t4, tr.theta4) <= bound_rad(r, residual, tr.sin34, 4)
    else:
        assert math.isnan(t3) and math.isnan(t4)
        if status == S.NOT_ASSEMBLABLE:
            # mpmath agrees, or the angle is within rounding of a toggle
            assert tr is None or abs(float(tr.sin34)) < 1e-7 or near_toggle(r, t2, 1e-12)
        elif status in (S.SINGULAR, S.MAX_ITERATIONS, S.PRECISION_LOSS):
            # only below the documented singular threshold (SINGULAR), where double
            # precision cannot comfortably resolve tol rad, or within rounding of a toggle
            assert (
                tr is None
                or (status == S.SINGULAR and below_singular_threshold(r, tr.sin34))
                or not resolvable(r, tr.sin34, tol)
                or near_toggle(r, t2, 1e-9)
            )
        elif status == S.NON_FINITE:
            assert not math.isfinite(t2)
        else:
            raise AssertionError(f"unexpected status {status!r}")


@SETTINGS
@given(r=lengths, t2=angle, mode=mode_st, tol=tol_st)
def test_solve_matches_truth(r, t2, mode, tol):
    fb = pk.FourBar(*r)
    s = fb.solve(t2, mode=mode, tol=tol)
    assert s.nit <= 100
    assert s.success == (s.status == S.CONVERGED)
    check_point(r, t2, mode, s.theta3, s.theta4, s.status, s.residual, tol)
    if mp_solve(r, t2, mode) is None and not near_toggle(r, t2, 1e-12):
        assert s.status == S.NOT_ASSEMBLABLE and s.nit == 0


@SETTINGS
@given(
    r=lengths,
    t2=st.lists(angle, min_size=1, max_size=8),
    mode=mode_st,
    predictor=predictor_st,
    tol=tol_st,
)
def test_sweep_points_match_truth(r, t2, mode, predictor, tol):
    fb = pk.FourBar(*r)
    s = fb.sweep(t2, mode=mode, predictor=predictor, tol=tol)
    assert len(s) == len(t2)
    for k in range(len(t2)):
        check_point(r, t2[k], mode, s.theta3[k], s.theta4[k], S(s.status[k]), s.residual[k], tol)


@SETTINGS
@given(
    r=lengths,
    t2=st.lists(angle, min_size=1, max_size=6),
    mode=mode_st,
    predictor=predictor_st,
    max_iter=st.sampled_from([1, 2, 3, 5, 100]),
    guess=st.one_of(st.none(), st.tuples(angle, angle)),
)
def test_nit_never_exceeds_max_iter(r, t2, mode, predictor, max_iter, guess):
    """nit <= max_iter for solve(), and for every sweep point (with the retry from the
    closed form counted in), whatever the guess."""
    fb = pk.FourBar(*r)
    for t in t2:
        s = fb.solve(t, mode=mode, max_iter=max_iter, guess=guess)
        assert 0 <= s.nit <= max_iter
        if s.status == S.MAX_ITERATIONS:
            assert s.nit == max_iter and math.isnan(s.theta3)
    sw = fb.sweep(t2, mode=mode, predictor=predictor, max_iter=max_iter, guess=guess)
    assert (sw.nit <= max_iter).all(), (sw.nit, sw.status)
    assert sw.nit.dtype == np.uint32


@settings(max_examples=examples(300), deadline=None, derandomize=True)
@given(
    r=lengths,
    t2=st.lists(any_float, min_size=1, max_size=6),
    mode=mode_st,
    predictor=predictor_st,
    guess=st.one_of(st.none(), st.tuples(any_float, any_float)),
)
def test_nothing_raises_for_any_crank_angle(r, t2, mode, predictor, guess):
    """Any float (NaN, +-inf, subnormal, huge) gives statuses, never an exception; angles
    in (-pi, pi] or NaN, NaN exactly where not CONVERGED."""
    fb = pk.FourBar(*r)
    sw = fb.sweep(t2, mode=mode, predictor=predictor, guess=guess, omega2=1.0, alpha2=0.5)
    ok = sw.status == S.CONVERGED
    for a in (sw.theta3, sw.theta4):
        assert ((a[ok] > -math.pi) & (a[ok] <= math.pi)).all()
        assert np.isnan(a[~ok]).all()
    nonfinite = ~np.isfinite(np.asarray(t2))
    assert (sw.status[nonfinite] == S.NON_FINITE).all()
    assert (sw.nit[nonfinite] == 0).all()
    assert set(np.unique(sw.status).tolist()) <= {int(x) for x in S}
    for t in t2:
        s = fb.solve(t, mode=mode, guess=guess, history=True)
        assert isinstance(s.status, S)
        assert s.history is not None
    c3, c4 = fb.closed_form(np.asarray(t2), mode)
    st_ = fb.closed_form_status(np.asarray(t2), mode)
    assert (np.isnan(c3) == np.isnan(c4)).all()
    assert (st_[nonfinite] == S.NON_FINITE).all()
    pk.sweep_batch([r], t2, mode=mode, predictor=predictor)
    pk.closed_form_batch([r], t2, mode)


@settings(max_examples=examples(200), deadline=None, derandomize=True)
@given(r=lengths, t2=angle, mode=mode_st)
def test_closed_form_status_matches_truth(r, t2, mode):
    fb = pk.FourBar(*r)
    (c3,), (c4,) = fb.closed_form([t2], mode)
    (code,) = fb.closed_form_status([t2], mode)
    tr = mp_solve(r, t2, mode)
    if tr is None:
        assert code in (S.NOT_ASSEMBLABLE, S.SINGULAR)
        assert code == S.NOT_ASSEMBLABLE or near_toggle(r, t2, 1e-12)
        assert math.isnan(c3) and math.isnan(c4)
    elif not below_singular_threshold(r, tr.sin34, margin=1.01):
        assert code == S.CONVERGED
        assert angdiff(c3, tr.theta3) <= bound_rad(r, 0.0, tr.sin34, 3)
        assert angdiff(c4, tr.theta4) <= bound_rad(r, 0.0, tr.sin34, 4)


@settings(max_examples=examples(200), deadline=None, derandomize=True)
@given(r=lengths, t2=angle)
def test_two_modes_are_mirrors_about_a_o4(r, t2):
    """DESIGN.md: crossed is the mirror of open about the line from the crank pin A to O4:
    both put B at the same distance from that line, on opposite sides, at the same foot."""
    fb = pk.FourBar(*r)
    o = fb.solve(t2, mode="open")
    c = fb.solve(t2, mode="crossed")
    assert o.status == c.status or S.SINGULAR in (o.status, c.status)
    if o.success and c.success:
        ax, ay = r[1] * math.cos(t2), r[1] * math.sin(t2)
        ux, uy = r[0] - ax, -ay
        n = math.hypot(ux, uy)
        bo = (ax + r[2] * math.cos(o.theta3), ay + r[2] * math.sin(o.theta3))
        bc = (ax + r[2] * math.cos(c.theta3), ay + r[2] * math.sin(c.theta3))
        side_o = (ux * (bo[1] - ay) - uy * (bo[0] - ax)) / n
        side_c = (ux * (bc[1] - ay) - uy * (bc[0] - ax)) / n
        foot_o = (ux * (bo[0] - ax) + uy * (bo[1] - ay)) / n
        foot_c = (ux * (bc[0] - ax) + uy * (bc[1] - ay)) / n
        scale = max(r)
        assert side_o > 0 > side_c  # open: B left of the directed line A -> O4
        assert abs(side_o + side_c) < 1e-7 * scale
        assert abs(foot_o - foot_c) < 1e-7 * scale


# --- threads -------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def thread_links():
    rng = np.random.default_rng(41)
    return np.vstack([random_links(rng, 150, "grashof"), random_links(rng, 100, "non-grashof")])


@pytest.mark.parametrize("mode", MODES)
def test_sweep_batch_concurrent_threads_identical(thread_links, mode):
    """The same sweep_batch call from 4 Python threads at once (the GIL is released, and
    rayon runs inside each): every result bit-identical to a single-thread run."""
    t2 = np.concatenate([np.arange(361) * math.pi / 180, [np.nan, 1e9]])
    single = pk.sweep_batch(thread_links, t2, mode=mode, threads=1)

    def run(i):
        return pk.sweep_batch(thread_links, t2, mode=mode, threads=(None, 1, 2, 3)[i % 4])

    with ThreadPoolExecutor(max_workers=4) as ex:
        results = list(ex.map(run, range(8)))
    for res in results:
        for f in ("theta3", "theta4", "status", "nit", "residual"):
            assert_array_equal(getattr(res, f), getattr(single, f), err_msg=f)


def test_sweep_and_closed_form_concurrent_threads_identical(thread_links):
    """FourBar.sweep (all predictors, with rates) and closed_form_batch from 4 threads."""
    jobs = [(r, p, m) for r in thread_links[:40] for p in PREDICTORS for m in MODES]

    def one(job):
        r, p, m = job
        s = pk.FourBar(*r).sweep(mode=m, predictor=p, omega2=3.0, alpha2=1.0)
        return np.stack([s.theta3, s.theta4, s.residual, s.omega3, s.alpha4, s.status, s.nit])

    serial = [one(j) for j in jobs]
    with ThreadPoolExecutor(max_workers=4) as ex:
        parallel = list(ex.map(one, jobs))
    for a, b in zip(serial, parallel, strict=True):
        assert_array_equal(a, b)

    t2 = np.linspace(-7, 7, 201)
    c_single = pk.closed_form_batch(thread_links, t2, "crossed", threads=1)
    with ThreadPoolExecutor(max_workers=4) as ex:
        outs = list(ex.map(lambda _: pk.closed_form_batch(thread_links, t2, "crossed"), range(4)))
    for o in outs:
        assert_array_equal(o[0], c_single[0])
        assert_array_equal(o[1], c_single[1])


# --- parity on arbitrary inputs ----------------------------------------------------------------

finite_or_nan = st.one_of(angle, any_float)


@settings(max_examples=examples(300), deadline=None, derandomize=True)
@given(
    r=lengths,
    t2=st.lists(finite_or_nan, min_size=1, max_size=6),
    mode=mode_st,
    predictor=predictor_st,
    tol=st.floats(1e-15, 1e-3),
    max_iter=st.integers(1, 60),
    guess=st.one_of(st.none(), st.tuples(angle, angle), st.tuples(any_float, any_float)),
)
def test_kernel_reference_parity_arbitrary(r, t2, mode, predictor, tol, max_iter, guess):
    """Kernel and reference bit-identical on arbitrary options, any float crank angles and
    guesses (NaN, +-inf, huge, subnormal)."""
    fb = pk.FourBar(*r)
    kw = dict(mode=mode, tol=tol, max_iter=max_iter, guess=guess)
    with pk.use_simd(False):  # bit for bit: the scalar path (SIMD parity: test_simd.py)
        a = fb.sweep(t2, predictor=predictor, omega2=1.5, alpha2=-0.5, **kw)
    b = pk.reference.sweep(fb, t2, predictor=predictor, omega2=1.5, alpha2=-0.5, **kw)
    for f in ("theta3", "theta4", "status", "nit", "residual", "omega3", "omega4", "alpha3",
              "alpha4"):  # fmt: skip
        assert_array_equal(getattr(a, f), getattr(b, f), err_msg=f)
    for t in t2[:2]:
        sa = fb.solve(t, history=True, **kw)
        sb = pk.reference.solve(fb, t, history=True, **kw)
        assert (sa.status, sa.nit) == (sb.status, sb.nit)
        assert_array_equal([sa.theta3, sa.theta4, sa.residual], [sb.theta3, sb.theta4, sb.residual])
        assert_array_equal(sa.history, sb.history)


def test_documented_singular_threshold():
    assert pk.SINGULAR_THRESHOLD == DOCUMENTED_SINGULAR_THRESHOLD
