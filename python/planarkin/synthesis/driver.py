"""The optimizer: a random search over the box for starts whose true linkage moves through
the whole range on one branch, then SLSQP from each start (least squares, then a minimax
polish on the dense grid), on any concurrent.futures.Executor. Gradients are forward
finite differences of the Rust sweeps, all residuals and constraints of one candidate
from one sweep per coordinate."""

from __future__ import annotations

import math
import os
import signal
import time
import warnings
from collections.abc import Callable, Sequence
from concurrent.futures import Executor, Future, ProcessPoolExecutor
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from .problem import Problem

#: forward-difference step on joint coordinates, relative to the box size
FD_STEP = 1e-7


@dataclass
class StartResult:
    """One SLSQP run: where it started and ended, scipy's status, and the true figures."""

    x0: np.ndarray
    x: np.ndarray
    fun: float
    max_error: float
    rms_error: float
    min_abs_det: float
    feasible: bool
    status: int
    message: str
    nit: int
    phases: list[dict[str, Any]] = field(default_factory=list)
    #: the branch combination of the closed form (relative to the drawn pose)
    signs: tuple[int, int, int] = (1, 1, 1)


class _Cache:
    """Residual vectors and their forward-difference Jacobians, one sweep per point."""

    def __init__(self, problem: Problem, grid: tuple, step: float) -> None:
        self.p = problem
        self.grid = grid
        self.step = step
        self._x: bytes | None = None
        self._v: tuple[np.ndarray, ...] = ()
        self._jx: bytes | None = None
        self._j: tuple[np.ndarray, ...] = ()

    def values(self, x: np.ndarray) -> tuple[np.ndarray, ...]:
        k = np.asarray(x, dtype=np.float64).tobytes()
        if k != self._x:
            self._v = self.p.residuals(np.asarray(x, dtype=np.float64), self.grid)
            self._x = k
        return self._v

    def jac(self, x: np.ndarray) -> tuple[np.ndarray, ...]:
        x = np.asarray(x, dtype=np.float64)
        k = x.tobytes()
        if k != self._jx:
            v0 = self.values(x)
            cols: list[list[np.ndarray]] = [[] for _ in v0]
            for j in range(x.size):
                xj = x.copy()
                xj[j] += self.step
                vj = self.p.residuals(xj, self.grid)
                for c, a, b in zip(cols, vj, v0, strict=True):
                    c.append((a - b) / self.step)
            self._j = tuple(np.stack(c, axis=1) for c in cols)
            self._jx = k
        return self._j


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
) -> StartResult:
    """SLSQP from ``x0``: least squares on the objective's residuals at the design points,
    then (``minimax``) the largest true residual on the dense grid, both under the branch,
    closed-form assemblability and link-length constraints and the box bounds."""
    from scipy.optimize import minimize  # imported here: the CLI's parser stays light

    sp = problem.space
    grid = problem.grid()
    box = max(float(np.max(sp.upper - sp.lower)), 1e-300)
    cache = _Cache(problem, grid, FD_STEP * box)
    bounds = list(zip(sp.lower, sp.upper, strict=True))
    x0 = np.clip(np.asarray(x0, dtype=np.float64), sp.lower, sp.upper)
    phases: list[dict[str, Any]] = []

    def cons_fun(x: np.ndarray) -> np.ndarray:
        _, _, br, lc = cache.values(x)
        return np.concatenate([br, lc])

    def cons_jac(x: np.ndarray) -> np.ndarray:
        _, _, br, lc = cache.jac(x)
        return np.vstack([br, lc])

    r0 = cache.values(x0)[0]
    w = 1.0 / max(float(np.sqrt(np.mean(r0**2))), 1e-12)

    def f(x: np.ndarray) -> float:
        r = cache.values(x)[0]
        return float(np.mean((w * r) ** 2))

    def fj(x: np.ndarray) -> np.ndarray:
        r = cache.values(x)[0]
        jr = cache.jac(x)[0]
        return 2.0 * w * w * (r @ jr) / r.size

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        res = minimize(
            f,
            x0,
            jac=fj,
            method="SLSQP",
            bounds=bounds,
            constraints=[{"type": "ineq", "fun": cons_fun, "jac": cons_jac}],
            options={"maxiter": maxiter, "ftol": ftol},
        )
    x = np.clip(res.x, sp.lower, sp.upper)
    phases.append(
        {
            "phase": "least-squares",
            "status": int(res.status),
            "message": str(res.message),
            "nit": int(res.nit),
        }
    )
    status, message, nit = int(res.status), str(res.message), int(res.nit)
    if minimax and problem.objective == "true" and np.isfinite(problem.target.dense_in).all():
        d0 = cache.values(x)[1]
        t0 = max(float(np.max(np.abs(d0))), 1e-15)
        z0 = np.concatenate([x, [1.0]])

        def mm_cons(z: np.ndarray) -> np.ndarray:
            xx, t = z[:-1], z[-1]
            _, d, br, lc = cache.values(xx)
            return np.concatenate([t - d / t0, t + d / t0, br, lc])

        def mm_jac(z: np.ndarray) -> np.ndarray:
            xx = z[:-1]
            _, jd, jb, jl = cache.jac(xx)
            one = np.ones((jd.shape[0], 1))
            rows = [
                np.hstack([-jd / t0, one]),
                np.hstack([jd / t0, one]),
                np.hstack([jb, np.zeros((jb.shape[0], 1))]),
                np.hstack([jl, np.zeros((jl.shape[0], 1))]),
            ]
            return np.vstack(rows)

        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            r2 = minimize(
                lambda z: float(z[-1]),
                z0,
                jac=lambda z: np.concatenate([np.zeros(z.size - 1), [1.0]]),
                method="SLSQP",
                bounds=[*bounds, (0.0, 10.0)],
                constraints=[{"type": "ineq", "fun": mm_cons, "jac": mm_jac}],
                options={"maxiter": maxiter, "ftol": ftol},
            )
        x2 = np.clip(r2.x[:-1], sp.lower, sp.upper)
        phases.append(
            {
                "phase": "minimax",
                "status": int(r2.status),
                "message": str(r2.message),
                "nit": int(r2.nit),
            }
        )
        f1, f2 = figures(problem, x), figures(problem, x2)
        if f2["one_branch"] and f2["max_error"] <= f1["max_error"] and _feasible(problem, x2):
            x, status, message, nit = x2, int(r2.status), str(r2.message), nit + int(r2.nit)
    fig = figures(problem, x)
    return StartResult(
        x0=x0,
        x=x,
        fun=float(res.fun),
        max_error=fig["max_error"],
        rms_error=fig["rms_error"],
        min_abs_det=fig["min_abs_det"],
        feasible=_feasible(problem, x),
        status=status,
        message=message,
        nit=nit,
        phases=phases,
        signs=problem.signs,
    )


