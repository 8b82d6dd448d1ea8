"""A synthesis problem: a design space (free joint coordinates of a template's drawn pose),
a target (function or path), and the objective and constraints evaluated on the true
linkage by the Rust scene solver (one sweep per candidate), or on the seed's generated
mechanism (closed form)."""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..scene import Scene
from .generated import SeedPlan
from .topology import Template

OBJECTIVES = ("true", "generated", "corrected")
#: Newton tolerance of the sweeps (tight: finite differences read their angles)
SWEEP_TOL = 1e-12


def _wrap(a: np.ndarray) -> np.ndarray:
    return np.angle(np.exp(1j * np.asarray(a)))


def _monotone(name: str, a: np.ndarray) -> None:
    # the seed's order constraint: the input moves one way through the design points
    d = np.diff(a)
    if a.ndim != 1 or a.size < 2 or not (np.all(d > 0) or np.all(d < 0)):
        raise ValueError(
            f"{name} must be a strictly monotone 1-D array of >= 2 input angles (order "
            "constraint: the input must pass the design points in order)"
        )


@dataclass(frozen=True)
class FunctionTarget:
    """Function generation: output rotations ``phi_out`` at input rotations ``phi_in``
    (radians from the drawn pose; the drawn pose itself is input 0, output 0), and the
    same on a dense grid for the branch constraint and verification (``dense_in``,
    ``dense_out``)."""

    phi_in: np.ndarray
    phi_out: np.ndarray
    dense_in: np.ndarray
    dense_out: np.ndarray
    #: the prescribed function itself (a picklable callable), for verification off the grid
    function: Callable[[np.ndarray], np.ndarray] | None = None

    def __post_init__(self) -> None:
        for name in ("phi_in", "phi_out", "dense_in", "dense_out"):
            a = np.asarray(getattr(self, name), dtype=np.float64)
            if a.ndim != 1 or not np.all(np.isfinite(a)):
                raise ValueError(f"{name} must be a 1-D array of finite angles (radians)")
            object.__setattr__(self, name, a)
        _monotone("phi_in", self.phi_in)
        _monotone("dense_in", self.dense_in)
        if self.phi_out.shape != self.phi_in.shape:
            raise ValueError(f"phi_out must have the shape of phi_in {self.phi_in.shape}")
        if self.dense_out.shape != self.dense_in.shape:
            raise ValueError(f"dense_out must have the shape of dense_in {self.dense_in.shape}")
        if np.ptp(self.phi_out) <= 0:
            raise ValueError("phi_out must not be constant (its range scales the objective)")

    @property
    def scale(self) -> float:
        """The prescribed output range (the objective's denominator)."""
        return float(np.ptp(self.phi_out))


@dataclass(frozen=True)
class PathTarget:
    """Path generation with prescribed timing: point ``point`` at ``xy`` (n, 2) at input
    rotations ``phi_in``; ``dense_in`` is the grid of the branch constraint."""

    point: str
    phi_in: np.ndarray
    xy: np.ndarray
    dense_in: np.ndarray

    def __post_init__(self) -> None:
        pi = np.asarray(self.phi_in, dtype=np.float64)
        xy = np.asarray(self.xy, dtype=np.float64)
        di = np.asarray(self.dense_in, dtype=np.float64)
        _monotone("phi_in", pi)
        _monotone("dense_in", di)
        if xy.shape != (pi.size, 2) or not np.all(np.isfinite(xy)):
            raise ValueError(f"xy must be finite points of shape ({pi.size}, 2), got {xy.shape}")
        object.__setattr__(self, "phi_in", pi)
        object.__setattr__(self, "xy", xy)
        object.__setattr__(self, "dense_in", di)

    @property
    def scale(self) -> float:
        """The size of the prescribed path (the larger side of its bounding box)."""
        return float(np.ptp(self.xy, axis=0).max())


Target = FunctionTarget | PathTarget


