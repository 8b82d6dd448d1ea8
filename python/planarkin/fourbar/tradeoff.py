"""Speed/accuracy trade-off of the four-bar solvers (``planarkin tradeoff``): for each
tolerance and method, mean Newton iterations per point, time per point and the largest
angle error against an independent truth solved in mpmath at 40 significant digits.

>>> from planarkin.fourbar.tradeoff import tradeoff
>>> result = tradeoff(tols=(1e-6, 1e-12), n_random=3, truth_links=2, repeat=1)
>>> print(result.table())  # doctest: +SKIP

The truth: at each crank angle B is the intersection of two circles (radius r3 about the
crank pin A, r4 about O4) on the side the mode asks for. It is computed in mpmath at 40
digits from the exact binary values of the lengths and the crank angle, a different
formulation from the kernel's closed form, and checked: its loop residual is below
1e-30 and sin(theta4 - theta3) has the mode's sign, so it is the unique solution of the
mode, good to far below 1e-16 rad. Errors are measured against it as double-double
numbers, so an error of one ulp is still resolved. mpmath is slow (~0.1 ms a point), so
the truth covers a subset: every angle of the seed linkage and of the first few random
ones; times cover all of the linkages.
"""

from __future__ import annotations

import functools
import math
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from .._angles import DEFAULT_THETA2, TAU
from .._status import Status
from ._batch import closed_form_batch, sweep_batch
from ._results import BatchSweep

#: Tolerances swept by default: 1e-3 down to 1e-15.
DEFAULT_TOLS = tuple(10.0**-k for k in range(3, 16))

#: Method name -> (label, predictor); closed form has no predictor and no tolerance.
METHODS = {
    "previous": ("Newton (previous point)", "previous"),
    "tangent": ("Newton + tangent", "tangent"),
    "quadratic": ("Newton + quadratic", "quadratic"),
    "closed-form": ("closed form", None),
}

SEED_LINKAGE = (6.0, 2.0, 5.0, 5.0)
TRUTH_DPS = 40


def random_crank_rockers(m: int, seed: int = 1) -> np.ndarray:
    """M random Grashof crank-rockers as an (M, 4) array of (r1, r2, r3, r4): the crank r2
    in [0.5, 1.5] is the shortest link, r1, r3, r4 in [2, 6], and S + L <= P + Q - 0.25,
    so every crank angle assembles and no toggle is met (a fair field for solvers without
    status logic)."""
    rng = np.random.default_rng(seed)
    out = np.empty((0, 4))
    while len(out) < m:
        r = rng.uniform((2.0, 0.5, 2.0, 2.0), (6.0, 1.5, 6.0, 6.0), size=(2 * m + 8, 4))
        s = r.min(axis=1)
        big = r.max(axis=1)
        ok = s + big <= r.sum(axis=1) - s - big - 0.25
        out = np.concatenate([out, r[ok]])
    return np.ascontiguousarray(out[:m])


# --- independent truth ------------------------------------------------------------------


def _mp_truth(r, theta2: float, sign: int, mp):
    """(theta3, theta4) of the mode at 40 digits, wrapped to (-pi, pi], or None."""
    r1, r2, r3, r4 = (mp.mpf(x) for x in r)
    t2 = mp.mpf(theta2)
    ax, ay = r2 * mp.cos(t2), r2 * mp.sin(t2)
    ux, uy = r1 - ax, -ay  # A -> O4
    dd = ux * ux + uy * uy
    if dd == 0:
        return None
    d = mp.sqrt(dd)
    a = (r3 * r3 - r4 * r4 + dd) / (2 * d)  # A to the foot of B on the line A-O4
    hh = r3 * r3 - a * a
    if hh < 0:
        return None
    h = mp.sqrt(hh)
    # open: B left of the line from A to O4, i.e. sin(theta4 - theta3) > 0
    bx = ax + (a * ux - sign * h * uy) / d
    by = ay + (a * uy + sign * h * ux) / d
    t3 = mp.atan2(by - ay, bx - ax)
    t4 = mp.atan2(by, bx - r1)
    f1 = r2 * mp.cos(t2) + r3 * mp.cos(t3) - r4 * mp.cos(t4) - r1
    f2 = r2 * mp.sin(t2) + r3 * mp.sin(t3) - r4 * mp.sin(t4)
    s34 = mp.sin(t4 - t3)
    if max(abs(f1), abs(f2)) > mp.mpf(10) ** -30 * max(r1, r2, r3, r4) or s34 * sign <= 0:
        raise AssertionError(f"mpmath truth failed its own check at r={r}, theta2={theta2}")
    return t3, t4