def _feasible(problem: Problem, x: np.ndarray, tol: float = 1e-6) -> bool:
    _, _, br, lc = problem.residuals(x)
    ok = bool(np.all(br >= -tol) and np.all(lc >= -tol))
    sp = problem.space
    return ok and bool(np.all(x >= sp.lower - 1e-12) and np.all(x <= sp.upper + 1e-12))


def sample_starts(
    problem: Problem,
    n_samples: int,
    n_keep: int,
    rng: np.random.Generator,
    sampler: Callable[[np.random.Generator], np.ndarray] | None = None,
) -> list[tuple[float, np.ndarray]]:
    """Random candidates in the box (or from ``sampler``) whose true linkage passes every
    grid angle on one branch, ranked by the RMS residual at the design points."""
    sp = problem.space
    grid = problem.grid()
    lite = replace(problem, objective="true")
    found: list[tuple[float, np.ndarray]] = []
    for _ in range(n_samples):
        x = sampler(rng) if sampler is not None else rng.uniform(sp.lower, sp.upper)
        r, _, br, lc = lite.residuals(x, grid)
        if np.all(br > -1.0) and np.all(lc >= 0):
            found.append((float(np.sqrt(np.mean(r**2))), x))
    found.sort(key=lambda t: t[0])
    return found[:n_keep]


@dataclass
class SynthesisResult:
    """The best run, every run, and how the search went."""

    best: StartResult
    runs: list[StartResult]
    starts: int
    sampled: int
    wall_s: float
    objective: str


def _signs(s: Sequence[int]) -> tuple[int, int, int]:
    if len(s) != 3 or any(v not in (1, -1) for v in s):
        raise ValueError(f"sign_combinations must hold three of +1 / -1 each, got {s!r}")
    return (int(s[0]), int(s[1]), int(s[2]))


