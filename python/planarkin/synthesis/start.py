"""One SLSQP start (:func:`run_start`): least squares on the design points, then a minimax
polish on the dense grid, under the branch, assemblability, link-length and envelope
constraints; the derivatives exact or by forward differences of whole sweeps, all of one
candidate from one sweep per coordinate; the true figures and feasibility checked again
at its end."""

from __future__ import annotations

import math
import time
import warnings
from typing import Any

import numpy as np

from .exact import Picks, Rows, available, exact_rows, extrema, fd_rows, picks, subgrid
from .problem import Evaluation, FunctionTarget, Problem, Residuals
from .results import TIME_LIMIT, StartResult

#: forward-difference step on joint coordinates, relative to the box size
FD_STEP = 1e-7
#: the subgrid of the dense grid SLSQP sees the branch constraint on (with its smallest
#: value on the whole grid), and the dense error's largest local extrema added to it for
#: the minimax phase (with its largest value on the whole grid)
SUBGRID, K_DENSE = 41, 64
#: how the optimizer differentiates: the solver's exact derivatives, or forward
#: differences of whole sweeps (the check)
GRADIENTS = ("exact", "fd")
#: the minimax polish's unit of design steps, relative to the box size. SLSQP's first
#: quadratic model has the identity for Hessian: in the joint coordinates it weighed a move
#: of a whole box like a unit drop of the bound t (the error's largest at the polish's
#: start, whose rows have slopes of 1e5 there), so its first step left the least-squares
#: design for a 10-20 deg error and the polish wandered until its line search failed (the
#: default Ackermann run kept it in 2 of 12 starts). In these units a joint move of about
#: 1e-3 wheelbase weighs like that drop: the polish stays near the design it polishes.
MINIMAX_STEP = 1.5e-3
#: the least-squares phase hands over to the minimax polish once its best feasible
#: objective has fallen by less than STALL_DROP over the last STALL_ITER iterations. SLSQP's
#: own test (a change of the objective below ftol, absolute, with every constraint within
#: ftol) cannot trigger there: the objective, 1 at the start, ends near 1e-7 still falling
#: about 1% an iteration on an ill-conditioned fit (singular values over nine decades), so
#: the default Ackermann run ended every start at the 200-iteration limit
STALL_ITER, STALL_DROP = 30, 0.1
#: the most iterations of the minimax polish (its error falls by half to a tenth in the
#: first few tens; SLSQP's own test rarely stops it on the nonsmooth largest-error rows)
MINIMAX_ITER = 60


