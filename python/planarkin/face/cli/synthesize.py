"""``planarkin synthesize ackermann``: the seed's example 2 end to end (multistart SLSQP on
the true error, verification, tolerance sensitivity, design.json, report.json, figures),
with progress bars on a terminal. Ctrl-C stops the worker processes at once and
``--time-limit`` stops the search; either way the best feasible design found so far is
written and the report says why it stopped. A search with no feasible design writes
nothing and exits 1. report.json records every option, the command that reproduces the
run, and the versions it ran with. ``synthesize path`` is registered here too; it lives in
:mod:`.synthesize_path`."""

from __future__ import annotations

import argparse
import math
import shlex
import sys
import time
from dataclasses import fields, replace
from pathlib import Path
from typing import Any

import numpy as np

from ...scene import Scene
from ...synthesis import ackermann as ak
from ...synthesis import ackermann_report as rep
from ...synthesis import driver
from ...synthesis.problem import OBJECTIVES, FunctionTarget, Problem
from ...synthesis.results import versions
from ...synthesis.start import MINIMAX_ITER
from ..figures import synthesis as synthesis_figures
from ..progress import bar, shown
from . import synthesize_path
from ._common import figure_file, format_argument, json_text, parsed_options, quiet_argument

PROBLEMS = ("ackermann", "path")
#: defaults of the full run (the shipped design in examples/ackermann/ is this run's)
STARTS, SAMPLES, SEED = 12, 3000, 2
DESIGN_JSON = "design.json"
REPORT_JSON = "report.json"
#: Figure file -> the function of ``figures.synthesis`` that draws it.
FIGURES = {
    "error.png": synthesis_figures.error,
    "conditioning.png": synthesis_figures.conditioning,
    "linkage.png": synthesis_figures.linkage,
}


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Registers ``synthesize`` and its problems: ``ackermann`` (here) and ``path``
    (:mod:`.synthesize_path`)."""
    y = sub.add_parser(
        "synthesize",
        help="synthesis: ackermann (a double butterfly), path (a linkage tracing a curve)",
        description="Synthesize a linkage: 'ackermann' (the double butterfly of Ackermann "
        "steering, by multistart SLSQP on the true linkage's error) or 'path' (linkages whose "
        "point traces a given curve). 'planarkin synthesize PROBLEM --help' lists each one's "
        "options.",
    )
    problems = y.add_subparsers(dest="problem", required=True, metavar="PROBLEM")
    a = problems.add_parser(
        "ackermann",
        help="defect-free synthesis of a double butterfly for Ackermann steering",
        description="Synthesize a double butterfly by multistart SLSQP on the true linkage's "
        f"error, verify it, and write {DESIGN_JSON}, {REPORT_JSON} and the study's figures.",
    )
    add_arguments(a)
    a.set_defaults(func=run)
    synthesize_path.add_parser(problems)
    return y


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The options of ``synthesize ackermann``."""
    p.add_argument(
        "--out",
        type=Path,
        default=Path("synthesis"),
        metavar="DIR",
        help="output folder (default: %(default)s)",
    )
    p.add_argument(
        "--starts",
        type=int,
        default=STARTS,
        metavar="N",
        help="SLSQP starts (default: %(default)s; 2 gives a quick run)",
    )
    p.add_argument(
        "--samples",
        type=int,
        default=SAMPLES,
        metavar="M",
        help="random candidates screened for starts (default: %(default)s)",
    )
    p.add_argument("--seed", type=int, default=SEED, help="random seed (default: %(default)s)")
    p.add_argument(
        "--objective",
        choices=OBJECTIVES,
        default="true",
        help="what SLSQP minimises: the true linkage's error (default), the seed's "
        "generated-mechanism error, or the generated error divided by 1 - k",
    )
    p.add_argument(
        "--det-margin",
        type=float,
        default=ak.DET_MARGIN,
        metavar="D",
        help="smallest |conditioning| allowed over the range (default: %(default)s)",
    )
    p.add_argument(
        "--min-link",
        type=float,
        default=0.06,
        metavar="L",
        help="shortest distance between two joints of a link, wheelbases (default: %(default)s)",
    )
    p.add_argument(
        "--select",
        choices=("robust", "accurate"),
        default="robust",
        help="robust (default): of the designs within --budget deg, the least "
        "sensitive to joint tolerances; accurate: the smallest true error",
    )
    p.add_argument(
        "--budget",
        type=float,
        default=rep.BUDGET_DEG,
        metavar="DEG",
        help="nominal true max error allowed by --select robust (default: %(default)s)",
    )
    p.add_argument(
        "--gradient",
        choices=driver.GRADIENTS,
        default="exact",
        help="SLSQP's derivatives: exact (default; the solver's implicit differentiation) or "
        "fd (forward differences, one sweep per coordinate: the check)",
    )
    p.add_argument(
        "--envelope",
        action=argparse.BooleanOptionalAction,
        default=True,
        help=f"keep every joint within the box (|x|, |y| <= {ak.BOX} wheelbases) over the "
        "whole steering range, not only as drawn (default: on)",
    )
    p.add_argument(
        "--tolerance",
        action=argparse.BooleanOptionalAction,
        default=True,
        help="add tolerance_sensitivity (joint noise 1e-5, 1e-4, 1e-3; 200 samples) "
        "to report.json (default: on)",
    )
    p.add_argument(
        "--maxiter",
        type=int,
        default=200,
        metavar="N",
        help="SLSQP iterations per phase: least squares, then the minimax polish (at most "
        f"{MINIMAX_ITER}) (default: %(default)s)",
    )
    p.add_argument(
        "--time-limit",
        type=float,
        default=None,
        metavar="SECONDS",
        help="stop the search (screening and starts) after SECONDS and keep the best "
        "feasible design found by then (default: none)",
    )
    p.add_argument(
        "--workers",
        type=int,
        default=None,
        help="worker processes (default: 2); the result does not depend on it",
    )
    p.add_argument(
        "--no-figures", action="store_true", help="write design.json and report.json only"
    )
    p.add_argument("--json", action="store_true", help="print report.json to stdout")
    format_argument(p)
    quiet_argument(p)


