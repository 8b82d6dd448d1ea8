"""The Ackermann steering search's report as plain data: every finished run verified on
the true linkage, the most accurate and the least tolerance-sensitive designs chosen (the
robust one polished where that verifies), the design as a scene, and report.json's
content. ``planarkin synthesize ackermann`` runs the search, then writes and prints this."""

from __future__ import annotations

import math
import os
import platform
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..scene import Scene
from . import ackermann as ak
from .problem import FunctionTarget, Problem
from .results import StartResult, SynthesisResult
from .robust import linearized_tolerance, robust_start
from .start import feasible
from .verify import tolerance_sensitivity, verify

__all__ = [
    "BUDGET_DEG",
    "GRADIENT_WORDS",
    "ROBUST_GAIN",
    "SIGMA",
    "SIGMAS",
    "Choice",
    "Settings",
    "choose",
    "design_dict",
    "p95",
    "report",
    "verify_runs",
]

#: nominal true max error (deg) a design may have and still be preferred for robustness
BUDGET_DEG = 0.002
#: joint noise (wheelbases) of the robustness measure: the linearised 95th percentile
SIGMA = 1e-4
#: the least relative drop of the p95 for which the polished robust design is kept
ROBUST_GAIN = 0.01
#: the noise levels reported for both shipped designs (wheelbases)
SIGMAS = (1e-5, 1e-4)
#: the noise levels of the chosen design's sampled study (report.json's
#: tolerance_sensitivity)
TOLERANCE_SIGMAS = (1e-5, 1e-4, 1e-3)
#: report.json's words for the optimizer's derivatives
GRADIENT_WORDS = {
    "exact": "exact: implicit differentiation of the whole linkage by the Rust solver (one "
    "factorisation per angle for every coordinate; the conditioning along the exact tangent)",
    "fd": "forward finite differences of the Rust scene sweeps (one per coordinate)",
}
#: the verified error the designs are compared by
KEY = "true_max_error_deg_1001"

#: a run, its verification on the true linkage ({} when infeasible) and its p95 (deg)
Row = tuple[StartResult, dict[str, Any], float]


@dataclass(frozen=True)
class Settings:
    """The options of the search the report records."""

    seed: int
    objective: str
    select: str
    budget: float
    envelope: bool
    det_margin: float
    min_link: float
    maxiter: int
    time_limit: float | None
    tolerance: bool


@dataclass(frozen=True)
class Choice:
    """The designs chosen from the verified rows: the most accurate, the least
    tolerance-sensitive within the budget (polished: ``polish`` says how), and the one
    written as design.json with why."""

    accurate: Row
    robust: Row
    within: int
    polish: dict[str, Any] | None
    chosen: Row
    why: str


def grid_1001(target: FunctionTarget) -> np.ndarray:
    """The 1001 input rotations designs are verified on."""
    return np.linspace(target.dense_in[0], target.dense_in[-1], 1001)


def p95(sc: Scene, grid: np.ndarray) -> float:
    """The linearised 95th percentile of the true max error (deg) at joint noise SIGMA."""
    try:
        return linearized_tolerance(sc, grid, ak.right_steer(grid), (SIGMA,))[0][
            "p95_max_error_deg"
        ]
    except ValueError:
        return math.inf


def verify_runs(
    truth: Problem,
    runs: Sequence[StartResult],
    grid: np.ndarray,
    progress: Callable[[], object] | None = None,
) -> list[Row]:
    """Every run (by start index) with its verification and p95 where it is feasible;
    ``progress()`` after each."""
    rows: list[Row] = []
    for r in runs:
        if r.feasible:
            v = verify(truth, r.x)
            s = p95(truth.scene(r.x), grid)
        else:
            v, s = {}, math.nan
        rows.append((r, v, s))
        if progress is not None:
            progress()
    return rows