class Cache:
    """One design at a time: its residuals (one sweep), the critical points the reduced
    constraints take there, and their derivatives (exact, or forward differences), with
    the constraint vector SLSQP sees assembled from them."""

    def __init__(self, problem: Problem, grid: tuple, step: float, gradient: str) -> None:
        self.p = problem
        self.grid = grid
        self.step = step
        self.gradient = gradient
        self._x: bytes | None = None
        self._res: Residuals | None = None
        self._ev: Evaluation | None = None
        self._picks: Picks | None = None
        self._jx: tuple[bytes, bool] | None = None
        self._rows: Rows | None = None
        m = grid[2].size
        self.sub = subgrid(m, SUBGRID)
        self.dense_fixed = self.sub

    def fix_dense(self, x: np.ndarray) -> None:
        """The minimax phase's fixed set: the subgrid and the dense error's largest local
        extrema at ``x`` (its start)."""
        d = np.abs(self.values(x).dense)
        self.dense_fixed = np.union1d(subgrid(d.size, 3 * SUBGRID), extrema(d, K_DENSE))
        self._x = self._jx = None  # the picks change

    def _at(self, x: np.ndarray) -> None:
        k = x.tobytes()
        if k != self._x:
            grid = self.p.grid(x) if self.p.timing else self.grid
            self._ev = self.p.evaluate(x, grid)
            self._res = self.p.residuals_of(x, self._ev)
            self._picks = picks(self._res, self.sub, self.dense_fixed)
            self._x = k

    def values(self, x: np.ndarray) -> Residuals:
        x = np.asarray(x, dtype=np.float64)
        self._at(x)
        assert self._res is not None
        return self._res

    def cons(self, x: np.ndarray) -> np.ndarray:
        """The constraints SLSQP sees: branch at its critical points, the extra ones, link
        lengths, each envelope column at its tightest point."""
        res = self.values(x)
        p = self._picks
        assert p is not None
        env = res.envelope[p.envelope, np.arange(p.envelope.size)] if p.envelope.size else []
        return np.concatenate([res.branch[p.branch], res.extra, res.lengths, env])

    def dense(self, x: np.ndarray) -> np.ndarray:
        """The dense error on the minimax phase's fixed set and, last, where its magnitude
        is largest on the whole grid."""
        res = self.values(x)
        assert self._picks is not None
        return res.dense[self._picks.dense]

    def jac(self, x: np.ndarray, dense: bool = False) -> Rows:
        x = np.asarray(x, dtype=np.float64)
        self._at(x)
        key = (x.tobytes(), dense)
        if self._jx is None or self._jx[0] != key[0] or (dense and not self._jx[1]):
            assert self._res is not None and self._picks is not None and self._ev is not None
            if self.gradient == "exact":
                self._rows = exact_rows(self.p, x, self._ev, self._res, self._picks, dense=dense)
            else:
                grid = self.p.grid(x) if self.p.timing else self.grid
                self._rows = fd_rows(self.p, x, self._res, self._picks, grid, self.step)
            self._jx = (key[0], dense or self.gradient != "exact")
        assert self._rows is not None
        return self._rows

    def cons_jac(self, x: np.ndarray) -> np.ndarray:
        j = self.jac(x)
        return np.vstack([j.branch, j.extra, j.lengths, j.envelope])


def figures(problem: Problem, x: np.ndarray) -> dict[str, float]:
    """Max and RMS true error (dimensionless, design points and dense grid) and the
    smallest |conditioning| on the dense grid."""
    ev = problem.evaluate(x)
    s = problem.target.scale
    dense = ev.dense_err if np.isfinite(ev.dense_err).any() else ev.err
    det = ev.det
    same_sign = bool(np.all(np.isfinite(det)) and (np.all(det > 0) or np.all(det < 0)))
    return {
        "max_error": float(np.max(np.abs(np.concatenate([ev.err, dense]))) / s)
        if ev.ok
        else math.inf,
        "rms_error": float(np.sqrt(np.mean(ev.err**2)) / s) if ev.ok else math.inf,
        "min_abs_det": float(np.nanmin(np.abs(det))) if np.isfinite(det).any() else 0.0,
        "one_branch": same_sign and ev.ok,
    }