def _check(args: argparse.Namespace) -> None:
    if args.starts < 1:
        raise ValueError(f"--starts must be >= 1, got {args.starts}")
    if args.samples < 0:
        raise ValueError(f"--samples must be >= 0, got {args.samples}")
    for name in ("det_margin", "min_link", "budget"):
        v = getattr(args, name)
        if not (math.isfinite(v) and v >= 0):
            raise ValueError(f"--{name.replace('_', '-')} must be finite and >= 0, got {v}")
    if args.maxiter < 1:
        raise ValueError(f"--maxiter must be >= 1, got {args.maxiter}")
    if args.workers is not None and args.workers < 1:
        raise ValueError(f"--workers must be >= 1, got {args.workers}")
    t = args.time_limit
    if t is not None and not (math.isfinite(t) and t > 0):
        raise ValueError(f"--time-limit must be finite and > 0 seconds, got {t}")


#: the options that decide the result, as (flag, dest), in the order the command is written
RESULT_FLAGS = (
    ("--starts", "starts"),
    ("--samples", "samples"),
    ("--seed", "seed"),
    ("--objective", "objective"),
    ("--det-margin", "det_margin"),
    ("--min-link", "min_link"),
    ("--select", "select"),
    ("--budget", "budget"),
    ("--maxiter", "maxiter"),
    ("--gradient", "gradient"),
)


def command_line(args: argparse.Namespace) -> str:
    """The command that reproduces this run's files: every option that decides them
    written out (so that a later change of a default does not change what it means)."""
    words = ["planarkin", "synthesize", args.problem, "--out", str(args.out)]
    for flag, dest in RESULT_FLAGS:
        words += [flag, _word(getattr(args, dest))]
    words.append("--envelope" if args.envelope else "--no-envelope")
    words.append("--tolerance" if args.tolerance else "--no-tolerance")
    if args.time_limit is not None:
        words += ["--time-limit", _word(args.time_limit)]
    if args.no_figures:
        words.append("--no-figures")
    elif args.format != "png":
        words += ["--format", args.format]
    return shlex.join(words)


def _word(v: object) -> str:
    # repr: the shortest text that reads back to the same float
    return repr(v) if isinstance(v, float) else str(v)


