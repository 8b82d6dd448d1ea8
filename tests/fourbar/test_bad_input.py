"""Bad input: every invalid argument raises ValueError whose message starts with the
parameter's name (DESIGN.md), in the Rust-backed API and in the NumPy reference alike."""

from __future__ import annotations

import math
import re

import numpy as np
import planarkin as pk
import pytest
from planarkin import reference as ref
from truth import SEED_LINKAGE, mp_solve

BAD_LENGTHS = [0, 0.0, -0.0, -1, -1e-300, math.nan, math.inf, -math.inf, np.float64("nan"),
               "abc", "", None, 1j, 1 + 0j, np.complex128(2), [1.0, 2.0], object(),
               True, np.bool_(False)]  # fmt: skip
NAMES = ("r1", "r2", "r3", "r4")
S = pk.Status


def raises_named(name: str):
    """pytest.raises(ValueError) whose message starts with ``name`` (as a whole word)."""
    return pytest.raises(ValueError, match=r"^" + re.escape(name) + r"(?!\w)")


class Lengths:
    """A plain object with r1..r4, as the reference accepts."""

    def __init__(self, r1, r2, r3, r4):
        self.r1, self.r2, self.r3, self.r4 = r1, r2, r3, r4


@pytest.fixture
def fb():
    return pk.FourBar(*SEED_LINKAGE)


# --- lengths -------------------------------------------------------------------------------


@pytest.mark.parametrize("i", range(4))
@pytest.mark.parametrize("bad", BAD_LENGTHS, ids=repr)
def test_bad_length(i, bad):
    args = list(SEED_LINKAGE)
    args[i] = bad
    with raises_named(NAMES[i]):
        pk.FourBar(*args)


@pytest.mark.parametrize("i", range(4))
@pytest.mark.parametrize("bad", [0, -1, math.nan, math.inf, "abc", None, 1j], ids=repr)
def test_bad_length_reference(i, bad):
    args = list(SEED_LINKAGE)
    args[i] = bad
    obj = Lengths(*args)
    with raises_named(NAMES[i]):
        ref.solve(obj, 0.3)
    with raises_named(NAMES[i]):
        ref.sweep(obj)
    with raises_named(NAMES[i]):
        ref.closed_form(obj, 0.3)
    with raises_named(NAMES[i]):
        ref.velocity(obj, 0.3, 1.0, 2.0, 1.0)


def test_first_bad_length_is_named():
    with raises_named("r2"):
        pk.FourBar(1.0, 0.0, -1.0, math.nan)


def test_good_lengths_accepted():
    for r in [(1, 2, 3, 4), (np.float64(1), np.int64(2), 3.5, np.float32(4)), (1e-300,) * 4,
              (1e300,) * 4, (5e-324, 1, 1, 1)]:  # fmt: skip
        fb = pk.FourBar(*r)
        assert fb.lengths == tuple(float(x) for x in r)


# --- options -------------------------------------------------------------------------------

BAD_TOL = [0, 0.0, -1e-9, -math.inf, math.nan, math.inf, "x", None, 1j]
BAD_MAX_ITER = [0, -1, 1.5, 2.0, True, False, None, "3", 2**32, np.float64(3)]


def calls(fb):
    """Every entry point that takes tol / max_iter, as callables of keyword options."""
    links = np.array([SEED_LINKAGE])
    return {
        "solve": lambda **kw: fb.solve(0.3, **kw),
        "sweep": lambda **kw: fb.sweep(**kw),
        "sweep_batch": lambda **kw: pk.sweep_batch(links, **kw),
        "ref.solve": lambda **kw: ref.solve(fb, 0.3, **kw),
        "ref.sweep": lambda **kw: ref.sweep(fb, **kw),
    }


@pytest.mark.parametrize("bad", BAD_TOL, ids=repr)
def test_bad_tol(fb, bad):
    for call in calls(fb).values():
        with raises_named("tol"):
            call(tol=bad)


@pytest.mark.parametrize("bad", BAD_MAX_ITER, ids=repr)
def test_bad_max_iter(fb, bad):
    for call in calls(fb).values():
        with raises_named("max_iter"):
            call(max_iter=bad)


def _results(out):
    """(status, nit, theta3) arrays of a Solution, Sweep or BatchSweep (one row)."""
    return (np.ravel(out.status), np.ravel(out.nit), np.ravel(out.theta3))


