"""Parity: the Rust kernel against the plain NumPy reference (``planarkin.reference``).

The reference follows the kernel's operation order, so the two must agree bit for bit:
angles, statuses, iteration counts, residuals, velocities, accelerations and residual
histories. Measured on this machine: 100% of points bit-identical (several thousand
sweeps of 361 points, random Grashof and non-Grashof linkages, all predictors, both
modes), so every comparison here is exact (``assert_array_equal``, NaN == NaN).
That holds on the scalar path (``pk.use_simd(False)``, which every test here uses); the
SIMD kernels' parity, at 1e-12 rad, is in ``test_simd.py``.
"""

from __future__ import annotations

import math

import numpy as np
import planarkin as pk
import pytest
from numpy.testing import assert_array_equal
from planarkin import reference as ref
from truth import SEED_LINKAGE, random_links

pytestmark = pytest.mark.usefixtures("scalar_path")

MODES = ("open", "crossed")
PREDICTORS = ("quadratic", "tangent", "previous")
SWEEP_FIELDS = ("theta2", "theta3", "theta4", "status", "nit", "residual")
RATE_FIELDS = ("omega3", "omega4", "alpha3", "alpha4")


def assert_sweeps_identical(a: pk.Sweep, b: pk.Sweep, rates: bool = False) -> None:
    for f in SWEEP_FIELDS + (RATE_FIELDS if rates else ()):
        x, y = getattr(a, f), getattr(b, f)
        assert x is not None and y is not None, f
        assert x.dtype == y.dtype, f
        assert_array_equal(x, y, err_msg=f"{f} differs (lengths {a.lengths}, mode {a.mode})")
    assert a.mode == b.mode
    assert tuple(a.lengths) == tuple(b.lengths)


def assert_solutions_identical(a: pk.Solution, b: pk.Solution) -> None:
    """Every field equal, NaN == NaN, status of the same type; histories identical."""
    for f in ("theta2", "theta3", "theta4", "residual"):
        assert_array_equal(getattr(a, f), getattr(b, f), err_msg=f)
    assert (a.success, a.status, a.nit) == (b.success, b.status, b.nit)
    if a.history is None or b.history is None:
        assert a.history is None and b.history is None
    else:
        assert_array_equal(a.history, b.history)


@pytest.fixture(scope="module")
def grashof_links():
    return random_links(np.random.default_rng(101), 300, "grashof")


@pytest.fixture(scope="module")
def non_grashof_links():
    return random_links(np.random.default_rng(202), 200, "non-grashof")


# --- the seed linkage ---------------------------------------------------------------


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("predictor", PREDICTORS)
def test_seed_sweep_parity_with_rates(mode, predictor):
    fb = pk.FourBar(*SEED_LINKAGE)
    kw = dict(mode=mode, predictor=predictor, omega2=10.0, alpha2=-3.0)
    a, b = fb.sweep(**kw), ref.sweep(fb, **kw)
    assert_sweeps_identical(a, b, rates=True)
    assert a.omega2 == b.omega2 == 10.0 and a.alpha2 == b.alpha2 == -3.0
    assert a.summary() == b.summary()


@pytest.mark.parametrize("mode", MODES)
def test_seed_sweep_parity_velocity_only(mode):
    fb = pk.FourBar(*SEED_LINKAGE)
    a, b = fb.sweep(mode=mode, omega2=1.5), ref.sweep(fb, mode=mode, omega2=1.5)
    assert_sweeps_identical(a, b)
    assert_array_equal(a.omega3, b.omega3)
    assert_array_equal(a.omega4, b.omega4)
    assert a.alpha3 is None and b.alpha3 is None and a.alpha4 is None and b.alpha4 is None


def test_seed_no_rates_unless_asked():
    fb = pk.FourBar(*SEED_LINKAGE)
    for s in (fb.sweep(), ref.sweep(fb)):
        assert s.omega3 is None and s.omega4 is None and s.alpha3 is None and s.alpha4 is None


# --- random linkages ----------------------------------------------------------------


