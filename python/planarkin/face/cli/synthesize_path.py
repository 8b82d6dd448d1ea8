"""``planarkin synthesize path TARGET``: linkages whose tracer point follows a curve (a CSV,
JSON or SVG file), by :func:`planarkin.synthesis.path.path`: progress bars per stage on a
terminal; writes design_1.json, ... (scene files ``analyze`` and ``web`` open),
report.json (every option, the command that reproduces the run, the seed, versions,
timings, errors and defects) and the figures, all or nothing (Ctrl-C: exit 130, nothing
half-written)."""

from __future__ import annotations

import argparse
import math
import shlex
import sys
import time
from dataclasses import replace
from pathlib import Path

from ...synthesis.path.results import PathResult, staged
from ...synthesis.path.targets import KINDS, SVG_SAMPLES, load_target
from ..progress import Stages
from ._common import (
    figure_file,
    format_argument,
    json_text,
    out_argument,
    parsed_options,
    quiet_argument,
)

#: the topologies a path synthesis draws from ("auto": every one, the best kept)
TOPOLOGIES = ("four-bar", "slider-crank", "watt2", "stephenson3", "auto")
DESIGNS = 5
OUT = Path("path")
#: the figure of design k is DESIGN_FIGURE.format(k=k); the error along the target is
#: ERROR_FIGURE
DESIGN_FIGURE = "path_design_{k}.png"
ERROR_FIGURE = "error.png"