def truth(links: np.ndarray, theta2: np.ndarray, mode: str = "open") -> np.ndarray:
    """The exact angles as double-double numbers: an (M, N, 2, 2) array indexed
    [link, angle, theta3/theta4, hi/lo]; NaN where the linkage cannot assemble."""
    try:
        import mpmath
    except ImportError:  # pragma: no cover - mpmath is in the test extra
        raise ImportError("planarkin tradeoff needs mpmath: pip install mpmath") from None
    sign = 1 if mode == "open" else -1
    links = np.asarray(links, dtype=np.float64)
    out = np.full((len(links), len(theta2), 2, 2), np.nan)
    with mpmath.workdps(TRUTH_DPS):
        mp = mpmath.mp
        for i, r in enumerate(links.tolist()):
            for j, t2 in enumerate(np.asarray(theta2, dtype=np.float64).tolist()):
                sol = _mp_truth(r, t2, sign, mp)
                if sol is None:
                    continue
                for k, t in enumerate(sol):
                    hi = float(t)
                    out[i, j, k] = hi, float(t - hi)
    return out


def angle_error(theta: np.ndarray, exact: np.ndarray) -> np.ndarray:
    """|theta - exact| wrapped to [0, pi], with ``exact`` as (..., 2) hi/lo pairs. theta -
    hi is exact in double when they are close (Sterbenz), so one ulp is still seen."""
    d = np.abs((theta - exact[..., 0]) - exact[..., 1])
    # reduce only what needs it: pi - mod(pi - d, 2 pi) would round a tiny d to 0
    far = d > np.pi
    if np.any(far):
        d = np.where(far, np.abs(np.pi - np.mod(np.pi - d, TAU)), d)
    return d


# --- the measurement --------------------------------------------------------------------


@dataclass(frozen=True)
class Row:
    """One method at one tolerance."""

    method: str
    label: str
    #: None for the closed form (no tolerance).
    tol: float | None
    #: Mean Newton iterations per point, over all linkages (0 for the closed form).
    nit_mean: float
    #: Mean Newton iterations per point on the seed linkage alone.
    nit_seed: float
    #: Nanoseconds per point on one thread (best of ``repeat``), over all linkages.
    ns_per_point: float
    #: Largest |angle error| (theta3 and theta4, rad) on the truth subset.
    err_max: float
    #: Largest error on the seed linkage alone.
    err_seed: float
    #: Median error on the truth subset.
    err_median: float
    #: Points (of all linkages) that did not converge.
    failed: int
    #: On the Pareto front of (time, max error): nothing is both faster and more accurate.
    pareto: bool = False
    #: On the Pareto front among the Newton rows only (what to pick when Newton it is).
    pareto_newton: bool = False