# 300 linkages take about 0.8 s a combination: the inner loop keeps one (the irregular
# grids and the non-Grashof linkages below cover every mode and predictor in it)
@pytest.mark.parametrize("mode", ["open", pytest.param("crossed", marks=pytest.mark.slow)])
@pytest.mark.parametrize(
    "predictor",
    ["quadratic", *(pytest.param(p, marks=pytest.mark.slow) for p in ("tangent", "previous"))],
)
def test_random_grashof_sweep_parity(grashof_links, mode, predictor):
    """A few hundred Grashof linkages (lengths 0.1..10): every point bit-identical."""
    batch = pk.sweep_batch(grashof_links, mode=mode, predictor=predictor)
    for i, r in enumerate(grashof_links):
        fb = pk.FourBar(*r)
        a = fb.sweep(mode=mode, predictor=predictor)
        b = ref.sweep(fb, mode=mode, predictor=predictor)
        assert_sweeps_identical(a, b)
        # the batch is the same kernel run in parallel: identical to the single sweep
        for f in ("theta3", "theta4", "status", "nit", "residual"):
            assert_array_equal(getattr(batch, f)[i], getattr(a, f), err_msg=f)


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("predictor", PREDICTORS)
def test_random_non_grashof_sweep_parity(non_grashof_links, mode, predictor):
    """Non-Grashof linkages: statuses match, NOT_ASSEMBLABLE spans included."""
    seen = set()
    for r in non_grashof_links:
        fb = pk.FourBar(*r)
        a = fb.sweep(mode=mode, predictor=predictor)
        b = ref.sweep(fb, mode=mode, predictor=predictor)
        assert_sweeps_identical(a, b)
        seen.update(int(s) for s in np.unique(a.status))
    assert {pk.Status.CONVERGED, pk.Status.NOT_ASSEMBLABLE} <= seen


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("predictor", PREDICTORS)
def test_irregular_grids_parity(mode, predictor):
    """Coarse, backward, repeated, huge and NaN crank angles exercise the fallback to the
    closed form, the wrap of the step and NON_FINITE: still bit-identical. (Infinite
    angles: see test_reference_sweep_infinite_crank_angle.)"""
    rng = np.random.default_rng(303)
    links = np.vstack([random_links(rng, 40, "grashof"), random_links(rng, 40, "non-grashof")])
    grid = np.concatenate(
        [
            rng.uniform(-20, 20, 40),
            [np.nan, 0.5, 0.5, 1e10, -1e300, 0.0, np.nan, 3.0],
            np.linspace(7, -7, 30),
        ]
    )
    batch = pk.sweep_batch(links, grid, mode=mode, predictor=predictor)
    for i, r in enumerate(links):
        fb = pk.FourBar(*r)
        a = fb.sweep(grid, mode=mode, predictor=predictor)
        b = ref.sweep(fb, grid, mode=mode, predictor=predictor)
        assert_sweeps_identical(a, b)
        assert_array_equal(batch.status[i], a.status)
        assert_array_equal(batch.theta3[i], a.theta3)
        assert_array_equal(batch.nit[i], a.nit)


def test_kernel_sweep_infinite_crank_angle():
    """The kernel flags +-inf as NON_FINITE for that point only and carries on."""
    fb = pk.FourBar(*SEED_LINKAGE)
    s = fb.sweep([0.5, np.inf, 0.6, -np.inf, np.nan, 0.7])
    assert s.status.tolist() == [0, -3, 0, -3, -3, 0]
    assert s.nit[1] == s.nit[3] == s.nit[4] == 0


@pytest.mark.parametrize("grid", [[0.5, np.inf, 0.6], [0.5, -np.inf], [np.inf, 0.5, -np.inf]])
def test_reference_sweep_infinite_crank_angle(grid):
    fb = pk.FourBar(*SEED_LINKAGE)
    assert_sweeps_identical(fb.sweep(grid), ref.sweep(fb, grid))


@pytest.mark.parametrize("mode", MODES)
def test_sweep_with_guess_and_options_parity(grashof_links, mode):
    rng = np.random.default_rng(404)
    for r in grashof_links[:60]:
        fb = pk.FourBar(*r)
        guess = tuple(rng.uniform(-4, 4, 2))
        tol = float(10 ** rng.uniform(-13, -5))
        max_iter = int(rng.integers(1, 8))
        kw = dict(mode=mode, guess=guess, tol=tol, max_iter=max_iter, omega2=2.0, alpha2=0.5)
        assert_sweeps_identical(fb.sweep(**kw), ref.sweep(fb, **kw), rates=True)


