"""The path objective and its constraints as functions of one design vector (the scene's
drawn coordinates and, timing free, each target point's input value), with their exact
derivatives; and where a refinement starts its inputs (each target point matched, in
order, to the start's own curve)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ...scene import Scene
from .targets import CurveTarget

#: the smallest |conditioning| (a four-bar's or slider-crank's transmission sine; the
#: product of the plan's steps' otherwise) allowed on the traced arc's samples
DET_FLOOR = 0.02
#: the smallest input step between consecutive target points (radians): strictly monotone
ORDER_GAP = 1e-3
#: conditioning samples per segment between consecutive inputs: about one per SAMPLE_STEP
#: of the starting inputs, within MIN_SAMPLES..MAX_SAMPLES (fixed for the run: SLSQP needs
#: a constant number of constraints)
SAMPLE_STEP = math.radians(2.0)
MIN_SAMPLES, MAX_SAMPLES = 2, 64
#: the drawn coordinates stay within this many target sizes of the target's centre
COORD_BOUND = 10.0
#: a constraint counts as holding down to this (dimensionless) violation
FEAS_TOL = 1e-9
#: Newton tolerance of the model's sweeps
SWEEP_TOL = 1e-13


#: input values farther than this many turns from the drawn input angle fail outright
FAR_TURNS = 3


def _check(cond: bool, name: str, message: str) -> None:
    if not cond:
        raise ValueError(f"{name}: {message}")


def fourbar_joints(scene: Scene) -> tuple[str, str, str, str] | None:
    """(O2, A, B, O4) of a pin-jointed four-bar driven at O2 (ground O2-O4, crank O2-A,
    coupler through A and B, rocker O4-B), or None for any other scene."""
    if scene.slots or scene.prismatic or scene.input_kind != "angle" or len(scene.links) != 4:
        return None
    joints = scene.joints
    ground = [p for p in scene.links[scene.ground] if p in joints]
    crank, o2 = scene.input
    tips = [p for p in scene.links[crank] if p != o2 and p in joints]
    if len(ground) != 2 or o2 not in ground or len(tips) != 1:
        return None
    o4, a = next(p for p in ground if p != o2), tips[0]
    rockers = [n for n, ps in scene.links.items() if o4 in ps and n != scene.ground]
    if len(rockers) != 1:
        return None
    bs = [p for p in scene.links[rockers[0]] if p != o4 and p in joints]
    couplers = [n for n in scene.links if n not in (scene.ground, crank, rockers[0])]
    if len(bs) != 1 or not couplers or not {a, bs[0]} <= set(scene.links[couplers[0]]):
        return None
    return o2, a, bs[0], o4


def link_pairs(scene: Scene) -> list[tuple[int, int]]:
    """The link dimensions: every pair of joints (points on two or more links, or held in a
    slot) on one link, as indices into ``scene.points``."""
    names = list(scene.points)
    joints = set(scene.joints) | {s[0] for s in scene.slots.values()}
    out = []
    for pts in scene.links.values():
        js = [names.index(p) for p in pts if p in joints]
        out += [(a, b) for i, a in enumerate(js) for b in js[i + 1 :]]
    return out


def direction(inputs: np.ndarray) -> float:
    """+1 where the inputs mostly increase along the target, -1 where they decrease."""
    d = np.angle(np.exp(1j * np.diff(inputs)))
    return 1.0 if d.sum() >= 0 else -1.0


def unwrapped(inputs: np.ndarray) -> np.ndarray:
    """The inputs from the first, each step taken as the shorter way round (within pi):
    a small step backwards stays one (the order constraint corrects it), never a turn."""
    steps = np.angle(np.exp(1j * np.diff(inputs)))
    return np.concatenate([[inputs[0]], inputs[0] + np.cumsum(steps)])


def reachable(scene: Scene, t: np.ndarray, margin: float) -> np.ndarray:
    """The inputs ``t`` with each one the linkage does not reach (its sweep fails there, or
    its conditioning is within ``margin`` of a dead point) moved to the nearest input it
    reaches with that margin, on a grid a little wider than the inputs: a start whose
    points are all solved, so that every residual has a derivative (a monotone sequence
    stays monotone, if not strictly)."""
    try:
        sw = scene.sweep(t, outputs="all")
    except ValueError:
        return t
    ok = (sw.status == 0) & (np.abs(sw.det) >= margin)
    if ok.all():
        return t
    lo, hi = float(t.min()), float(t.max())
    pad = 0.1 * (hi - lo) + 1e-3
    grid = np.linspace(lo - pad, hi + pad, REACH_GRID)
    g = scene.sweep(grid, outputs="all")
    good = (g.status == 0) & (np.abs(g.det) >= margin)
    if not good.any():
        return t
    gv = grid[good]
    near = gv[np.argmin(np.abs(t[:, None] - gv[None, :]), axis=1)]
    return np.where(ok, t, near)


#: the grid :func:`reachable` looks for reachable inputs on
REACH_GRID = 721


#: samples of the start's curve that :func:`initial_inputs` assigns target points to; on a
#: full turn the first point's candidates are the samples within INIT_AROUND of the
#: INIT_MINIMA deepest local minima of its distance
INIT_SAMPLES, INIT_MINIMA, INIT_AROUND = 360, 4, 3


def initial_inputs(
    scene: Scene, tracer: str, target: CurveTarget, *, samples: int = INIT_SAMPLES
) -> np.ndarray:
    """Starting input values for :func:`refine`: each target point assigned to a sample of
    the scene's curve (swept over the turn around its drawing, or the arc its input
    reaches), in the target's order, the assignment that minimises the sum of squared
    distances by dynamic programming over both directions (on a full turn, over the first
    point's place too, the whole target within one turn). Unwrapped along the motion."""
    _check(isinstance(scene, Scene), "scene", f"must be a planarkin.Scene, got {scene!r}")
    _check(tracer in scene.points, "tracer", f"no point {tracer!r} in the scene")
    _check(isinstance(target, CurveTarget), "target", "must be a CurveTarget")
    _check(
        isinstance(samples, int) and samples >= 8,
        "samples",
        f"must be an integer >= 8, got {samples!r}",
    )
    q = np.asarray(target.points, dtype=np.float64)
    n, m = q.shape[0], samples
    grid = scene.input_angle + np.linspace(-math.pi, math.pi, m + 1)[:-1]
    sw = scene.sweep(grid, outputs="all")
    ok = (sw.status == 0) & np.isfinite(sw.det) & (np.abs(sw.det) > DET_FLOOR)
    _check(bool(ok.any()), "scene", "its tracer reaches no point of the turn around its drawing")
    curve = sw.coords[:, list(scene.points).index(tracer)]
    cost = ((q[:, None, :] - curve[None]) ** 2).sum(-1)
    cost = np.where(ok[None], cost, np.inf)
    full = bool(ok.all())
    # one turn of increasing angles from just after an unreached sample (a reachable arc
    # is then one run, not split at the grid's ends)
    start = 0 if full else int(np.flatnonzero(~ok)[-1] + 1) % m
    base_t = grid[start] + np.arange(m) * (2 * math.pi / m)
    base_c = np.roll(cost, -start, axis=1)
    best: tuple[float, np.ndarray] = (math.inf, base_t[:n])
    for sign in (1.0, -1.0):
        c, t = (base_c, base_t) if sign > 0 else (base_c[:, ::-1], base_t[::-1])
        if full:
            c2 = np.concatenate([c, c], axis=1)
            t2 = np.concatenate([t, t + sign * 2 * math.pi])
            firsts: np.ndarray | None = _near_first(c[0])
        else:
            c2, t2, firsts = c, t, None
        idx, total = _monotone(c2, firsts, m)
        if total < best[0]:
            best = (total, t2[idx])
    return best[1]


def _near_first(c0: np.ndarray) -> np.ndarray:
    """The first point's candidate samples on a full turn: around each of the few deepest
    local minima of its cost (cyclic), where its best assignment lies."""
    m = c0.size
    minima = np.flatnonzero((c0 <= np.roll(c0, 1)) & (c0 <= np.roll(c0, -1)))
    minima = minima[np.argsort(c0[minima])][:INIT_MINIMA]
    near = (minima[:, None] + np.arange(-INIT_AROUND, INIT_AROUND + 1)[None]) % m
    return np.unique(near)


def _monotone(cost: np.ndarray, firsts: np.ndarray | None, span: int) -> tuple[np.ndarray, float]:
    """Strictly increasing sample indices, one per row of ``cost`` (n, M), of least total
    cost: with ``firsts``, the first index one of them and every index within ``span``
    samples past it (one per start, all at once); otherwise any."""
    n, big = cost.shape
    cols = np.arange(big)
    if firsts is None:
        d = cost[0][None].copy()
        lim = np.full((1, big), True)
    else:
        k = firsts.size
        d = np.full((k, big), np.inf)
        d[np.arange(k), firsts] = cost[0, firsts]
        lim = (cols[None] >= firsts[:, None]) & (cols[None] < firsts[:, None] + span)
    back = np.zeros((n, d.shape[0], big), dtype=np.int64)
    # the previous row's column each column looks back to (column 0: none, read as 0)
    arg = np.concatenate([[0], np.arange(big - 1)])[None]
    for i in range(1, n):
        # the best of the previous row strictly before each column
        prev = np.concatenate([np.full((d.shape[0], 1), np.inf), d[:, :-1]], axis=1)
        acc = np.minimum.accumulate(prev, axis=1)
        # where the running minimum was set
        first = prev == acc
        pos = np.where(first, arg, 0)
        pos = np.maximum.accumulate(pos, axis=1)
        back[i] = pos
        d = np.where(lim, cost[i][None] + acc, np.inf)
    r = int(np.argmin(d.min(axis=1)))
    j = int(np.argmin(d[r]))
    total = float(d[r, j])
    idx = np.zeros(n, dtype=np.int64)
    for i in range(n - 1, -1, -1):
        idx[i] = j
        j = int(back[i, r, j])
    return idx, total


class PathModel:
    """The path objective and constraints of one design as functions of the design
    vector u = [(coordinates - centre) / size, timing]: timing free, the n inputs; given,
    one offset added to the target's inputs (a placement turns the input's frame), or
    nothing with ``timing_offset`` False. One
    sweep per design, its exact derivatives on demand."""

    def __init__(
        self,
        scene: Scene,
        tracer: str,
        target: CurveTarget,
        inputs: Any,
        *,
        floor: float = DET_FLOOR,
        box: Any = None,
        max_link_ratio: float | None = None,
        full_turn: bool = False,
        timing_offset: bool = True,
    ) -> None:
        _check(isinstance(scene, Scene), "scene", f"must be a planarkin.Scene, got {scene!r}")
        _check(scene.input_kind == "angle", "scene", "the input must be an angle (a crank)")
        _check(tracer in scene.points, "tracer", f"no point {tracer!r} in the scene")
        _check(isinstance(target, CurveTarget), "target", "must be a CurveTarget")
        q = np.asarray(target.points, dtype=np.float64)
        n = q.shape[0]
        t0 = np.asarray(inputs, dtype=np.float64)
        _check(t0.shape == (n,), "inputs", f"must hold one value per target point ({n})")
        _check(bool(np.all(np.isfinite(t0))), "inputs", "must be finite")
        self.scene, self.tracer, self.target = scene, tracer, target
        self.q, self.n = q, n
        self.size = float(target.size)
        self.centre = q.mean(axis=0)
        self.names = list(scene.points)
        self.k_tr = self.names.index(tracer)
        self.np = len(self.names)
        self.cols = [(j, a) for j in range(self.np) for a in (0, 1)]
        self.nc = len(self.cols)
        data = scene.to_dict()
        for key in ("lengths", "loads", "outputs"):
            data.pop(key, None)  # the model sweeps the exact pose, every point
        self.data = data
        self.floor = float(floor)
        closed = target.kind == "closed"
        self.wrap = closed or bool(full_turn)
        self.free = target.inputs is None
        if self.free:
            self.sign = direction(t0) if n > 1 else 1.0
            t0 = reachable(scene, unwrapped(t0), 2 * self.floor)
            self.t_fixed = np.zeros(n)
            self.T = np.eye(n)
            tau0 = t0
        else:
            # the given timing, turned by the offset that suits the start best (the
            # inputs' circular mean less the timing's)
            ti = np.asarray(target.inputs, dtype=np.float64)
            _check(ti.shape == (n,), "target", "its inputs must hold one value per point")
            self.sign = direction(ti) if n > 1 else 1.0
            off = float(np.angle(np.mean(np.exp(1j * (t0 - ti)))))
            off += float(t0[0] - ti[0]) - float(np.angle(np.exp(1j * (t0[0] - ti[0]))))
            if not timing_offset:
                off = 0.0  # the given values as they are: no timing variable
            self.t_fixed = ti
            self.T = np.ones((n, 1)) if timing_offset else np.zeros((n, 0))
            tau0 = np.array([off]) if timing_offset else np.zeros(0)
            t0 = ti + off
        # samples: each segment's start (a target point) and its interior, then the last
        # point, or (closed, full turn) the way back to the first point
        gaps = np.abs(np.diff(np.concatenate([t0, [t0[0] + 2 * math.pi * self.sign]])))
        nseg = n if self.wrap else n - 1
        rows: list[np.ndarray] = []
        at = []
        for i in range(nseg):
            k = int(np.clip(math.ceil(gaps[i] / SAMPLE_STEP), MIN_SAMPLES, MAX_SAMPLES))
            at.append(len(rows))
            for j in range(k):
                w = np.zeros(n + 1)
                w[i], w[i + 1] = 1 - j / k, j / k
                rows.append(w)
        if not self.wrap:
            at.append(len(rows))
            w = np.zeros(n + 1)
            w[n - 1] = 1.0
            rows.append(w)
        W = np.array(rows)  # samples from [t_0 .. t_{n-1}, t_0 + 2 pi sign]
        E = np.vstack([np.eye(n), np.eye(1, n)])
        c = np.zeros(n + 1)
        c[n] = 2 * math.pi * self.sign
        A = W @ E
        self.at = np.array(at)
        # each sample's segment (the last point, open, belongs to the last segment): the
        # constraint is the segment's smallest margin, so SLSQP sees one row per segment
        self.seg = np.minimum(
            np.searchsorted(self.at, np.arange(len(rows)), side="right") - 1, nseg - 1
        )
        self.nseg = nseg
        self.M = A @ self.T  # samples = M tau + m0
        self.m0 = A @ self.t_fixed + W @ c
        self.nt = self.T.shape[1]
        x0 = np.array([scene.points[p][a] for p in self.names for a in (0, 1)])
        self.u0 = np.concatenate([(x0 - np.tile(self.centre, self.np)) / self.size, tau0])
        self.nu = self.u0.size
        # the user's constraints, on coordinates
        self.box = _box(box)
        pivots = [p for p in scene.links[scene.ground] if p in scene.joints]
        self.pivots = [self.names.index(p) for p in pivots]
        self.ratio = None if max_link_ratio is None else float(max_link_ratio)
        if self.ratio is not None:
            _check(
                math.isfinite(self.ratio) and self.ratio >= 1.0,
                "max_link_ratio",
                f"must be a finite number >= 1, got {max_link_ratio!r}",
            )
        self.pairs = link_pairs(scene)
        # a four-bar that turns fully: its transmission is extreme where the crank lies
        # along the ground (|A - O4| = r1 + r2 and |r1 - r2|), so |cos mu| there within
        # cos(asin(floor)) is the whole turn's floor exactly, Grashof's condition with a
        # margin (crank-rocker or double crank), and smooth in the lengths
        self.bars: list[tuple[int, int]] | None = None
        fb = fourbar_joints(scene)
        if fb is not None and self.wrap:
            o2, a, b, o4 = (self.names.index(p) for p in fb)
            self.bars = [(o2, o4), (o2, a), (a, b), (o4, b)]
        self.det_sign = 0.0
        self.evaluations = 0
        self._key: bytes | None = None
        self._val: dict[str, Any] = {}
        self._jkey: bytes | None = None
        self._jac: dict[str, np.ndarray] = {}
        ev = self.values(self.u0)
        d0 = ev["det"][self.at[0]] if ev["ok"][self.at[0]] else np.nan
        finite = ev["det"][np.isfinite(ev["det"])]
        ref = d0 if math.isfinite(d0) else (finite.sum() if finite.size else 1.0)
        self.det_sign = 1.0 if ref >= 0 else -1.0
        self._key = None  # the constraints change with the sign

    # --- the design vector -------------------------------------------------------------

    def coords(self, u: np.ndarray) -> np.ndarray:
        """The drawn coordinates (P, 2) of ``u``."""
        return self.centre + self.size * np.asarray(u[: self.nc]).reshape(self.np, 2)

    def inputs(self, u: np.ndarray) -> np.ndarray:
        """Each target point's input value at ``u``."""
        return np.asarray(self.T @ u[self.nc :] + self.t_fixed)

    def samples(self, u: np.ndarray) -> np.ndarray:
        return np.asarray(self.M @ u[self.nc :] + self.m0)

    def scene_at(self, u: np.ndarray, data: dict[str, Any] | None = None) -> Scene:
        xy = self.coords(u)
        d = dict(self.data if data is None else data)
        d["points"] = {p: [float(x), float(y)] for p, (x, y) in zip(self.names, xy, strict=True)}
        return Scene.from_dict(d)

    # --- values --------------------------------------------------------------------------

    def values(self, u: np.ndarray) -> dict[str, Any]:
        u = np.asarray(u, dtype=np.float64)
        key = u.tobytes()
        if key == self._key:
            return self._val
        self.evaluations += 1
        s = self.samples(u)
        m = s.size
        val: dict[str, Any] = {"samples": s}
        sc: Scene | None
        sw: Any
        try:
            sc = self.scene_at(u)
            # a step that throws the inputs turns away (a least-squares step can) fails here:
            # sweeping there would follow the motion through every one of those turns
            far = np.abs(s - sc.input_angle).max(initial=0.0) > FAR_TURNS * 2 * math.pi
            sw = (
                None
                if far or not np.all(np.isfinite(s))
                else sc.sweep(s, outputs="all", rate=1.0, tol=SWEEP_TOL)
            )
        except ValueError:
            sc = sw = None
        val["scene"], val["sweep"] = sc, sw
        if sw is None:
            val["ok"] = np.zeros(m, dtype=bool)
            val["det"] = np.full(m, np.nan)
            val["r"] = np.full(2 * self.n, np.nan)
        else:
            ok = (sw.status == 0) & np.isfinite(sw.det)
            val["ok"] = ok
            val["det"] = np.where(ok, sw.det, np.nan)
            p = sw.coords[self.at, self.k_tr]
            val["r"] = np.where(ok[self.at, None], (p - self.q) / self.size, np.nan).ravel()
        val["cons"] = self._constraints(u, val)
        self._key, self._val = key, val
        return val

    def residuals(self, u: np.ndarray) -> np.ndarray:
        """(2n,) the target points' x and y distances to the tracer at their inputs over
        the target's size (failures: 1)."""
        r = self.values(u)["r"]
        return np.where(np.isfinite(r), r, 1.0)  # type: ignore[no-any-return]

    def objective(self, u: np.ndarray) -> float:
        r = self.residuals(u)
        return float(r @ r)

    def constraints(self, u: np.ndarray) -> np.ndarray:
        """Every constraint, >= 0 where it holds."""
        return self.values(u)["cons"]  # type: ignore[no-any-return]

    def _constraints(self, u: np.ndarray, val: dict[str, Any]) -> np.ndarray:
        det = val["det"]
        margin = np.where(np.isfinite(det), self.det_sign * det - self.floor, -1.0)
        # each segment's tightest sample: ordered by segment, then margin (stable, so the
        # first of equal margins), segment i's samples begin at at[i]
        pick = np.lexsort((margin, self.seg))[self.at[: self.nseg]]
        val["pick"] = pick
        # a four-bar's full turn has its floor exactly in the lengths (``bars``): the
        # samples would only add rows that are -1, with no derivative, where it does not
        # turn yet
        out = [margin[pick] if self.bars is None else np.zeros(0)]
        if self.free:
            t = self.inputs(u)
            out.append(self.sign * np.diff(t) - ORDER_GAP)
            if self.wrap:
                out.append(np.array([2 * math.pi - ORDER_GAP - self.sign * (t[-1] - t[0])]))
        xy = self.coords(u)
        if self.box is not None:
            (xl, xh), (yl, yh) = self.box
            for i in self.pivots:
                x, y = xy[i]
                out.append(np.array([x - xl, xh - x, y - yl, yh - y]) / self.size)
        if self.ratio is not None:
            ln = np.array([np.hypot(*(xy[a] - xy[b])) for a, b in self.pairs])
            out.append(
                (self.ratio * ln[None, :] - ln[:, None])[~np.eye(ln.size, dtype=bool)] / self.size
            )
        if self.bars is not None:
            c, _ = self._turn_cosines(xy)
            k = math.sqrt(1.0 - self.floor**2)
            out.append(np.concatenate([k - c, k + c]))
        return np.concatenate(out)

    def _turn_cosines(self, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """A four-bar's cos mu where the crank lies along the ground, outwards and inwards
        (2,), and their derivatives by u (2, U)."""
        assert self.bars is not None
        rho = np.array([np.hypot(*(xy[a] - xy[b])) for a, b in self.bars]) / self.size
        dl = self._length_rows(xy, self.bars)
        r1, r2, r3, r4 = rho
        c, dc = np.zeros(2), np.zeros((2, self.nu))
        for i, sg in enumerate((1.0, -1.0)):
            d = r1 + sg * r2
            c[i] = (r3**2 + r4**2 - d**2) / (2 * r3 * r4)
            by = [-d / (r3 * r4), -sg * d / (r3 * r4), 1 / r4 - c[i] / r3, 1 / r3 - c[i] / r4]
            dc[i] = np.asarray(by) @ dl
        return c, dc

    # --- derivatives ----------------------------------------------------------------------

    def jacobians(self, u: np.ndarray) -> dict[str, np.ndarray]:
        """``r`` (2n, U): the residuals' exact derivatives; ``cons`` (C, U): the
        constraints'."""
        u = np.asarray(u, dtype=np.float64)
        key = u.tobytes()
        if key == self._jkey:
            return self._jac
        val = self.values(u)
        sc, sw = val["scene"], val["sweep"]
        m, n = val["samples"].size, self.n
        nc, nu = self.nc, self.nu
        dpos = np.zeros((m, self.np, 2, nc))
        vel = np.zeros((m, self.np, 2))
        ddet = np.zeros((m, nu))
        if sw is not None:
            # the poses SLSQP needs: the target points' and each segment's tightest sample
            need = np.zeros(m, dtype=bool)
            need[self.at] = need[val["pick"]] = True
            need &= val["ok"]
            rows_ = np.flatnonzero(need)
            coords = np.ascontiguousarray(sw.coords[rows_])
            pts = coords.reshape(-1, 2)
            g = sc._core.pose_gradient(pts, self.cols, False).reshape(rows_.size, self.np, 2, nc)
            v = sw.velocity_array[rows_]
            good = np.isfinite(g).all(axis=(1, 2, 3)) & np.isfinite(v).all(axis=(1, 2))
            gi = rows_[good]
            dpos[gi], vel[gi] = g[good], v[good]
            if gi.size:
                # the conditioning along the exact tangent: by the coordinates, then (one
                # more column, the first coordinate's tangent plus the motion's) by the input
                gp = np.ascontiguousarray(coords[good]).reshape(-1, 2)
                gg = np.ascontiguousarray(g[good])
                dc = sc._core.dets_gradient(gp, gg.ravel(), self.cols, self.names)
                g1 = np.ascontiguousarray(gg[..., :1] + v[good][..., None])
                d1 = sc._core.dets_gradient(gp, g1.ravel(), self.cols[:1], self.names)
                dt = d1[:, 0] - dc[:, 0]
                rows = np.zeros((gi.size, nu))
                rows[:, :nc] = dc * self.size
                rows[:, nc:] = dt[:, None] * self.M[gi]
                ddet[gi] = np.where(np.isfinite(rows), rows, 0.0)
        jr = np.zeros((2 * n, nu))
        jr[:, :nc] = dpos[self.at, self.k_tr].reshape(2 * n, nc)  # d(p / size) / d(x / size)
        dv = vel[self.at, self.k_tr] / self.size  # (n, 2): by each point's own input
        jt = np.zeros((2 * n, n))
        jt[0::2, :] = np.diag(dv[:, 0])
        jt[1::2, :] = np.diag(dv[:, 1])
        jr[:, nc:] = jt @ self.T
        self._jkey, self._jac = key, {"r": jr, "cons": self._cons_jac(u, ddet)}
        return self._jac

    def _cons_jac(self, u: np.ndarray, ddet: np.ndarray) -> np.ndarray:
        nc, nu = self.nc, self.nu
        out = [
            self.det_sign * ddet[self.values(u)["pick"]] if self.bars is None else np.zeros((0, nu))
        ]
        if self.free:
            n = self.n
            d = np.zeros((n - 1, nu))
            idx = np.arange(n - 1)
            d[idx, nc + idx] = -self.sign
            d[idx, nc + idx + 1] = self.sign
            out.append(d)
            if self.wrap:
                w = np.zeros((1, nu))
                w[0, nc], w[0, nc + n - 1] = self.sign, -self.sign
                out.append(w)
        xy = self.coords(u)
        if self.box is not None:
            for i in self.pivots:
                b = np.zeros((4, nu))
                b[0, 2 * i], b[1, 2 * i] = 1.0, -1.0
                b[2, 2 * i + 1], b[3, 2 * i + 1] = 1.0, -1.0
                out.append(b)
        if self.ratio is not None:
            dl = self._length_rows(xy, self.pairs)
            big = self.ratio * dl[None, :, :] - dl[:, None, :]
            out.append(big[~np.eye(len(self.pairs), dtype=bool)])
        if self.bars is not None:
            _, dc = self._turn_cosines(xy)
            out.append(np.vstack([-dc, dc]))
        return np.vstack(out)

    def _length_rows(self, xy: np.ndarray, pairs: Sequence[tuple[int, int]]) -> np.ndarray:
        """d(length / size) / du of each pair (the coordinates are size * u)."""
        out = np.zeros((len(pairs), self.nu))
        for r, (a, b) in enumerate(pairs):
            d = xy[a] - xy[b]
            e = d / max(float(np.hypot(*d)), 1e-300)
            out[r, 2 * a : 2 * a + 2] += e
            out[r, 2 * b : 2 * b + 2] -= e
        return out

    def bounds(self) -> list[tuple[float | None, float | None]]:
        """SLSQP's bounds: every coordinate within COORD_BOUND target sizes of the target's
        centre (a design that flies away is no design), the inputs free."""
        b: list[tuple[float | None, float | None]] = [(-COORD_BOUND, COORD_BOUND)] * self.nc
        return b + [(None, None)] * self.nt

    def feasible(self, u: np.ndarray) -> bool:
        val = self.values(u)
        return bool(np.all(val["ok"]) and np.all(val["cons"] >= -FEAS_TOL))


def _box(box: Any) -> tuple[tuple[float, float], tuple[float, float]] | None:
    if box is None:
        return None
    try:
        (xl, xh), (yl, yh) = ((float(a), float(b)) for a, b in box)
    except (TypeError, ValueError):
        raise ValueError(f"box must be ((xmin, xmax), (ymin, ymax)), got {box!r}") from None
    ok = all(math.isfinite(v) for v in (xl, xh, yl, yh)) and xl < xh and yl < yh
    _check(ok, "box", f"must be finite with min < max on both axes, got {box!r}")
    return (xl, xh), (yl, yh)
