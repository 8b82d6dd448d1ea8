"""The NumPy reference of scenes: any scene solved by a route independent of the Rust
planner. Every link other than ground and input is a rigid body with an unknown pose, and
all the joint constraints are solved at once by Newton-Raphson from the drawn pose (no
plan, no dyad peeling), so parity tests compare two different formulations. Slots and
prismatic pairs are equations too (a point's signed distance from a line; a pair's
relative rotation and offset); a linear input adds the displacement it holds, with every
non-ground link free.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from .._angles import TAU, wrap
from .._status import Status
from ..scene._results import SceneSweep
from ._rules import check_options, positive_finite

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

__all__ = ["scene_assemble_check", "scene_mobility", "scene_sweep"]

#: A Jacobian whose reciprocal condition number (smallest over largest singular value,
#: unknowns and residuals both scale-free) is below this is SINGULAR.
RCOND_THRESHOLD = 1e-10

_REQUIRED = ("points", "links", "ground", "input")


class Scene(Protocol):
    """A :class:`planarkin.Scene`, as the reference sees it (it imports nothing of the
    kernel's): something that writes itself in the file format."""

    def to_dict(self) -> dict[str, Any]: ...


class _System:
    """The scene's joint equations over the free links' poses.

    Unknowns, three per free link: the displacement of its first listed point divided by
    the scene's size (two) and its rotation from the drawn pose (one). Residuals: at every
    point carried by two or more links, its position through each other link minus its
    position through the point's reference link (ground if it carries the point, else the
    input, else the first link listing it), divided by the size. The input's pivot is on
    both ground and input by construction and gives no equation there.
    """

    def __init__(self, scene: Mapping | Scene) -> None:
        scene = as_mapping(scene)
        if not isinstance(scene, Mapping):
            raise ValueError(f"scene must be a mapping, got {type(scene).__name__}")
        for key in _REQUIRED:
            if key not in scene:
                raise ValueError(f"scene is missing the key {key!r}")
        inp = scene["input"]
        linear = (
            isinstance(inp, Mapping) and len(inp) == 1 and next(iter(inp)) in ("slot", "prismatic")
        )
        if not linear and (not isinstance(inp, Mapping) or "link" not in inp or "pivot" not in inp):
            raise ValueError(
                "scene['input'] must hold the keys 'link' and 'pivot', or 'slot' or 'prismatic'"
            )
        self.points = {
            str(k): np.array([float(v[0]), float(v[1])]) for k, v in scene["points"].items()
        }
        self.links = {str(k): [str(p) for p in v] for k, v in scene["links"].items()}
        self.ground = str(scene["ground"])
        # slots: name -> (point, guide, line); prismatic pairs: name -> (link, guide, line)
        self.slots = {
            str(k): (str(v["point"]), str(v["guide"]), tuple(map(str, v["line"])))
            for k, v in (scene.get("slots") or {}).items()
        }
        self.prismatic = {
            str(k): (str(v["link"]), str(v["guide"]), tuple(map(str, v["line"])))
            for k, v in (scene.get("prismatic") or {}).items()
        }
        # a linear input: ("slot" | "prismatic", name); else the input link and its pivot
        self.linear = next(iter(inp.items())) if linear else None
        self.input = "" if linear else str(inp["link"])
        self.pivot = "" if linear else str(inp["pivot"])
        for name in (self.ground, *([] if linear else [self.input])):
            if name not in self.links:
                raise ValueError(f"unknown link {name!r} (ground or input)")
        for link, pts in self.links.items():
            for p in pts:
                if p not in self.points:
                    raise ValueError(f"link {link!r} carries the unknown point {p!r}")
        if not linear and (
            self.pivot not in self.links[self.input] or self.pivot not in self.links[self.ground]
        ):
            raise ValueError(f"input pivot {self.pivot!r} must be on ground and input links")
        out = scene.get("output")
        self.output = None
        if isinstance(out, Mapping) and "link" in out:  # an angle output (not a linear one)
            self.output = (str(out["link"]), str(out["pivot"]))

        # the scene's size: its longest link (largest distance between two points of a link)
        self.size = 0.0
        for pts in self.links.values():
            xy = np.array([self.points[p] for p in pts])
            d = np.sqrt(((xy[:, None, :] - xy[None, :, :]) ** 2).sum(-1))
            self.size = max(self.size, float(d.max()))
        if not (self.size > 0 and math.isfinite(self.size)):
            raise ValueError("scene['points'] must span a positive, finite size")

        self.free = [k for k in self.links if k not in (self.ground, self.input)]
        self.index = {k: i for i, k in enumerate(self.free)}
        if linear:
            self.theta0 = 0.0  # displacements are measured from the drawn pose
        else:
            pin = self.points[self.pivot]
            first_other = next(p for p in self.links[self.input] if p != self.pivot)
            d = self.points[first_other] - pin
            self.theta0 = math.atan2(d[1], d[0])

        carriers: dict[str, list[str]] = {p: [] for p in self.points}
        for link, pts in self.links.items():
            for p in dict.fromkeys(pts):
                carriers[p].append(link)
        self.carriers = carriers
        self.equations: list[tuple[str, str, str]] = []  # (point, link, reference link)
        self.home: dict[str, str] = {}  # the link each point is computed through
        for p, ls in carriers.items():
            if not ls:
                raise ValueError(f"point {p!r} is on no link")
            ref = self.ground if self.ground in ls else self.input if self.input in ls else ls[0]
            self.home[p] = ref
            for link in ls:
                if link == ref:
                    continue
                if p == self.pivot and {link, ref} == {self.ground, self.input}:
                    continue
                self.equations.append((p, link, ref))
        self.n = 3 * len(self.free)
        self.m = 2 * len(self.equations) + len(self.slots) + 2 * len(self.prismatic) + bool(linear)
        if self.m != self.n:
            raise ValueError(
                f"scene has {self.m} joint equations for {self.n} unknowns: its mobility "
                f"is {scene_mobility(scene)}, the reference needs mobility 1"
            )

    def _first(self, link: str) -> np.ndarray:
        return self.points[self.links[link][0]]

    def position(self, p: str, link: str, x: np.ndarray, cs: tuple[float, float]):
        """(position of p through link, d position / d unknowns of that link or None)."""
        p0 = self.points[p]
        if link == self.ground:
            return p0, None
        if link == self.input:
            c, s = cs
            piv = self.points[self.pivot]
            v = p0 - piv
            return piv + np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]]), None
        i = self.index[link]
        f = self._first(link)
        v = p0 - f
        phi = x[3 * i + 2]
        c, s = math.cos(phi), math.sin(phi)
        rv = np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])
        pos = f + self.size * x[3 * i : 3 * i + 2] + rv
        return pos, (i, rv)

    def _through(self, p: str, link: str, x: np.ndarray, cs: tuple[float, float]):
        """(position of p through link, its (2, n) Jacobian by the unknowns)."""
        pos, d = self.position(p, link, x, cs)
        jac = np.zeros((2, self.n))
        if d is not None:
            i, rv = d
            jac[0, 3 * i], jac[1, 3 * i + 1] = self.size, self.size
            jac[:, 3 * i + 2] = (-rv[1], rv[0])
        return pos, jac

    def _rotation(self, link: str, x: np.ndarray, cs: tuple[float, float]):
        """(a link's rotation from the drawn pose, its (n,) gradient)."""
        g = np.zeros(self.n)
        if link == self.ground:
            return 0.0, g
        if link == self.input:
            return math.atan2(cs[1], cs[0]), g
        i = self.index[link]
        g[3 * i + 2] = 1.0
        return float(x[3 * i + 2]), g

    def _line_terms(self, p: str, home: str, guide: str, line, x, cs):
        """Along and across coordinates of p from the guide's line (through line[0],
        directed to line[1]), with their gradients: (along, d along, across, d across)."""
        a, ja = self._through(line[0], guide, x, cs)
        b, jb = self._through(line[1], guide, x, cs)
        q, jq = self._through(p, home, x, cs)
        u, ju = b - a, jb - ja
        ell = float(np.hypot(*(self.points[line[1]] - self.points[line[0]])))
        w, jw = q - a, jq - ja
        along = float(u @ w) / ell
        d_along = (ju.T @ w + jw.T @ u) / ell
        across = float(u[0] * w[1] - u[1] * w[0]) / ell
        d_across = (ju[0] * w[1] - ju[1] * w[0] + u[0] * jw[1] - u[1] * jw[0]) / ell
        return along, d_along, across, d_across

    def _drawn_line_terms(self, p: str, line) -> tuple[float, float]:
        u = self.points[line[1]] - self.points[line[0]]
        w = self.points[p] - self.points[line[0]]
        ell = float(np.hypot(*u))
        return float(u @ w) / ell, float(u[0] * w[1] - u[1] * w[0]) / ell

    def _slider_rows(self, x: np.ndarray, cs: tuple[float, float], s: float):
        """The slots', prismatic pairs' and linear input's residuals and gradients."""
        rows = []
        for name, (p, guide, line) in self.slots.items():
            along, da, across, dc = self._line_terms(p, self.home[p], guide, line, x, cs)
            a0, c0 = self._drawn_line_terms(p, line)
            rows.append((across - c0, dc))
            if self.linear == ("slot", name):
                rows.append((along - a0 - s, da))
        for name, (link, guide, line) in self.prismatic.items():
            q = self.links[link][0]
            along, da, across, dc = self._line_terms(q, link, guide, line, x, cs)
            a0, c0 = self._drawn_line_terms(q, line)
            rows.append((across - c0, dc))
            (r1, g1), (r2, g2) = self._rotation(link, x, cs), self._rotation(guide, x, cs)
            rows.append((wrap(r1 - r2) * self.size, (g1 - g2) * self.size))
            if self.linear == ("prismatic", name):
                rows.append((along - a0 - s, da))
        return rows

    def residual_jacobian(self, x: np.ndarray, cs: tuple[float, float], s: float = 0.0):
        """F (m,) and J (m, n), both scale-free; ``s`` is a linear input's displacement."""
        f = np.empty(self.m)
        j = np.zeros((self.m, self.n))
        base = 2 * len(self.equations)
        for k, (r, g) in enumerate(self._slider_rows(x, cs, s)):
            f[base + k] = r / self.size
            j[base + k] = g / self.size
        for k, (p, link, ref) in enumerate(self.equations):
            a, da = self.position(p, link, x, cs)
            b, db = self.position(p, ref, x, cs)
            f[2 * k : 2 * k + 2] = (a - b) / self.size
            for sign, d in ((1.0, da), (-1.0, db)):
                if d is None:
                    continue
                i, rv = d
                j[2 * k, 3 * i] += sign
                j[2 * k + 1, 3 * i + 1] += sign
                j[2 * k, 3 * i + 2] += -sign * rv[1] / self.size
                j[2 * k + 1, 3 * i + 2] += sign * rv[0] / self.size
        return f, j

    def drive(self, theta: float) -> tuple[tuple[float, float], float]:
        """The input link's turn (cos, sin) from the drawn pose and a linear input's
        displacement, at input value theta."""
        if self.linear is not None:
            return (1.0, 0.0), theta
        dt = theta - self.theta0
        return (math.cos(dt), math.sin(dt)), 0.0

    def newton(self, x: np.ndarray, theta: float, tol: float, max_iter: int):
        """Newton-Raphson from x at input value theta: (x, Status, nit)."""
        cs, s = self.drive(theta)
        x = x.copy()
        nit = 0
        while True:
            f, j = self.residual_jacobian(x, cs, s)
            if not (np.all(np.isfinite(f)) and np.all(np.isfinite(x))):
                return x, Status.NON_FINITE, nit
            if self.n:
                sv = np.linalg.svd(j, compute_uv=False)
                if not sv[0] > 0 or sv[-1] / sv[0] < RCOND_THRESHOLD:
                    return x, Status.SINGULAR, nit
                try:
                    step = np.linalg.solve(j, -f)
                except np.linalg.LinAlgError:
                    return x, Status.SINGULAR, nit
            else:
                step = np.zeros(0)
            if not np.all(np.isfinite(step)):
                return x, Status.NON_FINITE, nit
            res = float(np.max(np.abs(f))) if f.size else 0.0
            if res < tol and (float(np.max(np.abs(step))) if step.size else 0.0) < tol:
                x += step  # the last correction is applied, without a further evaluation
                return self.normalize(x), Status.CONVERGED, nit
            if nit >= max_iter:
                return x, Status.MAX_ITERATIONS, nit
            x = self.normalize(x + step)
            nit += 1

    def normalize(self, x: np.ndarray) -> np.ndarray:
        """Rotations kept in (-pi, pi]: iterates that wander lose bits."""
        for i in range(len(self.free)):
            x[3 * i + 2] = wrap(float(x[3 * i + 2]))
        return x

    def sign(self, x: np.ndarray, theta: float) -> float:
        """The sign of det J at x: it names the branch (it flips at a dead point)."""
        _, j = self.residual_jacobian(x, *self.drive(theta))
        return float(np.linalg.slogdet(j)[0]) if self.n else 1.0

    def conditioning(self, x: np.ndarray, theta: float) -> float:
        """The Hadamard ratio det J / prod |columns of J| at x: signed (the sign names the
        branch, as in ``sign``), scale-free, 0 at a dead point; 1 with no free link."""
        if not self.n:
            return 1.0
        _, j = self.residual_jacobian(x, *self.drive(theta))
        return float(np.linalg.det(j) / np.prod(np.linalg.norm(j, axis=0)))

    def pose(self, x: np.ndarray, theta: float) -> dict[str, np.ndarray]:
        """Every point's position, each through its home link."""
        cs, _ = self.drive(theta)
        return {p: self.position(p, self.home[p], x, cs)[0] for p in self.points}

    def angle_points(self, link: str) -> tuple[str, str]:
        """The two points whose direction is the link's angle."""
        pts = self.links[link]
        for pivot_link, pivot in ((self.input, self.pivot), self.output or (None, None)):
            if link == pivot_link and pivot in pts:
                return pivot, next(p for p in pts if p != pivot)
        return pts[0], next(p for p in pts if p != pts[0])


