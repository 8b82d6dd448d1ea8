"""``planarkin synthesize ackermann``: the seed's example 2 end to end (multistart SLSQP on
the true error, verification, tolerance sensitivity, design.json, report.json, figures).
Ctrl-C stops the worker processes at once."""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import time
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from ...scene import Scene
from ...synthesis import ackermann as ak
from ...synthesis import driver
from ...synthesis.problem import OBJECTIVES, Problem
from ...synthesis.verify import linear_sensitivity, tolerance_sensitivity, verify
from ..figures import synthesis as synthesis_figures
from ..progress import bar
from ._common import figure_file, format_argument, quiet_argument

PROBLEMS = ("ackermann",)
#: defaults of the full run (the shipped design in examples/ackermann/ is this run's)
STARTS, SAMPLES, SEED = 12, 3000, 2
#: nominal true max error (deg) a design may have and still be preferred for robustness
BUDGET_DEG = 0.002


DESIGN_JSON = "design.json"
REPORT_JSON = "report.json"
#: Figure file -> the function of ``figures.synthesis`` that draws it.
FIGURES = {
    "error.png": synthesis_figures.error,
    "conditioning.png": synthesis_figures.conditioning,
    "linkage.png": synthesis_figures.linkage,
}


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Registers ``synthesize``."""
    y = sub.add_parser(
        "synthesize",
        help="defect-free synthesis of a double butterfly: ackermann",
        description="Synthesize a double butterfly by multistart SLSQP on the true linkage's "
        f"error, verify it, and write {DESIGN_JSON}, {REPORT_JSON} and the study's figures.",
    )
    add_arguments(y)
    y.set_defaults(func=run)
    return y


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The options of ``synthesize``."""
    p.add_argument(
        "problem",
        choices=PROBLEMS,
        help="the synthesis problem (the study's example 2: Ackermann steering)",
    )
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
        default=BUDGET_DEG,
        metavar="DEG",
        help="nominal true max error allowed by --select robust (default: %(default)s)",
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
        help="SLSQP iterations per phase (default: %(default)s)",
    )
    p.add_argument("--workers", type=int, default=None, help="worker processes (default: 2)")
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


