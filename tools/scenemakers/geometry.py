"""What the scene generators share: circle intersections and small vector helpers, and
how far a drawn circuit's input turns (the NumPy reference's continuation)."""

from __future__ import annotations

import math

import numpy as np
from planarkin import Status
from planarkin.reference import scene as ref

DEG = math.pi / 180


# --- geometry ------------------------------------------------------------------------


def circles(p, rp, q, rq):
    """Both intersections of the circle (p, rp) with (q, rq): (left, right) of p -> q."""
    p, q = np.asarray(p, float), np.asarray(q, float)
    u = q - p
    d = math.hypot(u[0], u[1])
    a = (rp * rp - rq * rq + d * d) / (2 * d)
    hh = rp * rp - a * a
    if hh < 0:
        raise ValueError(f"circles do not meet: d={d}, rp={rp}, rq={rq}")
    h = math.sqrt(hh)
    m = p + a * u / d
    n = np.array([-u[1], u[0]]) / d
    return m + h * n, m - h * n


def pick(p, rp, q, rq, key):
    """The intersection that minimises key(point)."""
    return min(circles(p, rp, q, rq), key=key)


def rot(v, a):
    c, s = math.cos(a), math.sin(a)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def dist(a, b):
    return math.hypot(a[0] - b[0], a[1] - b[1])


# --- reach: how far the drawn circuit's input turns ------------------------------------


def reach(scene, direction, limit=2 * math.pi, step=1 * DEG, h_min=1e-9):
    """How far the drawn circuit's input turns from the drawn angle in ``direction``
    before a dead point (capped at ``limit``), by the reference's own continuation with
    step halving near the end (to about h_min). Returns (angle turned, [(angle turned,
    reciprocal condition number of the Jacobian)], final state)."""
    sys_ = ref._System(scene)
    t0 = sys_.theta0
    x, st, _ = sys_.newton(np.zeros(sys_.n), t0, 1e-13, 50)
    assert st == Status.CONVERGED, st
    hist = [(t0, x, sys_.sign(x, t0))]
    done, h, trace = 0.0, step, []
    while done < limit - 1e-12:
        h = min(h, limit - done)
        t = done + h
        xn, st, _, hn = ref._march(sys_, hist, t0 + direction * t, 1e-13, 30, h)
        if st != Status.CONVERGED:
            h /= 2
            if h < h_min:
                break
            continue
        _, j = sys_.residual_jacobian(xn, (math.cos(direction * t), math.sin(direction * t)))
        sv = np.linalg.svd(j, compute_uv=False)
        trace.append((t, sv[-1] / sv[0]))
        hist, done, x = hn, t, xn
        h = min(step, 2 * h)
    return done, trace, x


def motion(scene, margin=5 * DEG):
    """(lo, hi, full_turn, worst conditioning): the drawn circuit's input range about the
    drawn angle (radians, relative to it), and the smallest reciprocal condition number
    of the Jacobian met on it more than ``margin`` from its ends (dead points)."""
    hi, tr, xe = reach(scene, +1)
    if hi >= 2 * math.pi - 1e-12:
        closed = np.max(np.abs(np.array([ref.wrap(v) for v in xe]))) < 1e-8
        return 0.0, 2 * math.pi, bool(closed), min(r for _, r in tr)
    lo, tr2, _ = reach(scene, -1)
    inner = [r for t, r in tr if t < hi - margin] + [r for t, r in tr2 if t < lo - margin]
    return -lo, hi, False, min(inner, default=0.0)


def redraw(scene, dtheta):
    """The scene redrawn by the reference at the drawn angle + dtheta (continuation)."""
    th = ref._System(scene).theta0 + np.linspace(0, dtheta, max(2, int(abs(dtheta) / DEG) + 2))
    sw = ref.scene_sweep(scene, th, tol=1e-14)
    assert np.all(sw.status == 0), sw.status
    out = dict(scene)
    out["points"] = {p: [float(v) for v in sw.points[p][-1]] for p in scene["points"]}
    return out
