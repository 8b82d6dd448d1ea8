"""The NumPy reference of the four-bar: the same algorithms as the Rust kernel, written
plainly (a scalar loop over ``math``), so tests can prove the kernel computes the same
thing and benchmarks can show what Rust buys. It reaches no kernel (see the package).

Operation order follows the kernel's scalar path, so on the same machine the two agree
bit for bit with ``pk.use_simd(False)`` (or ``PLANARKIN_SIMD=0``). The SIMD kernels, the
default where the CPU has AVX2 and FMA, evaluate sin/cos/atan2 by polynomials: their
statuses are the same, their angles agree with this reference to 1e-12 rad (the stated
parity tolerance; measured below 1e-13 rad).
Functions take any object with ``r1, r2, r3, r4`` attributes (e.g. ``planarkin.FourBar``).
"""

from __future__ import annotations

import math

import numpy as np

from .._angles import TAU, wrap
from .._args import as_float, check_guess
from .._status import SINGULAR_THRESHOLD, Status
from ..fourbar._results import Solution, Sweep
from ._rules import check_mode, check_options, motion_args, sweep_args

_NAN = float("nan")


def _raw_lengths(fb: object) -> tuple[float, float, float, float]:
    r = tuple(as_float(n, getattr(fb, n)) for n in ("r1", "r2", "r3", "r4"))
    for n, v in zip(("r1", "r2", "r3", "r4"), r, strict=True):
        if not (math.isfinite(v) and v > 0):
            raise ValueError(f"{n} must be finite and > 0, got {v}")
    return r  # type: ignore[return-value]


def unit_lengths(r: tuple[float, float, float, float]) -> tuple[float, float, float, float]:
    """The lengths divided by 2^e with 2^e <= longest < 2^(e+1) (exact): the scale-free
    problem the kernel solves, so any scale neither overflows nor underflows and
    power-of-two scales give bit-identical results. A length below about 1e-308 times the
    longest that the division does not keep exactly: ValueError naming it."""
    e = math.frexp(max(r))[1] - 1
    u = tuple(math.ldexp(v, -e) for v in r)
    for n, v, raw in zip(("r1", "r2", "r3", "r4"), u, r, strict=True):
        if v == 0.0 or math.ldexp(v, e) != raw:  # subnormal unit lengths: kept if exact
            raise ValueError(
                f"{n} is too short relative to the longest link to be represented "
                f"(ratio below ~1e-308), got {raw}"
            )
    return u  # type: ignore[return-value]


def _lengths(fb: object) -> tuple[float, float, float, float]:
    """The validated unit lengths of ``fb`` (what every computation uses)."""
    return unit_lengths(_raw_lengths(fb))


#: As the kernel: sides that close within this many ulp of the longest link are flat.
FLAT_ULPS = 8.0
EPS = 2.220446049250313e-16


def _flat(q: float, slack: float) -> float:
    return 0.0 if -slack <= q < 0.0 else q


def _closed(r: tuple, c2: float, s2: float, sign: float):
    """(theta3, theta4, sin34) or the strings 'not-assemblable' / 'indeterminate'.

    Circle intersection: B at distance r3 from A and r4 from O4. 2 d h (h the height of B
    over the line A-O4) from Heron's formula in factored form; the directions A->B and
    O4->B are u = O4 - A turned by the angles at A and O4, whose (cos, sin) are
    proportional to (k + d^2, 2dh) and (k - d^2, 2dh), k = r3^2 - r4^2.
    """
    r1, r2, r3, r4 = r
    ux = r1 - r2 * c2
    uy = -(r2 * s2)
    d2 = ux * ux + uy * uy
    d = math.sqrt(d2)
    if d == 0.0:
        return "indeterminate" if r3 == r4 else "not-assemblable"
    # a triangle that closes within a few ulp of the longest link is flat (a dead point)
    slack = FLAT_ULPS * EPS * max(r)
    q1 = _flat(d + r3 - r4, slack)
    q2 = _flat(d - r3 + r4, slack)
    q3 = _flat(r3 + r4 - d, slack)
    if not (q1 >= 0.0 and q2 >= 0.0 and q3 >= 0.0):
        return "not-assemblable"
    two_dh = math.sqrt((r3 + r4 + d) * q1 * q2 * q3)
    k = (r3 - r4) * (r3 + r4)
    h = sign * two_dh
    ca, cb = k + d2, k - d2
    t3 = math.atan2(uy * ca + ux * h + 0.0, ux * ca - uy * h)
    t4 = math.atan2(uy * cb + ux * h + 0.0, ux * cb - uy * h)
    return t3, t4, h / (2.0 * (r3 * r4))


