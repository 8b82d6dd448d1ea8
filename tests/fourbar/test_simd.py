"""The SIMD kernels (polynomial sin/cos/atan2, 4 lanes) against the scalar path and the
NumPy reference: statuses identical everywhere (toggles, spans that cannot assemble,
NaN and infinite angles, both modes, every predictor), angles within 1e-12 rad (the
documented parity tolerance; measured below 1e-13), and the switch back to the bit-exact
scalar path (``pk.use_simd(False)``, ``PLANARKIN_SIMD=0``)."""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import planarkin as pk
import pytest
from truth import SEED_LINKAGE, random_links

TOL = 1e-12  # documented parity tolerance of the SIMD path (rad)

pytestmark = pytest.mark.skipif(not pk.simd_available(), reason="CPU without AVX2 + FMA")


@pytest.fixture(autouse=True)
def simd_on():
    with pk.use_simd(True):
        yield


def _angle_diff(a, b):
    d = np.angle(np.exp(1j * (np.asarray(a) - np.asarray(b))))
    return np.abs(d)


def assert_close(a, b, tol=TOL):
    """Same NaN pattern, angles within ``tol`` (mod 2 pi)."""
    a, b = np.asarray(a), np.asarray(b)
    np.testing.assert_array_equal(np.isnan(a), np.isnan(b))
    ok = ~np.isnan(a)
    err = float(_angle_diff(a[ok], b[ok]).max(initial=0.0))
    assert err <= tol, err
    return err


def _links(rng, n):
    seed = np.array(
        [SEED_LINKAGE, (6.0, 2.0, 6.0, 2.0), (2.0, 5.0, 2.5, 2.0), (1.0, 1.0, 1.0, 1.0)]
    )
    parts = [seed, random_links(rng, n, "grashof"), random_links(rng, n, "non-grashof")]
    return np.vstack(parts)


def _angles():
    t2 = np.concatenate([pk.DEFAULT_THETA2, np.linspace(-np.pi, np.pi, 2001)[1::7]])
    t2[[5, 40, 41]] = [np.nan, np.inf, -np.inf]
    return t2


def test_switch_and_environment_variable():
    assert pk.simd_enabled()
    with pk.use_simd(False):
        assert not pk.simd_enabled()
    assert pk.simd_enabled()
    code = "import planarkin as pk; print(pk.simd_enabled())"
    env = {**os.environ, "PLANARKIN_SIMD": "0"}
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert out.stdout.strip() == "False", out.stderr


@pytest.mark.parametrize("predictor", ["quadratic", "tangent", "previous"])
@pytest.mark.parametrize("mode", ["open", "crossed"])
def test_sweep_statuses_equal_the_reference_and_angles_within_1e12(rng, mode, predictor):
    t2 = _angles()
    nit_diff = 0
    for r in _links(rng, 6):
        fb = pk.FourBar(*r)
        a = fb.sweep(t2, mode=mode, predictor=predictor, omega2=1.0)
        b = pk.reference.sweep(fb, t2, mode=mode, predictor=predictor, omega2=1.0)
        np.testing.assert_array_equal(a.status, b.status)
        assert_close(a.theta3, b.theta3)
        assert_close(a.theta4, b.theta4)
        nit_diff += int((a.nit != b.nit).sum())
        assert np.abs(a.nit.astype(int) - b.nit.astype(int)).max() <= 1
        with pk.use_simd(False):
            c = fb.sweep(t2, mode=mode, predictor=predictor, omega2=1.0)
        np.testing.assert_array_equal(c.theta3, b.theta3)  # the switch: bit for bit
        np.testing.assert_array_equal(c.nit, b.nit)
    assert nit_diff <= 5  # a last correction within rounding of tol, at most


