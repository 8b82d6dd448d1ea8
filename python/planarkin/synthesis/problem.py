"""A synthesis problem: a design space (free joint coordinates of any scene, or of a double
butterfly template's drawn pose), a target (function, or path with or without prescribed
timing), and the objective and constraints evaluated on the true linkage by the Rust scene
solver (one sweep per candidate), or on the seed's generated mechanism (closed form, double
butterfly templates only)."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np

from .._angles import wrap_array
from ..scene import Scene
from .generated import SeedPlan
from .space import SceneSpace
from .targets import FunctionTarget, PathPoints, PathTarget, Target
from .topology import Template

OBJECTIVES = ("true", "generated", "corrected")
#: Newton tolerance of the sweeps (tight: finite differences read their angles)
SWEEP_TOL = 1e-12


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

    @property
    def coords(self) -> tuple[tuple[str, int], ...]:
        """The design vector's entries as (point, axis 0 or 1)."""
        return tuple((p, a) for p in self.free for a in (0, 1))

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

    @property
    def links(self) -> dict[str, tuple[str, ...]]:
        return self.template.links

    def lengths(self, points: Mapping[str, Sequence[float]]) -> np.ndarray:
        """Every distance between two points of one link."""
        return link_lengths(points, self.template)


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
    #: (m, 4 M) the envelope's margins on the dense grid (empty without an envelope)
    envelope: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))


class Residuals(NamedTuple):
    """A design's objective and constraints as vectors (``Problem.residuals``), every
    constraint >= 0 where it holds, on every point of the dense grid (the optimizer
    hands SLSQP the critical ones: :func:`~planarkin.synthesis.start.run_start`)."""

    #: dimensionless residuals at the design points (per objective)
    r: np.ndarray
    #: (m,) the true error on the dense grid over the target's scale (function targets)
    dense: np.ndarray
    #: (m,) the branch constraint s det / det_margin - 1 on the dense grid (failures -1)
    branch: np.ndarray
    #: the closed forms' radicands (double butterfly templates) and a PathPoints target's
    #: order constraint
    extra: np.ndarray
    #: (length - min_link) / min_link per pair of joints on one link (1 with no minimum)
    lengths: np.ndarray
    #: (m, 4 M) every moving joint inside the envelope at every dense point: margins to
    #: its four sides over the envelope's size, columns (x to high, x to low, y to high,
    #: y to low) per joint
    envelope: np.ndarray