def _sign(mode: str) -> float:
    return 1.0 if mode == "open" else -1.0


def _jac_of(r: tuple, s3: float, c3: float, s4: float, c4: float) -> tuple:
    _, _, r3, r4 = r
    return (-r3 * s3, r4 * s4, r3 * c3, -r4 * c4)


def _sin(x: float) -> float:
    """math.sin, but NaN for an infinite argument (as libm and the kernel give)."""
    return math.sin(x) if math.isfinite(x) else _NAN


def _cos(x: float) -> float:
    return math.cos(x) if math.isfinite(x) else _NAN


def _jac(r: tuple, t3: float, t4: float):
    s3, c3 = _sin(t3), _cos(t3)
    s4, c4 = _sin(t4), _cos(t4)
    return _jac_of(r, s3, c3, s4, c4), (s3, c3, s4, c4)


#: Largest angle change updated by angle addition instead of libm (2^-7), as in the kernel.
INCREMENT_MAX = 0.0078125
_SIN_C = (-1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0)
_COS_C = (-0.5, 1.0 / 24.0, -1.0 / 720.0, 1.0 / 40320.0)


def sin_cos_shifted(s: float, c: float, dx: float) -> tuple[float, float]:
    """sin(x + dx), cos(x + dx) from sin x, cos x for |dx| <= 2^-7 (Taylor, degree 7/8)."""
    x2 = dx * dx
    sd = dx + dx * x2 * (_SIN_C[0] + x2 * (_SIN_C[1] + x2 * _SIN_C[2]))
    cm = x2 * (_COS_C[0] + x2 * (_COS_C[1] + x2 * (_COS_C[2] + x2 * _COS_C[3])))
    return s + (s * cm + c * sd), c + (c * cm - s * sd)


def _trig(x3: float, x4: float, cache: list) -> tuple:
    """sin/cos of the iterate: by angle addition from the loop's last libm evaluation when
    both angles are within 2^-7 of it, else from libm (which then becomes the anchor);
    shifts never chain. The cache is one per crank angle."""
    last = cache[0]
    if last is not None and abs(x3 - last[0]) < INCREMENT_MAX and abs(x4 - last[1]) < INCREMENT_MAX:
        s3, c3 = sin_cos_shifted(last[2], last[3], x3 - last[0])
        s4, c4 = sin_cos_shifted(last[4], last[5], x4 - last[1])
    else:
        s3, c3 = _sin(x3), _cos(x3)
        s4, c4 = _sin(x4), _cos(x4)
        cache[0] = (x3, x4, s3, c3, s4, c4)  # only libm values anchor rotations
    return s3, c3, s4, c4


def _conditioning(r: tuple, sin34: float) -> float:
    """|sin(theta4 - theta3)| min(r3, r4) / L, as the kernel measures it."""
    return abs(sin34) * (min(r[2], r[3]) / max(r))


def _cramer(j: tuple, b0: float, b1: float):
    j00, j01, j10, j11 = j
    d = j00 * j11 - j01 * j10
    if d == 0.0:
        return None
    return (b0 * j11 - b1 * j01) / d, (j00 * b1 - j10 * b0) / d


def _sin34(r: tuple, j: tuple) -> float:
    j00, j01, j10, j11 = j
    return -(j00 * j11 - j01 * j10) / (r[2] * r[3])


