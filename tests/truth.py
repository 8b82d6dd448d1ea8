"""Independent truths shared by every test folder: a high-precision four-bar and the
Ackermann steering condition.

Nothing here imports planarkin: ``mp_solve`` intersects two circles in mpmath at 50
significant digits, from the exact binary values of the lengths and the crank angle (which
mpmath reduces itself, however large it is). Fixtures live in conftest.py; this module is
on the path through ``pythonpath = ["tests"]`` in pyproject.toml.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import mpmath
import numpy as np

MP_DPS = 50


SEED_LINKAGE = (6.0, 2.0, 5.0, 5.0)


@dataclass(frozen=True)
class MpPoint:
    """A solution of the loop equations in mpmath: angles in (-pi, pi] and sin(t4 - t3)."""

    theta3: mpmath.mpf
    theta4: mpmath.mpf
    sin34: mpmath.mpf

    @property
    def t3(self) -> float:
        return float(self.theta3)

    @property
    def t4(self) -> float:
        return float(self.theta4)


def _mp_wrap(a):
    """Wraps an mpf to (-pi, pi]."""
    two_pi = 2 * mpmath.pi
    r = a - two_pi * mpmath.floor((a + mpmath.pi) / two_pi)  # in [-pi, pi)
    return mpmath.pi if r == -mpmath.pi else r


def _mp_points(r, t):
    """Both circle intersections (B at r3 from the crank pin A and r4 from O4) at crank
    angle t (an mpf), or None where the circles do not meet or A coincides with O4."""
    r1, r2, r3, r4 = r
    ax, ay = r2 * mpmath.cos(t), r2 * mpmath.sin(t)
    ux, uy = r1 - ax, -ay  # A -> O4
    dd = ux * ux + uy * uy
    if dd == 0:
        return None
    d = mpmath.sqrt(dd)
    a = (r3 * r3 - r4 * r4 + dd) / (2 * d)  # distance from A to the foot of B along A->O4
    hh = r3 * r3 - a * a
    if hh < 0:
        return None
    h = mpmath.sqrt(hh)
    px, py = ax + a * ux / d, ay + a * uy / d
    out = []
    for side in (1, -1):
        bx, by = px - side * h * uy / d, py + side * h * ux / d
        t3 = mpmath.atan2(by - ay, bx - ax)
        t4 = mpmath.atan2(by, bx - r1)
        out.append(MpPoint(_mp_wrap(t3), _mp_wrap(t4), mpmath.sin(t4 - t3)))
    return out


def mp_solve(r, theta2, mode="open", dps=MP_DPS):
    """The solution of ``mode`` (sin(t4 - t3) > 0 open, < 0 crossed) at the float crank
    angle ``theta2``, computed in mpmath; None where the linkage cannot assemble. At an
    exact toggle (h = 0) both modes give the same point."""
    # memoised on the exact floats: the extreme-case tests ask for the same truth once per
    # predictor, and an MpPoint (mpf fields, frozen) is immutable, so sharing it is safe
    return _mp_solve(tuple(float(x) for x in r), float(theta2), mode, dps)


@functools.lru_cache(maxsize=1 << 16)
def _mp_solve(r, theta2, mode, dps):
    with mpmath.workdps(dps):
        rr = [mpmath.mpf(x) for x in r]
        pts = _mp_points(rr, mpmath.mpf(theta2))
        if pts is None:
            return None
        want = 1 if mode == "open" else -1
        for p in pts:
            if mpmath.sign(p.sin34) == want:
                return p
        return pts[0]  # toggle: sin34 == 0 for both


def mp_residual(r, theta2, t3, t4, dps=MP_DPS):
    """max(|f1|, |f2|) / longest link of the loop equations in mpmath at float angles."""
    with mpmath.workdps(dps):
        r1, r2, r3, r4 = (mpmath.mpf(float(x)) for x in r)
        t2, a3, a4 = (mpmath.mpf(float(x)) for x in (theta2, t3, t4))
        f1 = r2 * mpmath.cos(t2) + r3 * mpmath.cos(a3) - r4 * mpmath.cos(a4) - r1
        f2 = r2 * mpmath.sin(t2) + r3 * mpmath.sin(a3) - r4 * mpmath.sin(a4)
        return float(max(abs(f1), abs(f2)) / max(r1, r2, r3, r4))


def mp_angle_of(r, mode, which, dps=MP_DPS):
    """theta3 or theta4 (``which`` 3 or 4) of ``mode`` as a smooth function of an mpf crank
    angle (unwrapped around its value at the first call's neighbourhood), for mpmath.diff."""
    rr = None

    def f(t):
        nonlocal rr
        if rr is None:
            rr = [mpmath.mpf(float(x)) for x in r]
        pts = _mp_points(rr, t)
        want = 1 if mode == "open" else -1
        p = next(q for q in pts if mpmath.sign(q.sin34) == want)
        return p.theta3 if which == 3 else p.theta4

    return f


def mp_rates(r, theta2, mode, omega2, alpha2=0.0, dps=MP_DPS):
    """(omega3, omega4, alpha3, alpha4) by mpmath.diff of the mpmath closed form:
    omega = x' w2, alpha = x'' w2^2 + x' a2 (x as a function of the crank angle)."""
    with mpmath.workdps(dps):
        t0 = mpmath.mpf(float(theta2))
        out = []
        for which in (3, 4):
            f = mp_angle_of(r, mode, which)
            ref = f(t0)

            def g(t, f=f, ref=ref):  # unwrapped near t0: no jump at +-pi
                return ref + _mp_wrap(f(t) - ref)

            d1 = mpmath.diff(g, t0, 1)
            d2 = mpmath.diff(g, t0, 2)
            out.append((d1, d2))
        w2, a2 = mpmath.mpf(float(omega2)), mpmath.mpf(float(alpha2))
        (d13, d23), (d14, d24) = out
        return (
            float(d13 * w2),
            float(d14 * w2),
            float(d23 * w2 * w2 + d13 * a2),
            float(d24 * w2 * w2 + d14 * a2),
        )


def angdiff(a, b) -> float:
    """|a - b| reduced to [0, pi], computed exactly enough in mpmath (a, b floats or mpf)."""
    with mpmath.workdps(MP_DPS):
        return float(abs(_mp_wrap(mpmath.mpf(a) - mpmath.mpf(b))))


def mp_toggles(r, dps=MP_DPS):
    """Crank angles in [0, pi] where the loop toggles: |A O4| = r3 + r4 or |r3 - r4|,
    from cos t2 = (r1^2 + r2^2 - d^2) / (2 r1 r2); only those that exist."""
    with mpmath.workdps(dps):
        r1, r2, r3, r4 = (mpmath.mpf(float(x)) for x in r)
        out = []
        for d in (r3 + r4, abs(r3 - r4)):
            c = (r1 * r1 + r2 * r2 - d * d) / (2 * r1 * r2)
            if -1 <= c <= 1:
                out.append(mpmath.acos(c))
        return out


def bound_rad(r, residual, sin34, which) -> float:
    """First-order bound on the angle error from a dimensionless residual:
    sqrt(2) * residual * L / (r_other * |sin(t4 - t3)|), r_other = r3 for theta3, r4 for
    theta4. The residual itself is only known to a few ulp (it is evaluated in double),
    so 4 eps is added to it; then a 2x safety factor and a floor of a few ulp of pi."""
    r3, r4 = float(r[2]), float(r[3])
    big = max(float(x) for x in r)
    other = r3 if which == 3 else r4
    res = float(residual) + 4 * 2.220446049250313e-16
    if float(sin34) == 0.0:  # an exact dead or change point: no first-order bound
        return math.inf
    return 2.0 * math.sqrt(2.0) * res * big / (other * abs(float(sin34))) + 4e-15


def random_links(rng, n, condition="grashof", lo=0.1, hi=10.0):
    """n random linkages (log-uniform lengths in [lo, hi]) with the given Grashof
    condition, decided independently with exact rational arithmetic."""
    from fractions import Fraction

    out = []
    while len(out) < n:
        r = np.exp(rng.uniform(math.log(lo), math.log(hi), 4))
        s = sorted(Fraction(float(x)) for x in r)
        lhs, rhs = s[0] + s[3], s[1] + s[2]
        cond = "grashof" if lhs < rhs else "non-grashof" if lhs > rhs else "change-point"
        if cond == condition:
            out.append(r)
    return np.array(out)


def near_toggle(r, theta2, within=1e-12) -> bool:
    """Whether the float crank angle lies within ``within`` rad of a toggle angle
    (+-mp_toggles, modulo 2 pi)."""
    with mpmath.workdps(MP_DPS):
        t = mpmath.mpf(float(theta2))
        for tg in mp_toggles(r):
            for s in (tg, -tg):
                if abs(_mp_wrap(t - s)) < within:
                    return True
    return False


EPS = 2.220446049250313e-16


#: The documented SINGULAR threshold on |sin(t4 - t3)| min(r3, r4) / L (docs/site/fourbar.rst); kept
#: here so the truth helpers import nothing from planarkin (test_properties checks it).
DOCUMENTED_SINGULAR_THRESHOLD = 1e-6


def below_singular_threshold(r, sin34, margin=1.01) -> bool:
    """Whether the exact position's conditioning |sin(t4 - t3)| min(r3, r4) / L is below
    the documented SINGULAR threshold (with a margin for the rounding of sin34 itself)."""
    r = [float(x) for x in r]
    cond = abs(float(sin34)) * min(r[2], r[3]) / max(r)
    return cond < margin * DOCUMENTED_SINGULAR_THRESHOLD


def resolvable(r, sin34, tol, margin=1000.0) -> bool:
    """Whether double precision can comfortably resolve the angles to ``tol`` rad at a
    point with this |sin(t4 - t3)|: margin * eps * L / (min(r3, r4) |sin|) < tol. Only at
    such points is a SINGULAR / MAX_ITERATIONS verdict a mislabel."""
    s = abs(float(sin34))
    if s == 0.0:
        return False
    big = max(float(x) for x in r)
    return margin * EPS * big / (min(float(r[2]), float(r[3])) * s) < tol


def ackermann(dl: np.ndarray) -> np.ndarray:
    """The right knuckle's rotation that the Ackermann condition asks of a steering linkage
    at left knuckle rotation ``dl`` (track 0.6 of the wheelbase)."""
    # cot(delta_outer) - cot(delta_inner) = 0.6, counter-clockwise positive
    out = np.zeros_like(dl)
    p, n = dl > 0, dl < 0
    out[p] = np.arctan(1 / (1 / np.tan(dl[p]) + 0.6))
    out[n] = -np.arctan(1 / (1 / np.tan(-dl[n]) - 0.6))
    return out
