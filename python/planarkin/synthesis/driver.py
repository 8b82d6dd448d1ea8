"""The optimizer: a random search over the box for starts whose true linkage moves through
the whole range on one branch, then SLSQP from each start (least squares, then a minimax
polish on the dense grid), on any concurrent.futures.Executor. Gradients are forward
finite differences of the Rust sweeps, all residuals and constraints of one candidate
from one sweep per coordinate. Runs are collected by start index (never by the order in
which workers finish); a time limit or Ctrl-C stops the search and keeps what finished."""

from __future__ import annotations

import math
import os
import signal
import threading
import time
import warnings
from collections.abc import Callable, Sequence
from concurrent.futures import (
    FIRST_COMPLETED,
    Executor,
    Future,
    ProcessPoolExecutor,
    as_completed,
    wait,
)
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from .exact import Picks, Rows, available, exact_rows, extrema, fd_rows, picks, subgrid
from .problem import Evaluation, FunctionTarget, PathPoints, Problem, Residuals

#: forward-difference step on joint coordinates, relative to the box size
FD_STEP = 1e-7
#: the subgrid of the dense grid SLSQP sees the branch constraint on (with its smallest
#: value on the whole grid), and the dense error's largest local extrema added to it for
#: the minimax phase (with its largest value on the whole grid)
SUBGRID, K_DENSE = 41, 64
#: how the optimizer differentiates: the solver's exact derivatives, or forward
#: differences of whole sweeps (the check)
GRADIENTS = ("exact", "fd")
#: seconds the running starts get, after the time limit, to hand back their iterate (they
#: stop at their next SLSQP iteration) before an own process pool is terminated
GRACE_S = 30.0
#: what :attr:`StartResult.stopped` and :attr:`SynthesisResult.stopped` say
TIME_LIMIT, INTERRUPTED = "time limit", "interrupted"


@dataclass
class StartResult:
    """One SLSQP run: where it started and ended, scipy's status, and the true figures.
    ``optimizer_status``, ``message`` and ``success`` are scipy's, of the phase whose ``x``
    this is (scipy's integer exit code; 99: stopped at the time limit, as scipy reports a
    callback's stop; -1: the start raised); ``fun`` is the least-squares phase's final
    objective; ``feasible``: every constraint and bound holds at ``x``, checked again here
    (not taken from scipy). ``status`` is ``optimizer_status`` under its former name (as
    scipy's ``OptimizeResult.status``): an integer code of scipy's, not a
    :class:`planarkin.Status`."""

    x0: np.ndarray
    x: np.ndarray
    fun: float
    max_error: float
    rms_error: float
    min_abs_det: float
    feasible: bool
    optimizer_status: int
    message: str
    nit: int
    phases: list[dict[str, Any]] = field(default_factory=list)
    #: the branch combination of the closed form (relative to the drawn pose)
    signs: tuple[int, int, int] = (1, 1, 1)
    #: scipy's ``success`` for the phase whose ``x`` this is
    success: bool = False
    #: the start's index in the multistart (its results are collected by it)
    index: int = 0
    #: why the run stopped early ("" ran to scipy's own end; TIME_LIMIT)
    stopped: str = ""

    @property
    def status(self) -> int:
        """scipy's integer exit code: :attr:`optimizer_status` (its former name, kept)."""
        return self.optimizer_status

    @property
    def converged(self) -> bool:
        """scipy reported success AND the constraints were verified to hold at ``x``."""
        return self.success and self.feasible