def as_mapping(scene: object) -> Any:
    """A scene as the file format's mapping: a :class:`planarkin.Scene` (anything with
    ``to_dict()``) read through it, anything else as given (checked by the caller)."""
    to_dict = getattr(scene, "to_dict", None)
    return to_dict() if callable(to_dict) and not isinstance(scene, Mapping) else scene


def scene_mobility(scene: Mapping | Scene) -> int:
    """Gruebler's count 3 (links - 1) - 2 sum over points (links at the point - 1), less
    one per slot and two per prismatic pair."""
    d = as_mapping(scene)
    links = d["links"]
    count: dict[str, int] = {}
    for pts in links.values():
        for p in set(pts):
            count[p] = count.get(p, 0) + 1
    pins = 3 * (len(links) - 1) - 2 * sum(k - 1 for k in count.values())
    return pins - len(d.get("slots") or {}) - 2 * len(d.get("prismatic") or {})


#: A substep whose solution lies farther than this (rotation in radians, translation over
#: the scene's size) from its linear prediction is a jump to another branch, not a step.
JUMP = 0.5


def _march(sys_, hist, t_to, tol, max_iter, max_step):
    """Continuation from the last state of ``hist`` (a list of converged (t, x, sign of
    det J), oldest first) to ``t_to`` in substeps no larger than max_step, each predicted
    linearly from the last two converged states. A substep that converges where det J has
    the other sign (past a dead point) or far from its prediction is BRANCH_JUMP.
    Returns (x, status, nit, history at t_to); the caller's list is left alone, so a
    failure leaves the last converged state in place."""
    hist = list(hist[-2:])
    t_from, x, sign = hist[-1]
    span = t_to - t_from
    steps = max(1, math.ceil(abs(span) / max_step))
    nit = 0
    for k in range(1, steps + 1):
        t = t_to if k == steps else t_from + span * (k / steps)
        if len(hist) >= 2 and hist[-1][0] != hist[-2][0]:
            (t1, x1, _), (t2, x2, _) = hist[-2], hist[-1]
            guess = x2 + (x2 - x1) * ((t - t2) / (t2 - t1))
        else:
            guess = x
        x, st, n = sys_.newton(guess, t, tol, max_iter)
        nit += n
        if st == Status.CONVERGED:
            far = x.size and float(np.max(np.abs(sys_.normalize(x - guess)))) > JUMP
            if far or sys_.sign(x, t) != sign:
                st = Status.BRANCH_JUMP
        if st != Status.CONVERGED:
            return x, st, nit, hist
        hist = [hist[-1], (t, x, sign)]
    return x, Status.CONVERGED, nit, hist