@pytest.mark.parametrize("method", ["newton", "closed-form"])
@pytest.mark.parametrize("mode", ["open", "crossed"])
def test_batch_statuses_equal_the_scalar_path(rng, mode, method):
    links = _links(rng, 30)
    t2 = _angles()
    a = pk.sweep_batch(links, t2, mode=mode, method=method, threads=2)
    with pk.use_simd(False):
        b = pk.sweep_batch(links, t2, mode=mode, method=method, threads=1)
    np.testing.assert_array_equal(a.status, b.status)
    assert set(np.unique(b.status)) >= {0, -3, -5}
    assert_close(a.theta3, b.theta3)
    assert_close(a.theta4, b.theta4)
    assert (a.nit != b.nit).sum() <= 5


@pytest.mark.parametrize("mode", ["open", "crossed"])
def test_closed_form_within_1e12_of_the_reference_and_statuses_equal(rng, mode):
    t2 = _angles()
    links = _links(rng, 20)
    worst = 0.0
    for r in links:
        fb = pk.FourBar(*r)
        t3, t4, st = fb._core.closed_form(t2, mode)
        with pk.use_simd(False):
            u3, u4, su = fb._core.closed_form(t2, mode)
        np.testing.assert_array_equal(st, su)
        r3, r4 = pk.reference.closed_form(fb, t2, mode)
        worst = max(worst, assert_close(t3, r3), assert_close(t4, r4))
    b3, b4 = pk.closed_form_batch(links, t2, mode)
    with pk.use_simd(False):
        c3, c4 = pk.closed_form_batch(links, t2, mode)
    assert_close(b3, c3)
    assert_close(b4, c4)
    # written in place, the same bits as new arrays
    out = (np.full_like(b3, 7.0), np.full_like(b4, 7.0))
    pk.closed_form_batch(links, t2, mode, out=out)
    assert out[0].tobytes() == b3.tobytes() and out[1].tobytes() == b4.tobytes()
    assert worst < 1e-13


def test_toggles_and_indeterminate_positions():
    """Angles on and next to the toggles of a triple rocker, and the crank pin on O4 with
    r3 = r4 (indeterminate) or r3 != r4: the scalar path's statuses."""
    for r in [
        (2.0, 5.0, 2.5, 2.0),
        (1.0, 1.0, 1.0, 1.0),
        (1.0, 1.0, 2.0, 1.5),
        (6.0, 2.0, 6.0, 2.0),
    ]:
        fb = pk.FourBar(*r)
        lim = fb.limits()
        t2 = [0.0, np.pi, np.nextafter(0.0, 1.0)]
        for a in lim.dead_points:
            t2 += list(a + np.arange(-3, 4) * 1e-15) + list(a + np.arange(-3, 4) * 1e-9)
        t2 = np.array(t2)
        for mode in ("open", "crossed"):
            a = fb._core.closed_form(t2, mode)
            s = fb.sweep(t2, mode=mode)
            with pk.use_simd(False):
                b = fb._core.closed_form(t2, mode)
                c = fb.sweep(t2, mode=mode)
            np.testing.assert_array_equal(a[2], b[2])
            np.testing.assert_array_equal(s.status, c.status)
            assert_close(a[0], b[0], 1e-6)  # at a toggle rounding moves angles by ~sqrt(eps)


@pytest.mark.parametrize("mode", ["open", "crossed"])
def test_closed_form_predictor_across_angles_agrees_with_the_scalar_path(mode):
    # predictor="closed-form" on the SIMD path: the closed form at 4 angles at once, one
    # Newton evaluation across them; statuses the scalar path's, angles within TOL
    rng = np.random.default_rng(21)
    t2 = _angles()
    for r in _links(rng, 40):
        fb = pk.FourBar(*r)
        fast = fb.sweep(t2, mode=mode, predictor="closed-form", omega2=1.5)
        with pk.use_simd(False):
            slow = fb.sweep(t2, mode=mode, predictor="closed-form", omega2=1.5)
        np.testing.assert_array_equal(fast.status, slow.status, err_msg=str(r))
        assert_close(fast.theta3, slow.theta3)
        assert_close(fast.theta4, slow.theta4)
        np.testing.assert_array_equal(np.isnan(fast.omega3), np.isnan(slow.omega3))
