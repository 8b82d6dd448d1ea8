"""method="closed-form" sweeps: the closed form of the mode, with the sweep's statuses
and velocities, against the closed form itself, the NumPy reference and mpmath."""

import math

import numpy as np
import planarkin as pk
import pytest
from truth import mp_solve

# bit-for-bit parity with the reference: the scalar path (SIMD parity: test_simd.py)
pytestmark = pytest.mark.usefixtures("scalar_path")

S = pk.Status
LINKS = [(6, 2, 5, 5), (2, 5, 2.5, 2), (100, 40, 120, 80), (6, 2, 6, 2), (2, 2, 6, 6)]


@pytest.mark.parametrize("r", LINKS)
@pytest.mark.parametrize("mode", ["open", "crossed"])
def test_closed_form_sweep_equals_the_closed_form_and_the_reference(r, mode):
    fb = pk.FourBar(*r)
    t2 = np.append(pk.DEFAULT_THETA2, [np.nan, 1e6])
    s = fb.sweep(t2, mode=mode, method="closed-form", omega2=2.0, alpha2=-1.0)
    ref = pk.reference.sweep(fb, t2, mode=mode, method="closed-form", omega2=2.0, alpha2=-1.0)
    for name in ("theta3", "theta4", "status", "nit", "omega3", "omega4", "alpha3", "alpha4"):
        np.testing.assert_array_equal(getattr(s, name), getattr(ref, name), err_msg=name)
    assert s.method == "closed-form" and np.all(s.nit == 0) and np.all(np.isnan(s.residual))
    # statuses are the closed form's; angles equal it wherever CONVERGED, NaN elsewhere
    np.testing.assert_array_equal(s.status, fb.closed_form_status(t2, mode))
    c3, c4 = fb.closed_form(t2, mode)
    ok = s.success
    np.testing.assert_array_equal(s.theta3[ok], c3[ok])
    assert np.all(np.isnan(s.theta3[~ok]))
    assert s.status[-2] == S.NON_FINITE
    # velocities are the API's at the same angles
    w3, w4 = fb.velocity(t2[ok], s.theta3[ok], s.theta4[ok], 2.0)
    np.testing.assert_array_equal(s.omega3[ok], w3)


def test_closed_form_sweep_matches_mpmath_and_the_newton_sweep():
    fb = pk.FourBar(6, 2, 5, 5)
    cf = fb.sweep(method="closed-form")
    nr = fb.sweep()
    assert cf.summary().converged == nr.summary().converged == 361
    assert np.max(np.abs(np.angle(np.exp(1j * (cf.theta3 - nr.theta3))))) < 1e-9
    for k in range(0, 361, 30):
        tr = mp_solve((6, 2, 5, 5), float(cf.theta2[k]), "open")
        assert abs(float(tr.theta3) - cf.theta3[k]) < 1e-14
        assert abs(float(tr.theta4) - cf.theta4[k]) < 1e-14


def test_closed_form_batch_rows_equal_single_sweeps():
    links = np.array(LINKS, dtype=float)
    b = pk.sweep_batch(links, method="closed-form", mode="crossed", threads=2)
    assert b.method == "closed-form"
    for m, r in enumerate(LINKS):
        s = pk.FourBar(*r).sweep(mode="crossed", method="closed-form")
        np.testing.assert_array_equal(b.theta3[m], s.theta3)
        np.testing.assert_array_equal(b.status[m], s.status)


def test_method_is_validated():
    fb = pk.FourBar(6, 2, 5, 5)
    for call in (
        lambda: fb.sweep(method="bogus"),
        lambda: pk.reference.sweep(fb, method="bogus"),
        lambda: pk.sweep_batch([[6, 2, 5, 5]], method="closed_form"),
    ):
        with pytest.raises(ValueError, match=r"^method "):
            call()
    assert math.isnan(fb.sweep(method="closed-form").summary().residual_max)


# --- predictor="closed-form": every point from its own closed form, verified by Newton -----


@pytest.mark.parametrize("r", LINKS)
@pytest.mark.parametrize("mode", ["open", "crossed"])
def test_closed_form_predictor_equals_the_reference_bit_for_bit(r, mode):
    fb = pk.FourBar(*r)
    t2 = np.append(pk.DEFAULT_THETA2, [np.nan, 1e6, -7.0])
    s = fb.sweep(t2, mode=mode, predictor="closed-form", omega2=2.0)
    ref = pk.reference.sweep(fb, t2, mode=mode, predictor="closed-form", omega2=2.0)
    for name in ("theta3", "theta4", "status", "nit", "residual", "omega3", "omega4"):
        np.testing.assert_array_equal(getattr(s, name), getattr(ref, name), err_msg=name)


@pytest.mark.parametrize("r", LINKS)
@pytest.mark.parametrize("mode", ["open", "crossed"])
def test_closed_form_predictor_keeps_the_mode_and_the_closed_forms_statuses(r, mode):
    # each point is the closed form of the mode, polished: within the Newton tolerance of
    # it, and never the other mode; where the closed form has no assembly, neither has it
    fb = pk.FourBar(*r)
    s = fb.sweep(mode=mode, predictor="closed-form", tol=1e-12)
    c3, c4 = fb.closed_form(s.theta2, mode)
    cst = fb.closed_form_status(s.theta2, mode)
    ok = s.success
    np.testing.assert_array_equal(ok, cst == S.CONVERGED)
    gap = np.angle(np.exp(1j * (s.theta3[ok] - c3[ok])))
    assert np.max(np.abs(gap), initial=0.0) < 1e-11
    sign = 1.0 if mode == "open" else -1.0
    assert np.all(np.sin(s.theta4[ok] - s.theta3[ok]) * sign > 0)
    # no point depends on another: a sweep of one angle gives the same point
    for k in np.flatnonzero(ok)[::40]:
        one = fb.sweep(s.theta2[k : k + 1], mode=mode, predictor="closed-form", tol=1e-12)
        assert one.theta3[0] == s.theta3[k] and one.theta4[0] == s.theta4[k]


def test_closed_form_predictor_batch_rows_equal_single_sweeps():
    links = np.array(LINKS, dtype=float)
    b = pk.sweep_batch(links, predictor="closed-form", threads=2)
    for m, r in enumerate(LINKS):
        s = pk.FourBar(*r).sweep(predictor="closed-form")
        np.testing.assert_array_equal(b.theta3[m], s.theta3)
        np.testing.assert_array_equal(b.status[m], s.status)