def scene_sweep(
    scene: Mapping | Scene,
    theta: ArrayLike | None = None,
    *,
    tol: float = 1e-12,
    max_iter: int = 50,
    max_step: float | None = None,
) -> SceneSweep:
    """Sweeps a scene over input values ``theta`` (angles in radians, or a linear input's
    displacements), following the drawn assembly; returns a :class:`planarkin.SceneSweep`
    (no plan: ``plan``, ``limit``, the per-step and per-point status arrays are None;
    ``det`` is the Hadamard ratio of this reference's own Jacobian, NaN where unsolved).

    ``scene`` is a :class:`planarkin.Scene` or a scene dict (``points``, ``links``,
    ``ground``, ``input`` {link, pivot}, optional ``output``). The input link turns about
    its pivot by theta minus the drawn input angle (the direction from the pivot to the
    input's first other listed point);
    every other non-ground link is a rigid body whose pose is unknown, and all the joint
    equations are solved together by Newton-Raphson (``np.linalg.solve``). Residuals and
    translations are divided by the scene's size (its longest link); a solve converges
    when the largest residual and the largest Newton correction are both below ``tol``.

    Continuation: from the drawn pose at the drawn angle to ``theta[0]`` along the
    wrapped shortest difference, then along ``theta`` in order (the raw differences: a
    jump of k turns is marched through, k turns of substeps), in substeps no larger than
    ``max_step`` (default 1 degree; for a linear input, whose theta is a displacement from
    the drawn pose and is required, the scene's size times 1 degree), each predicted
    linearly from the last two converged states. A
    non-finite theta is NON_FINITE and skipped. An angle that fails gets NaN points and
    angles and status MAX_ITERATIONS, SINGULAR (reciprocal condition number of the
    Jacobian below 1e-10), NON_FINITE, or BRANCH_JUMP (a substep converged where det J
    has the other sign than at the drawn pose, i.e. past a dead point, or farther than
    0.5 from its prediction); the next angle marches again from the last converged pose
    and its angle. Default ``theta``: the drawn angle + 0, 1, ..., 360 degrees.
    """
    data = as_mapping(scene)
    sys_ = _System(data)
    if theta is None and sys_.linear is not None:
        raise ValueError("theta: a linear input's displacements must be given")
    if theta is None:
        th = sys_.theta0 + np.arange(361) * (TAU / 360)
    else:
        th = np.atleast_1d(np.asarray(theta, dtype=np.float64)).ravel()
    # the kernel's rules for these options (SceneSweepOptions::new), as the reference's own
    tol, max_iter = check_options(tol, max_iter)
    if max_step is None:  # 1 degree; for a linear input, 1 degree's worth of the drawing
        max_step = math.radians(1.0) * (1.0 if sys_.linear is None else sys_.size)
    max_step = positive_finite("max_step", max_step)
    n = th.size
    status = np.zeros(n, dtype=np.int8)
    nit = np.zeros(n, dtype=np.int64)
    det = np.full(n, np.nan)
    names, links = list(sys_.points), list(sys_.links)
    coords = np.full((n, len(names), 2), np.nan)
    angles = np.full((n, len(links)), np.nan)
    ang_pts = [sys_.angle_points(k) for k in links]

    x, st, _ = sys_.newton(np.zeros(sys_.n), sys_.theta0, tol, max_iter)
    hist: list = []
    if st != Status.CONVERGED:
        status[:] = st  # the drawn pose itself does not solve
    drawn = (x, sys_.sign(x, sys_.theta0)) if st == Status.CONVERGED else None
    for i in range(n if drawn else 0):
        t = float(th[i])
        if not math.isfinite(t):
            status[i] = Status.NON_FINITE
            continue
        if not hist:
            # the drawn state, re-labelled t minus the wrapped shortest difference
            start = 0.0 if sys_.linear is not None else t - wrap(t - sys_.theta0)
            hist = [(start, *drawn)]  # type: ignore[misc]
        x, s, k, h = _march(sys_, hist, t, tol, max_iter, max_step)
        nit[i] = k
        status[i] = s
        if s != Status.CONVERGED:
            continue
        hist = h
        det[i] = sys_.conditioning(x, t)
        pose = sys_.pose(x, t)
        for j, p in enumerate(names):
            coords[i, j] = pose[p]
        for j, (a, b) in enumerate(ang_pts):
            d = pose[b] - pose[a]
            angles[i, j] = wrap(math.atan2(d[1], d[0]))
    for j, p in enumerate(names):
        if sys_.home[p] == sys_.ground:
            coords[:, j] = sys_.points[p]
    a, b = ang_pts[links.index(sys_.ground)]
    d = sys_.points[b] - sys_.points[a]
    angles[:, links.index(sys_.ground)] = wrap(math.atan2(d[1], d[0]))
    return SceneSweep(
        plan=None, theta=th, coords=coords, angle_array=angles, status=status, nit=nit,
        det=det, limit=None, step_status=None, step_det=None, point_status_array=None,
        point_names=tuple(names), link_names=tuple(links),
        input_kind="angle" if sys_.linear is None else "displacement",
        units=data.get("units"),
    )  # fmt: skip


def scene_assemble_check(scene: Mapping | Scene) -> float:
    """How far the drawing is from an assembled pose of its own links, relative to size.

    Solves the scene at its drawn input angle from the drawn pose (as ``scene_sweep``
    does) and returns the largest change, over links, of the distance between two of the
    link's points, and over points, of a position, both divided by the scene's size
    (its longest link). A consistent scene gives 0 or a few ulp.
    """
    sys_ = _System(scene)
    x, st, _ = sys_.newton(np.zeros(sys_.n), sys_.theta0, 1e-14, 50)
    if st != Status.CONVERGED:
        return math.inf
    pose = sys_.pose(x, sys_.theta0)
    worst = 0.0
    for p, v in pose.items():
        worst = max(worst, float(np.max(np.abs(v - sys_.points[p]))) / sys_.size)
    for pts in sys_.links.values():
        for a in range(len(pts)):
            for b in range(a + 1, len(pts)):
                d0 = np.hypot(*(sys_.points[pts[a]] - sys_.points[pts[b]]))
                d1 = np.hypot(*(pose[pts[a]] - pose[pts[b]]))
                worst = max(worst, abs(float(d1 - d0)) / sys_.size)
    return worst
