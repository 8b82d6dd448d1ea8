"""Screening for starts: random candidates in the box (or from a sampler) whose true
linkage passes every grid angle on one branch, ranked by the RMS residual at the design
points; on the caller's thread or in chunks on an executor, with the same starts either
way."""

from __future__ import annotations

import time
from collections.abc import Callable
from concurrent.futures import Executor, Future, as_completed
from dataclasses import replace

import numpy as np

from .pool import SigintDeferred
from .problem import FunctionTarget, PathPoints, Problem

__all__ = ["SCREEN_CHUNK", "SCREEN_DENSE", "sample_starts", "screen_on"]

#: candidates screened between two calls of a screening progress callback
SCREEN_CHUNK = 50
#: the most dense-grid points screening looks at (a filter for starts, not a verification)
SCREEN_DENSE = 121


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
    lite, grid = _lite(problem)
    found: list[tuple[float, np.ndarray]] = []
    done = told = 0
    for _ in range(n_samples):
        if deadline is not None and time.time() >= deadline:
            break
        x = _draw(problem, rng, sampler)
        v = _rms(lite, grid, x)
        if v is not None:
            found.append((v, x))
        done += 1
        if progress is not None and done - told >= SCREEN_CHUNK:
            progress(done - told)
            told = done
    if progress is not None and done > told:
        progress(done - told)
    found.sort(key=lambda t: t[0])
    return found[:n_keep]


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


def _lite(problem: Problem) -> tuple[Problem, tuple]:
    """The problem screening solves (the true objective on a coarse grid, no envelope)
    and its grid."""
    lite = _coarse(replace(problem, objective="true", envelope=None))
    return lite, lite.grid()


def _draw(
    problem: Problem,
    rng: np.random.Generator,
    sampler: Callable[[np.random.Generator], np.ndarray] | None,
) -> np.ndarray:
    return sampler(rng) if sampler is not None else rng.uniform(problem.lower, problem.upper)


def _rms(lite: Problem, grid: tuple, x: np.ndarray) -> float | None:
    """The RMS residual of a candidate that passes the screen (one branch over the grid,
    the extra constraints not far off, the link lengths valid); None: rejected."""
    if not np.all(lite.lengths(x) >= 0):
        return None  # a link too short: rejected before its sweep (a fifth of the draws)
    r, _, br, extra, lc, _ = lite.residuals(x, grid)
    ok = np.all(br > -1.0) and np.all(extra > -1.0) and np.all(lc >= 0)
    return float(np.sqrt(np.mean(r**2))) if ok else None


def _screen_chunk(
    lite: Problem, grid: tuple, xs: list[np.ndarray], deadline: float | None
) -> tuple[list[float | None], int]:
    """RMS residual of each candidate that passes the screen (None: rejected, or not
    screened before ``deadline``), and how many were screened."""
    out: list[float | None] = []
    for x in xs:
        if deadline is not None and time.time() >= deadline:
            break
        out.append(_rms(lite, grid, x))
    n = len(out)
    return out + [None] * (len(xs) - n), n


def screen_on(
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
    """:func:`sample_starts` on ``ex``, with how many were screened: the candidates drawn
    here in order, screened in chunks by the workers (their futures added to ``track``),
    ranked by (RMS, order drawn): the same starts whatever the workers' number or the
    order they finish in."""
    lite, grid = _lite(problem)
    xs = [_draw(problem, rng, sampler) for _ in range(n_samples)]
    with SigintDeferred():
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