class _Bars:
    """Screening, then starts: done / total, the best feasible true error so far and the
    time left (tqdm's estimate); one bar at a time, none in a pipe or with --quiet."""

    def __init__(self, args: argparse.Namespace, scale_deg: float) -> None:
        self.args, self.scale_deg = args, scale_deg
        self.best = math.inf
        self.screen = bar(args.samples, "synthesize: screening", quiet=args.quiet, unit="sample")
        self.starts: Any = None

    def screened(self, n: int) -> None:
        self.screen.update(n)
        if self.screen.n >= self.screen.total:
            self._open_starts()

    def _open_starts(self) -> None:
        if self.starts is None:
            self.screen.close()
            self.starts = bar(
                self.args.starts, "synthesize: starts", quiet=self.args.quiet, unit="start"
            )
            self.starts.set_postfix_str("best: none yet", refresh=True)

    def finished(self, run: driver.StartResult) -> None:
        self._open_starts()
        if run.feasible and run.max_error < self.best:
            self.best = run.max_error
        shown = f"{self.best * self.scale_deg:.3g} deg" if math.isfinite(self.best) else "none yet"
        self.starts.set_postfix_str(f"best: {shown}", refresh=False)
        self.starts.update()

    def close(self) -> None:
        self.screen.close()
        if self.starts is not None:
            self.starts.close()
        if shown(self.args.quiet):
            # a bar cut short by Ctrl-C as it was drawn is not closed: clear its line, so
            # that what the command prints next starts at the left margin
            sys.stderr.write("\r\x1b[K")
            sys.stderr.flush()


def run(args: argparse.Namespace) -> int:
    """``planarkin synthesize``; returns the exit code."""
    _check(args)
    t0 = time.perf_counter()
    space = ak.space(min_link=args.min_link)
    problem = replace(
        ak.problem(objective=args.objective, det_margin=args.det_margin, envelope=args.envelope),
        space=space,
    )
    interrupted = False
    bars = _Bars(args, math.degrees(problem.target.scale))
    try:
        # the search owns its process pool: Ctrl-C stops its workers at once
        res = driver.synthesize(
            problem,
            starts=args.starts,
            samples=args.samples,
            seed=args.seed,
            sampler=ak.mirror_sampler(space),
            workers=args.workers,
            maxiter=args.maxiter,
            progress=bars.finished,
            screening=bars.screened,
            time_limit=args.time_limit,
            gradient=args.gradient,
        )
    except driver.SynthesisInterrupted as e:
        res, interrupted = e.result, True
    finally:
        bars.close()
    stop = _stop_words(res, args)
    written = _finish(args, problem, res, stop, t0)
    if interrupted:
        # the line every command prints on Ctrl-C, and what was kept when something was
        kept = f": wrote the best feasible design so far to {args.out} ({_finished(res)})"
        print(f"planarkin: interrupted{kept if written else ''}", file=sys.stderr)
        return 130
    if not written:
        why = f"{stop}: {_finished(res)}" if stop else f"{_finished(res)}, none feasible"
        more = "--starts, --samples or --time-limit" if stop else "--starts or --samples"
        print(
            f"planarkin: no feasible design ({why}); nothing written (raise {more})",
            file=sys.stderr,
        )
        return 1
    return 0


def _finished(res: driver.SynthesisResult) -> str:
    """How far the search got, in words: "2 of 3 starts finished", "1 of 3 starts ran to
    its end, 1 stopped at the limit, 1 not run", "while screening (50 of 300 candidates)"."""
    if res.starts == 0:
        if res.screened >= res.sampled:
            return f"before any start ran ({res.screened} candidates screened)"
        return f"while screening ({res.screened} of {res.sampled} candidates)"
    n, total = len(res.runs), res.starts
    cut = sum(1 for r in res.runs if r.stopped)
    if not cut:
        return f"{n} of {total} start{'' if total == 1 else 's'} finished"
    words = [f"{n - cut} of {total} start{'' if total == 1 else 's'} ran to the end"]
    words.append(f"{cut} stopped at the limit")
    if total > n:
        words.append(f"{total - n} not run")
    return ", ".join(words)


def _stop_words(res: driver.SynthesisResult, args: argparse.Namespace) -> str:
    if res.stopped == driver.INTERRUPTED:
        return "interrupted (Ctrl-C)"
    if res.stopped == driver.TIME_LIMIT:
        return f"stopped at the time limit ({args.time_limit:g} s)"
    return ""