def _newton(r, c2, s2, x3, x4, sign, tol, max_iter, hist, cache):
    """Newton-Raphson from (x3, x4); returns (t3, t4, status, nit, residual, jacobian)."""
    r1, r2, r3, r4 = r
    scale = max(r1, r2, r3, r4)
    nit = 0
    last_small_step = math.inf
    while True:
        s3, c3, s4, c4 = _trig(x3, x4, cache)
        j = _jac_of(r, s3, c3, s4, c4)
        f1 = r2 * c2 + r3 * c3 - r4 * c4 - r1
        f2 = r2 * s2 + r3 * s3 - r4 * s4
        residual = max(0.0, abs(f1), abs(f2)) / scale
        finite = all(math.isfinite(v) for v in (f1, f2, x3, x4))
        if hist is not None:
            hist.append(residual if finite else _NAN)
        if not finite:
            return _NAN, _NAN, Status.NON_FINITE, nit, _NAN, j
        if _conditioning(r, _sin34(r, j)) < SINGULAR_THRESHOLD:
            return _NAN, _NAN, Status.SINGULAR, nit, residual, j
        step = _cramer(j, -f1, -f2)
        if step is None:
            return _NAN, _NAN, Status.SINGULAR, nit, residual, j
        if residual < tol:
            size = max(abs(step[0]), abs(step[1]))
            if size < tol:
                if _sin34(r, j) * sign < 0.0:
                    return _NAN, _NAN, Status.BRANCH_JUMP, nit, residual, j
                # the last correction is applied, without a further evaluation
                return wrap(x3 + step[0]), wrap(x4 + step[1]), Status.CONVERGED, nit, residual, j
            if size > 0.5 * last_small_step:
                return _NAN, _NAN, Status.PRECISION_LOSS, nit, residual, j
            last_small_step = size
        if nit >= max_iter:
            return _NAN, _NAN, Status.MAX_ITERATIONS, nit, residual, j
        x3 = wrap(x3 + step[0])  # angles stay in (-pi, pi]: large iterates lose bits
        x4 = wrap(x4 + step[1])
        nit += 1


def solve(fb, theta2, *, mode="open", guess=None, tol=1e-9, max_iter=100, history=False):
    """Reference of :meth:`planarkin.FourBar.solve`."""
    r = _lengths(fb)
    t2 = as_float("theta2", theta2)
    mode = check_mode(mode)
    tol, max_iter = check_options(tol, max_iter)
    g = check_guess(guess)
    hist = [] if history else None
    out = _point(r, t2, mode, g, tol, max_iter, hist)
    t3, t4, st, nit, res = out[:5]
    h = np.array(hist, dtype=np.float64) if hist is not None else None
    return Solution(t2, t3, t4, st == Status.CONVERGED, st, nit, res, h)


def _point(r, t2, mode, guess, tol, max_iter, hist, cache=None):
    if not math.isfinite(t2):
        return _NAN, _NAN, Status.NON_FINITE, 0, _NAN, None
    s2, c2 = math.sin(t2), math.cos(t2)
    cf = _closed(r, c2, s2, _sign(mode))
    if cf == "not-assemblable":
        return _NAN, _NAN, Status.NOT_ASSEMBLABLE, 0, _NAN, None
    if guess is not None:
        x0 = guess
    elif cf == "indeterminate":
        return _NAN, _NAN, Status.SINGULAR, 0, _NAN, None
    else:
        x0 = cf[:2]
    return _newton(r, c2, s2, x0[0], x0[1], _sign(mode), tol, max_iter, hist, cache or [None])


def _rates(r, t2, j, predictor):
    """dx/dtheta2 and d2x/dtheta2^2 at unit crank speed, from the Jacobian."""
    if predictor == "previous":
        return (0.0, 0.0), (0.0, 0.0)
    r2 = r[1]
    s2, c2 = math.sin(t2), math.cos(t2)
    v = _cramer(j, r2 * s2, -(r2 * c2))
    if v is None:
        return (0.0, 0.0), (0.0, 0.0)
    if predictor == "tangent":
        return v, (0.0, 0.0)
    j00, j01, j10, j11 = j
    w3s, w4s = v[0] * v[0], v[1] * v[1]
    a = _cramer(j, r2 * c2 + j10 * w3s + j11 * w4s, r2 * s2 - j00 * w3s - j01 * w4s)
    return v, (a if a is not None else (0.0, 0.0))


def _solve_checked(r, j, b0, b1):
    """J x = b by Cramer's rule; NaN for non-finite input or a singular position."""
    if not all(math.isfinite(v) for v in (*j, b0, b1)):
        return _NAN, _NAN
    if _conditioning(r, _sin34(r, j)) < SINGULAR_THRESHOLD:
        return _NAN, _NAN
    out = _cramer(j, b0, b1)
    return out if out is not None else (_NAN, _NAN)


def _velocity(r, t2, t3, t4, w2):
    j, _ = _jac(r, t3, t4)
    r2 = r[1]
    s2, c2 = math.sin(t2), math.cos(t2)
    return _solve_checked(r, j, r2 * s2 * w2, -(r2 * c2) * w2)


