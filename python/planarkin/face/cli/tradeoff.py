"""``planarkin tradeoff``: the four-bar solvers' speed against their accuracy (see
``planarkin.fourbar.tradeoff``), printed as a table and saved as a Pareto plot and JSON."""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np

from ..._angles import TAU
from ...fourbar.tradeoff import DEFAULT_TOLS, METHODS, row_count, tradeoff
from ..figures.tradeoff import save
from ..progress import bar
from ._common import FORMATS, quiet_argument


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Registers ``tradeoff``."""
    t = sub.add_parser("tradeoff", help="measure the speed/accuracy trade-off")
    add_arguments(t)
    t.set_defaults(func=run)
    return t


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
    parser.add_argument(
        "--format",
        choices=FORMATS,
        help="the plot's file format (png, svg or pdf); default: the suffix of --plot",
    )
    parser.add_argument("--no-plot", action="store_true", help="do not save the plot")
    quiet_argument(parser)
    parser.add_argument("--json", metavar="PATH", help="also write the results as JSON")
    parser.add_argument("--markdown", action="store_true", help="print the table as Markdown")


def run(args: argparse.Namespace) -> int:
    """Runs the ``tradeoff`` subcommand; returns the exit code."""
    theta2 = np.linspace(0.0, TAU, args.points) if args.points != 361 else None
    plot = Path(args.plot)
    if args.format is not None:
        plot = plot.with_suffix(f".{args.format}")
    elif not args.no_plot and plot.suffix.lstrip(".") not in FORMATS:
        raise ValueError(f"--plot must end in .png, .svg or .pdf, got {args.plot!r}")
    total = row_count(args.tols, args.methods)
    try:
        with bar(total, "tradeoff", quiet=args.quiet, unit="row") as b:
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
                progress=b.update,
            )
    except ImportError as e:
        print(f"planarkin tradeoff: {e}", file=sys.stderr)
        return 2
    print(res.summary())
    print()
    print(res.markdown() if args.markdown else res.table())
    if not args.no_plot:
        save(res, str(plot))
        print(f"\nPareto plot saved to {plot}")
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump(res.to_dict(), f, indent=1)
        print(f"results saved to {args.json}")
    return 0
