"""The multistart's orchestrator (:func:`synthesize`): starts screened from random
candidates (:mod:`.screening`), then one SLSQP run each (:mod:`.start`) on any
concurrent.futures.Executor (:mod:`.pool`). Runs are collected by start index (never by
the order in which workers finish); a time limit or Ctrl-C stops the search and keeps what
finished (:mod:`.results`). The names of those modules that callers used from here are
imported here too."""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from concurrent.futures import FIRST_COMPLETED, Executor, Future, wait
from dataclasses import replace

import numpy as np

from .pool import SigintDeferred, abandon, process_pool, stop_pool
from .problem import Problem
from .results import INTERRUPTED, TIME_LIMIT, StartResult, SynthesisInterrupted, SynthesisResult
from .screening import SCREEN_CHUNK, sample_starts, screen_on
from .start import FD_STEP, GRADIENTS, feasible, figures, resolve_gradient, run_start

__all__ = [
    "FD_STEP",
    "GRACE_S",
    "GRADIENTS",
    "INTERRUPTED",
    "SCREEN_CHUNK",
    "TIME_LIMIT",
    "StartResult",
    "SynthesisInterrupted",
    "SynthesisResult",
    "feasible",
    "figures",
    "process_pool",
    "resolve_gradient",
    "run_start",
    "sample_starts",
    "stop_pool",
    "synthesize",
]

#: seconds the running starts get, after the time limit, to hand back their iterate (they
#: stop at their next SLSQP iteration) before an own process pool is terminated
GRACE_S = 30.0


def _signs(s: Sequence[int]) -> tuple[int, int, int]:
    if len(s) != 3 or any(v not in (1, -1) for v in s):
        raise ValueError(f"sign_combinations must hold three of +1 / -1 each, got {s!r}")
    return (int(s[0]), int(s[1]), int(s[2]))


def _collect(f: Future, x0: np.ndarray, index: int, signs: tuple[int, int, int]) -> StartResult:
    # a start that raised gets its status (-1) and message; the others go on
    try:
        r: StartResult = f.result()
        return r
    except Exception as e:  # noqa: BLE001 - any failure of one start is that start's status
        what = " ".join(f"{type(e).__name__}: {e}".split())
        return StartResult.failed(x0, f"start failed: {what}", index=index, signs=signs)


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
                with SigintDeferred():
                    ex = process_pool(workers)
            found, _ = screen_on(
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
        with SigintDeferred():
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
        abandon([*futs, *screens], ex if own else None)
        raise SynthesisInterrupted(result(INTERRUPTED)) from None
    except BaseException:
        # what has not run is not run; an own pool is stopped at once, a caller's
        # executor is left to the caller
        abandon([*futs, *screens], ex if own else None)
        raise
    if own and ex is not None:
        if pending:
            stop_pool(ex)  # starts that did not stop within the grace period
        else:
            ex.shutdown()
    return result(stopped)