def _acceleration(r, t2, t3, t4, w2, w3, w4, a2):
    _, r2, r3, r4 = r
    s2, c2 = math.sin(t2), math.cos(t2)
    j, (s3, c3, s4, c4) = _jac(r, t3, t4)
    w2s, w3s, w4s = w2 * w2, w3 * w3, w4 * w4
    b1 = r2 * s2 * a2 + r2 * c2 * w2s + r3 * c3 * w3s - r4 * c4 * w4s
    b2 = -(r2 * c2) * a2 + r2 * s2 * w2s + r3 * s3 * w3s - r4 * s4 * w4s
    return _solve_checked(r, j, b1, b2)


def sweep(
    fb,
    theta2=None,
    *,
    mode="open",
    guess=None,
    tol=1e-9,
    max_iter=100,
    predictor="quadratic",
    method="newton",
    omega2=None,
    alpha2=None,
):
    """Reference of :meth:`planarkin.FourBar.sweep`: the same continuation, predictors
    and closed-form fallback (or the closed form alone), one point at a time in Python."""
    raw = _raw_lengths(fb)
    r = unit_lengths(raw)
    t2s, mode, tol, max_iter, predictor, method = sweep_args(
        theta2, mode, tol, max_iter, predictor, method
    )
    g = check_guess(guess)
    omega2, alpha2 = motion_args(omega2, alpha2)
    sign = _sign(mode)
    n = len(t2s)
    t3o, t4o, reso = np.empty(n), np.empty(n), np.empty(n)
    sto, nito = np.empty(n, dtype=np.int8), np.empty(n, dtype=np.uint32)
    w3o = w4o = a3o = a4o = None
    if omega2 is not None:
        w3o, w4o = np.full(n, _NAN), np.full(n, _NAN)
        if alpha2 is not None:
            a3o, a4o = np.full(n, _NAN), np.full(n, _NAN)
    prev = None
    for i, t2 in enumerate(t2s.tolist()):
        if method == "closed-form":
            t3, t4, st = _closed_point(r, t2, sign)
            t3o[i], t4o[i], sto[i], nito[i], reso[i] = t3, t4, st, 0, _NAN
            if st == Status.CONVERGED and w3o is not None:
                w3, w4 = _velocity(r, t2, t3, t4, omega2)
                w3o[i], w4o[i] = w3, w4
                if a3o is not None:
                    a3o[i], a4o[i] = _acceleration(r, t2, t3, t4, omega2, w3, w4, alpha2)
            continue
        if prev is not None:
            pt2, (x3, x4), (v3, v4), (a3, a4) = prev
            h = wrap(t2 - pt2)
            if predictor == "previous":
                start = (x3, x4)
            elif predictor == "tangent":
                start = (x3 + v3 * h, x4 + v4 * h)
            else:
                hh = 0.5 * h * h
                start = (x3 + v3 * h + a3 * hh, x4 + v4 * h + a4 * hh)
        else:
            start = g if i == 0 else None
        t3, t4, st, nit, res, j = _sweep_point(r, t2, mode, sign, start, tol, max_iter)
        t3o[i], t4o[i], sto[i], nito[i], reso[i] = t3, t4, st, nit, res
        if st == Status.CONVERGED:
            if w3o is not None:
                w3, w4 = _velocity(r, t2, t3, t4, omega2)
                w3o[i], w4o[i] = w3, w4
                if a3o is not None:
                    a3o[i], a4o[i] = _acceleration(r, t2, t3, t4, omega2, w3, w4, alpha2)
            if predictor == "closed-form":
                continue  # every point starts from its own closed form: no previous point
            v, a = _rates(r, t2, j, predictor)
            prev = (t2, (t3, t4), v, a)
        else:
            prev = None
    return Sweep(
        raw, mode, t2s, t3o, t4o, sto, nito, reso,
        omega2=omega2, omega3=w3o, omega4=w4o,
        alpha2=alpha2 if a3o is not None else None, alpha3=a3o, alpha4=a4o, method=method,
        geometry=_NUMPY_GEOMETRY,
    )  # fmt: skip


class _NumpyGeometry:
    """The lazy ``det`` and ``points`` of the reference's sweeps, in NumPy (never the
    kernel: parity tests compare them with the kernel's)."""

    def branch(self, theta3: np.ndarray, theta4: np.ndarray) -> np.ndarray:
        return np.sin(theta4 - theta3)

    def pins(self, lengths, theta2, theta3):  # noqa: ANN001, ANN201
        _, r2, r3, _ = lengths
        t2, t3 = np.asarray(theta2), np.asarray(theta3)
        a = np.column_stack((r2 * np.cos(t2), r2 * np.sin(t2)))
        return a, a + np.column_stack((r3 * np.cos(t3), r3 * np.sin(t3)))