def run(args: argparse.Namespace) -> int:
    """``planarkin synthesize``; returns the exit code."""
    _check(args)
    t0 = time.perf_counter()
    problem = ak.problem(objective=args.objective, det_margin=args.det_margin)
    problem = replace(problem, space=ak.space(min_link=args.min_link))
    # the command's own pool, so that Ctrl-C (KeyboardInterrupt here) stops its workers
    # at once instead of waiting for the starts they run and have queued
    executor = driver.process_pool(args.workers)
    try:
        with bar(args.starts, "synthesize: starts", quiet=args.quiet, unit="start") as b:
            res = driver.synthesize(
                problem,
                starts=args.starts,
                samples=args.samples,
                seed=args.seed,
                sampler=ak.mirror_sampler(problem.space),
                executor=executor,
                maxiter=args.maxiter,
                progress=b.update,
            )
    except BaseException:
        driver.stop_pool(executor)
        raise
    executor.shutdown()
    # verify every run on the true linkage, then choose
    truth = replace(problem, objective="true")
    grid = np.linspace(problem.target.dense_in[0], problem.target.dense_in[-1], 201)
    rows: list[tuple[driver.StartResult, dict[str, Any], float]] = []
    with bar(len(res.runs), "synthesize: verify", quiet=args.quiet, unit="design") as b:
        for r in res.runs:
            v = verify(truth, r.x)
            s = linear_sensitivity(truth.space.scene(r.x), grid, ak.right_steer(grid))
            rows.append((r, v, s))
            b.update()
    good = [
        row
        for row in rows
        if row[1]["converged"] and row[1]["det_sign_changes"] == 0 and row[0].feasible
    ]
    if not good:
        raise ValueError("no start ended in a verified design (raise --starts or --samples)")
    key = "true_max_error_deg_1001"
    within = [row for row in good if row[1][key] <= args.budget]
    if args.select == "robust" and within:
        chosen = min(within, key=lambda row: row[2])
        why = (
            f"the least tolerance-sensitive of {len(within)} verified designs within "
            f"{args.budget} deg"
        )
    else:
        chosen = min(good, key=lambda row: row[1][key])
        why = "the smallest true max error of the verified designs"
    best, v, sens = chosen
    sc = truth.space.scene(best.x)
    d = sc.to_dict()
    d["name"] = "Ackermann steering double butterfly"
    d["description"] = (
        f"{problem.space.template.description} Synthesized by planarkin synthesize ackermann "
        f"(seed {args.seed}, {res.starts} starts, objective {args.objective}); lengths in "
        "wheelbases, drawn straight ahead (both knuckles at 0 deg, axles collinear)."
    )
    d["units"] = "wheelbase"
    sc = Scene.from_dict(d)
    report: dict[str, Any] = {
        "problem": "ackermann",
        "track_over_wheelbase": ak.TRACK,
        "inner_deg": ak.INNER_DEG,
        "outer_deg": ak.OUTER_DEG,
        **v,
        "box": ak.BOX,
        "in_box": bool(v["max_abs_x"] <= ak.BOX + 1e-12 and v["max_abs_y"] <= ak.BOX + 1e-12),
        "linear_sensitivity_deg_per_unit": sens,
        "objective_optimized": args.objective,
        "selection": f"{args.select}: {why}",
        "optimizer": {
            "method": "SLSQP (scipy), least squares then minimax polish",
            "gradients": "forward finite differences of the Rust scene sweeps (Python loop)",
            "status": best.status,
            "message": best.message,
            "nit": best.nit,
            "phases": best.phases,
            "feasible": best.feasible,
        },
        "det_margin": args.det_margin,
        "min_link": args.min_link,
        "starts": res.starts,
        "samples": res.sampled,
        "maxiter": args.maxiter,
        "seed": args.seed,
        "runs": [
            {
                "true_max_error_deg_1001": rv[key],
                "min_abs_conditioning": rv["min_abs_conditioning"],
                "linear_sensitivity_deg_per_unit": s,
                "status": r.status,
                "feasible": r.feasible,
            }
            for r, rv, s in rows
        ],
        "optimize_wall_s": res.wall_s,
        "cpu_count": os.cpu_count(),
        "machine": platform.machine(),
    }
    if args.tolerance:
        g1001 = np.linspace(problem.target.dense_in[0], problem.target.dense_in[-1], 1001)
        report["tolerance_sensitivity"] = tolerance_sensitivity(sc, g1001, ak.right_steer(g1001))
    report["wall_s"] = time.perf_counter() - t0
    paths = write(args.out, truth, best.x, report, sc, figures=not args.no_figures, fmt=args.format)
    if args.json:
        print(json.dumps(report, indent=2))
    else:
        print(
            f"planarkin synthesize ackermann: true max error {v[key]:.3g} deg (1001 points), "
            f"{v['true_max_error_deg']:.3g} deg (31 design points), generated "
            f"{v['generated_max_error_deg']:.3g} deg; det sign changes {v['det_sign_changes']}, "
            f"min conditioning {v['min_abs_conditioning']:.3g}, link ratio {v['link_ratio']:.3g}; "
            f"{res.starts} starts, {report['wall_s']:.1f} s"
        )
        print("  written: " + ", ".join(str(p) for p in paths))
    return 0


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
    p.write_text(json.dumps(report, indent=2, default=_json_default) + "\n", encoding="utf-8")
    paths.append(p)
    if figures:
        for name, make in FIGURES.items():
            path = out / figure_file(name, fmt)
            make(problem, x).savefig(path, dpi=120)
            paths.append(path)
    return paths


def _json_default(o: object) -> object:
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, (np.floating, np.integer)):
        return o.item()
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")