@dataclass(frozen=True, init=False)
class Problem:
    """What one optimizer run needs (plain data: it travels to worker processes).

    ``Problem(scene, free=["A.x", "A.y", "B"], target=...)`` designs any scene: the named
    joint coordinates are the design variables (``"B"``: both of B's), the others are
    held as drawn (a :class:`SceneSpace` with its default bounds; build one to set them).
    A double butterfly :class:`DesignSpace` works the same and adds the seed's closed
    form. Targets: :class:`FunctionTarget` (the output's rotation, or displacement for a
    linear output, against the input's, both from the drawn pose), :class:`PathTarget`
    (a point at given inputs) and :class:`PathPoints` (a point through given points in
    order, its inputs found too). Constraints, all on the real linkage swept by the scene
    solver from the drawn pose: branch (every point of the range solved on the drawn
    assembly, the plan's conditioning keeping the drawn sign with ``det_margin``), order
    (the input passes the design points in order), link lengths (``min_link``), and
    with ``envelope`` ((x_low, y_low), (x_high, y_high), scene units) every moving joint
    inside that box at every point of the dense grid (a packaging space over the whole
    motion, not only as drawn)."""

    space: DesignSpace | SceneSpace
    target: Target
    #: the smallest |conditioning| allowed on the dense grid, with one sign throughout
    det_margin: float = 0.02
    #: the smallest dimensionless radicand of the closed forms (generated objective)
    radicand_margin: float = 1e-3
    objective: str = "true"
    #: sign combination (relative to the drawn pose) of the generated objective
    signs: tuple[int, int, int] = (1, 1, 1)
    #: constrain the closed forms' radicands (>= radicand_margin) on the dense grid
    #: (double butterfly templates with a function target)
    closed_form: bool = True
    #: the free joint coordinates of a SceneSpace ("A.x", "A.y", "B" for both)
    free: tuple[str, ...] | None = None
    #: the box every moving joint stays in over the motion: ((x_low, y_low), (x_high, y_high))
    envelope: tuple[tuple[float, float], tuple[float, float]] | None = None

    def __init__(
        self,
        space: DesignSpace | SceneSpace | Scene,
        target: Target,
        det_margin: float = 0.02,
        radicand_margin: float = 1e-3,
        objective: str = "true",
        signs: tuple[int, int, int] = (1, 1, 1),
        closed_form: bool = True,
        free: Sequence[str] | None = None,
        envelope: Any = None,
    ) -> None:
        # written out (not the dataclass's): ``space`` may be a Scene, made a SceneSpace
        given = {
            "target": target,
            "det_margin": det_margin,
            "radicand_margin": radicand_margin,
            "objective": objective,
            "signs": signs,
            "closed_form": closed_form,
        }
        for k, v in given.items():
            object.__setattr__(self, k, v)
        sp = space
        if isinstance(sp, Scene):
            if free is None:
                raise ValueError(
                    "free must name the joint coordinates to design (e.g. ['A.x', 'B']) "
                    "when space is a Scene"
                )
            sp = SceneSpace(sp, free)
        if not isinstance(sp, (DesignSpace, SceneSpace)):
            raise ValueError(
                f"space must be a Scene, SceneSpace or DesignSpace, got {type(sp).__name__}"
            )
        if free is not None and (not isinstance(sp, SceneSpace) or tuple(free) != sp.free):
            raise ValueError("free is given with a Scene (a design space names its own)")
        object.__setattr__(self, "space", sp)
        object.__setattr__(self, "free", sp.free if isinstance(sp, SceneSpace) else None)
        if self.objective not in OBJECTIVES:
            raise ValueError(f"objective must be one of {OBJECTIVES}, got {self.objective!r}")
        if not (math.isfinite(self.det_margin) and self.det_margin >= 0):
            raise ValueError(f"det_margin must be finite and >= 0, got {self.det_margin}")
        t = self.target
        object.__setattr__(self, "envelope", _box(envelope))
        if not isinstance(t, (FunctionTarget, PathTarget, PathPoints)):
            raise ValueError(
                f"target must be a FunctionTarget, PathTarget or PathPoints, got {type(t).__name__}"
            )
        if isinstance(sp, SceneSpace):
            if self.objective != "true":
                raise ValueError(
                    f"objective {self.objective!r} is the seed's closed form: it needs a double "
                    "butterfly DesignSpace; a scene's is 'true'"
                )
            if isinstance(t, FunctionTarget) and sp.drawn.output is None:
                raise ValueError("target: a function target needs the scene's output")
        if isinstance(t, (PathTarget, PathPoints)) and t.point not in sp.points:
            raise ValueError(f"target point {t.point!r} is not a point of the scene")

    # --- the design vector ---------------------------------------------------------------

    @property
    def timing(self) -> int:
        """How many input values the design vector carries after the joint coordinates
        (those of a :class:`PathPoints` target; 0 otherwise)."""
        return self.target.n if isinstance(self.target, PathPoints) else 0

    @property
    def lower(self) -> np.ndarray:
        """Lower bounds of the design vector."""
        t = self.target
        if isinstance(t, PathPoints):
            return np.concatenate([self.space.lower, np.full(t.n, t.span[0])])
        return self.space.lower  # type: ignore[no-any-return]

    @property
    def upper(self) -> np.ndarray:
        """Upper bounds of the design vector."""
        t = self.target
        if isinstance(t, PathPoints):
            return np.concatenate([self.space.upper, np.full(t.n, t.span[1])])
        return self.space.upper  # type: ignore[no-any-return]

    @property
    def x0(self) -> np.ndarray:
        """The design vector of the drawing itself (and the target's ``phi0``)."""
        x = self.space.x_of(self.space.points)
        t = self.target
        if isinstance(t, PathPoints):
            assert t.phi0 is not None
            x = np.concatenate([x, t.phi0])
        return x

    def coordinates(self, x: np.ndarray) -> np.ndarray:
        """The joint coordinates of design vector ``x`` (without its input values)."""
        return np.asarray(x, dtype=np.float64)[: self.space.size]

    def scene(self, x: np.ndarray) -> Scene:
        """The linkage of design vector ``x``, drawn at its design pose."""
        return self.space.scene(self.coordinates(x))

    def inputs(self, x: np.ndarray | None = None) -> np.ndarray:
        """The design points' input values (from the drawn pose): the target's, or for a
        :class:`PathPoints` target those in ``x`` (default its ``phi0``)."""
        t = self.target
        if isinstance(t, PathPoints):
            if x is None:
                assert t.phi0 is not None
                return t.phi0
            return np.asarray(x, dtype=np.float64)[self.space.size :]
        return t.phi_in

    # --- the true linkage --------------------------------------------------------------

    def grid(self, x: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The sweep grid (design points, dense grid and 0, the drawn pose, sorted) and the
        indices of the design points and of the dense grid in it. A :class:`PathPoints`
        target's depends on the input values in ``x``."""
        t = self.target
        if isinstance(t, PathPoints):
            phi = self.inputs(x)
            dense = np.linspace(phi[0], phi[-1], t.dense)
        else:
            phi, dense = t.phi_in, t.dense_in
        allv = np.concatenate([phi, dense, [0.0]])
        grid, inv = np.unique(np.round(allv, 14), return_inverse=True)
        n, m = phi.size, dense.size
        return grid, inv[:n], inv[n : n + m]

    def evaluate(self, x: np.ndarray, grid: tuple | None = None) -> Evaluation:
        try:
            return self._evaluate(np.asarray(x, dtype=np.float64), grid)
        except ValueError:
            # a drawing the scene solver cannot plan (coincident joints, ...) fails
            t = self.target
            if isinstance(t, FunctionTarget):
                n, m = t.phi_in.size, t.dense_in.size
            elif isinstance(t, PathTarget):
                n, m = 2 * t.phi_in.size, t.dense_in.size
            else:
                n, m = 2 * t.n, t.dense
            nan = np.full(m, np.nan)
            return Evaluation(np.full(n, np.nan), nan, nan, math.nan, False)

    def _evaluate(self, x: np.ndarray, grid: tuple | None) -> Evaluation:
        # the whole plan swept (its conditioning covers every step), inputs and outputs
        # measured from the drawn pose
        t = self.target
        if isinstance(t, PathPoints):
            grid = self.grid(x)  # its input values are design variables
        g, i_des, i_den = grid if grid is not None else self.grid()
        sc = self.space.scene(self.coordinates(x))
        vals = sc.input_angle + g if sc.input_kind == "angle" else g
        sw = sc.sweep(vals, outputs="all", tol=SWEEP_TOL)
        if isinstance(t, FunctionTarget):
            out = output_from_drawn(sc, sw.output)
            err = out[i_des] - t.phi_out
            dense_err = out[i_den] - t.dense_out
        else:
            xy = sw.points[t.point]
            err = (xy[i_des] - t.xy).ravel()  # x and y deviations: smooth at zero
            dense_err = np.full(i_den.size, np.nan)
        ok_all = sw.status == 0
        det = np.where(ok_all, sw.det, np.nan)
        det0 = float(det[int(np.argmin(np.abs(g)))])
        env = np.zeros((i_den.size, 0))
        if self.envelope is not None:
            (xl, yl), (xh, yh) = self.envelope
            w = max(xh - xl, yh - yl)
            c = sw.coords[i_den][:, self.moving_indices(sc)]  # (m, M, 2)
            env = np.stack(
                [
                    (xh - c[..., 0]) / w,
                    (c[..., 0] - xl) / w,
                    (yh - c[..., 1]) / w,
                    (c[..., 1] - yl) / w,
                ],
                axis=-1,
            ).reshape(i_den.size, -1)
            env = np.where(np.isfinite(env), env, -1.0)
        extra = {"scene": sc, "sweep": sw, "grid": (g, i_des, i_den)}
        return Evaluation(err, dense_err, det[i_den], det0, bool(np.all(ok_all)), extra, env)

    def moving_indices(self, sc: Scene) -> list[int]:
        """Indices (in ``sc.points`` order) of the joints that move: the envelope's."""
        ground = set(sc.links[sc.ground])
        return [i for i, p in enumerate(sc.points) if p not in ground]

    # --- the seed's generated mechanism -------------------------------------------------

    def generated(
        self, x: np.ndarray, signs: tuple[int, int, int] | None = None, with_k: bool = True
    ) -> Any:
        if not isinstance(self.target, FunctionTarget):
            raise ValueError("objective 'generated' needs a function-generation target")
        if not isinstance(self.space, DesignSpace):
            raise ValueError("objective 'generated' needs a double butterfly DesignSpace")
        plan = SeedPlan(self.space.template, self.space.points_of(x))
        return plan.generated(
            self.target.phi_in, self.target.phi_out, signs or self.signs, with_k=with_k
        )

    # --- objective and constraints as vectors ------------------------------------------

    def residuals(self, x: np.ndarray, grid: tuple | None = None) -> Residuals:
        """The objective and constraints at ``x`` as vectors (:class:`Residuals`): residuals
        at the design points (per objective) and on the dense grid (true linkage), the
        branch constraint s det / margin - 1 on the dense grid (failures -1), the closed
        forms' radicands or a PathPoints target's order, the link lengths, the envelope."""
        x = np.asarray(x, dtype=np.float64)
        return self.residuals_of(x, self.evaluate(x, grid))

    def residuals_of(self, x: np.ndarray, ev: Evaluation) -> Residuals:
        """:meth:`residuals` from ``ev``, the evaluation of ``x``."""
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
        r = np.where(np.isfinite(r), r, 1.0)
        dense = np.where(np.isfinite(ev.dense_err), ev.dense_err / scale, 1.0)
        env = ev.envelope
        if self.envelope is not None and env.size == 0:  # a drawing that could not be planned
            env = np.full((branch.size, 4 * self.moving_count), -1.0)
        return Residuals(r, dense, branch, self.extra_constraints(x), self.lengths(x), env)

    @property
    def moving_count(self) -> int:
        """How many joints move (the envelope holds 4 margins for each)."""
        sp = self.space
        ground = set(sp.links[_ground_name(sp)])
        return sum(1 for p in sp.points if p not in ground)

    def extra_constraints(self, x: np.ndarray) -> np.ndarray:
        """The closed forms' radicands (double butterfly templates with ``closed_form``) and
        a PathPoints target's order constraint (no sweep needed)."""
        out = []
        t = self.target
        if (
            self.closed_form
            and isinstance(t, FunctionTarget)
            and isinstance(self.space, DesignSpace)
        ):
            # every closed form assemblable with a margin on the dense grid (its radicands),
            # so that the generated mechanism stays on the drawn branch of each loop
            plan = SeedPlan(self.space.template, self.space.points_of(self.coordinates(x)))
            gd = plan.generated(t.dense_in, t.dense_out, self.signs, with_k=False)
            rm = max(self.radicand_margin, 1e-12)
            out.append((gd.radicand.ravel() - rm) / rm)
        if isinstance(t, PathPoints):
            # order: each point's input at least order_margin past the one before
            out.append(np.diff(self.inputs(x)) / t.order_margin - 1.0)
        return np.concatenate(out) if out else np.zeros(0)

    def lengths(self, x: np.ndarray) -> np.ndarray:
        """The link-length constraint (length - min_link) / min_link (1 with no minimum)."""
        pts = self.space.points_of(self.coordinates(x))
        ml = self.space.min_link
        lengths = self.space.lengths(pts)
        return (lengths - ml) / ml if ml > 0 else np.ones_like(lengths)


def _ground_name(sp: DesignSpace | SceneSpace) -> str:
    return sp.template.ground if isinstance(sp, DesignSpace) else sp.drawn.ground


def _box(envelope: Any) -> tuple[tuple[float, float], tuple[float, float]] | None:
    if envelope is None:
        return None
    try:
        (xl, yl), (xh, yh) = ((float(a), float(b)) for a, b in envelope)
    except (TypeError, ValueError):
        raise ValueError(
            f"envelope must be ((x_low, y_low), (x_high, y_high)), got {envelope!r}"
        ) from None
    if not all(math.isfinite(v) for v in (xl, yl, xh, yh)) or not (xl < xh and yl < yh):
        raise ValueError(f"envelope must be finite with low < high on both axes, got {envelope!r}")
    return (xl, yl), (xh, yh)


def output_from_drawn(sc: Scene, output: np.ndarray | None) -> np.ndarray:
    """A sweep's output coordinate measured from the drawn pose: the output link's rotation
    (wrapped to (-pi, pi]) or a linear output's displacement (already from the drawn
    pose)."""
    if output is None:
        raise ValueError("scene must have an output, among the points swept")
    o = sc.output
    assert o is not None
    if "link" in sc.to_dict()["output"]:
        link, pivot = o
        pts = sc.points
        tip = next(p for p in sc.links[link] if p != pivot)
        a0 = math.atan2(pts[tip][1] - pts[pivot][1], pts[tip][0] - pts[pivot][0])
        return wrap_array(output - a0)
    return np.asarray(output, dtype=np.float64)