def _finish(
    args: argparse.Namespace,
    problem: Problem,
    res: driver.SynthesisResult,
    stop: str,
    t0: float,
) -> bool:
    """Verifies every finished run on the true linkage, chooses, and writes the design,
    report and figures (:mod:`planarkin.synthesis.ackermann_report`); False (nothing
    written) when no run is a feasible, verified design."""
    truth = replace(problem, objective="true")
    target = problem.target
    assert isinstance(target, FunctionTarget)
    grid = rep.grid_1001(target)
    if not any(r.feasible for r in res.runs):
        return False
    with bar(len(res.runs), "synthesize: verify", quiet=args.quiet, unit="design") as b:
        rows = rep.verify_runs(truth, res.runs, grid, b.update)
    choice = rep.choose(truth, rows, args.budget, args.select, grid)
    if choice is None:
        return False
    best, v, _ = choice.chosen
    d = rep.design_dict(truth, best.x, args.seed, res.starts, args.objective)
    sc = Scene.from_dict(d)
    settings = rep.Settings(**{f.name: getattr(args, f.name) for f in fields(rep.Settings)})
    report = rep.report(
        problem, res, rows, choice, sc, settings, command=command_line(args),
        options=parsed_options(args), versions=versions(), stop=stop,
    )  # fmt: skip
    report["wall_s"] = time.perf_counter() - t0
    paths = write(args.out, truth, best.x, report, sc, figures=not args.no_figures, fmt=args.format)
    for name, row in (("accurate", choice.accurate), ("robust", choice.robust)):
        alt = dict(d)
        alt["description"] = f"{d['description']} The {name} design of the search."
        paths.append(
            Scene.from_dict({**alt, "points": truth.scene(row[0].x).to_dict()["points"]}).save(
                args.out / f"design_{name}.json"
            )
        )
    key = rep.KEY
    if not args.no_figures:
        path = args.out / figure_file("tolerance.png", args.format)
        synthesis_figures.tolerance(
            [(r.index, rv[key], s) for r, rv, s in rows if rv and math.isfinite(s)],
            {"accurate": choice.accurate[0].index, "robust": choice.robust[0].index},
            rep.SIGMA,
        ).savefig(path, dpi=120)
        paths.append(path)
    if args.json:
        print(json_text(report))
    elif res.stopped != driver.INTERRUPTED:
        print(
            f"planarkin synthesize ackermann: true max error {v[key]:.3g} deg (1001 points), "
            f"{v['true_max_error_deg']:.3g} deg (31 design points), generated "
            f"{_generated_words(v)}; det sign changes {v['det_sign_changes']}, "
            f"min conditioning {v['min_abs_conditioning']:.3g}, link ratio {v['link_ratio']:.3g}; "
            f"{res.starts} starts, {report['wall_s']:.1f} s"
        )
        if stop:
            print(f"  {stop}: {_finished(res)}; the best feasible design so far")
        print("  written: " + ", ".join(str(p) for p in paths))
    return True


def _generated_words(v: dict[str, Any]) -> str:
    # the closed form on the linkage's own roots; with the drawn signs held fixed it can
    # change root where the linkage passes a loop's turning point, and then describes
    # another mechanism: said, not printed as this design's generated error
    words = f"{v['generated_max_error_deg']:.3g} deg"
    n = v["generated_root_changes"]
    if n:
        first = v["generated_root_changes_deg"][0]
        words += (
            f" (on the linkage's own roots; the drawn signs held fixed change root at {n} of "
            f"{v['design_points']} design points from {first:.3g} deg and read "
            f"{v['generated_fixed_signs_max_error_deg']:.3g} deg)"
        )
    return words


def write(
    out: Path,
    problem: Problem,
    x: np.ndarray,
    report: dict[str, Any],
    scene: Scene,
    figures: bool = True,
    fmt: str = "png",
) -> list[Path]:
    """design.json, report.json and (``figures``) the three figures (``fmt``: png, svg,
    pdf) into ``out``."""
    out.mkdir(parents=True, exist_ok=True)
    paths = [scene.save(out / DESIGN_JSON)]
    p = out / REPORT_JSON
    p.write_text(json_text(report) + "\n", encoding="utf-8")
    paths.append(p)
    if figures:
        for name, make in FIGURES.items():
            path = out / figure_file(name, fmt)
            make(problem, x).savefig(path, dpi=120)
            paths.append(path)
    return paths