def run_start(
    problem: Problem,
    x0: np.ndarray,
    *,
    maxiter: int = 200,
    ftol: float = 1e-14,
    minimax: bool = True,
    deadline: float | None = None,
    index: int = 0,
    gradient: str = "auto",
    polish_maxiter: int = MINIMAX_ITER,
    stall_iter: int | None = STALL_ITER,
) -> StartResult:
    """SLSQP from ``x0``: least squares on the objective's residuals at the design points
    (at most ``maxiter`` iterations), then (``minimax``) the largest true residual on the
    dense grid (at most ``polish_maxiter`` and ``maxiter`` iterations, in steps scaled by
    :data:`MINIMAX_STEP`), both under the branch, closed-form assemblability and
    link-length constraints and the box bounds. The least squares hand over once their
    best feasible objective falls by less than :data:`STALL_DROP` in ``stall_iter``
    iterations (None: they run to SLSQP's own end). At
    ``deadline`` (``time.time()`` seconds: it holds across processes) SLSQP stops at its
    next iteration (status 99) and the iterate it reached is returned, verified like any
    other (``stopped``); the minimax phase is skipped once it has passed. ``gradient``:
    "exact" (the solver's derivatives), "fd" (forward differences, one sweep per design
    variable), or "auto" (exact where available: :func:`resolve_gradient`). SLSQP sees
    the constraints over the dense grid as :class:`~planarkin.synthesis.exact.Picks` says
    (the branch constraint on a subgrid of :data:`SUBGRID` points and at its smallest;
    each envelope side at its tightest point; in the minimax phase the error on a subgrid,
    at its :data:`K_DENSE` largest extrema at the phase's start, and at its largest); the
    whole grid is checked at the end."""
    from scipy.optimize import minimize  # imported here: the CLI's parser stays light

    def late() -> bool:
        return deadline is not None and time.time() >= deadline

    def stop_at_deadline(intermediate_result: Any) -> None:
        if late():
            raise StopIteration

    lo, hi = problem.lower, problem.upper
    grid = problem.grid()
    box = max(float(np.max(hi - lo)), 1e-300)
    gradient = resolve_gradient(problem, gradient)
    cache = Cache(problem, grid, FD_STEP * box, gradient)
    bounds = list(zip(lo, hi, strict=True))
    x0 = np.clip(np.asarray(x0, dtype=np.float64), lo, hi)
    phases: list[dict[str, Any]] = []

    r0 = cache.values(x0).r
    w = 1.0 / max(float(np.sqrt(np.mean(r0**2))), 1e-12)

    def f(x: np.ndarray) -> float:
        r = cache.values(x).r
        return float(np.mean((w * r) ** 2))

    def fj(x: np.ndarray) -> np.ndarray:
        r = cache.values(x).r
        jr = cache.jac(x).r
        return 2.0 * w * w * (r @ jr) / r.size

    best: list[float] = []  # the best feasible objective after each iteration
    stalled = False

    def stop_when_stalled(intermediate_result: Any) -> None:
        nonlocal stalled
        stop_at_deadline(intermediate_result)
        xk = np.clip(intermediate_result.x, lo, hi)
        fk = float(intermediate_result.fun) if np.all(cache.cons(xk) >= -1e-6) else math.inf
        best.append(min(fk, best[-1] if best else math.inf))
        w = stall_iter or 0
        before = best[-1 - w] if w and len(best) > w else math.inf
        if math.isfinite(before) and best[-1] > (1.0 - STALL_DROP) * before:
            stalled = True
            raise StopIteration

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        res = minimize(
            f,
            x0,
            jac=fj,
            method="SLSQP",
            bounds=bounds,
            constraints=[{"type": "ineq", "fun": cache.cons, "jac": cache.cons_jac}],
            options={"maxiter": maxiter, "ftol": ftol},
            callback=stop_when_stalled,
        )
    x = np.clip(res.x, lo, hi)
    phases.append(_phase("least-squares", res))
    status, message, nit, success = int(res.status), str(res.message), int(res.nit), res.success
    stopped = TIME_LIMIT if int(res.status) == 99 and not stalled else ""
    if stalled:
        phases[-1]["stalled"] = True
        message = (
            f"{message} (least squares stalled: its best feasible objective fell by less than "
            f"{STALL_DROP:.0%} in {STALL_ITER} iterations)"
        )
    if (
        minimax
        and not stopped
        and not late()
        and problem.objective == "true"
        and isinstance(problem.target, FunctionTarget)
        and np.isfinite(problem.target.dense_in).all()
    ):
        cache.fix_dense(x)
        d0 = cache.values(x).dense
        t0 = max(float(np.max(np.abs(d0))), 1e-15)
        # z = ((x - xc) / step, t): the joints in units of MINIMAX_STEP of the box
        xc, step = x.copy(), MINIMAX_STEP * box
        z0 = np.concatenate([np.zeros_like(x), [1.0]])

        def mm_cons(z: np.ndarray) -> np.ndarray:
            # t >= |e| on the fixed set (two rows each) and at the largest |e| (one row)
            xx, t = xc + step * z[:-1], z[-1]
            d = cache.dense(xx) / t0
            return np.concatenate([t - d[:-1], t + d[:-1], [t - abs(d[-1])], cache.cons(xx)])

        def mm_jac(z: np.ndarray) -> np.ndarray:
            xx = xc + step * z[:-1]
            d = cache.dense(xx)
            jd = cache.jac(xx, dense=True).dense * (step / t0)
            one = np.ones((jd.shape[0] - 1, 1))
            jc = cache.cons_jac(xx) * step
            rows = [
                np.hstack([-jd[:-1], one]),
                np.hstack([jd[:-1], one]),
                np.r_[-np.sign(d[-1]) * jd[-1], 1.0][None, :],
                np.hstack([jc, np.zeros((jc.shape[0], 1))]),
            ]
            return np.vstack(rows)

        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            r2 = minimize(
                lambda z: float(z[-1]),
                z0,
                jac=lambda z: np.concatenate([np.zeros(z.size - 1), [1.0]]),
                method="SLSQP",
                bounds=[*zip((lo - xc) / step, (hi - xc) / step, strict=True), (0.0, 10.0)],
                constraints=[{"type": "ineq", "fun": mm_cons, "jac": mm_jac}],
                options={"maxiter": min(maxiter, polish_maxiter), "ftol": ftol},
                callback=stop_at_deadline if deadline is not None else None,
            )
        x2 = np.clip(xc + step * r2.x[:-1], lo, hi)
        phases.append(_phase("minimax", r2))
        f1, f2 = figures(problem, x), figures(problem, x2)
        phases[-1]["kept"] = bool(
            f2["one_branch"] and f2["max_error"] <= f1["max_error"] and feasible(problem, x2)
        )
        if phases[-1]["kept"]:
            x, status, message = x2, int(r2.status), str(r2.message)
            nit, success = nit + int(r2.nit), r2.success
            stopped = TIME_LIMIT if int(r2.status) == 99 else ""
    if stopped:
        message = f"{message} (stopped at the time limit)"
    fig = figures(problem, x)
    return StartResult(
        x0=x0,
        x=x,
        fun=float(res.fun),
        max_error=fig["max_error"],
        rms_error=fig["rms_error"],
        min_abs_det=fig["min_abs_det"],
        feasible=feasible(problem, x),
        optimizer_status=status,
        message=message,
        nit=nit,
        phases=phases,
        signs=problem.signs,
        success=bool(success),
        index=index,
        stopped=stopped,
    )