def _polish(truth: Problem, row: Row, budget: float, grid: np.ndarray) -> tuple[Row, dict]:
    """The least tolerance-sensitive design, polished by SLSQP on the linearised p95 at
    SIGMA with its nominal error held within ``budget`` deg (robust_start); the polished
    design is kept only where it verifies (one branch, every constraint, within the
    budget on 1001 points) and its p95 is at least ROBUST_GAIN lower."""
    r, v, s = row
    deg = math.degrees(truth.target.scale)
    try:
        x, info = robust_start(truth, r.x, SIGMA, budget / deg)
    except ValueError as e:
        return row, {"kept": False, "message": str(e)}
    info["p95_start"] *= math.degrees(1.0)
    info["p95_end"] *= math.degrees(1.0)
    v2 = verify(truth, x)
    s2 = p95(truth.scene(x), grid)
    checks = {
        "one_branch": bool(v2["sweep_converged"] and v2["det_sign_changes"] == 0),
        "feasible": feasible(truth, x),
        "within_budget": bool(v2[KEY] <= budget),
        "p95_lower": bool(s2 < (1 - ROBUST_GAIN) * s),
    }
    ok = all(checks.values())
    info.update(kept=ok, checks=checks, true_max_error_deg_1001=v2[KEY], p95_deg_before=s,
                p95_deg_after=s2)  # fmt: skip
    if not ok:
        return row, info
    return (replace(r, x=x), v2, s2), info


def choose(
    truth: Problem, rows: Sequence[Row], budget: float, select: str, grid: np.ndarray
) -> Choice | None:
    """The designs of the verified rows (one branch, feasible); None when there is none.
    Ties go to the lower start index: the choice never depends on which worker finished
    first. ``select``: "robust" writes the least tolerance-sensitive design within
    ``budget`` deg (where there is one), else the most accurate."""
    good = [
        row
        for row in rows
        if row[0].feasible and row[1]["sweep_converged"] and row[1]["det_sign_changes"] == 0
    ]
    if not good:
        return None
    within = [row for row in good if row[1][KEY] <= budget]
    accurate = min(good, key=lambda row: (row[1][KEY], row[0].index))
    robust = min(within, key=lambda row: (row[2], row[0].index)) if within else accurate
    polish: dict[str, Any] | None = None
    if within:
        robust, polish = _polish(truth, robust, budget, grid)
    if select == "robust" and within:
        why = (
            f"the least tolerance-sensitive (linearised p95 at sigma {SIGMA:g}) of "
            f"{len(within)} verified designs within {budget} deg"
        )
        return Choice(accurate, robust, len(within), polish, robust, why)
    why = "the smallest true max error of the verified designs"
    return Choice(accurate, robust, len(within), polish, accurate, why)


def design_dict(truth: Problem, x: np.ndarray, seed: int, starts: int, objective: str) -> dict:
    """The design ``x`` as the scene data written to design.json: named, described (how it
    was found), in wheelbases."""
    d = truth.scene(x).to_dict()
    d["name"] = "Ackermann steering double butterfly"
    d["description"] = (
        f"{ak.space().template.description} Synthesized by planarkin synthesize ackermann "
        f"(seed {seed}, {starts} starts, objective {objective}); lengths in "
        "wheelbases, drawn straight ahead (both knuckles at 0 deg, axles collinear)."
    )
    d["units"] = "wheelbase"
    return d