@dataclass(frozen=True)
class TradeoffResult:
    """The table behind ``planarkin tradeoff``."""

    rows: list[Row]
    mode: str
    n_links: int
    n_points: int
    truth_links: int
    max_iter: int
    repeat: int
    seconds: float
    truth: str = f"mpmath circle intersection at {TRUTH_DPS} digits, checked by its loop residual"
    notes: list[str] = field(default_factory=list)

    def table(self) -> str:
        """The table as aligned plain text."""
        head = (
            "method",
            "tol",
            "iter/pt",
            "seed",
            "ns/pt",
            "max err",
            "seed err",
            "median err",
            "failed",
            "pareto",
        )
        lines = [self._fmt_row(head)]
        for r in self.rows:
            lines.append(self._fmt_row(_cells(r)))
        return "\n".join(lines)

    @staticmethod
    def _fmt_row(cells) -> str:
        widths = (24, 6, 7, 5, 6, 8, 8, 10, 6, 7)
        return "  ".join(
            c.ljust(w) if i == 0 or i == len(widths) - 1 else c.rjust(w)
            for i, (c, w) in enumerate(zip(cells, widths, strict=True))
        ).rstrip()

    def markdown(self) -> str:
        """The table in Markdown."""
        head = (
            "| method | tol | iter/pt | iter/pt (seed) | ns/pt | max error (rad) "
            "| seed max error | median error | failed | Pareto (all / Newton) |"
        )
        sep = "|---|---:|---:|---:|---:|---:|---:|---:|---:|:---:|"
        return "\n".join([head, sep] + ["| " + " | ".join(_cells(r)) + " |" for r in self.rows])

    def summary(self) -> str:
        total = self.n_links * self.n_points
        return (
            f"{self.n_links} linkages (seed {SEED_LINKAGE} + {self.n_links - 1} random "
            f"crank-rockers) x {self.n_points} crank angles = {total} points, {self.mode} mode; "
            f"time: one thread, best of {self.repeat}; errors against the {self.truth}, on "
            f"{self.truth_links} linkages ({self.truth_links * self.n_points} points); "
            f"max_iter {self.max_iter}"
        )

    def to_dict(self) -> dict:
        d = asdict(self)
        d["summary"] = self.summary()
        return d


def _sci(v: float) -> str:
    return "nan" if not math.isfinite(v) else f"{v:.1e}"


def _cells(r: Row) -> tuple[str, ...]:
    return (
        r.label,
        "-" if r.tol is None else f"{r.tol:.0e}",
        f"{r.nit_mean:.2f}",
        f"{r.nit_seed:.2f}",
        f"{r.ns_per_point:.0f}",
        _sci(r.err_max),
        _sci(r.err_seed),
        _sci(r.err_median),
        str(r.failed),
        "/".join(x for x, on in (("all", r.pareto), ("N", r.pareto_newton)) if on),
    )


def _best_time(fn, repeat: int) -> float:
    best = math.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def _errors(t3: np.ndarray, t4: np.ndarray, exact: np.ndarray) -> np.ndarray:
    """Per-point max(err theta3, err theta4) on the truth subset; NaN where unsolved."""
    k = exact.shape[0]
    e = np.maximum(angle_error(t3[:k], exact[:, :, 0]), angle_error(t4[:k], exact[:, :, 1]))
    return e


def _max(a: np.ndarray) -> float:
    a = a[np.isfinite(a)]
    return float(a.max()) if a.size else math.nan


def _median(a: np.ndarray) -> float:
    a = a[np.isfinite(a)]
    return float(np.median(a)) if a.size else math.nan


def row_count(tols: tuple[float, ...], methods: tuple[str, ...]) -> int:
    """Rows :func:`tradeoff` measures: one per closed-form method, one per tolerance of
    each Newton method."""
    return sum(1 if METHODS[m][1] is None else len(tols) for m in methods if m in METHODS)