def add_parser(problems: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Registers ``synthesize path`` under ``synthesize``."""
    p = problems.add_parser(
        "path",
        help="linkages whose point traces a curve (CSV, JSON or SVG)",
        description="Find linkages whose tracer point follows TARGET: candidates from an "
        "atlas of coupler curves, placed on the target, refined by SLSQP with exact "
        "gradients under branch, order and transmission constraints, and verified on a dense "
        "sweep. Writes design_1.json, ... (scene files, best first), report.json and "
        "figures into --out.",
    )
    p.add_argument(
        "target",
        metavar="TARGET",
        help="the path: a .csv (rows x,y[,input]; optional header x,y,input or input_deg; "
        "'#' comments), a .json (an array of [x, y] or an object with 'points') or an .svg "
        "(the first <path>'s d, or a file holding only path data)",
    )
    p.add_argument(
        "--kind",
        choices=KINDS,
        default=None,
        help="closed (the whole coupler curve), open, or partial (part of a curve) "
        "(default: as the file says (SVG Z, JSON kind), else closed when the last point "
        "repeats the first, else open)",
    )
    p.add_argument(
        "--topology",
        choices=TOPOLOGIES,
        default="four-bar",
        help="the linkages searched (default: %(default)s; auto: every one)",
    )
    p.add_argument(
        "--designs",
        type=int,
        default=DESIGNS,
        metavar="N",
        help="designs returned, best first (default: %(default)s)",
    )
    p.add_argument(
        "--timing",
        action="store_true",
        help="use TARGET's input values per point (CSV column input (rad) or input_deg, "
        "JSON inputs or inputs_deg); without it every point's input is free",
    )
    p.add_argument(
        "--min-transmission",
        type=float,
        default=None,
        metavar="DEG",
        help="least transmission angle allowed over the traced arc, degrees (default: none; "
        "it is always reported)",
    )
    p.add_argument(
        "--box",
        type=float,
        nargs=4,
        default=None,
        metavar=("XMIN", "XMAX", "YMIN", "YMAX"),
        help="the fixed pivots must lie inside this box, in the target's units (default: anywhere)",
    )
    p.add_argument(
        "--max-link-ratio",
        type=float,
        default=None,
        metavar="R",
        help="the longest link at most R times the shortest (default: any)",
    )
    p.add_argument(
        "--full-turn",
        action="store_true",
        help="the input must turn fully (always so for a closed or partial target)",
    )
    p.add_argument(
        "--atlas",
        type=Path,
        default=None,
        metavar="DIR",
        help="an atlas built by 'planarkin atlas build' (default: the default four-bar atlas, "
        "built once into the user cache)",
    )
    p.add_argument(
        "--scheduler",
        default=None,
        metavar="ADDRESS",
        help="a Dask scheduler to run on (default: this machine); the designs do not depend on it",
    )
    p.add_argument(
        "--time-limit",
        type=float,
        default=None,
        metavar="SECONDS",
        help="stop refining after SECONDS and keep the designs verified by then (default: none)",
    )
    p.add_argument("--seed", type=int, default=0, help="random seed (default: %(default)s)")
    p.add_argument(
        "--svg-samples",
        type=int,
        default=SVG_SAMPLES,
        metavar="N",
        help="points an SVG path is sampled into, at equal arc length (default: %(default)s)",
    )
    out_argument(p, str(OUT))
    p.add_argument(
        "--no-figures", action="store_true", help="write the designs and report.json only"
    )
    p.add_argument("--json", action="store_true", help="print report.json to stdout")
    format_argument(p)
    quiet_argument(p)
    p.set_defaults(func=run)
    return p


def _check(args: argparse.Namespace) -> None:
    if args.designs < 1:
        raise ValueError(f"--designs must be >= 1, got {args.designs}")
    m = args.min_transmission
    if m is not None and not (math.isfinite(m) and 0 <= m < 90):
        raise ValueError(f"--min-transmission must be in [0, 90) deg, got {m}")
    t = args.time_limit
    if t is not None and not (math.isfinite(t) and t > 0):
        raise ValueError(f"--time-limit must be finite and > 0 seconds, got {t}")
    if args.svg_samples < 3:
        raise ValueError(f"--svg-samples must be >= 3, got {args.svg_samples}")
    if args.box is not None:
        x0, x1, y0, y1 = args.box
        if not all(map(math.isfinite, args.box)) or x0 >= x1 or y0 >= y1:
            raise ValueError(f"--box must be finite XMIN < XMAX, YMIN < YMAX, got {args.box}")
    r = args.max_link_ratio
    if r is not None and not (math.isfinite(r) and r >= 1):
        raise ValueError(f"--max-link-ratio must be finite and >= 1, got {r}")
    if args.atlas is not None and not args.atlas.is_dir():
        raise ValueError(f"--atlas {str(args.atlas)!r} is not a folder")


def command_line(args: argparse.Namespace) -> str:
    """The command that reproduces this run's files: every option that decides them
    written out (the defaults too, so that a later change of one does not change what the
    command means); --scheduler is left out (the designs do not depend on it)."""
    words = ["planarkin", "synthesize", "path", str(args.target), "--out", str(args.out)]
    if args.kind is not None:
        words += ["--kind", args.kind]
    words += ["--topology", args.topology, "--designs", str(args.designs)]
    if args.timing:
        words.append("--timing")
    if args.min_transmission is not None:
        words += ["--min-transmission", repr(args.min_transmission)]
    if args.box is not None:
        words += ["--box", *map(repr, args.box)]
    if args.max_link_ratio is not None:
        words += ["--max-link-ratio", repr(args.max_link_ratio)]
    if args.full_turn:
        words.append("--full-turn")
    if args.atlas is not None:
        words += ["--atlas", str(args.atlas)]
    words += ["--seed", str(args.seed), "--svg-samples", str(args.svg_samples)]
    if args.time_limit is not None:
        words += ["--time-limit", repr(args.time_limit)]
    if args.no_figures:
        words.append("--no-figures")
    elif args.format != "png":
        words += ["--format", args.format]
    return shlex.join(words)


def run(args: argparse.Namespace) -> int:
    """``planarkin synthesize path``; returns the exit code."""
    _check(args)
    t0 = time.perf_counter()
    target = load_target(
        args.target, kind=args.kind, timing=args.timing, svg_samples=args.svg_samples
    )
    from ...synthesis import path as path_api

    bars = Stages("synthesize path", args.quiet)
    try:
        res = path_api.path(
            target,
            topology=args.topology,
            designs=args.designs,
            min_transmission=args.min_transmission,
            box=None if args.box is None else (tuple(args.box[:2]), tuple(args.box[2:])),
            max_link_ratio=args.max_link_ratio,
            full_turn=True if args.full_turn else None,
            atlas=None if args.atlas is None else str(args.atlas),
            scheduler=args.scheduler,
            time_limit=args.time_limit,
            seed=args.seed,
            progress=bars,
        )
    except KeyboardInterrupt:
        bars.close()
        print("planarkin: interrupted; nothing written", file=sys.stderr)
        return 130
    bars.close()
    res = replace(res, options={**parsed_options(args, ("problem",)), **res.options})
    interrupted = res.stopped == "interrupted"
    if not res.designs:
        why = f" ({res.stopped})" if res.stopped != "done" else ""
        print(f"planarkin: no design found{why}; nothing written", file=sys.stderr)
        return 130 if interrupted else 1
    try:
        paths = write(res, args)
    except KeyboardInterrupt:
        print("planarkin: interrupted; nothing written", file=sys.stderr)
        return 130
    if interrupted:
        print(f"planarkin: interrupted: wrote the {len(res.designs)} designs found so far to "
              f"{args.out}", file=sys.stderr)  # fmt: skip
        return 130
    if args.json:
        print(json_text(res.report(command=command_line(args))))
    else:
        _summary(res, paths, time.perf_counter() - t0)
    return 0


def write(res: PathResult, args: argparse.Namespace) -> list[Path]:
    """The designs, report.json and (unless --no-figures) the figures, moved into --out
    together once all are written."""
    with staged(args.out) as tmp:
        names = [p.name for p in res.write_into(tmp, command=command_line(args))]
        if not args.no_figures:
            from ..figures import path as figures

            for k, d in enumerate(res.designs, 1):
                name = figure_file(DESIGN_FIGURE.format(k=k), args.format)
                figures.design(res.target, d, k).savefig(tmp / name, dpi=120)
                names.append(name)
            name = figure_file(ERROR_FIGURE, args.format)
            figures.error(res.target, res.designs).savefig(tmp / name, dpi=120)
            names.append(name)
    return [args.out / n for n in names]


def _summary(res: PathResult, paths: list[Path], wall_s: float) -> None:
    t = res.target
    timing = "timing given" if t.inputs is not None else "timing free"
    print(f"planarkin synthesize path: {len(t)} points, {t.kind}, {timing}; "
          f"{len(res.designs)} designs ({len(res.verified)} verified), {wall_s:.1f} s")  # fmt: skip
    for k, d in enumerate(res.designs, 1):
        bad = [n for n in ("circuit", "branch", "order") if getattr(d.defects, n)]
        check = "verified" if d.verified else "NOT verified"
        if bad:
            check += f", {' and '.join(bad)} defect"
        print(f"  design {k}: {d.topology}, error max {d.error.max:.3g}, rms {d.error.rms:.3g} "
              f"(of the target's size), min transmission {d.min_transmission:.1f} deg, "
              f"{check}")  # fmt: skip
    if res.stopped != "done":
        print(f"  stopped: {res.stopped}")
    print("  written: " + ", ".join(str(p) for p in paths))