def test_good_options_accepted(fb):
    """The extremes of the valid range are accepted and mean what they say; every run is
    bounded (the largest max_iter only with a tolerance that converges in a few steps)."""
    for name, call in calls(fb).items():
        # at most one Newton step per attempt (a sweep point may make two attempts)
        st, nit, _ = _results(call(tol=1e-300, max_iter=1))
        assert (nit <= 2).all(), name
        assert set(st.tolist()) <= {S.CONVERGED, S.MAX_ITERATIONS, S.PRECISION_LOSS}, name
        # a tolerance of 1: the start (closed form or prediction) is already converged
        st, nit, _ = _results(call(tol=1.0, max_iter=np.int64(7)))
        assert (st == S.CONVERGED).all() and (nit == 0).all(), name
        # a float32 tolerance and the largest max_iter: converged in a few steps, right
        out = call(tol=np.float32(1e-6), max_iter=2**32 - 1)
        st, nit, t3 = _results(out)
        assert (st == S.CONVERGED).all() and nit.max() <= 10, name
        t2 = np.ravel(out.theta2) if np.ndim(out.theta2) else np.array([out.theta2])
        for k in range(0, len(t2), 60):
            assert abs(t3[k] - mp_solve(SEED_LINKAGE, t2[k]).t3) < 1e-6, name


@pytest.mark.parametrize("bad", ["bogus", "", "OPEN", "Crossed", None, 0, b"open"], ids=repr)
def test_bad_mode(fb, bad):
    links = np.array([SEED_LINKAGE])
    for call in (
        lambda: fb.solve(0.3, mode=bad),
        lambda: fb.sweep(mode=bad),
        lambda: fb.closed_form(0.3, bad),
        lambda: fb.closed_form_status(0.3, bad),
        lambda: pk.sweep_batch(links, mode=bad),
        lambda: pk.closed_form_batch(links, mode=bad),
        lambda: ref.solve(fb, 0.3, mode=bad),
        lambda: ref.sweep(fb, mode=bad),
        lambda: ref.closed_form(fb, 0.3, bad),
    ):
        with raises_named("mode"):
            call()


@pytest.mark.parametrize("bad", ["bogus", "", "Quadratic", None, 1], ids=repr)
def test_bad_predictor(fb, bad):
    for call in (
        lambda: fb.sweep(predictor=bad),
        lambda: pk.sweep_batch(np.array([SEED_LINKAGE]), predictor=bad),
        lambda: ref.sweep(fb, predictor=bad),
    ):
        with raises_named("predictor"):
            call()


@pytest.mark.parametrize(
    "bad",
    [(1.0,), (1.0, 2.0, 3.0), 1.0, np.zeros(3), (), [[1, 2]], 7],
    ids=repr,
)
def test_bad_guess_shape(fb, bad):
    for call in (
        lambda: fb.solve(0.3, guess=bad),
        lambda: fb.sweep(guess=bad),
        lambda: ref.solve(fb, 0.3, guess=bad),
        lambda: ref.sweep(fb, guess=bad),
    ):
        with raises_named("guess"):
            call()


@pytest.mark.parametrize(
    "bad, which",
    [((1.0, "x"), "guess[1]"), (("y", 1.0), "guess[0]"), ((1j, 0.0), "guess[0]"),
     ((0.0, None), "guess[1]")],
)  # fmt: skip
def test_bad_guess_entry(fb, bad, which):
    for call in (lambda: fb.solve(0.3, guess=bad), lambda: ref.sweep(fb, guess=bad)):
        with raises_named(which):
            call()


def test_non_finite_guess_is_a_status_not_an_error(fb):
    for g in ((math.nan, 1.0), (1.0, math.inf), (-math.inf, math.nan)):
        s = fb.solve(0.3, guess=g, history=True)
        assert s.status == pk.Status.NON_FINITE and s.nit == 0
        # a sweep only uses the guess for its first point and retries from the closed form
        assert fb.sweep([0.3], guess=g).status[0] == pk.Status.CONVERGED
    assert ref.solve(fb, 0.3, guess=(math.nan, 1.0)).status == pk.Status.NON_FINITE


@pytest.mark.parametrize("g", [(1.0, math.inf), (-math.inf, 0.0)])
def test_infinite_guess_reference(fb, g):
    assert ref.solve(fb, 0.3, guess=g).status == pk.Status.NON_FINITE
    assert ref.sweep(fb, [0.3], guess=g).status[0] == pk.Status.CONVERGED


# --- arrays --------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "bad", [np.zeros((3, 2)), np.zeros((1, 1)), [[0.1, 0.2]], np.zeros((2, 2, 2))]
)
def test_theta2_not_1d_for_sweep(fb, bad):
    for call in (
        lambda: fb.sweep(bad),
        lambda: ref.sweep(fb, bad),
        lambda: pk.sweep_batch(np.array([SEED_LINKAGE]), bad),
        lambda: pk.closed_form_batch(np.array([SEED_LINKAGE]), bad),
    ):
        with raises_named("theta2"):
            call()