@dataclass(frozen=True)
class DesignSpace:
    """The design vector: the coordinates of ``free`` points of ``template`` drawn at
    ``points`` (the others fixed), each within ``lower``..``upper`` (per coordinate,
    x then y of each free point in order)."""

    template: Template
    points: Mapping[str, tuple[float, float]]
    free: tuple[str, ...]
    #: per coordinate, or one number for all (stored as arrays)
    lower: Any
    upper: Any
    #: shortest allowed distance between two joints of one link (scene units)
    min_link: float = 0.0

    def __post_init__(self) -> None:
        names = self.template.point_names
        missing = [p for p in names if p not in self.points]
        if missing:
            raise ValueError(f"points must give every point of the template; missing {missing}")
        bad = [p for p in self.free if p not in names]
        if bad:
            raise ValueError(f"free must name points of the template; unknown {bad}")
        lo = np.broadcast_to(np.asarray(self.lower, dtype=np.float64), (2 * len(self.free),))
        hi = np.broadcast_to(np.asarray(self.upper, dtype=np.float64), (2 * len(self.free),))
        if not np.all(lo < hi):
            raise ValueError("lower must be below upper in every coordinate")
        object.__setattr__(self, "lower", lo.copy())
        object.__setattr__(self, "upper", hi.copy())
        object.__setattr__(
            self, "points", {k: (float(v[0]), float(v[1])) for k, v in self.points.items()}
        )
        if not (math.isfinite(self.min_link) and self.min_link >= 0):
            raise ValueError(f"min_link must be finite and >= 0, got {self.min_link}")

    @property
    def size(self) -> int:
        return 2 * len(self.free)

    def x_of(self, points: Mapping[str, Sequence[float]]) -> np.ndarray:
        return np.array([float(points[p][i]) for p in self.free for i in (0, 1)])

    def points_of(self, x: np.ndarray) -> dict[str, tuple[float, float]]:
        pts = dict(self.points)
        for j, p in enumerate(self.free):
            pts[p] = (float(x[2 * j]), float(x[2 * j + 1]))
        return pts

    def scene_dict(self, x: np.ndarray, name: str | None = None) -> dict[str, Any]:
        return self.template.scene_dict(self.points_of(x), name)

    def scene(self, x: np.ndarray) -> Scene:
        return Scene.from_dict(self.scene_dict(x))

    def link_pairs(self) -> list[tuple[str, str]]:
        """Every pair of points on one link (their distances are the link dimensions)."""
        out = []
        for pts in self.template.links.values():
            for i, a in enumerate(pts):
                for b in pts[i + 1 :]:
                    out.append((a, b))
        return out


def link_lengths(points: Mapping[str, Sequence[float]], template: Template) -> np.ndarray:
    """Every distance between two points of one link."""
    out = []
    for pts in template.links.values():
        for i, a in enumerate(pts):
            for b in pts[i + 1 :]:
                out.append(math.dist(points[a], points[b]))
    return np.array(out)


