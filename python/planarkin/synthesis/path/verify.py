"""Verification of a path design on the real linkage: a dense sweep of the traced arc by the
scene solver (nothing of the refinement's model is reused), each target point's closest
point on it, the design's true errors, its circuit, branch and order defects, its smallest
transmission angle and whether its input turns fully."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.optimize import minimize_scalar

from ..._kernel import TRACE_STEP
from ...scene import Scene
from .model import _check, direction
from .results import Defects, PathError
from .targets import CurveTarget

#: samples of the traced arc per target point (a uniform grid over the arc)
DENSE = 64
#: |conditioning| at or below this on the traced arc is a dead point (a branch defect)
DEAD = 1e-3
#: Newton steps refining each closest point along the input
NEWTON = 8
#: a target point lies on a circuit when that circuit's curve passes within a tolerance of
#: it and every other circuit's that much farther again: the tolerance is CIRCUIT_GAP of
#: the target's size, or CIRCUIT_NOISE times the median distance from the points to the
#: nearest circuit where that is more (a noisy target near where the curves cross)
CIRCUIT_GAP, CIRCUIT_NOISE = 1e-3, 3.0
#: the circuits' traces, this much finer than the default trace (their polylines are read
#: as curves)
TRACE_REFINE = 4


@dataclass(frozen=True)
class Verification:
    """The real linkage against the target. ``error``: largest and RMS distance from the
    target's points to the traced arc over the target's size (``distances`` per point);
    ``defects``; ``inputs``: the input value of each point's closest point on the arc;
    ``min_transmission``: degrees, asin of the smallest |conditioning| on the arc (for a
    four-bar or slider-crank the sweep's conditioning is the transmission angle's sine, so
    this is the transmission angle measured from the dead point, 0..90; for other
    linkages the product of the plan's steps' conditionings, which bounds each step's);
    ``full_turn``: the input turns a whole turn on the design's circuit with no dead point;
    ``converged``: every sample of the arc solved; ``ok``: converged, no defect, and the
    transmission angle at least the one asked for."""

    error: PathError
    defects: Defects
    inputs: np.ndarray
    min_transmission: float
    full_turn: bool
    ok: bool
    distances: np.ndarray
    converged: bool


def _polyline_distance(q: np.ndarray, line: np.ndarray) -> np.ndarray:
    """(n,) distance from each of the points ``q`` (n, 2) to the polyline ``line`` (m, 2)
    (its non-finite vertices dropped)."""
    line = line[np.all(np.isfinite(line), axis=1)]
    if line.shape[0] == 0:
        return np.full(q.shape[0], np.inf)
    if line.shape[0] == 1:
        return np.hypot(*(q - line[0]).T)  # type: ignore[no-any-return]
    a, b = line[:-1], line[1:]
    ab = b - a
    ll = np.maximum((ab**2).sum(1), 1e-300)
    w = q[:, None, :] - a[None]
    s = np.clip((w * ab[None]).sum(-1) / ll[None], 0.0, 1.0)
    d = w - s[..., None] * ab[None]
    return np.sqrt((d**2).sum(-1).min(axis=1))  # type: ignore[no-any-return]


def _sweep(sc: Scene, t: np.ndarray, rate: bool = False) -> Any:
    return sc.sweep(t, outputs="all", rate=1.0 if rate else None)


def _at(
    sc: Scene, s: np.ndarray, sign: float, k: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Point ``k``'s position, velocity and acceleration by the input at the values ``s``
    (swept in order along the arc) and where they were solved."""
    order = np.argsort(sign * s, kind="stable")
    sw = _sweep(sc, s[order], rate=True)
    back = np.empty_like(order)
    back[order] = np.arange(s.size)
    p, v, a = (arr[back, k] for arr in (sw.coords, sw.velocity_array, sw.acceleration_array))
    return p, v, a, (sw.status == 0)[back]


def verify(
    scene: Scene,
    tracer: str,
    target: CurveTarget,
    inputs: Any,
    *,
    dense: int = DENSE,
    min_transmission: float | None = None,
    floor: float = DEAD,
) -> Verification:
    """Verifies ``scene`` against ``target``: its point ``tracer`` traced by the scene
    solver along the arc from ``inputs[0]`` to ``inputs[-1]`` (a closed target: the whole
    turn from ``inputs[0]``, the way the inputs go), ``dense`` samples per target point,
    each target point's closest point on the arc refined by Newton along the input.
    Defects: ``branch`` (a sample of the arc not solved, the conditioning changing sign or
    at most ``floor`` on it: a dead point), ``order`` (the closest points not strictly
    monotone along the arc in the target's order; cyclically for a closed target),
    ``circuit`` (a point nearer the curve of another circuit of the linkage than its own,
    :meth:`Scene.circuits`). ``min_transmission`` (degrees), when given, must be met for
    ``ok``. Returns :class:`Verification`."""
    _check(isinstance(scene, Scene), "scene", f"must be a planarkin.Scene, got {scene!r}")
    _check(scene.input_kind == "angle", "scene", "the input must be an angle (a crank)")
    _check(tracer in scene.points, "tracer", f"no point {tracer!r} in the scene")
    _check(isinstance(target, CurveTarget), "target", "must be a CurveTarget")
    _check(
        isinstance(dense, int) and dense >= 2, "dense", f"must be an integer >= 2, got {dense!r}"
    )
    _check(math.isfinite(floor) and 0 <= floor < 1, "floor", f"must be in [0, 1), got {floor!r}")
    if min_transmission is not None:
        mt = float(min_transmission)
        _check(0.0 <= mt < 90.0, "min_transmission", f"must be in [0, 90) degrees, got {mt!r}")
    q = np.asarray(target.points, dtype=np.float64)
    n = q.shape[0]
    t_in = np.asarray(inputs, dtype=np.float64)
    _check(t_in.shape == (n,), "inputs", f"must hold one value per target point ({n})")
    _check(bool(np.all(np.isfinite(t_in))), "inputs", "must be finite")
    size = float(target.size)
    names = list(scene.points)
    k = names.index(tracer)
    closed = target.kind == "closed"
    if closed:
        sign = direction(t_in)
        span = 2 * math.pi
    else:
        d = t_in[-1] - t_in[0]
        sign = 1.0 if d >= 0 else -1.0
        span = abs(d)
    t0 = float(t_in[0])
    m = dense * (n if closed else max(n - 1, 1)) + 1
    grid = t0 + sign * np.linspace(0.0, span, m)
    sw = _sweep(scene, grid)
    solved = (sw.status == 0) & np.isfinite(sw.det)
    converged = bool(np.all(solved))
    det = np.where(solved, sw.det, np.nan)
    fin = det[np.isfinite(det)]
    same_sign = bool(fin.size and (np.all(fin > 0) or np.all(fin < 0)))
    mind = float(np.min(np.abs(fin))) if fin.size else 0.0
    if converged and same_sign:
        mind = _smallest(scene, grid, np.abs(det), mind)
    branch = not converged or not same_sign or mind <= floor
    min_mu = math.degrees(math.asin(min(mind, 1.0)))
    # each point's closest point on the arc, from two starts: its nearest sample and the
    # sample at its given input. The given input's is kept unless the other is nearer: a
    # curve through a point twice (a rocker's joint goes and comes back) reaches it at the
    # input the design assigns it
    curve = np.where(solved[:, None], sw.coords[:, k], np.nan)
    d2 = ((q[:, None, :] - curve[None]) ** 2).sum(-1)
    d2 = np.where(np.isfinite(d2), d2, np.inf)
    h = span / (m - 1)
    at_in = sign * (t_in - t0)
    at_in = np.mod(at_in, 2 * math.pi) if closed else np.clip(at_in, 0.0, span)
    starts = np.concatenate([np.argmin(d2, axis=1), np.rint(at_in / h).astype(int)])
    starts = np.clip(starts, 0, m - 1)
    s2, d_2 = _closest(scene, np.vstack([q, q]), grid, curve, starts, sign, k, converged)
    given = d_2[n:] <= d_2[:n] * (1 + 1e-9) + 1e-12 * size
    s = np.where(given, s2[n:], s2[:n])
    dist = np.where(given, d_2[n:], d_2[:n])
    # order: positions along the arc strictly increasing (cyclically, closed)
    pos = sign * (s - t0)
    if closed:
        pos = np.mod(pos, 2 * math.pi)
        steps = np.diff(np.concatenate([pos, pos[:1]]))
        order_defect = bool(np.sum(steps <= 0) > 1 or np.any(steps == 0))
    else:
        order_defect = bool(np.any(np.diff(pos) <= 0))
    circuit = _circuit_defect(scene, k, q, dist, t0, sw, size)
    full = _full_turn(scene, t0, sign, floor, closed, converged, same_sign, mind, dense * n)
    err = PathError(float(np.max(dist)) / size, float(np.sqrt(np.mean(dist**2))) / size)
    defects = Defects(circuit=circuit, branch=branch, order=order_defect)
    meets = min_transmission is None or min_mu >= float(min_transmission)
    ok = converged and not defects.any and meets and bool(np.all(np.isfinite(dist)))
    return Verification(
        error=err,
        defects=defects,
        inputs=s,
        min_transmission=min_mu,
        full_turn=full,
        ok=ok,
        distances=dist / size,
        converged=converged,
    )


def _smallest(scene: Scene, grid: np.ndarray, a: np.ndarray, at_grid: float) -> float:
    """The smallest |conditioning| of the arc: its smallest sample's, refined by a bounded
    scalar minimisation between the samples either side (each value a sweep of the real
    linkage)."""
    j = int(np.argmin(a))
    lo, hi = grid[max(j - 1, 0)], grid[min(j + 1, grid.size - 1)]
    if lo == hi:
        return at_grid

    def f(t: float) -> float:
        sw = _sweep(scene, np.array([t]))
        return float(abs(sw.det[0])) if sw.status[0] == 0 else math.inf

    res = minimize_scalar(
        f, bounds=(min(lo, hi), max(lo, hi)), method="bounded", options={"xatol": 1e-10}
    )
    return min(at_grid, float(res.fun)) if np.isfinite(res.fun) else at_grid


def _closest(
    scene: Scene,
    q: np.ndarray,
    grid: np.ndarray,
    curve: np.ndarray,
    starts: np.ndarray,
    sign: float,
    k: int,
    newton: bool,
) -> tuple[np.ndarray, np.ndarray]:
    """Input values and distances of the points ``q`` to the traced curve, each from the
    grid sample ``starts`` (``curve`` its tracer positions, NaN where unsolved), refined
    with ``newton`` by Newton's method on 1/2 |p(t) - q|^2 within one grid step of it."""
    s = grid[starts].copy()
    dist = np.hypot(*(curve[starts] - q).T)
    dist = np.where(np.isfinite(dist), dist, np.inf)
    if not newton:
        return s, dist
    h = abs(grid[-1] - grid[0]) / (grid.size - 1)
    lo = np.maximum(s - h, min(grid[0], grid[-1]))
    hi = np.minimum(s + h, max(grid[0], grid[-1]))
    best = s.copy()
    for _ in range(NEWTON):
        p, v, a, hit = _at(scene, s, sign, k)
        e = p - q
        dn = np.hypot(e[:, 0], e[:, 1])
        better = hit & (dn < dist)
        dist = np.where(better, dn, dist)
        best = np.where(better, s, best)
        g1 = (v * e).sum(1)
        g2 = (v * v).sum(1) + (a * e).sum(1)
        g2 = np.where(g2 > 0, g2, (v * v).sum(1) + 1e-300)
        s_new = np.where(hit, np.clip(s - g1 / g2, lo, hi), s)
        if np.all(np.abs(s_new - s) <= 1e-15 * (1 + np.abs(s))):
            break
        s = s_new
    return best, dist


def _circuit_defect(
    scene: Scene, k: int, q: np.ndarray, dist: np.ndarray, t0: float, sw: Any, size: float
) -> bool:
    """True where the target's points lie on two or more circuits (see CIRCUIT_GAP;
    points near where the curves cross, or near none, count for no circuit). The design's
    own circuit is the one through the arc's first pose; its distance is the arc's where
    that is nearer."""
    try:
        circuits = scene.circuits(t0, step=TRACE_STEP / TRACE_REFINE)
    except ValueError:
        return False
    if len(circuits) < 2 or not np.all(np.isfinite(sw.coords[0])):
        return False
    names = list(scene.points)
    pose = sw.coords[0]

    def gap(c: Any) -> float:
        if not c.assemblies:
            return math.inf
        return min(
            float(np.max(np.hypot(*(np.array([a[p] for p in names]) - pose).T)))
            for a in c.assemblies
        )

    own = int(np.argmin([gap(c) for c in circuits]))
    d = np.stack([_polyline_distance(q, c.trace.coords[:, k]) for c in circuits])
    d[own] = np.minimum(d[own], dist)
    # the fit's own level: how near the union of the circuits passes the points
    tol = max(CIRCUIT_GAP * size, CIRCUIT_NOISE * float(np.median(d.min(axis=0))))
    # each point's nearest circuit counts where it is within tol and every other is farther
    # by more than tol
    cols = np.arange(d.shape[1])
    near = np.argmin(d, axis=0)
    best = d[near, cols]
    others = d.copy()
    others[near, cols] = np.inf
    with np.errstate(invalid="ignore"):  # inf - inf where no circuit is finite: not on
        on = (best <= tol) & np.all(others - best > tol, axis=0)
    return np.unique(near[on]).size > 1


def _full_turn(
    scene: Scene,
    t0: float,
    sign: float,
    floor: float,
    closed: bool,
    converged: bool,
    same_sign: bool,
    mind: float,
    m: int,
) -> bool:
    """The input turns a whole turn from ``t0`` on the design's circuit, no dead point on
    the way (a closed target's arc is that turn already)."""
    if closed:
        return converged and same_sign and mind > floor
    sw = _sweep(scene, t0 + sign * np.linspace(0.0, 2 * math.pi, max(m, 361) + 1))
    det = sw.det
    ok = (sw.status == 0) & np.isfinite(det)
    return bool(np.all(ok) and (np.all(det > floor) or np.all(det < -floor)))