def resolve_gradient(problem: Problem, gradient: str) -> str:
    """ "exact" or "fd" for ``problem``: "auto" is "exact" where it is available; "exact"
    where it is not is an error saying why."""
    if gradient not in (*GRADIENTS, "auto"):
        raise ValueError(f"gradient must be 'auto', 'exact' or 'fd', got {gradient!r}")
    if gradient == "fd":
        return gradient
    why = available(problem)
    if why and gradient == "exact":
        raise ValueError(f"gradient='exact' is not available here: {why}")
    return "fd" if why else "exact"


def _phase(name: str, res: Any) -> dict[str, Any]:
    # scipy's words as scipy gave them (99 is scipy's code for a callback's stop)
    return {
        "phase": name,
        "status": int(res.status),
        "success": bool(res.success),
        "message": str(res.message),
        "nit": int(res.nit),
    }


def feasible(problem: Problem, x: np.ndarray, tol: float = 1e-6) -> bool:
    """Every constraint at every point of the dense grid (not only the critical ones
    SLSQP saw) and the box bounds hold at ``x``, to ``tol``."""
    res = problem.residuals(x)
    ok = all(bool(np.all(v >= -tol)) for v in (res.branch, res.extra, res.lengths, res.envelope))
    lo, hi = problem.lower, problem.upper
    return ok and bool(np.all(x >= lo - 1e-12) and np.all(x <= hi + 1e-12))