@pytest.mark.parametrize("bad", [["a", "b"], [1j, 2.0], "abc", [[1.0], [2.0, 3.0]], [None, 1.0]],
                         ids=repr)  # fmt: skip
def test_theta2_not_real(fb, bad):
    for call in (lambda: fb.sweep(bad), lambda: fb.closed_form(bad), lambda: ref.sweep(fb, bad)):
        with raises_named("theta2"):
            call()


@pytest.mark.parametrize("bad", ["abc", None, 1j, [0.1, 0.2]], ids=repr)
def test_solve_theta2_not_a_real_scalar(fb, bad):
    for call in (lambda: fb.solve(bad), lambda: ref.solve(fb, bad)):
        with raises_named("theta2"):
            call()


@pytest.mark.parametrize(
    "bad",
    [np.ones((3, 3)), np.ones(4), np.ones((2, 4, 1)), [[6, 2, 5]], np.ones((2, 5)), "abcd",
     [[1, 2, 3, 4], [1, 2, 3]], np.ones((4, 2))],
    ids=["3x3", "4", "2x4x1", "1x3", "2x5", "str", "ragged", "4x2"],
)  # fmt: skip
def test_links_wrong_shape(bad):
    for call in (lambda: pk.sweep_batch(bad), lambda: pk.closed_form_batch(bad)):
        with raises_named("links"):
            call()


@pytest.mark.parametrize("bad", [0.0, -1.0, math.nan, math.inf, -math.inf, -0.0])
@pytest.mark.parametrize("pos", [(0, 0), (1, 2), (4, 3), (2, 1)])
def test_links_bad_entry_named(bad, pos):
    links = np.tile(np.array(SEED_LINKAGE), (5, 1))
    links[pos] = bad
    i, j = pos
    for call in (lambda: pk.sweep_batch(links), lambda: pk.closed_form_batch(links)):
        with pytest.raises(ValueError, match=r"^" + re.escape(f"links[{i}, {j}]")):
            call()


def _out_cases():
    """Each a bad `out` for 2 linkages at 5 angles, with the entry its error names."""
    ok = np.zeros((2, 5))
    shared = np.zeros((4, 5))
    readonly = np.zeros((2, 5))
    readonly.flags.writeable = False
    return {
        "list": (list((ok, ok.copy())), "out"),
        "one array": ((ok,), "out"),
        "int": ((np.zeros((2, 5), dtype=np.int64), ok), "out[0]"),
        "float32": ((ok, np.zeros((2, 5), dtype=np.float32)), "out[1]"),
        "not an array": ((ok, [[0.0] * 5] * 2), "out[1]"),
        "transposed shape": ((np.zeros((5, 2)), ok), "out[0]"),
        "one row short": ((ok, np.zeros((1, 5))), "out[1]"),
        "strided": ((np.zeros((2, 10))[:, ::2], ok), "out[0]"),
        "Fortran order": ((np.asfortranarray(np.zeros((2, 5))), ok), "out[0]"),
        "read-only": ((ok, readonly), "out[1]"),
        "same array": ((ok, ok), "out[0]"),
        "overlapping views": ((shared[:2], shared[1:3]), "out[0]"),
    }


@pytest.mark.parametrize("case", list(_out_cases()))
def test_closed_form_batch_bad_out_named(case):
    out, name = _out_cases()[case]
    links = np.array([SEED_LINKAGE, SEED_LINKAGE])
    with raises_named(name):
        pk.closed_form_batch(links, np.linspace(0.0, 1.0, 5), out=out)


def test_binding_refuses_fortran_ordered_arrays():
    """The kernel's own checks (the public functions make their inputs C-ordered first): a
    Fortran-ordered array, whose flat values run down its columns, is refused by name rather
    than read or written in the wrong order."""
    from planarkin import _kernel

    links = np.array([SEED_LINKAGE, [2.0, 0.5, 1.5, 1.8], [1.0, 0.2, 1.2, 0.9]])
    t = np.linspace(0.0, 1.0, 5)
    with raises_named("links"):
        _kernel.closed_form_batch(np.asfortranarray(links), t, "open", 1)
    with raises_named("links"):
        args = ("open", 1e-9, 100, "quadratic", "newton", 1)
        _kernel.sweep_batch(np.asfortranarray(links), t, *args)
    out = (np.zeros((3, 5), order="F"), np.zeros((3, 5)))
    with raises_named("out[0]"):
        _kernel.closed_form_batch(links, t, "open", 1, out)


def test_closed_form_batch_out_sharing_theta2_named():
    """An output that holds the crank angles it is computed from: the kernel's borrow check
    refuses it, naming the output."""
    out0 = np.zeros((1, 5))
    out0[0] = np.linspace(0.0, 1.0, 5)
    with raises_named("out[0]"):
        pk.closed_form_batch(np.array([SEED_LINKAGE]), out0[0], out=(out0, np.zeros((1, 5))))