@dataclass
class Evaluation:
    """The true linkage at one design vector: residuals at the design points (``err``,
    radians or scene units), on the dense grid (``dense_err``), the signed conditioning on
    the dense grid (``det``, failures as NaN), the drawn pose's conditioning ``det0``."""

    err: np.ndarray
    dense_err: np.ndarray
    det: np.ndarray
    det0: float
    ok: bool
    extra: dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class Problem:
    """What one optimizer run needs (plain data: it travels to worker processes)."""

    space: DesignSpace
    target: FunctionTarget | PathTarget
    #: the smallest |conditioning| allowed on the dense grid, with one sign throughout
    det_margin: float = 0.02
    #: the smallest dimensionless radicand of the closed forms (generated objective)
    radicand_margin: float = 1e-3
    objective: str = "true"
    #: sign combination (relative to the drawn pose) of the generated objective
    signs: tuple[int, int, int] = (1, 1, 1)
    #: constrain the closed forms' radicands (>= radicand_margin) on the dense grid
    closed_form: bool = True

    def __post_init__(self) -> None:
        if self.objective not in OBJECTIVES:
            raise ValueError(f"objective must be one of {OBJECTIVES}, got {self.objective!r}")
        if not (math.isfinite(self.det_margin) and self.det_margin >= 0):
            raise ValueError(f"det_margin must be finite and >= 0, got {self.det_margin}")

    # --- the true linkage --------------------------------------------------------------

    def grid(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The sweep grid (design points, dense grid and 0, the drawn pose, sorted) and the
        indices of the design points and of the dense grid in it."""
        t = self.target
        allv = np.concatenate([t.phi_in, t.dense_in, [0.0]])
        grid, inv = np.unique(np.round(allv, 14), return_inverse=True)
        n, m = t.phi_in.size, t.dense_in.size
        return grid, inv[:n], inv[n : n + m]

    def evaluate(self, x: np.ndarray, grid: tuple | None = None) -> Evaluation:
        try:
            return self._evaluate(x, grid)
        except ValueError:
            # a drawing the scene solver cannot plan (coincident joints, ...) fails
            n, m = self.target.phi_in.size, self.target.dense_in.size
            nan = np.full(m, np.nan)
            return Evaluation(np.full(n, np.nan), nan, nan, math.nan, False)

    def _evaluate(self, x: np.ndarray, grid: tuple | None) -> Evaluation:
        sp = self.space
        sc = sp.scene(x)
        g, i_des, i_den = grid if grid is not None else self.grid()
        t = self.target
        tpl = sp.template
        if isinstance(t, FunctionTarget):
            link, pivot = tpl.output
            sw = sc.sweep(sc.input_angle + g, outputs=[link], tol=SWEEP_TOL)
            pts = sc.points
            first = next(p for p in tpl.links[link] if p != pivot)
            a0 = math.atan2(pts[first][1] - pts[pivot][1], pts[first][0] - pts[pivot][0])
            rot = _wrap(sw.angles[link] - a0)
            err = rot[i_des] - t.phi_out
            dense_err = rot[i_den] - t.dense_out
        else:
            sw = sc.sweep(sc.input_angle + g, outputs=[t.point], tol=SWEEP_TOL)
            xy = sw.points[t.point]
            err = (xy[i_des] - t.xy).ravel()  # x and y deviations: smooth at zero
            dense_err = np.full(i_den.size, np.nan)
        ok_all = sw.status == 0
        det = np.where(ok_all, sw.det, np.nan)
        i0 = int(np.argmin(np.abs(g)))
        det0 = float(det[i0])
        ok = bool(np.all(ok_all))
        return Evaluation(err, dense_err, det[i_den], det0, ok)

    # --- the seed's generated mechanism -------------------------------------------------

    def generated(
        self, x: np.ndarray, signs: tuple[int, int, int] | None = None, with_k: bool = True
    ) -> Any:
        if not isinstance(self.target, FunctionTarget):
            raise ValueError("objective 'generated' needs a function-generation target")
        plan = SeedPlan(self.space.template, self.space.points_of(x))
        return plan.generated(
            self.target.phi_in, self.target.phi_out, signs or self.signs, with_k=with_k
        )

    # --- objective and constraints as vectors ------------------------------------------

    def residuals(self, x: np.ndarray, grid: tuple | None = None) -> tuple[np.ndarray, ...]:
        """(r, dense_r, branch, lengths): dimensionless residuals at the design points
        (per objective) and on the dense grid (true linkage), the branch constraint
        s det / margin - 1 on the dense grid (failures -1), the link-length constraint
        (length - min_link) / min_link (or 1 with no minimum)."""
        ev = self.evaluate(x, grid)
        scale = self.target.scale
        s = 1.0 if not math.isfinite(ev.det0) or ev.det0 >= 0 else -1.0
        m = max(self.det_margin, 1e-12)
        branch = np.where(np.isfinite(ev.det), s * ev.det / m - 1.0, -1.0)
        if not math.isfinite(ev.det0):
            branch[:] = -1.0
        if self.objective == "true":
            r = ev.err / scale
        else:
            g = self.generated(x, with_k=self.objective == "corrected")
            e = (g.theta - self.target.phi_out) / scale  # type: ignore[union-attr]
            one_k = np.where(np.abs(1 - g.k) > 1e-3, 1 - g.k, 1e-3)
            r = e if self.objective == "generated" else e / one_k
        if self.closed_form and isinstance(self.target, FunctionTarget):
            # every closed form assemblable with a margin on the dense grid (its radicands),
            # so that the generated mechanism stays on the drawn branch of each loop
            t = self.target
            plan = SeedPlan(self.space.template, self.space.points_of(x))
            gd = plan.generated(t.dense_in, t.dense_out, self.signs, with_k=False)
            rm = max(self.radicand_margin, 1e-12)
            branch = np.concatenate([branch, (gd.radicand.ravel() - rm) / rm])
        r = np.where(np.isfinite(r), r, 1.0)
        dense = np.where(np.isfinite(ev.dense_err), ev.dense_err / scale, 1.0)
        pts = self.space.points_of(x)
        ml = self.space.min_link
        lengths = link_lengths(pts, self.space.template)
        lc = (lengths - ml) / ml if ml > 0 else np.ones_like(lengths)
        return r, dense, branch, lc