def _ignore_sigint() -> None:
    # in the workers: Ctrl-C goes to the whole process group, and only the parent should
    # act on it (it stops the workers); a worker would print a traceback and go on
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def process_pool(workers: int | None = None) -> ProcessPoolExecutor:
    """A process pool for :func:`synthesize`: ``workers`` processes (default up to 2)
    that ignore Ctrl-C, so that it reaches only the parent, which stops them
    (:func:`stop_pool`)."""
    return ProcessPoolExecutor(
        max_workers=workers or min(2, os.cpu_count() or 1), initializer=_ignore_sigint
    )


def stop_pool(ex: Executor) -> None:
    """Stops a pool at once: queued starts are cancelled and, for a process pool, the
    worker processes terminated (``shutdown(cancel_futures=True)`` alone waits for the
    running starts, minutes of SLSQP)."""
    terminate = getattr(ex, "terminate_workers", None)  # Python >= 3.14
    if terminate is not None:
        terminate()
        return
    # before 3.14 a process pool's workers have no public handle
    processes = list((getattr(ex, "_processes", None) or {}).values())
    ex.shutdown(wait=False, cancel_futures=True)
    for p in processes:
        if p.is_alive():
            p.terminate()
    for p in processes:
        p.join(timeout=5)


def _cancel(futures: Sequence[Future]) -> None:
    for f in futures:
        f.cancel()


def synthesize(
    problem: Problem,
    *,
    starts: int = 8,
    samples: int = 2000,
    seed: int = 0,
    x0: Sequence[np.ndarray] = (),
    executor: Executor | None = None,
    sampler: Callable[[np.random.Generator], np.ndarray] | None = None,
    maxiter: int = 200,
    minimax: bool = True,
    sign_combinations: Sequence[tuple[int, int, int]] = (),
    progress: Callable[[], object] | None = None,
) -> SynthesisResult:
    """Multistart SLSQP. ``starts`` runs: the given ``x0`` first, then the best of
    ``samples`` random candidates (``seed``); on ``executor`` (default
    :func:`process_pool`: up to 2 workers; a dask.distributed Client's ``get_executor()``
    works the same). On Ctrl-C the starts not yet run are cancelled and the default pool
    is stopped at once (a caller's executor is the caller's to stop: :func:`stop_pool`).
    ``sign_combinations`` (objectives on the seed's closed form): start i uses combination
    i modulo their number, so the starts cover the branch combinations. ``progress()`` is
    called once per start finished (a progress bar's update)."""
    if starts < 1:
        raise ValueError(f"starts must be >= 1, got {starts}")
    if samples < 0:
        raise ValueError(f"samples must be >= 0, got {samples}")
    t0 = time.perf_counter()
    rng = np.random.default_rng(seed)
    xs = [np.asarray(x, dtype=np.float64) for x in x0][:starts]
    need = starts - len(xs)
    if need > 0:
        found = sample_starts(problem, samples, need, rng, sampler)
        xs += [x for _, x in found]
    if not xs:
        raise ValueError(
            "no start: none of the random samples moves through the range on one branch "
            "(raise samples or give x0)"
        )
    own = executor is None
    ex: Executor = process_pool() if executor is None else executor
    futs: list[Future] = []
    try:
        probs = [
            replace(problem, signs=_signs(sign_combinations[i % len(sign_combinations)]))
            if sign_combinations
            else problem
            for i in range(len(xs))
        ]
        for p, x in zip(probs, xs, strict=True):
            futs.append(ex.submit(run_start, p, x, maxiter=maxiter, minimax=minimax))
        runs = []
        for f in futs:
            runs.append(f.result())
            if progress is not None:
                progress()
    except BaseException:
        # Ctrl-C or a failed start: what has not run is not run; an own pool is stopped at
        # once, a caller's executor is left to the caller
        _cancel(futs)
        if own:
            stop_pool(ex)
        raise
    if own:
        ex.shutdown()
    ranked = sorted(runs, key=lambda r: (not r.feasible, r.max_error))
    return SynthesisResult(
        best=ranked[0],
        runs=runs,
        starts=len(xs),
        sampled=samples,
        wall_s=time.perf_counter() - t0,
        objective=problem.objective,
    )