def tradeoff(
    tols: tuple[float, ...] = DEFAULT_TOLS,
    methods: tuple[str, ...] = tuple(METHODS),
    *,
    n_random: int = 127,
    truth_links: int = 32,
    seed: int = 1,
    theta2: object = None,
    mode: str = "open",
    max_iter: int = 100,
    repeat: int = 5,
    links: np.ndarray | None = None,
    progress: Callable[[], object] | None = None,
) -> TradeoffResult:
    """Measures every (method, tol): mean iterations per point and time per point over
    the seed linkage plus ``n_random`` random crank-rockers (or ``links``, an (M, 4)
    array), and the max angle error against the mpmath truth on the first
    ``truth_links`` of them. Times are the best of ``repeat`` single-thread batch calls.
    ``progress()`` is called once per row measured (a progress bar's update): one row per
    closed-form method, one per tolerance of each Newton method (:func:`row_count`).
    """
    t_start = time.perf_counter()
    for name in methods:
        if name not in METHODS:
            raise ValueError(f"methods: unknown method {name!r}; choose from {', '.join(METHODS)}")
    tols = tuple(float(t) for t in tols)
    if any(not (math.isfinite(t) and t > 0) for t in tols):
        raise ValueError(f"tols must be finite and > 0, got {tols}")
    if repeat < 1:
        raise ValueError(f"repeat must be >= 1, got {repeat}")
    if links is None:
        links = np.vstack([np.array([SEED_LINKAGE]), random_crank_rockers(n_random, seed)])
    links = np.ascontiguousarray(links, dtype=np.float64)
    if links.ndim != 2 or links.shape[1] != 4:
        raise ValueError(f"links must have shape (M, 4), got {links.shape}")
    t2 = DEFAULT_THETA2 if theta2 is None else np.ascontiguousarray(theta2, dtype=np.float64)
    m, n = len(links), len(t2)
    k = max(1, min(truth_links, m))
    exact = truth(links[:k], t2, mode)
    points = m * n

    def closed_form(out: tuple[np.ndarray, np.ndarray]) -> tuple:
        t3, t4 = out
        return t3, t4, 0.0, 0.0, int(np.count_nonzero(np.isnan(t3)))

    def newton(b: BatchSweep) -> tuple:
        failed = int(np.count_nonzero(b.status != Status.CONVERGED))
        return b.theta3, b.theta4, float(b.nit.mean()), float(b.nit[0].mean()), failed

    # one row per closed-form method, one per tolerance of each Newton method: the call
    # that is timed (the batch alone), and what the row reads from its result
    cases: list[tuple[str, str, float | None, Callable[[], Any], Callable[[Any], tuple]]] = []
    for method in methods:
        label, predictor = METHODS[method]
        if predictor is None:
            cf = functools.partial(closed_form_batch, links, t2, mode, threads=1)
            cases.append((method, label, None, cf, closed_form))
            continue
        for t in tols:
            nr = functools.partial(
                sweep_batch, links, t2, mode=mode, tol=t, max_iter=max_iter,
                predictor=predictor, threads=1,
            )  # fmt: skip
            cases.append((method, label, t, nr, newton))
    rows: list[Row] = []
    for method, label, tol, call, read in cases:
        t3, t4, nit_mean, nit_seed, failed = read(call())
        secs = _best_time(call, repeat)
        e = _errors(t3, t4, exact)
        ns = secs / points * 1e9
        rows.append(
            Row(method, label, tol, nit_mean, nit_seed, ns, _max(e), _max(e[0]), _median(e), failed)
        )
        if progress is not None:
            progress()
    rows = _mark_pareto(rows)
    return TradeoffResult(rows, mode, m, n, k, max_iter, repeat, time.perf_counter() - t_start)


#: Relative differences in time per point below this are timing noise, not speed.
TIME_NOISE = 0.10
#: Relative differences in max error below this are the same accuracy (rounding).
ERR_TIE = 0.10


def _front(rows: list[Row]) -> set[int]:
    """Indices of the rows no other row beats on time and max error (NaN: never).

    Times within :data:`TIME_NOISE` of each other, and errors within :data:`ERR_TIE`, are
    ties, not wins: a row beats another only if it is no worse on both beyond that and
    better on one beyond it, or, when tied on both, if it has the looser tolerance (it
    does no more work; the closed form has none). So the front does not follow timing
    noise between rows of equal error.
    """

    def looser(o: Row, r: Row) -> bool:
        return r.tol is not None and (o.tol is None or o.tol > r.tol)

    def beats(o: Row, r: Row) -> bool:
        if not math.isfinite(o.err_max):
            return False
        err_tie = abs(o.err_max - r.err_max) <= ERR_TIE * max(o.err_max, r.err_max)
        time_tie = abs(o.ns_per_point - r.ns_per_point) <= TIME_NOISE * max(
            o.ns_per_point, r.ns_per_point
        )
        no_worse = (err_tie or o.err_max < r.err_max) and (
            time_tie or o.ns_per_point < r.ns_per_point
        )
        better = not err_tie or not time_tie or looser(o, r)
        return no_worse and better

    return {
        i
        for i, r in enumerate(rows)
        if math.isfinite(r.err_max) and not any(beats(o, r) for o in rows if o is not r)
    }


def _mark_pareto(rows: list[Row]) -> list[Row]:
    front = _front(rows)
    newton = [i for i, r in enumerate(rows) if r.tol is not None]
    front_n = {newton[i] for i in _front([rows[i] for i in newton])}
    return [
        Row(**{**asdict(r), "pareto": i in front, "pareto_newton": i in front_n})
        for i, r in enumerate(rows)
    ]