def report(
    problem: Problem,
    res: SynthesisResult,
    rows: Sequence[Row],
    choice: Choice,
    sc: Scene,
    settings: Settings,
    *,
    command: str,
    options: dict[str, Any],
    versions: dict[str, str],
    stop: str,
) -> dict[str, Any]:
    """report.json's content (but its wall time): the chosen design (``sc``) verified, both
    designs of the search with their tolerance, the optimizer's words, every run, and what
    it ran with (``command``, ``options``, ``versions``, this machine)."""
    truth = replace(problem, objective="true")
    target = problem.target
    assert isinstance(target, FunctionTarget)
    grid = grid_1001(target)
    a = settings
    best, v, sens = choice.chosen
    want = ak.right_steer(grid)
    # the chosen design's sampled study (seeded: its first levels are SIGMAS's, draw for
    # draw), and each design's studies once where the accurate and the robust one coincide
    chosen_study = tolerance_sensitivity(sc, grid, want, TOLERANCE_SIGMAS) if a.tolerance else None
    studies: dict[bytes, tuple[list, list | None]] = {}

    def study(x: np.ndarray) -> tuple[list, list | None]:
        key = np.asarray(x, dtype=np.float64).tobytes()
        if key not in studies:
            s = truth.scene(x)
            sampled = None
            if chosen_study is not None:
                same = key == np.asarray(best.x, dtype=np.float64).tobytes()
                sampled = (
                    chosen_study[: len(SIGMAS)]
                    if same and TOLERANCE_SIGMAS[: len(SIGMAS)] == SIGMAS
                    else tolerance_sensitivity(s, grid, want, SIGMAS)
                )
            studies[key] = (linearized_tolerance(s, grid, want, SIGMAS), sampled)
        return studies[key]

    out: dict[str, Any] = {
        "problem": "ackermann",
        "command": command,
        "stopped": stop or None,
        # the line's words as numbers: starts run to their end, cut at the time limit
        "finished_starts": sum(1 for r in res.runs if not r.stopped),
        "stopped_starts": sum(1 for r in res.runs if r.stopped),
        "track_over_wheelbase": ak.TRACK,
        "inner_deg": ak.INNER_DEG,
        "outer_deg": ak.OUTER_DEG,
        # scipy said it converged AND the design was verified feasible (never one alone)
        "converged": bool(best.converged and v["sweep_converged"]),
        **v,
        "box": ak.BOX,
        "envelope": a.envelope,
        "in_box": bool(v["max_abs_x"] <= ak.BOX + 1e-12 and v["max_abs_y"] <= ak.BOX + 1e-12),
        "in_box_over_motion": bool(
            # to the optimizer's feasibility tolerance (1e-6 of the box)
            v["motion_max_abs_x"] <= ak.BOX + 1e-6 and v["motion_max_abs_y"] <= ak.BOX + 1e-6
        ),
        "p95_error_deg_at_sigma": {"sigma": SIGMA, "p95_max_error_deg": sens},
        # the robust design polished on the tolerance-aware objective (kept only where it
        # verified within the budget and lowered the p95)
        "robust_polish": choice.polish,
        # the most accurate and the least tolerance-sensitive designs of the search (both
        # written: design_accurate.json, design_robust.json), with their true error under
        # joint noise by linearisation (2000 draws) and by sampling (200 re-swept linkages)
        "designs": {
            name: {
                "start": row[0].index,
                "file": f"design_{name}.json",
                "true_max_error_deg_1001": row[1][KEY],
                "min_abs_conditioning": row[1]["min_abs_conditioning"],
                "motion_max_abs_x": row[1]["motion_max_abs_x"],
                "motion_max_abs_y": row[1]["motion_max_abs_y"],
                "linearized": study(row[0].x)[0],
                "sampled": study(row[0].x)[1],
            }
            for name, row in (("accurate", choice.accurate), ("robust", choice.robust))
        },
        "objective_optimized": a.objective,
        "selection": f"{a.select}: {choice.why}",
        "optimizer": {
            "method": "SLSQP (scipy), least squares then minimax polish",
            "gradients": GRADIENT_WORDS[res.gradient],
            "constraints": "branch (its lowest local minima on the 1001-angle grid), link "
            "lengths, box as drawn (bounds)"
            + (" and over the whole motion (each joint's extremes)" if a.envelope else "")
            + "; every constraint verified on the whole grid",
            "start": best.index,
            "status": best.status,
            "success": best.success,
            "message": best.message,
            "nit": best.nit,
            "phases": best.phases,
            "feasible": best.feasible,
            "converged": best.converged,
            "stopped": best.stopped or None,
        },
        "det_margin": a.det_margin,
        "min_link": a.min_link,
        "starts": res.starts,
        "samples": res.sampled,
        "screened": res.screened,
        "maxiter": a.maxiter,
        "seed": a.seed,
        "time_limit_s": a.time_limit,
        "options": options,
        "runs": [
            {
                "start": r.index,
                # as the optimizer measured it: design points and its dense grid
                "max_error_deg": r.max_error * math.degrees(problem.target.scale),
                "true_max_error_deg_1001": rv.get(KEY),
                "min_abs_conditioning": rv.get("min_abs_conditioning"),
                "p95_error_deg_at_sigma": s if r.feasible else None,
                "status": r.status,
                "success": r.success,
                "message": r.message,
                "feasible": r.feasible,
                "converged": r.converged,
                "stopped": r.stopped or None,
            }
            for r, rv, s in rows
        ],
        "versions": versions,
        "optimize_wall_s": res.wall_s,
        "cpu_count": os.cpu_count(),
        "machine": platform.machine(),
    }
    if chosen_study is not None:
        out["tolerance_sensitivity"] = chosen_study
    return out