_NUMPY_GEOMETRY = _NumpyGeometry()


def _closed_point(r, t2, sign):
    """One point of a closed-form sweep: (theta3, theta4, status)."""
    if not math.isfinite(t2):
        return _NAN, _NAN, Status.NON_FINITE
    cf = _closed(r, math.cos(t2), math.sin(t2), sign)
    if cf == "not-assemblable":
        return _NAN, _NAN, Status.NOT_ASSEMBLABLE
    if cf == "indeterminate" or _conditioning(r, cf[2]) < SINGULAR_THRESHOLD:
        return _NAN, _NAN, Status.SINGULAR
    return cf[0], cf[1], Status.CONVERGED


def _sweep_point(r, t2, mode, sign, start, tol, max_iter):
    if start is None or not math.isfinite(t2):
        return _point(r, t2, mode, None, tol, max_iter, None)
    s2, c2 = math.sin(t2), math.cos(t2)
    cf = _closed(r, c2, s2, sign)
    if cf == "not-assemblable":
        return _NAN, _NAN, Status.NOT_ASSEMBLABLE, 0, _NAN, None
    cache = [None]  # both attempts at this crank angle share the loop's trig cache
    first = _newton(r, c2, s2, start[0], start[1], sign, tol, max_iter, None, cache)
    if first[2] == Status.CONVERGED:
        return first
    if cf == "indeterminate":
        return _NAN, _NAN, Status.SINGULAR, first[3], _NAN, None
    second = _newton(r, c2, s2, cf[0], cf[1], sign, tol, max_iter, None, cache)
    return (*second[:3], second[3] + first[3], *second[4:])


def closed_form(fb, theta2, mode="open"):
    """Reference of :meth:`planarkin.FourBar.closed_form`: (theta3, theta4), NaN where
    the linkage cannot assemble or the position is indeterminate."""
    r = _lengths(fb)
    mode = check_mode(mode)
    t2 = np.asarray(theta2, dtype=np.float64)
    sign = _sign(mode)
    t3 = np.full(t2.shape, _NAN)
    t4 = np.full(t2.shape, _NAN)
    for idx, a in np.ndenumerate(t2):
        if not math.isfinite(a):
            continue
        cf = _closed(r, math.cos(a), math.sin(a), sign)
        if isinstance(cf, tuple):
            t3[idx], t4[idx] = cf[0], cf[1]
    if t2.ndim == 0:
        return float(t3), float(t4)
    return t3, t4


def closed_form_vectorized(r1, r2, r3, r4, theta2, mode="open"):
    """The closed form as a NumPy user would vectorize it (broadcasts over lengths and
    angles). Used by benchmarks as the fastest plain-NumPy way; NaN where not assemblable."""
    c2, s2 = np.cos(theta2), np.sin(theta2)
    ux = r1 - r2 * c2
    uy = -(r2 * s2)
    d = np.sqrt(ux * ux + uy * uy)
    with np.errstate(invalid="ignore"):
        two_dh = np.sqrt((r3 + r4 + d) * (d + r3 - r4) * (d - r3 + r4) * (r3 + r4 - d))
    k = (r3 - r4) * (r3 + r4)
    phi = np.arctan2(uy, ux)
    sign = _sign(check_mode(mode))
    t3 = phi + sign * np.arctan2(two_dh, k + d * d)
    t4 = phi + sign * np.arctan2(two_dh, k - d * d)
    # wrap to (-pi, pi]
    t3 = np.pi - np.mod(np.pi - t3, TAU)
    t4 = np.pi - np.mod(np.pi - t4, TAU)
    return t3, t4


def velocity(fb, theta2, theta3, theta4, omega2):
    """Reference of :meth:`planarkin.FourBar.velocity` for scalars."""
    return _velocity(_lengths(fb), float(theta2), float(theta3), float(theta4), float(omega2))


def acceleration(fb, theta2, theta3, theta4, omega2, alpha2=0.0):
    """Reference of :meth:`planarkin.FourBar.acceleration` for scalars."""
    r = _lengths(fb)
    t2, t3, t4, w2 = float(theta2), float(theta3), float(theta4), float(omega2)
    w3, w4 = _velocity(r, t2, t3, t4, w2)
    if math.isnan(w3):
        return _NAN, _NAN
    return _acceleration(r, t2, t3, t4, w2, w3, w4, float(alpha2))
