"""Speed/accuracy trade-off of the four-bar solvers (``planarkin tradeoff``): for each
tolerance and method, mean Newton iterations per point, time per point and the largest
angle error against an independent truth solved in mpmath at 40 significant digits.

>>> from planarkin.tradeoff import tradeoff
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

import argparse
import json
import math
import sys
import time
from dataclasses import asdict, dataclass, field

import numpy as np

from ._types import DEFAULT_THETA2, TAU, Status

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

    def plot(self, path: str) -> None:
        """Saves the Pareto plot (time per point vs max error, log-log)."""
        self.figure().savefig(path, dpi=120)

    def figure(self):  # -> matplotlib.figure.Figure (matplotlib is imported only here)
        """The Pareto plot as a matplotlib Figure (object API, no pyplot). Tolerances whose
        markers would print their labels on top of each other share one label
        ("1e-12..1e-15"); tick labels are plain numbers."""
        from matplotlib.figure import Figure
        from matplotlib.ticker import LogFormatter

        fig = Figure(figsize=(7.5, 5.0), layout="constrained")
        ax = fig.subplots()
        floor = 1e-17  # an error of exactly 0 has no place on a log axis
        labels = []
        for method, (label, _) in METHODS.items():
            rows = [r for r in self.rows if r.method == method]
            if not rows:
                continue
            x = [r.ns_per_point for r in rows]
            y = [max(r.err_max, floor) for r in rows]
            if method == "closed-form":
                ax.plot(x, y, "*", ms=14, label=label, color="k")
                continue
            (line,) = ax.plot(x, y, "o-", ms=4, label=label, alpha=0.8)
            for group in _close_runs(x, y):
                tols = [rows[i].tol for i in group]
                text = f"{tols[0]:.0e}" + (f"..{tols[-1]:.0e}" if len(tols) > 1 else "")
                i = group[len(group) // 2]
                labels.append(
                    ax.annotate(
                        text,
                        (x[i], y[i]),
                        fontsize=6,
                        xytext=(3, 2),
                        textcoords="offset points",
                        color=line.get_color(),
                    )
                )
        front = sorted((r for r in self.rows if r.pareto_newton), key=lambda r: r.ns_per_point)
        if front:
            ax.step(
                [r.ns_per_point for r in front],
                [max(r.err_max, floor) for r in front],
                where="post",
                color="0.6",
                lw=4,
                alpha=0.4,
                zorder=0,
                label="Pareto front of the Newton rows",
            )
        ax.set_xscale("log")
        ax.set_yscale("log")
        for axis in (ax.xaxis, ax.yaxis):  # "40", not "4x10^1"
            axis.set_major_formatter(LogFormatter(labelOnlyBase=False))
            axis.set_minor_formatter(LogFormatter(labelOnlyBase=False, minor_thresholds=(1, 0.4)))
        ax.set_xlabel("time per point (ns, one thread)")
        ax.set_ylabel("max angle error (rad)")
        ax.set_title(
            f"planarkin: speed vs accuracy ({self.n_links} linkages x {self.n_points} angles)"
        )
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        _drop_overlapping(fig, labels)
        return fig


def _close_runs(x: list[float], y: list[float], near: float = 0.06) -> list[list[int]]:
    """Consecutive points (in tolerance order) whose markers are within ``near`` decades
    of the previous one on both axes: one label for each run."""
    runs: list[list[int]] = []
    for i in range(len(x)):
        if runs and all(
            abs(math.log10(a[i]) - math.log10(a[runs[-1][-1]])) < near * (3 if a is y else 1)
            for a in (x, y)
        ):
            runs[-1].append(i)
        else:
            runs.append([i])
    return runs


def _drop_overlapping(fig, labels: list) -> None:
    """Hides a tolerance label that would overprint one already shown (the rows nearby
    are labelled; the table has every value)."""
    fig.draw_without_rendering()
    shown: list = []
    for t in labels:
        box = t.get_window_extent()
        if any(box.overlaps(b) for b in shown):
            t.set_visible(False)
        else:
            shown.append(box)


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
) -> TradeoffResult:
    """Measures every (method, tol): mean iterations per point and time per point over
    the seed linkage plus ``n_random`` random crank-rockers (or ``links``, an (M, 4)
    array), and the max angle error against the mpmath truth on the first
    ``truth_links`` of them. Times are the best of ``repeat`` single-thread batch calls.
    """
    from .fourbar import closed_form_batch, sweep_batch

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

    rows: list[Row] = []
    for method in methods:
        label, predictor = METHODS[method]
        if predictor is None:
            t3, t4 = closed_form_batch(links, t2, mode, threads=1)
            secs = _best_time(lambda: closed_form_batch(links, t2, mode, threads=1), repeat)
            e = _errors(t3, t4, exact)
            failed = int(np.count_nonzero(np.isnan(t3)))
            rows.append(
                Row(
                    method,
                    label,
                    None,
                    0.0,
                    0.0,
                    secs / points * 1e9,
                    _max(e),
                    _max(e[0]),
                    _median(e),
                    failed,
                )
            )
            continue
        for tol in tols:

            def run(tol=tol, predictor=predictor):
                return sweep_batch(
                    links, t2, mode=mode, tol=tol, max_iter=max_iter, predictor=predictor, threads=1
                )

            b = run()
            secs = _best_time(run, repeat)
            e = _errors(b.theta3, b.theta4, exact)
            failed = int(np.count_nonzero(b.status != Status.CONVERGED))
            rows.append(
                Row(
                    method,
                    label,
                    tol,
                    float(b.nit.mean()),
                    float(b.nit[0].mean()),
                    secs / points * 1e9,
                    _max(e),
                    _max(e[0]),
                    _median(e),
                    failed,
                )
            )
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


# --- CLI --------------------------------------------------------------------------------


def _tol_list(s: str) -> tuple[float, ...]:
    try:
        vals = tuple(float(x) for x in s.replace(" ", "").split(",") if x)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a comma-separated list of numbers: {s!r}") from None
    if not vals or any(not (math.isfinite(v) and v > 0) for v in vals):
        raise argparse.ArgumentTypeError(f"tolerances must be finite and > 0: {s!r}")
    return vals


def _method_list(s: str) -> tuple[str, ...]:
    vals = tuple(x for x in s.replace(" ", "").split(",") if x)
    bad = [v for v in vals if v not in METHODS]
    if bad or not vals:
        raise argparse.ArgumentTypeError(
            f"unknown method(s) {bad}; choose from {', '.join(METHODS)}"
        )
    return vals


def _positive(s: str) -> int:
    v = int(s)
    if v < 1:
        raise argparse.ArgumentTypeError(f"must be >= 1, got {v}")
    return v


def _non_negative(s: str) -> int:
    v = int(s)
    if v < 0:
        raise argparse.ArgumentTypeError(f"must be >= 0, got {v}")
    return v


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Adds the ``tradeoff`` subcommand's options."""
    parser.description = (
        "Speed/accuracy trade-off: for each tolerance and method, mean Newton iterations "
        "per point, time per point (one thread) and max angle error against an mpmath "
        "truth, over the seed linkage (6, 2, 5, 5) and random crank-rockers. Prints the "
        "table and saves a Pareto plot (time vs error, log-log)."
    )
    parser.add_argument(
        "--tols",
        type=_tol_list,
        default=DEFAULT_TOLS,
        metavar="T1,T2,...",
        help="tolerances (default: 1e-3,1e-4,...,1e-15)",
    )
    parser.add_argument(
        "--methods",
        type=_method_list,
        default=tuple(METHODS),
        metavar="M1,...",
        help=f"methods among {', '.join(METHODS)} (default: all)",
    )
    parser.add_argument(
        "--random",
        type=_non_negative,
        default=127,
        metavar="M",
        help="random crank-rockers besides the seed linkage (default 127)",
    )
    parser.add_argument(
        "--truth-links",
        type=_positive,
        default=32,
        metavar="K",
        help="linkages (seed first) checked against the mpmath truth (default 32)",
    )
    parser.add_argument(
        "--points",
        type=_positive,
        default=361,
        metavar="N",
        help="crank angles, 0..360 deg inclusive (default 361)",
    )
    parser.add_argument("--mode", choices=("open", "crossed"), default="open")
    parser.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    parser.add_argument(
        "--repeat", type=_positive, default=5, help="timing repeats, the best is kept (default 5)"
    )
    parser.add_argument("--max-iter", type=_positive, default=100, help="Newton iteration cap")
    parser.add_argument(
        "--plot",
        default="tradeoff.png",
        metavar="PATH",
        help="where to save the Pareto plot (default tradeoff.png)",
    )
    parser.add_argument("--no-plot", action="store_true", help="do not save the plot")
    parser.add_argument("--json", metavar="PATH", help="also write the results as JSON")
    parser.add_argument("--markdown", action="store_true", help="print the table as Markdown")


def run(args: argparse.Namespace) -> int:
    """Runs the ``tradeoff`` subcommand; returns the exit code."""
    theta2 = np.linspace(0.0, TAU, args.points) if args.points != 361 else None
    try:
        res = tradeoff(
            args.tols,
            args.methods,
            n_random=args.random,
            truth_links=args.truth_links,
            seed=args.seed,
            theta2=theta2,
            mode=args.mode,
            max_iter=args.max_iter,
            repeat=args.repeat,
        )
    except ImportError as e:
        print(f"planarkin tradeoff: {e}", file=sys.stderr)
        return 2
    print(res.summary())
    print()
    print(res.markdown() if args.markdown else res.table())
    if not args.no_plot:
        res.plot(args.plot)
        print(f"\nPareto plot saved to {args.plot}")
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump(res.to_dict(), f, indent=1)
        print(f"results saved to {args.json}")
    return 0