def test_solve_parity_with_history(grashof_links, non_grashof_links):
    """solve(): every field and the residual history, from the closed form, from random
    guesses and from the other mode's guess (BRANCH_JUMP)."""
    rng = np.random.default_rng(505)
    statuses = set()
    links = np.vstack([grashof_links[:100], non_grashof_links[:60]])
    for r in links:
        fb = pk.FourBar(*r)
        for _ in range(4):
            t2 = float(rng.uniform(-7, 7))
            mode = MODES[int(rng.integers(2))]
            other = MODES[1 - MODES.index(mode)]
            cf_other = ref.closed_form(fb, t2, other)
            guesses = [None, tuple(rng.uniform(-4, 4, 2))]
            if not math.isnan(cf_other[0]):
                guesses.append(cf_other)
            for guess in guesses:
                for max_iter in (100, 3):
                    kw = dict(mode=mode, guess=guess, max_iter=max_iter, history=True)
                    a, b = fb.solve(t2, **kw), ref.solve(fb, t2, **kw)
                    assert_solutions_identical(a, b)
                    assert_array_equal(a.history, b.history)
                    assert a.history.dtype == np.float64
                    if a.status == pk.Status.NOT_ASSEMBLABLE:  # known before any iterate
                        assert len(a.history) == 0 and a.nit == 0
                    else:  # one residual per iterate, the start included
                        assert len(a.history) == a.nit + 1
                    statuses.add(a.status)
                    assert type(a.status) is pk.Status
    assert {pk.Status.CONVERGED, pk.Status.NOT_ASSEMBLABLE, pk.Status.BRANCH_JUMP} <= statuses


def test_solve_history_off_by_default():
    fb = pk.FourBar(*SEED_LINKAGE)
    assert fb.solve(0.3).history is None
    assert ref.solve(fb, 0.3).history is None


def test_closed_form_parity(grashof_links, non_grashof_links):
    rng = np.random.default_rng(606)
    t = np.concatenate([rng.uniform(-10, 10, 200), [0.0, math.pi, -math.pi, np.nan, np.inf]])
    links = np.vstack([grashof_links[:80], non_grashof_links[:80]])
    for mode in MODES:
        b3, b4 = pk.closed_form_batch(links, t, mode)
        for i, r in enumerate(links):
            fb = pk.FourBar(*r)
            a3, a4 = fb.closed_form(t, mode)
            r3, r4 = ref.closed_form(fb, t, mode)
            assert_array_equal(a3, r3)
            assert_array_equal(a4, r4)
            assert_array_equal(b3[i], r3)
            assert_array_equal(b4[i], r4)


def test_closed_form_batch_out_is_written_in_place(grashof_links, non_grashof_links):
    """out=(theta3, theta4): the reference's closed form written into the caller's arrays
    (filled with other values first), which are the arrays returned."""
    t = np.concatenate([np.linspace(-7.0, 7.0, 301), [np.nan, np.inf]])
    links = np.vstack([grashof_links[:40], non_grashof_links[:40]])
    for mode in MODES:
        out = (np.full((80, t.size), 5.0), np.full((80, t.size), -5.0))
        b3, b4 = pk.closed_form_batch(links, t, mode, out=out)
        assert b3 is out[0] and b4 is out[1]
        for i, r in enumerate(links):
            r3, r4 = ref.closed_form(pk.FourBar(*r), t, mode)
            assert_array_equal(b3[i], r3)
            assert_array_equal(b4[i], r4)


def test_closed_form_keeps_array_shape():
    fb = pk.FourBar(*SEED_LINKAGE)
    t = np.linspace(0, 6, 12).reshape(3, 4)
    a3, a4 = fb.closed_form(t, "crossed")
    r3, r4 = ref.closed_form(fb, t, "crossed")
    assert a3.shape == a4.shape == (3, 4)
    assert_array_equal(a3, r3)
    assert_array_equal(a4, r4)


