"""The speed/accuracy study behind ``planarkin tradeoff`` (planarkin.fourbar.tradeoff): the
table's structure, the truth it measures against (checked here against textbook values and
an mpmath loop residual, not against planarkin), errors that shrink with the tolerance, and
a Pareto front that timing noise cannot move. No timing assertions; the command and its
figure are in face/test_tradeoff_cli.py.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import planarkin as pk
import pytest
from _support import tradeoff_rows
from planarkin.fourbar import tradeoff as tr

TOLS = (1e-3, 1e-6, 1e-9, 1e-12)


@pytest.fixture(scope="module")
def result() -> tr.TradeoffResult:
    # seed + 3 random crank-rockers, truth on the seed and one more: about a second
    return tr.tradeoff(TOLS, n_random=3, truth_links=2, repeat=1)


def test_rows_cover_every_method_and_tolerance(result):
    newton = [m for m, (_, p) in tr.METHODS.items() if p is not None]
    assert [(r.method, r.tol) for r in result.rows] == [
        *((m, t) for m in newton for t in TOLS),
        ("closed-form", None),
    ]
    assert (result.n_links, result.n_points, result.truth_links) == (4, 361, 2)
    for r in result.rows:
        assert r.label == tr.METHODS[r.method][0]
        assert r.ns_per_point > 0 and math.isfinite(r.ns_per_point)
        assert r.nit_mean >= 0 and r.nit_seed >= 0
        assert 0 <= r.err_median <= r.err_max and r.err_seed <= r.err_max
        assert r.failed == 0  # crank-rockers assemble everywhere, no toggles
    assert any(r.pareto for r in result.rows)
    assert any(r.pareto_newton for r in result.rows)
    assert not any(r.pareto_newton for r in result.rows if r.tol is None)


def test_errors_are_bounded_by_the_tolerance(result):
    """The last Newton correction (below tol) is applied to the returned angles, so the
    error is quadratic in it: never more than ~tol, and at the rounding floor once tol is
    small enough; iterations never fall as tol tightens."""
    for method in ("previous", "tangent", "quadratic"):
        rows = [r for r in result.rows if r.method == method]
        for r in rows:
            assert r.err_max <= 100 * r.tol + 1e-14, (method, r.tol, r.err_max)
            if r.tol <= 1e-8:
                assert r.err_max < 1e-14, (method, r.tol, r.err_max)
        nits = [r.nit_mean for r in rows]
        assert all(b >= a for a, b in zip(nits, nits[1:], strict=False)), (method, nits)


def test_closed_form_is_accurate_to_rounding(result):
    (cf,) = [r for r in result.rows if r.method == "closed-form"]
    assert cf.err_max < 1e-13 and cf.nit_mean == 0


def test_seed_tangent_iterations_at_1e_9(result):
    (row,) = [r for r in result.rows if r.method == "tangent" and r.tol == 1e-9]
    assert row.nit_seed <= 1.6


def test_truth_matches_textbook_values():
    deg = math.pi / 180
    # DESIGN.md: r = (6, 2, 5, 5), theta2 = 0, open: theta3 = 66.42, theta4 = 113.58 deg
    # Norton, Design of Machinery, Ex. 4-1: (100, 40, 120, 80) at 40 deg, open 20.30 / 57.32,
    # crossed -60.98 / -98.00 deg
    cases = [
        ((6, 2, 5, 5), 0.0, "open", 66.42, 113.58),
        ((100, 40, 120, 80), 40 * deg, "open", 20.30, 57.32),
        ((100, 40, 120, 80), 40 * deg, "crossed", -60.98, -98.00),
    ]
    for r, t2, mode, t3, t4 in cases:
        ex = tr.truth(np.array([r], dtype=float), np.array([t2]), mode)[0, 0]
        assert abs(ex[0, 0] / deg - t3) < 5e-3 and abs(ex[1, 0] / deg - t4) < 5e-3


def test_truth_closes_the_loop_to_far_below_double_precision():
    links = np.vstack([[tr.SEED_LINKAGE], tr.random_crank_rockers(2, seed=7)])
    t2 = np.array([0.0, 0.1, 1.0, 2.5, math.pi, 4.0, 6.2])
    ex = tr.truth(links, t2)
    with mpmath.workdps(40):
        for i, r in enumerate(links.tolist()):
            r1, r2, r3, r4 = (mpmath.mpf(x) for x in r)
            for j, a in enumerate(t2.tolist()):
                a3 = mpmath.mpf(ex[i, j, 0, 0]) + mpmath.mpf(ex[i, j, 0, 1])
                a4 = mpmath.mpf(ex[i, j, 1, 0]) + mpmath.mpf(ex[i, j, 1, 1])
                f1 = r2 * mpmath.cos(a) + r3 * mpmath.cos(a3) - r4 * mpmath.cos(a4) - r1
                f2 = r2 * mpmath.sin(a) + r3 * mpmath.sin(a3) - r4 * mpmath.sin(a4)
                assert max(abs(f1), abs(f2)) < 1e-28
                assert mpmath.sin(a4 - a3) > 0  # open
                assert abs(ex[i, j, 0, 1]) <= 1e-16 * abs(ex[i, j, 0, 0]) + 1e-300


def test_truth_is_nan_where_the_linkage_cannot_assemble():
    ex = tr.truth(np.array([[2.0, 5.0, 2.5, 2.0]]), np.array([0.0, math.pi]))
    assert np.isnan(ex[0, 1]).all() and np.isfinite(ex[0, 0]).all()


def test_angle_error_resolves_one_ulp_and_wraps():
    x = 1.2345
    ulp = np.nextafter(x, 2.0) - x
    assert tr.angle_error(np.nextafter(x, 2.0), np.array([x, 0.0])) == ulp
    assert tr.angle_error(np.array(x), np.array([x, ulp / 4])) == ulp / 4
    # -pi + 1e-3 and pi - 1e-3 are 2e-3 apart on the circle
    e = tr.angle_error(np.array(-math.pi + 1e-3), np.array([math.pi - 1e-3, 0.0]))
    assert abs(e - 2e-3) < 1e-15


def test_random_crank_rockers_are_grashof_crank_rockers_and_reproducible():
    links = tr.random_crank_rockers(200, seed=3)
    assert links.shape == (200, 4) and links.flags.c_contiguous
    np.testing.assert_array_equal(links, tr.random_crank_rockers(200, seed=3))
    for r in links[:20]:
        g = pk.FourBar(*r).grashof()
        assert g.is_grashof and g.kind == "crank-rocker"
    s, big = links.min(axis=1), links.max(axis=1)
    assert np.all(links[:, 1] == s)
    assert np.all(s + big <= links.sum(axis=1) - s - big - 0.25)


def test_bad_arguments_raise_value_error():
    with pytest.raises(ValueError, match="methods"):
        tr.tradeoff(methods=("bisection",))
    with pytest.raises(ValueError, match="tols"):
        tr.tradeoff(tols=(0.0,))
    with pytest.raises(ValueError, match="links"):
        tr.tradeoff(links=np.ones((3, 3)))


# --- the Pareto marks ------------------------------------------------------------------------


def test_pareto_front_does_not_follow_timing_noise():
    """Four tolerances reach the same error (the rounding floor) at the same cost; only
    timing noise (+-4%) tells them apart. In 50 noisy runs the front is the same every time:
    the loosest of the tied tolerances, not whichever happened to be fastest."""
    tols = [1e-3, 1e-6, 1e-9, 1e-12, 1e-13, 1e-14, 1e-15]
    errs = [2e-4, 3e-7, 5e-10, 4.4e-16, 4.4e-16, 4.4e-16, 4.4e-16]
    base = np.array([20.0, 35.0, 50.0, 80.0, 80.0, 80.0, 80.0])
    rng = np.random.default_rng(5)
    fronts = set()
    for _ in range(50):
        times = base * rng.uniform(0.96, 1.04, base.size)
        rows = tr._mark_pareto(tradeoff_rows(times.tolist(), errs, tols))
        fronts.add(tuple(r.tol for r in rows if r.pareto_newton))
    assert fronts == {(1e-3, 1e-6, 1e-9, 1e-12)}