def test_links_empty_is_fine():
    b = pk.sweep_batch(np.ones((0, 4)))
    assert b.theta3.shape == (0, 361)
    c3, c4 = pk.closed_form_batch(np.ones((0, 4)), [0.1, 0.2])
    assert c3.shape == c4.shape == (0, 2)


@pytest.mark.parametrize("bad", [0, -1, -100, 1.5, True, "2", 2.0])
def test_bad_threads(bad):
    links = np.array([SEED_LINKAGE])
    for call in (lambda: pk.sweep_batch(links, threads=bad),
                 lambda: pk.closed_form_batch(links, threads=bad)):  # fmt: skip
        with raises_named("threads"):
            call()


def test_good_threads(fb):
    links = np.array([SEED_LINKAGE] * 3)
    base = pk.sweep_batch(links)
    for th in (1, 2, np.int64(4), 64, None):
        b = pk.sweep_batch(links, threads=th)
        np.testing.assert_array_equal(b.theta3, base.theta3)


# --- rates and coupler point -------------------------------------------------------------------


def test_alpha2_without_omega2(fb):
    with raises_named("alpha2"):
        fb.sweep(alpha2=1.0)


def test_alpha2_without_omega2_reference(fb):
    with raises_named("alpha2"):
        ref.sweep(fb, alpha2=1.0)


@pytest.mark.parametrize("bad", ["x", 1j, [1.0, 2.0], math.nan, math.inf, -math.inf], ids=repr)
def test_bad_omega2_alpha2(fb, bad):
    with raises_named("omega2"):
        fb.sweep(omega2=bad)
    with raises_named("omega2"):
        ref.sweep(fb, omega2=bad)
    with raises_named("alpha2"):
        fb.sweep(omega2=1.0, alpha2=bad)
    with raises_named("alpha2"):
        ref.sweep(fb, omega2=1.0, alpha2=bad)


@pytest.mark.parametrize(
    "name, kw",
    [("p", dict(p="x", delta=0.0)), ("delta", dict(p=1.0, delta=None)),
     ("p", dict(p=1j, delta=0.0))],
)  # fmt: skip
def test_bad_coupler_point_parameters(fb, name, kw):
    with raises_named(name):
        fb.coupler_point(0.1, 0.2, **kw)


def test_shapes_that_do_not_broadcast(fb):
    with pytest.raises(ValueError, match="broadcast"):
        fb.velocity([1.0, 2.0], [1.0, 2.0, 3.0], 0.0, 1.0)
    with pytest.raises(ValueError, match="broadcast"):
        fb.acceleration(np.zeros(2), np.zeros(3), 0.0, 1.0, 0.0)
    with pytest.raises(ValueError, match="broadcast"):
        fb.coupler_point(np.zeros(2), np.zeros(3), 1.0, 0.0)


@pytest.mark.parametrize("bad", [["a"], [1j]], ids=repr)
def test_velocity_arrays_not_real(fb, bad):
    with raises_named("theta3"):
        fb.velocity(0.1, bad, 0.2, 1.0)
    with raises_named("omega2"):
        fb.velocity(0.1, 0.2, 0.3, bad)


@pytest.mark.parametrize("bad", [math.nan, math.inf], ids=repr)
def test_non_finite_crank_rates_at_given_positions(fb, bad):
    """A NaN or infinite crank rate at given positions is a ValueError naming omega2 or
    alpha2, as for lengths, never NaN rates at valid positions."""
    with raises_named("omega2"):
        fb.velocity(0.3, 1.2, 2.0, [1.0, bad])
    with raises_named("omega2"):
        fb.acceleration(0.3, 1.2, 2.0, bad, 0.0)
    with raises_named("alpha2"):
        fb.acceleration(0.3, 1.2, 2.0, 1.0, bad)


def test_coupler_curve_needs_a_sweep_of_this_linkage(fb):
    """coupler_curve takes a Sweep of this linkage only: another linkage's sweep or anything
    that is not a Sweep is a ValueError naming ``sweep``; its own sweep gives the curve."""
    other = pk.FourBar(6, 2, 5, 4.5).sweep()
    with raises_named("sweep"):
        fb.coupler_curve(other, 3.0, 0.5)
    for bad in (np.zeros(3), None, (1.0, 2.0)):
        with raises_named("sweep"):
            fb.coupler_curve(bad, 3.0, 0.5)
    x, y = fb.coupler_curve(fb.sweep(), 3.0, 0.5)  # its own sweep: accepted
    assert x.shape == y.shape == (361,)