def test_velocity_acceleration_parity(grashof_links):
    """fb.velocity / fb.acceleration against the reference, elementwise, at the solved
    positions and at arbitrary (not closing) angles."""
    rng = np.random.default_rng(707)
    for r in grashof_links[:60]:
        fb = pk.FourBar(*r)
        t2 = rng.uniform(-4, 4, 12)
        t3, t4 = fb.closed_form(t2, "open")
        t3 = np.concatenate([t3, rng.uniform(-4, 4, 6)])
        t4 = np.concatenate([t4, rng.uniform(-4, 4, 6)])
        t2 = np.concatenate([t2, rng.uniform(-4, 4, 6)])
        w2 = rng.uniform(-20, 20, t2.size)
        a2 = rng.uniform(-20, 20, t2.size)
        w3, w4 = fb.velocity(t2, t3, t4, w2)
        a3, a4 = fb.acceleration(t2, t3, t4, w2, a2)
        for k in range(t2.size):
            rw = ref.velocity(fb, t2[k], t3[k], t4[k], w2[k])
            ra = ref.acceleration(fb, t2[k], t3[k], t4[k], w2[k], a2[k])
            assert_array_equal([w3[k], w4[k]], rw)
            assert_array_equal([a3[k], a4[k]], ra)


def test_velocity_nan_at_dead_point_both():
    """At a dead point (theta4 = theta3) both implementations give NaN, not a number."""
    fb = pk.FourBar(*SEED_LINKAGE)
    w = fb.velocity(np.array([0.3]), np.array([1.0]), np.array([1.0]), np.array([1.0]))
    assert np.isnan(w[0]).all() and np.isnan(w[1]).all()
    assert all(math.isnan(x) for x in ref.velocity(fb, 0.3, 1.0, 1.0, 1.0))
    assert all(math.isnan(x) for x in ref.acceleration(fb, 0.3, 1.0, 1.0, 1.0, 0.0))


def test_scalar_inputs_give_scalars():
    """0-d inputs give Python floats / 0-d arrays, like the reference, not arrays of shape
    (1,) (what np.ascontiguousarray makes of a 0-d array)."""
    fb = pk.FourBar(*SEED_LINKAGE)
    t3, t4 = fb.closed_form(0.5, "open")
    r3, r4 = ref.closed_form(fb, 0.5, "open")
    assert isinstance(t3, float) and isinstance(t4, float)
    assert (t3, t4) == (r3, r4)
    w = fb.velocity(0.5, r3, r4, 2.0)
    assert all(isinstance(x, float) for x in w)
    assert w == ref.velocity(fb, 0.5, r3, r4, 2.0)
    assert isinstance(fb.transmission_angle(r3, r4), float)
    assert isinstance(fb.branch_indicator(r3, r4), float)
    assert all(isinstance(x, float) for x in fb.coupler_point(0.5, r3, 1.0, 0.2))
    assert np.shape(fb.closed_form(np.float64(0.5))[0]) == ()
    assert np.shape(fb.closed_form_status(0.5)) == ()


# --- result objects -----------------------------------------------------------------------


def test_sweep_repr_is_a_short_summary():
    """repr(Sweep) is one short line, not the arrays: it names the linkage, the mode and the
    status counts (counted here with NumPy); a batch's repr is as short."""
    fb = pk.FourBar(2.0, 5.0, 2.5, 2.0)  # triple rocker: two statuses
    s = fb.sweep(omega2=1.0, alpha2=0.0)
    text = repr(s)
    assert "\n" not in text and len(text) < 250, text
    n_na = int(np.count_nonzero(s.status == pk.Status.NOT_ASSEMBLABLE))
    n_ok = int(np.count_nonzero(s.status == pk.Status.CONVERGED))
    assert f"NOT_ASSEMBLABLE={n_na}" in text and f"CONVERGED={n_ok}" in text
    assert "(2.0, 5.0, 2.5, 2.0)" in text and "open" in text and "361" in text
    b = pk.sweep_batch(np.array([SEED_LINKAGE] * 3))
    assert len(repr(b)) < 250 and f"CONVERGED={3 * 361}" in repr(b)


def test_result_members_are_documented():
    for member in (pk.Sweep.summary, pk.BatchSweep.success, pk.Solution.message,
                   pk.Sweep.success, pk.Limits.rocker_swing):  # fmt: skip
        assert member.__doc__ and member.__doc__.strip()
