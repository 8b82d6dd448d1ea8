"""Exact derivatives of a synthesis problem's residuals by its design vector, from the Rust
scene solver's implicit differentiation (``Scene.gradient``'s core): one factorisation per
input angle for every joint coordinate, at only the grid points the optimizer needs (the
design points, and the critical points of the reduced constraints: :class:`Picks`). The
conditioning's derivative (the branch constraint) is taken along the exact tangent
(``dets_gradient``); the link lengths are differentiated here in closed form. What has no
exact form yet is differenced forward: the input values of a :class:`PathPoints` target,
and the closed forms' radicands of the seed's objectives (no sweep needed for those)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .problem import DesignSpace, Evaluation, FunctionTarget, PathPoints, Problem, Residuals

#: forward-difference step of the columns differenced here, relative to the box size
FD_STEP = 1e-7


def available(problem: Problem) -> str:
    """Why exact gradients are not available for ``problem`` ("" where they are): they
    need the true objective, an angle input, revolute joints only, and an angle output
    for a function target."""
    if problem.objective != "true":
        return f"objective {problem.objective!r} is the seed's closed form (not differentiated)"
    if isinstance(problem.space, DesignSpace):
        return ""  # a double butterfly template: revolute, angle input and output
    sc = problem.space.drawn
    if sc.input_kind != "angle" or sc.slots or sc.prismatic:
        return "the scene has slots, prismatic pairs or a linear input"
    o = sc.to_dict().get("output")
    if isinstance(problem.target, FunctionTarget) and (o is None or "link" not in o):
        return "a function target needs an angle output"
    return ""


@dataclass(frozen=True)
class Picks:
    """The dense-grid points SLSQP sees the constraints at: the branch constraint on a
    fixed subgrid and, last, at its smallest value on the whole grid; the dense error
    (the minimax phase) on a fixed set and, last, at its largest magnitude; each envelope
    column at its tightest point. A row "at the extreme" is the extreme itself, a
    continuous function of the design (Danskin: its derivative is the extreme point's),
    so the constraints never jump as the extreme point moves."""

    branch: np.ndarray
    dense: np.ndarray
    envelope: np.ndarray


def subgrid(m: int, n: int) -> np.ndarray:
    """At most about ``n`` evenly spaced indices of a grid of ``m`` points, both ends in."""
    if m <= n:
        return np.arange(m)
    k = -(-(m - 1) // (n - 1))
    return np.unique(np.r_[np.arange(0, m, k), m - 1])


def extrema(v: np.ndarray, k: int) -> np.ndarray:
    """Indices of the ``k`` largest local maxima of ``v`` along the grid (ends included),
    sorted by index."""
    hi = np.r_[True, v[1:] >= v[:-1]] & np.r_[v[:-1] >= v[1:], True]
    idx = np.flatnonzero(hi)
    return np.sort(idx[np.argsort(-v[idx], kind="stable")[:k]])


def picks(res: Residuals, sub: np.ndarray, dense_fixed: np.ndarray) -> Picks:
    """The rows of ``res`` SLSQP sees (:class:`Picks`)."""
    env = res.envelope
    return Picks(
        branch=np.r_[sub, np.argmin(res.branch)].astype(np.intp),
        dense=np.r_[dense_fixed, np.argmax(np.abs(res.dense))].astype(np.intp),
        envelope=np.argmin(env, axis=0) if env.size else np.zeros(0, dtype=np.intp),
    )


@dataclass(frozen=True)
class Rows:
    """Derivatives of the residuals by the design vector (rows, one column per design
    variable): the objective's residuals, the dense error and branch constraint at the
    picked points, the extra constraints, the link lengths, and each envelope column at
    its picked point."""

    r: np.ndarray
    dense: np.ndarray
    branch: np.ndarray
    extra: np.ndarray
    lengths: np.ndarray
    envelope: np.ndarray


def fd_rows(
    problem: Problem, x: np.ndarray, res: Residuals, p: Picks, grid: tuple, step: float
) -> Rows:
    """Forward differences of every residual (one sweep per design variable), the picked
    rows taken (``--gradient fd``: the check of the exact rows)."""
    cols: list[list[np.ndarray]] = [[] for _ in range(6)]
    for j in range(x.size):
        xj = x.copy()
        xj[j] += step
        rj = problem.residuals(xj, grid)
        for c, a, b in zip(cols, rj, res, strict=True):
            c.append((a - b) / step)
    r, dense, branch, extra, lengths, env = (np.stack(c, axis=-1) for c in cols)
    return Rows(
        r=r,
        dense=dense[p.dense],
        branch=branch[p.branch],
        extra=extra,
        lengths=lengths,
        envelope=env[p.envelope, np.arange(p.envelope.size)] if p.envelope.size else env[0, :0],
    )


def exact_rows(
    problem: Problem,
    x: np.ndarray,
    ev: Evaluation,
    res: Residuals,
    p: Picks,
    *,
    dense: bool = True,
) -> Rows:
    """The rows of :func:`fd_rows` from the solver's exact derivatives at the solved poses
    of ``ev`` (the evaluation of ``x``); the dense rows only with ``dense``."""
    sp, t = problem.space, problem.target
    if problem.objective != "true":
        raise ValueError("exact gradients are of the true linkage's error (objective 'true')")
    sc, sw = ev.extra["scene"], ev.extra["sweep"]
    _, i_des, i_den = ev.extra["grid"]
    names = list(sc.points)
    cols = [(names.index(q), a) for q, a in sp.coords]
    nx, nc = x.size, len(cols)
    # the poses whose derivatives are needed, once each
    want = [i_des, i_den[p.branch], i_den[p.envelope]]
    if dense:
        want.append(i_den[p.dense])
    poses, where = np.unique(np.concatenate(want), return_inverse=True)
    at = np.split(where, np.cumsum([w.size for w in want])[:-1])
    np_ = len(names)
    pts = np.ascontiguousarray(sw.coords[poses].reshape(-1, 2))
    raw = sc._core.pose_gradient(pts, cols, True)
    g = raw.reshape(poses.size, np_, 2, nc)  # d(point, axis) / d(coordinate)
    g = np.where(np.isfinite(g), g, 0.0)
    scale = t.scale

    def pad(a: np.ndarray) -> np.ndarray:  # joint-coordinate columns, then the timing ones
        return np.concatenate([a, np.zeros((*a.shape[:-1], nx - nc))], axis=-1)

    # objective (and dense) rows
    if isinstance(t, FunctionTarget):
        d_out = _output_rows(problem, sc, sw, g, poses)
        r = pad(d_out[at[0]] / scale)
        dn = pad(d_out[at[3]] / scale) if dense else np.zeros((0, nx))
    else:
        k = names.index(t.point)
        r = pad(g[at[0], k].reshape(-1, nc) / scale)  # x then y of each design point
        dn = np.zeros((at[3].size if dense else 0, nx))
    # branch: s det / margin - 1, along the exact tangent
    det0 = ev.det0
    s = 1.0 if not math.isfinite(det0) or det0 >= 0 else -1.0
    m = max(problem.det_margin, 1e-12)
    bi = at[1]
    if bi.size and math.isfinite(det0):
        gb = np.ascontiguousarray(g[bi]).ravel()
        pb = np.ascontiguousarray(sw.coords[poses[bi]].reshape(-1, 2))
        dd = sc._core.dets_gradient(pb, gb, cols, None)
        br = pad(np.where(np.isfinite(dd), s * dd / m, 0.0))
    else:
        br = np.zeros((bi.size, nx))
    # envelope: column c is joint c // 4's margin to side c % 4
    env = np.zeros((p.envelope.size, nx))
    if problem.envelope is not None and p.envelope.size:
        (xl, yl), (xh, yh) = problem.envelope
        w = max(xh - xl, yh - yl)
        moving = problem.moving_indices(sc)
        sign = np.array([-1.0, 1.0, -1.0, 1.0]) / w
        for c, i in enumerate(at[2]):
            j, side = moving[c // 4], c % 4
            env[c, :nc] = sign[side] * g[i, j, side // 2]
    rows = Rows(
        r=r,
        dense=dn,
        branch=br,
        extra=np.zeros((res.extra.size, nx)),
        lengths=_length_rows(problem, x),
        envelope=env,
    )
    if res.extra.size or nx > nc:
        rows = _difference_rest(problem, x, res, p, rows, nc, dense)
    return rows


def _output_rows(
    problem: Problem, sc: object, sw: object, g: np.ndarray, poses: np.ndarray
) -> np.ndarray:
    # the output link's rotation from its drawn angle: d(angle of tip - pivot) minus the
    # drawn angle's own change with the drawing
    o = sc.output  # type: ignore[attr-defined]
    if o is None or "link" not in sc.to_dict()["output"]:  # type: ignore[attr-defined]
        raise ValueError("exact gradients need an angle output (a linear one is differenced)")
    link, pivot = o
    names = list(sc.points)  # type: ignore[attr-defined]
    drawn = sc.points  # type: ignore[attr-defined]
    tip = next(q for q in sc.links[link] if q != pivot)  # type: ignore[attr-defined]
    i, j = names.index(pivot), names.index(tip)
    c = sw.coords[poses]  # type: ignore[attr-defined]
    d = c[:, j] - c[:, i]
    dd = g[:, j] - g[:, i]  # (N, 2, F)
    rows = (d[:, 0, None] * dd[:, 1] - d[:, 1, None] * dd[:, 0]) / (d**2).sum(1)[:, None]
    e = np.subtract(drawn[tip], drawn[pivot])
    e2 = float(e @ e)
    da0 = np.zeros(rows.shape[1])
    for f, (q, a) in enumerate(problem.space.coords):
        if q in (tip, pivot):
            sgn = 1.0 if q == tip else -1.0
            da0[f] += sgn * (-e[1] if a == 0 else e[0]) / e2
    return rows - da0  # type: ignore[no-any-return]


def _length_rows(problem: Problem, x: np.ndarray) -> np.ndarray:
    sp = problem.space
    pts = sp.points_of(problem.coordinates(x))
    col = {qa: f for f, qa in enumerate(sp.coords)}
    pairs = sp.link_pairs()
    out = np.zeros((len(pairs), x.size))
    ml = sp.min_link
    if ml <= 0:
        return out
    for r, (a, b) in enumerate(pairs):
        d = np.subtract(pts[a], pts[b])
        n = math.hypot(*d) or 1.0
        for q, sg in ((a, 1.0), (b, -1.0)):
            for k in (0, 1):
                f = col.get((q, k))
                if f is not None:
                    out[r, f] += sg * d[k] / n / ml
    return out


def _difference_rest(
    problem: Problem, x: np.ndarray, res: Residuals, p: Picks, rows: Rows, nc: int, dense: bool
) -> Rows:
    # the closed forms' radicands by the joint coordinates (no sweep), and every row by
    # a PathPoints target's input values (one sweep each)
    box = max(float(np.max(problem.upper - problem.lower)), 1e-300)
    h = FD_STEP * box
    extra = rows.extra.copy()
    if res.extra.size:
        for j in range(nc):
            xj = x.copy()
            xj[j] += h
            extra[:, j] = (problem.extra_constraints(xj) - res.extra) / h
    out = Rows(rows.r, rows.dense, rows.branch, extra, rows.lengths, rows.envelope)
    if x.size > nc and isinstance(problem.target, PathPoints):
        grid = problem.grid(x)
        for j in range(nc, x.size):
            xj = x.copy()
            xj[j] += h
            rj = problem.residuals(xj, grid)
            out.r[:, j] = (rj.r - res.r) / h
            out.extra[:, j] = (rj.extra - res.extra) / h
            out.branch[:, j] = ((rj.branch - res.branch) / h)[p.branch]
            if dense:
                out.dense[:, j] = ((rj.dense - res.dense) / h)[p.dense]
            if p.envelope.size:
                de = (rj.envelope - res.envelope) / h
                out.envelope[:, j] = de[p.envelope, np.arange(p.envelope.size)]
    return out