class _Cache:
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
) -> StartResult:
    """SLSQP from ``x0``: least squares on the objective's residuals at the design points,
    then (``minimax``) the largest true residual on the dense grid, both under the branch,
    closed-form assemblability and link-length constraints and the box bounds. At
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
    cache = _Cache(problem, grid, FD_STEP * box, gradient)
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
            callback=stop_at_deadline if deadline is not None else None,
        )
    x = np.clip(res.x, lo, hi)
    phases.append(_phase("least-squares", res))
    status, message, nit, success = int(res.status), str(res.message), int(res.nit), res.success
    stopped = TIME_LIMIT if int(res.status) == 99 else ""
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
        z0 = np.concatenate([x, [1.0]])

        def mm_cons(z: np.ndarray) -> np.ndarray:
            # t >= |e| on the fixed set (two rows each) and at the largest |e| (one row)
            xx, t = z[:-1], z[-1]
            d = cache.dense(xx) / t0
            return np.concatenate([t - d[:-1], t + d[:-1], [t - abs(d[-1])], cache.cons(xx)])

        def mm_jac(z: np.ndarray) -> np.ndarray:
            xx = z[:-1]
            d = cache.dense(xx)
            jd = cache.jac(xx, dense=True).dense / t0
            one = np.ones((jd.shape[0] - 1, 1))
            jc = cache.cons_jac(xx)
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
                bounds=[*bounds, (0.0, 10.0)],
                constraints=[{"type": "ineq", "fun": mm_cons, "jac": mm_jac}],
                options={"maxiter": maxiter, "ftol": ftol},
                callback=stop_at_deadline if deadline is not None else None,
            )
        x2 = np.clip(r2.x[:-1], lo, hi)
        phases.append(_phase("minimax", r2))
        f1, f2 = figures(problem, x), figures(problem, x2)
        phases[-1]["kept"] = bool(
            f2["one_branch"] and f2["max_error"] <= f1["max_error"] and _feasible(problem, x2)
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
        feasible=_feasible(problem, x),
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


def _feasible(problem: Problem, x: np.ndarray, tol: float = 1e-6) -> bool:
    # every constraint at every point of the dense grid (not only the critical ones)
    res = problem.residuals(x)
    ok = all(bool(np.all(v >= -tol)) for v in (res.branch, res.extra, res.lengths, res.envelope))
    lo, hi = problem.lower, problem.upper
    return ok and bool(np.all(x >= lo - 1e-12) and np.all(x <= hi + 1e-12))


def sample_starts(
    problem: Problem,
    n_samples: int,
    n_keep: int,
    rng: np.random.Generator,
    sampler: Callable[[np.random.Generator], np.ndarray] | None = None,
    *,
    deadline: float | None = None,
    progress: Callable[[int], object] | None = None,
) -> list[tuple[float, np.ndarray]]:
    """Random candidates in the box (or from ``sampler``) whose true linkage passes every
    grid angle on one branch, ranked by the RMS residual at the design points (ties in
    the order drawn). Screening ends early at ``deadline`` (``time.time()`` seconds);
    ``progress(n)`` is told every :data:`SCREEN_CHUNK` candidates screened."""
    return _screen(problem, n_samples, n_keep, rng, sampler, deadline, progress)[0]


#: candidates screened between two calls of a screening progress callback
SCREEN_CHUNK = 50


#: the most dense-grid points screening looks at (a filter for starts, not a verification)
SCREEN_DENSE = 121


def _coarse(problem: Problem) -> Problem:
    # every k-th point of the dense grid and its last one
    t = problem.target
    if isinstance(t, PathPoints) or t.dense_in.size <= SCREEN_DENSE:
        return problem
    k = -(-(t.dense_in.size - 1) // (SCREEN_DENSE - 1))
    keep = np.unique(np.r_[np.arange(0, t.dense_in.size, k), t.dense_in.size - 1])
    if isinstance(t, FunctionTarget):
        return replace(
            problem, target=replace(t, dense_in=t.dense_in[keep], dense_out=t.dense_out[keep])
        )
    return replace(problem, target=replace(t, dense_in=t.dense_in[keep]))


def _screen_chunk(
    lite: Problem, grid: tuple, xs: list[np.ndarray], deadline: float | None
) -> tuple[list[float | None], int]:
    """RMS residual of each candidate that passes the screen (None: rejected, or not
    screened before ``deadline``), and how many were screened."""
    out: list[float | None] = []
    for x in xs:
        if deadline is not None and time.time() >= deadline:
            break
        r, _, br, extra, lc, _ = lite.residuals(x, grid)
        ok = np.all(br > -1.0) and np.all(extra > -1.0) and np.all(lc >= 0)
        out.append(float(np.sqrt(np.mean(r**2))) if ok else None)
    n = len(out)
    return out + [None] * (len(xs) - n), n


def _screen_on(
    ex: Executor,
    problem: Problem,
    n_samples: int,
    n_keep: int,
    rng: np.random.Generator,
    sampler: Callable[[np.random.Generator], np.ndarray] | None,
    deadline: float | None,
    progress: Callable[[int], object] | None,
    track: set[Future],
) -> tuple[list[tuple[float, np.ndarray]], int]:
    # _screen on the executor: the candidates drawn here in order, screened in chunks by
    # the workers, ranked by (RMS, order drawn): the same starts as _screen, whatever the
    # workers' number or the order they finish in
    lite = _coarse(replace(problem, objective="true", envelope=None))
    grid = lite.grid()
    xs = [
        sampler(rng) if sampler is not None else rng.uniform(problem.lower, problem.upper)
        for _ in range(n_samples)
    ]
    with _SigintDeferred():
        subs = {
            ex.submit(_screen_chunk, lite, grid, xs[k : k + SCREEN_CHUNK], deadline): k
            for k in range(0, len(xs), SCREEN_CHUNK)
        }
        track.update(subs)
    rms: list[float | None] = [None] * len(xs)
    done = 0
    for f in as_completed(subs):
        k = subs[f]
        got, n = f.result()
        rms[k : k + len(got)] = got
        done += n
        if progress is not None and n:
            progress(n)
    found = sorted((v, i) for i, v in enumerate(rms) if v is not None)
    return [(v, xs[i]) for v, i in found[:n_keep]], done


def _screen(
    problem: Problem,
    n_samples: int,
    n_keep: int,
    rng: np.random.Generator,
    sampler: Callable[[np.random.Generator], np.ndarray] | None,
    deadline: float | None,
    progress: Callable[[int], object] | None,
) -> tuple[list[tuple[float, np.ndarray]], int]:
    lite = _coarse(replace(problem, objective="true", envelope=None))
    grid = lite.grid()
    found: list[tuple[float, np.ndarray]] = []
    done = told = 0
    for _ in range(n_samples):
        if deadline is not None and time.time() >= deadline:
            break
        x = sampler(rng) if sampler is not None else rng.uniform(problem.lower, problem.upper)
        r, _, br, extra, lc, _ = lite.residuals(x, grid)
        if np.all(br > -1.0) and np.all(extra > -1.0) and np.all(lc >= 0):
            found.append((float(np.sqrt(np.mean(r**2))), x))
        done += 1
        if progress is not None and done - told >= SCREEN_CHUNK:
            progress(done - told)
            told = done
    if progress is not None and done > told:
        progress(done - told)
    found.sort(key=lambda t: t[0])
    return found[:n_keep], done


@dataclass
class SynthesisResult:
    """The best run, every run that finished (by start index), and how the search went."""

    #: feasible before infeasible, then the smallest max_error, then the lowest index
    #: (None: no start finished)
    best: StartResult | None
    runs: list[StartResult]
    #: starts planned (the given x0 and the candidates kept from screening)
    starts: int
    #: candidates asked for (``samples``) and screened (fewer when stopped)
    sampled: int
    wall_s: float
    objective: str
    screened: int = 0
    #: "" (every start ran to its end), TIME_LIMIT or INTERRUPTED
    stopped: str = ""
    seed: int = 0
    #: how the derivatives were taken: "exact" or "fd"
    gradient: str = "exact"

    @property
    def feasible(self) -> list[StartResult]:
        """The runs whose constraints hold at their end, by start index."""
        return [r for r in self.runs if r.feasible]


class SynthesisInterrupted(KeyboardInterrupt):
    """Ctrl-C during :func:`synthesize`: the workers are stopped, and ``result`` holds the
    runs that had finished (``stopped`` is INTERRUPTED). A KeyboardInterrupt: code that
    does not look for it stops as on any Ctrl-C."""

    def __init__(self, result: SynthesisResult) -> None:
        super().__init__("interrupted")
        self.result = result


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


class _SigintDeferred:
    """Ctrl-C held back (raised on exit) while starts are submitted: worker processes are
    forked then, and one forked before its initializer ignores Ctrl-C would print a
    traceback; the pool's own bookkeeping is never cut half way. Only in the main thread
    (the only one Python delivers signals to)."""

    def __enter__(self) -> None:
        self.hits: list[int] = []
        self.old: Any = None
        self.own = threading.current_thread() is threading.main_thread()
        if self.own:
            self.old = signal.signal(signal.SIGINT, lambda sig, frame: self.hits.append(sig))

    def __exit__(self, kind: object, *exc: object) -> None:
        if self.own:
            signal.signal(signal.SIGINT, self.old if self.old is not None else signal.SIG_DFL)
            if self.hits and kind is None:
                raise KeyboardInterrupt


def _collect(f: Future, x0: np.ndarray, index: int, signs: tuple[int, int, int]) -> StartResult:
    # a start that raised gets its status (-1) and message; the others go on
    try:
        r: StartResult = f.result()
        return r
    except Exception as e:  # noqa: BLE001 - any failure of one start is that start's status
        what = " ".join(f"{type(e).__name__}: {e}".split())
        return StartResult(
            x0=x0,
            x=x0,
            fun=math.nan,
            max_error=math.inf,
            rms_error=math.inf,
            min_abs_det=0.0,
            feasible=False,
            optimizer_status=-1,
            message=f"start failed: {what}",
            nit=0,
            signs=signs,
            index=index,
        )


def synthesize(
    problem: Problem,
    *,
    starts: int = 8,
    samples: int = 2000,
    seed: int = 0,
    x0: Sequence[np.ndarray] = (),
    executor: Executor | None = None,
    workers: int | None = None,
    sampler: Callable[[np.random.Generator], np.ndarray] | None = None,
    maxiter: int = 200,
    minimax: bool = True,
    sign_combinations: Sequence[tuple[int, int, int]] = (),
    progress: Callable[[StartResult], object] | None = None,
    screening: Callable[[int], object] | None = None,
    time_limit: float | None = None,
    gradient: str = "auto",
) -> SynthesisResult:
    """Multistart SLSQP. ``starts`` runs: the given ``x0`` first, then the best of
    ``samples`` random candidates (``seed``); on ``executor`` (default
    :func:`process_pool` of ``workers`` processes, up to 2 by default; a
    dask.distributed Client's ``get_executor()`` works the same). Runs are collected by
    start index and ranked with ties broken by it, so the result does not depend on
    which worker finishes first.
    ``sign_combinations`` (objectives on the seed's closed form): start i uses combination
    i modulo their number, so the starts cover the branch combinations.
    ``progress(run)`` is called as each start finishes (in the order they finish: a
    progress bar's update); ``screening(n)`` as candidates are screened.
    ``time_limit`` (seconds from the call): screening ends, queued starts are cancelled,
    running ones stop at their next iteration and hand back their iterate (an own pool is
    terminated if they have not within :data:`GRACE_S`); the result says ``stopped``.
    Ctrl-C cancels what has not run and stops the default pool at once (a caller's
    executor is the caller's to stop: :func:`stop_pool`), then raises
    :class:`SynthesisInterrupted` holding the runs that had finished.
    ``gradient``: how SLSQP's derivatives are taken (:func:`run_start`)."""
    if starts < 1:
        raise ValueError(f"starts must be >= 1, got {starts}")
    if samples < 0:
        raise ValueError(f"samples must be >= 0, got {samples}")
    if workers is not None and workers < 1:
        raise ValueError(f"workers must be >= 1, got {workers}")
    if time_limit is not None and not (math.isfinite(time_limit) and time_limit > 0):
        raise ValueError(f"time_limit must be finite and > 0 seconds, got {time_limit}")
    gradient = resolve_gradient(problem, gradient)
    t0 = time.perf_counter()
    deadline = None if time_limit is None else time.time() + time_limit
    xs = [np.asarray(x, dtype=np.float64) for x in x0][:starts]
    screened = 0
    runs: dict[int, StartResult] = {}

    def result(stopped: str) -> SynthesisResult:
        done = [runs[i] for i in sorted(runs)]
        if not stopped and any(r.stopped for r in done):
            stopped = TIME_LIMIT
        ranked = sorted(done, key=lambda r: (not r.feasible, r.max_error, r.index))
        return SynthesisResult(
            best=ranked[0] if ranked else None,
            runs=done,
            starts=len(xs),
            sampled=samples,
            wall_s=time.perf_counter() - t0,
            objective=problem.objective,
            screened=screened,
            stopped=stopped,
            seed=seed,
            gradient=gradient,
        )

    def counted(n: int) -> None:
        nonlocal screened
        screened += n
        if screening is not None:
            screening(n)

    need = starts - len(xs)
    own = executor is None
    ex: Executor | None = executor
    futs: dict[Future, int] = {}
    screens: set[Future] = set()
    pending: set[Future] = set()
    stopped = ""
    try:
        if need > 0:
            rng = np.random.default_rng(seed)
            if ex is None:
                with _SigintDeferred():
                    ex = process_pool(workers)
            found, _ = _screen_on(
                ex, problem, samples, need, rng, sampler, deadline, counted, screens
            )
            xs += [x for _, x in found]
        if not xs:
            if deadline is not None and time.time() >= deadline:
                if own and ex is not None:
                    ex.shutdown()
                return result(TIME_LIMIT)
            raise ValueError(
                "no start: none of the random samples moves through the range on one branch "
                "(raise samples or give x0)"
            )
        probs = [
            replace(problem, signs=_signs(sign_combinations[i % len(sign_combinations)]))
            if sign_combinations
            else problem
            for i in range(len(xs))
        ]
        with _SigintDeferred():
            if ex is None:
                ex = process_pool(workers)
            for i, (p, x) in enumerate(zip(probs, xs, strict=True)):
                f = ex.submit(
                    run_start,
                    p,
                    x,
                    maxiter=maxiter,
                    minimax=minimax,
                    deadline=deadline,
                    index=i,
                    gradient=gradient,
                )
                futs[f] = i
        pending = set(futs)
        give_up = math.inf
        while pending:
            timeout = None
            if deadline is not None:
                now = time.time()
                if not stopped and now >= deadline:
                    stopped = TIME_LIMIT
                    for f in pending:
                        f.cancel()  # the queued ones; running ones stop by themselves
                    give_up = now + GRACE_S
                if stopped and now >= give_up:
                    break
                timeout = (give_up if stopped else deadline) - now
            done, pending = wait(pending, timeout=timeout, return_when=FIRST_COMPLETED)
            for f in sorted(done, key=futs.__getitem__):
                if f.cancelled():
                    continue
                i = futs[f]
                runs[i] = _collect(f, xs[i], i, probs[i].signs)
                if progress is not None:
                    progress(runs[i])
    except KeyboardInterrupt:
        _abandon([*futs, *screens], ex if own else None)
        raise SynthesisInterrupted(result(INTERRUPTED)) from None
    except BaseException:
        # what has not run is not run; an own pool is stopped at once, a caller's
        # executor is left to the caller
        _abandon([*futs, *screens], ex if own else None)
        raise
    if own and ex is not None:
        if pending:
            stop_pool(ex)  # starts that did not stop within the grace period
        else:
            ex.shutdown()
    return result(stopped)


def _abandon(futs: Sequence[Future] | dict[Future, int], own: Executor | None) -> None:
    for f in futs:
        f.cancel()
    if own is not None:
        stop_pool(own)
