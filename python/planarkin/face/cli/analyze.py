"""``planarkin analyze``: a four-bar (``--links``) or any SCENE swept, summarised in a
table, written as results.csv and summary.json, and drawn (the figures listed in
``--help``). Degrees on the command line and in the outputs; radians underneath."""

from __future__ import annotations

import argparse
import functools
import math
import os
import time
from collections.abc import Iterator
from pathlib import Path
from typing import NamedTuple

import numpy as np

from ..._results import true_runs
from ..._status import Status
from ...fourbar import FourBar, Limits, Solution, Sweep
from ...fourbar.analysis import convergence_order, unreachable_spans
from ...scene import Scene, SceneSweep
from ..degrees import unwrap_deg, wrap_deg, wrapped
from ..figures import fourbar as fig
from ..figures import scene as scene_fig
from ..progress import bar
from ._common import (
    figure_arguments,
    figure_file,
    finite,
    fourbar_setup,
    json_text,
    linkage_options,
    load_scene,
    out_argument,
    quiet_argument,
    refuse_fourbar_options,
    scene_angles,
    scene_argument,
    scene_predictor,
    table,
    warm_median,
    write_csv,
)

#: The seeds' convergence study: theta2 = 45 deg from the cold guess (80, 100) deg.
NEWTON_THETA2_DEG = 45.0
NEWTON_GUESS_DEG = {"open": (80.0, 100.0), "crossed": (-80.0, -100.0)}

RESULTS_CSV = "results.csv"
SUMMARY_JSON = "summary.json"
#: Figure file -> what it shows (listed in ``planarkin analyze --help``; drawn by ``_figures``).
FIGURES = {
    "figure_a_position_analysis.png": "theta3 and theta4 against theta2 (separate panels)",
    "figure_combined_positions.png": "theta3 and theta4 on one axes",
    "figure_b_convergence.png": "Newton residual per iteration (at --newton-at, 45 deg)",
    "figure_c_velocity.png": "angular velocities omega3, omega4",
    "figure_d_acceleration.png": "angular accelerations alpha3, alpha4",
    "figure_e_transmission_angle.png": "transmission angle and branch indicator",
    "figure_f_coupler_curve.png": "coupler-point curve",
    "figure_g_linkage.png": "the linkage drawn at several crank angles",
}
#: The figures of ``planarkin analyze SCENE``.
SCENE_FIGURES = {
    "scene_linkage.png": "the linkage as drawn, every point named, beside several poses",
    "scene_conditioning.png": "signed conditioning of each step and of the whole solve",
    "scene_tracers.png": "tracer point coordinates and speeds (only if it has tracers)",
}
#: CSV header, units in brackets; one row per crank angle. Angles in degrees as computed
#: (wrapped to (-180, 180]), NaN where the status is not CONVERGED.
CSV_COLUMNS = (
    "theta2 [deg]",
    "theta3 [deg]",
    "theta4 [deg]",
    "status [code]",
    "status_name",
    "nit [-]",
    "residual [-]",
    "closed_form_deviation [deg]",
    "omega3 [rad/s]",
    "omega4 [rad/s]",
    "alpha3 [rad/s^2]",
    "alpha4 [rad/s^2]",
    "transmission_angle [deg]",
    "branch_indicator [-]",
    "coupler_x [length]",
    "coupler_y [length]",
)

_FILES = {
    RESULTS_CSV: "one row per input angle, every computed column (units in the header)",
    SUMMARY_JSON: "the summary table as data (also on stdout with --json)",
    **FIGURES,
}


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Registers ``analyze``."""
    a = sub.add_parser(
        "analyze",
        parents=[linkage_options(rpm=True)],
        help="sweep, summary table, figures, CSV and JSON",
        description="Solve the sweep of a four-bar (--links) or of a SCENE, print a summary\n"
        f"table and write figures (--format: png, svg or pdf), {RESULTS_CSV} and "
        f"{SUMMARY_JSON} into the output folder.",
        epilog="files written (four-bar):\n"
        + "".join(f"  {k:34}{v}\n" for k, v in _FILES.items())
        + "files written (SCENE): the CSV and JSON as above, and\n"
        + "".join(f"  {k:34}{v}\n" for k, v in SCENE_FIGURES.items())
        + "\nAngles are in degrees, in (-180, 180]; omega in rad/s, alpha in rad/s^2; lengths "
        "in the unit of --links (or the scene's 'units'); the input turns at --rpm.",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    scene_argument(a, "analyze", "--newton-at")
    out_argument(a)
    figure_arguments(a, 300.0)
    quiet_argument(a)
    a.add_argument(
        "--newton-at",
        type=float,
        metavar="DEG",
        help="crank angle of the four-bar's convergence study, solved from the textbook's cold "
        f"guess (80, 100) deg, mirrored for crossed (default: {NEWTON_THETA2_DEG:g})",
    )
    a.add_argument("--no-figures", action="store_true", help="write the CSV and JSON only")
    a.add_argument(
        "--json", action="store_true", help="print the JSON summary to stdout instead of the table"
    )
    a.set_defaults(func=run)
    return a


def run(args: argparse.Namespace) -> int:
    """``planarkin analyze [SCENE]``; returns the exit code."""
    return _run_scene(args) if args.scene is not None else _run_fourbar(args)


# --- the four-bar ------------------------------------------------------------------------


def _setup(args: argparse.Namespace) -> tuple[FourBar, np.ndarray]:
    """The linkage and the crank angles, the four-bar options' defaults filled in."""
    if args.newton_at is None:
        args.newton_at = NEWTON_THETA2_DEG
    return fourbar_setup(args)


def _max_abs(x: object) -> float | None:
    """Largest finite |x|, or None when there is none."""
    a = np.abs(np.asarray(x, dtype=np.float64))
    a = a[np.isfinite(a)]
    return float(a.max()) if a.size else None


def _wrap(x: np.ndarray) -> np.ndarray:
    return np.remainder(x + math.pi, math.tau) - math.pi


class Analysis(NamedTuple):
    """What ``planarkin analyze`` computes: the JSON summary, the CSV columns, and the
    objects the figures are drawn from."""

    summary: dict
    columns: dict
    sweep: Sweep
    limits: Limits
    newton: Solution


def _frame(sweep: Sweep, theta2: object) -> list[float]:
    """Crank angles (radians, any turn) as sorted degrees in the sweep's frame
    [start, start + 360)."""
    t0 = float(sweep.theta2[0]) if len(sweep.theta2) else 0.0
    t = np.ravel(np.asarray(theta2, dtype=np.float64))
    return sorted(math.degrees(t0 + v) for v in np.remainder(t - t0, math.tau))


def _extremes(sweep: Sweep, y_deg: np.ndarray) -> dict:
    """min/max of ``y_deg`` over the sweep with the crank angles where they occur; the
    repeated last pose of a sweep that closes the circle is left out."""
    y = np.asarray(y_deg, dtype=np.float64)
    t2 = sweep.theta2
    if len(t2) > 1 and math.isclose(abs(t2[-1] - t2[0]), math.tau):
        y, t2 = y[:-1], t2[:-1]
    if not np.isfinite(y).any():
        return dict.fromkeys(("min", "max", "span", "theta2_at_min", "theta2_at_max"))
    i, j = np.nanargmin(y), np.nanargmax(y)
    return {
        "min": float(y[i]),
        "max": float(y[j]),
        "span": float(y[j] - y[i]),
        "theta2_at_min": math.degrees(t2[i]),
        "theta2_at_max": math.degrees(t2[j]),
    }


def analyze(fb: FourBar, sweep: Sweep, args: argparse.Namespace) -> Analysis:
    """Everything the table, the JSON and the CSV report, from the sweep and the API."""
    t2, t3, t4, ok = sweep.theta2, sweep.theta3, sweep.theta4, sweep.success
    s, g, limits = sweep.summary(), fb.grashof(), fb.limits(sweep.mode)
    cf3, cf4 = (np.asarray(v) for v in fb.closed_form(t2, sweep.mode))
    dev = np.degrees(np.fmax(np.abs(_wrap(t3 - cf3)), np.abs(_wrap(t4 - cf4))))
    dev[~ok] = np.nan
    mu = np.degrees(np.asarray(FourBar.transmission_angle(t3, t4)))
    p, delta = args.coupler[0], math.radians(args.coupler[1])
    px, py = (np.asarray(v) for v in fb.coupler_curve(sweep, p, delta))
    guess = NEWTON_GUESS_DEG[sweep.mode]
    sol = fb.solve(
        math.radians(args.newton_at),
        mode=sweep.mode,
        guess=(math.radians(guess[0]), math.radians(guess[1])),
        tol=args.tol,
        max_iter=args.max_iter,
        history=True,
    )
    assert sol.history is not None  # asked for with history=True
    r1, r2, r3, r4 = fb.lengths
    rocker = None
    if limits.rocker_min is not None and limits.rocker_max is not None:
        lo = math.degrees(limits.rocker_min)
        assert limits.rocker_swing is not None  # set whenever rocker_min and rocker_max are
        swing = math.degrees(limits.rocker_swing)
        rocker = {
            "min": lo,
            "max": lo + swing,  # counter-clockwise from min, so max >= min
            "swing": swing,
            "theta2_at_min": _frame(sweep, limits.rocker_min_theta2)[0],
            "theta2_at_max": _frame(sweep, limits.rocker_max_theta2)[0],
        }
    closes = s.converged == s.points > 1 and math.isclose(abs(t2[-1] - t2[0]), math.tau)
    theta3: dict[str, object] = {}
    theta4: dict[str, object] = {}
    for d, t in ((theta3, t3), (theta4, t4)):
        u = unwrap_deg(t)
        d.update(_extremes(sweep, u))
        # over a full crank turn a link that turns fully comes back one turn further on
        d["full_rotation"] = bool(closes and abs(u[-1] - u[0]) > 180)
    unsolved = {
        Status(int(c)).name: [math.degrees(v) for v in t2[sweep.status == c]]
        for c in np.unique(sweep.status)
        if c not in (Status.CONVERGED, Status.NOT_ASSEMBLABLE)
    }
    summary = {
        "linkage": {"r1": r1, "r2": r2, "r3": r3, "r4": r4, "mode": sweep.mode},
        "grashof": {k: getattr(g, k) for k in ("condition", "barker", "kind", "description")},
        "options": {
            "theta2_start_deg": math.degrees(t2[0]),
            "theta2_stop_deg": math.degrees(t2[-1]),
            "step_deg": args.step,
            "tol": args.tol,
            "max_iter": args.max_iter,
            "predictor": args.predictor,
            "rpm": args.rpm,
            "omega2_rad_s": sweep.omega2,
            "alpha2_rad_s2": sweep.alpha2,
            "coupler_p": p,
            "coupler_delta_deg": args.coupler[1],
        },
        "sweep": {
            "points": s.points,
            "converged": s.converged,
            "success_rate": s.success_rate,
            "nit_total": s.nit_total,
            "nit_mean": s.nit_mean,
            "residual_max": s.residual_max,
            "statuses": s.statuses,
        },
        "closed_form_max_deviation_deg": _max_abs(dev),
        "rocker_deg": rocker,
        "theta3_deg": theta3,
        "theta4_deg": theta4,
        "transmission_angle_deg": _extremes(sweep, mu),
        "peak_abs": {
            name: _max_abs(getattr(sweep, attr))
            for name, attr in (
                ("omega3_rad_s", "omega3"),
                ("omega4_rad_s", "omega4"),
                ("alpha3_rad_s2", "alpha3"),
                ("alpha4_rad_s2", "alpha4"),
            )
        },
        "limits": {
            "full_rotation": limits.full_rotation,
            "toggles_deg": _frame(sweep, limits.toggles),
            "dead_points_deg": _frame(sweep, limits.dead_points),
            "assemblable_intervals_deg": [
                [math.degrees(a), math.degrees(b)] for a, b in limits.intervals
            ],
        },
        "unreachable_spans_deg": [
            [math.degrees(a), math.degrees(b)] for a, b in unreachable_spans(sweep, limits)
        ],
        "unsolved_deg": unsolved,
        "newton": {
            "theta2_deg": args.newton_at,
            "guess_deg": list(guess),
            "status": sol.status.name,
            "nit": sol.nit,
            "residual": sol.residual,
            "history": sol.history.tolist(),
            "order": convergence_order(sol.history),
        },
    }
    columns = {
        "theta2 [deg]": np.degrees(t2),
        "theta3 [deg]": np.degrees(t3),
        "theta4 [deg]": np.degrees(t4),
        "status [code]": sweep.status,
        "status_name": [Status(int(c)).name for c in sweep.status],
        "nit [-]": sweep.nit,
        "residual [-]": sweep.residual,
        "closed_form_deviation [deg]": dev,
        "omega3 [rad/s]": sweep.omega3,
        "omega4 [rad/s]": sweep.omega4,
        "alpha3 [rad/s^2]": sweep.alpha3,
        "alpha4 [rad/s^2]": sweep.alpha4,
        "transmission_angle [deg]": mu,
        "branch_indicator [-]": FourBar.branch_indicator(t3, t4),
        "coupler_x [length]": px,
        "coupler_y [length]": py,
    }
    assert tuple(columns) == CSV_COLUMNS
    return Analysis(summary, columns, sweep, limits, sol)


def _figures(res: Analysis, args: argparse.Namespace) -> dict:
    """File name -> a function drawing that figure."""
    sweep, limits = res.sweep, res.limits
    p, delta = args.coupler[0], math.radians(args.coupler[1])
    guess_deg = NEWTON_GUESS_DEG[sweep.mode]
    guess = (math.radians(guess_deg[0]), math.radians(guess_deg[1]))
    builders = {
        "figure_a_position_analysis.png": lambda: fig.position(sweep, limits=limits),
        "figure_combined_positions.png": lambda: fig.positions_combined(sweep, limits=limits),
        "figure_b_convergence.png": lambda: fig.convergence(res.newton, guess=guess, tol=args.tol),
        "figure_c_velocity.png": lambda: fig.velocity(sweep, limits=limits),
        "figure_d_acceleration.png": lambda: fig.acceleration(sweep, limits=limits),
        "figure_e_transmission_angle.png": lambda: fig.transmission(sweep, limits=limits),
        "figure_f_coupler_curve.png": lambda: fig.coupler_curve(sweep, p, delta, limits=limits),
        "figure_g_linkage.png": lambda: fig.linkage(sweep, p, delta),
    }
    assert builders.keys() == FIGURES.keys()
    return builders


def _duration(s: float) -> str:
    """Seconds in the unit that reads best: 41.2 us, 3.27 ms, 1.52 s."""
    for unit, f in (("s", 1.0), ("ms", 1e-3)):
        if s >= f:
            return f"{s / f:.3g} {unit}"
    return f"{s / 1e-6:.3g} us"


def _angles(values: list[float], limit: int = 6) -> str:
    s = ", ".join(f"{v:.6g}" for v in values[:limit])
    return s + (f", ... ({len(values)} in all)" if len(values) > limit else "")


def format_table(summary: dict) -> str:
    """The summary table that ``planarkin analyze`` prints (ASCII only)."""
    L, g, o, sw = summary["linkage"], summary["grashof"], summary["options"], summary["sweep"]
    lim, spans = summary["limits"], summary["unreachable_spans_deg"]
    rows: list[tuple[str, str]] = []

    def add(key: str, value: str) -> None:
        rows.append((key, value))

    add(
        "linkage",
        f"r1 = {L['r1']:g} (ground), r2 = {L['r2']:g} (crank), r3 = {L['r3']:g} "
        f"(coupler), r4 = {L['r4']:g} (rocker); {L['mode']} mode",
    )
    add("Grashof / Barker", f"{g['condition']}, {g['barker']} {g['kind']}: {g['description']}")
    add(
        "crank sweep",
        f"{o['theta2_start_deg']:g} to {o['theta2_stop_deg']:g} deg in "
        f"{o['step_deg']:g} deg steps; {o['rpm']:g} rpm (omega2 = {o['omega2_rad_s']:.4f} rad/s, "
        "alpha2 = 0)",
    )
    counts = ", ".join(f"{k} {v}" for k, v in sw["statuses"].items())
    add("points solved", f"{sw['converged']} / {sw['points']} ({counts})")
    add(
        "iterations",
        f"total {sw['nit_total']}, mean {sw['nit_mean']:.3f} per point "
        f"({o['predictor']} predictor, tol {o['tol']:g})",
    )
    if sw["converged"] == 0:
        add("limit positions", "none: the linkage cannot be assembled at any crank angle")
    else:
        add("max residual", f"{sw['residual_max']:.3g} (max(|f1|, |f2|) / longest link)")
        add("max |sweep - closed form|", f"{summary['closed_form_max_deviation_deg']:.3g} deg")

    r, t4 = summary["rocker_deg"], summary["theta4_deg"]
    if r is not None:
        add(
            "rocker swing (theta4)",
            f"{r['swing']:.3f} deg: from {r['min']:.3f} deg at theta2 = "
            f"{r['theta2_at_min']:.3f} to {r['max']:.3f} deg at theta2 = {r['theta2_at_max']:.3f}",
        )
    elif t4["full_rotation"]:
        add("rocker swing (theta4)", "the output link turns fully round")
    elif t4["min"] is not None:
        add("rocker swing (theta4)", f"{t4['min']:.3f} to {t4['max']:.3f} deg (sampled)")
    t3 = summary["theta3_deg"]
    if t3["full_rotation"]:
        add("coupler range (theta3)", "the coupler turns fully round")
    elif t3["min"] is not None:
        add(
            "coupler range (theta3)",
            f"{t3['min']:.3f} to {t3['max']:.3f} deg ({t3['span']:.3f} deg)",
        )
    mu = summary["transmission_angle_deg"]
    if mu["min"] is not None:
        add(
            "transmission angle",
            f"{mu['min']:.3f} to {mu['max']:.3f} deg "
            f"(minimum at theta2 = {mu['theta2_at_min']:g} deg)",
        )
    if lim["toggles_deg"]:
        add(
            "limit positions",
            f"crank toggles at theta2 = {_angles(lim['toggles_deg'])} deg: "
            "the crank cannot turn fully round",
        )
    elif lim["full_rotation"]:
        add("limit positions", "none: the crank turns fully round")
    other = [d for d in lim["dead_points_deg"] if d not in lim["toggles_deg"]]
    if other:
        add("dead points", f"theta2 = {_angles(other)} deg (change points: the two modes meet)")
    add(
        "unreachable spans",
        "none"
        if not spans
        else "; ".join(f"theta2 {a:.3f} to {b:.3f} deg" for a, b in spans)
        + f" ({sw['statuses'].get('NOT_ASSEMBLABLE', 0)} points not assemblable, shaded)",
    )
    for name, where in summary["unsolved_deg"].items():
        add(
            f"{name.lower().replace('_', ' ')} points",
            f"theta2 = {_angles(where)} deg ({len(where)} points, marked on the figures)",
        )
    pk = summary["peak_abs"]
    if pk["omega4_rad_s"] is not None:
        add("peak |omega3|, |omega4|", f"{pk['omega3_rad_s']:.4g}, {pk['omega4_rad_s']:.4g} rad/s")
    if pk["alpha4_rad_s2"] is not None:
        add(
            "peak |alpha3|, |alpha4|",
            f"{pk['alpha3_rad_s2']:.4g}, {pk['alpha4_rad_s2']:.4g} rad/s^2",
        )
    n = summary["newton"]
    order = f"{n['order']:.2f}" if n["order"] is not None and math.isfinite(n["order"]) else "n/a"
    add(
        f"Newton at theta2 = {n['theta2_deg']:g}",
        f"{n['status'].lower().replace('_', ' ')} in {n['nit']} "
        f"iterations from the cold guess ({n['guess_deg'][0]:g}, {n['guess_deg'][1]:g}) deg; "
        f"order of convergence {order}",
    )
    if "wall_time_s" in summary:
        w = summary["wall_time_s"]
        add(
            "wall time",
            f"sweep {_duration(w['sweep'])} (Rust, median of {w['sweep_runs']} warm runs); "
            f"total {w['total']:.2f} s",
        )
    if "files" in summary:
        figs = [f for f in summary["files"] if f.startswith("figure_")]
        data = [f for f in summary["files"] if not f.startswith("figure_")]
        kind = figs[0].rsplit(".", 1)[-1].upper() if figs else ""
        what = ", ".join(data) + (f" and {len(figs)} figures ({kind})" if figs else "")
        add("written", f"{summary['out']}{os.sep}: {what}")
    head = f"planarkin analyze: four-bar ({L['r1']:g}, {L['r2']:g}, {L['r3']:g}, {L['r4']:g})"
    return head + "\n" + table(rows)


def _run_fourbar(args: argparse.Namespace) -> int:
    """``planarkin analyze`` of a four-bar."""
    t_start = time.perf_counter()
    fb, theta2 = _setup(args)

    def solve() -> Sweep:
        return fb.sweep(
            theta2,
            mode=args.mode,
            tol=args.tol,
            max_iter=args.max_iter,
            predictor=args.predictor,
            omega2=args.rpm * math.tau / 60,
            alpha2=0.0,
        )

    sweep = solve()
    t_sweep, n_runs = warm_median(solve)
    res = analyze(fb, sweep, args)

    out: Path = args.out
    out.mkdir(parents=True, exist_ok=True)
    write_csv(out / RESULTS_CSV, res.columns, zip(*res.columns.values(), strict=True))
    files = [RESULTS_CSV, SUMMARY_JSON]
    if not args.no_figures:
        builders = _figures(res, args)
        with bar(len(builders), "analyze: figures", quiet=args.quiet, unit="figure") as b:
            for name, draw in builders.items():
                name = figure_file(name, args.format)
                draw().savefig(out / name, dpi=args.dpi)
                files.append(name)
                b.update()
    summary = res.summary
    summary["wall_time_s"] = {
        "sweep": t_sweep,
        "sweep_runs": n_runs,
        "total": time.perf_counter() - t_start,
    }
    summary["out"] = str(out)
    summary["files"] = files
    text = json_text(summary)
    (out / SUMMARY_JSON).write_text(text + "\n", encoding="utf-8")
    print(text if args.json else format_table(summary))
    return 0


# --- a scene ------------------------------------------------------------------------------


def _none(x: float) -> float | None:
    return x if math.isfinite(x) else None


def scene_summary(scene: Scene, sw: SceneSweep, wall: dict[str, float]) -> dict:
    """The summary table as data (angles in degrees, in (-180, 180])."""
    plan, limit = sw.plan, sw.limit
    assert plan is not None and limit is not None  # a kernel sweep has both
    ok = sw.success
    angle = sw.input == "angle"  # else a linear input: displacements, as they are
    deg = wrap_deg(sw.theta) if angle else sw.theta
    absdet = np.abs(sw.det[ok])
    # where the motion stops: the edges of the solved spans (to the sweep's resolution)
    edges = []
    for a, b in true_runs(ok):
        if a > 0:
            edges.append({"deg": float(deg[a]), "det": float(sw.det[a]), "side": "start"})
        if b < len(ok):
            edges.append({"deg": float(deg[b - 1]), "det": float(sw.det[b - 1]), "side": "end"})
    dead = sorted(
        {round(wrapped(float(v)) if angle else float(v), 9) for v in limit if math.isfinite(v)}
    )
    omega = sw.omega
    unit = scene.units or "length"
    linear = scene.input_kind == "displacement"
    return {
        "scene": scene.name,
        "description": scene.description,
        "units": scene.units,
        "links": len(scene.links),
        "joints": sum(len(v) - 1 for v in scene.joints.values()),
        "points": len(scene.points),
        "mobility": scene.mobility,
        "input": scene.to_dict()["input"],
        "input_kind": scene.input_kind,
        "drawn_input_deg": wrapped(scene.input_angle) if linear is False else None,
        "stroke": None if linear is False else [float(sw.theta[0]), float(sw.theta[-1])],
        "input_speed": None
        if omega is None
        else {
            "omega_rad_s": None if linear else omega,
            "rpm": None if linear else scene_fig.rpm(omega),
            "speed": f"{omega:g} {unit}/s" if linear else None,
            "constant": True,
            "velocity_unit": f"{unit}/s",
            "acceleration_unit": f"{unit}/s^2",
        },
        "outputs": list(plan.outputs) if plan.outputs is not None else "all",
        "plan": [
            {"kind": s.kind, "points": list(s.points), "unknowns": list(s.unknowns)} for s in plan
        ],
        "points_solved": list(sw.points),
        "angles": len(sw),
        "converged": int(ok.sum()),
        "statuses": sw.statuses(),
        "nit_total": int(sw.nit.sum()),
        "nit_mean_converged": _none(float(sw.nit[ok].mean())) if ok.any() else None,
        "conditioning_min": float(absdet.min()) if ok.any() else None,
        "conditioning_max": float(absdet.max()) if ok.any() else None,
        "motion_stops_deg": edges,
        "dead_points_deg": dead,
        "wall_time_s": wall,
    }


def scene_table(s: dict) -> str:
    rows = [
        ("scene", s["scene"] or "(unnamed)"),
        ("links / joints / points", f"{s['links']} / {s['joints']} / {s['points']}"),
        ("mobility (Gruebler)", s["mobility"]),
    ]
    if s["input_kind"] == "displacement":
        ((kind, name),) = s["input"].items()
        lo, hi = s["stroke"]
        rows.append(("input", f"displacement along {kind} {name!r} from the drawn pose, "
                              f"stroke {lo:.6g} to {hi:.6g} (its dead points)"))  # fmt: skip
    else:
        rows.append(("input", f"{s['input']['link']} at {s['input']['pivot']}, drawn at "
                              f"{s['drawn_input_deg']:.3f} deg"))  # fmt: skip
    speed = s["input_speed"]
    if speed is not None and speed["speed"] is not None:
        rows.append(("input speed", f"{speed['speed']} (constant); velocities in "
                                    f"{speed['velocity_unit']}"))  # fmt: skip
    elif speed is not None:
        rows.append((
            "input speed",
            f"omega = {speed['omega_rad_s']:.4f} rad/s ({speed['rpm']:g} rpm, constant); "
            f"velocities in {speed['velocity_unit']}",
        ))  # fmt: skip
    rows.append(("outputs", ", ".join(s["outputs"]) if isinstance(s["outputs"], list) else "all"))
    for i, st in enumerate(s["plan"]):
        rows.append((f"plan step {i + 1}", f"{st['kind']}: {', '.join(st['points'])} "
                     f"(angles of {', '.join(st['unknowns'])})"))  # fmt: skip
    what = "input angles" if s["input_kind"] == "angle" else "input values"
    rows += [
        ("converged", f"{s['converged']} of {s['angles']} {what}"),
        ("statuses", ", ".join(f"{k}={v}" for k, v in s["statuses"].items())),
        (
            "Newton iterations",
            f"{s['nit_total']} total"
            + (
                f", {s['nit_mean_converged']:.3f} per solved {what.removeprefix('input ')[:-1]}"
                if s["nit_mean_converged"] is not None
                else ""
            ),
        ),  # fmt: skip
    ]
    if s["conditioning_min"] is not None:
        rows.append(
            ("|conditioning|", f"{s['conditioning_min']:.3g} .. {s['conditioning_max']:.3g}")
        )
    # a linear input's values are displacements (the keys keep their names in the JSON)
    unit = "deg" if s["input_kind"] == "angle" else (s["units"] or "length")
    if s["dead_points_deg"]:
        dead = ", ".join(f"{v:.4f}" for v in s["dead_points_deg"])
        rows.append((f"dead points met ({unit})", dead + " (the input must reverse there)"))
    if s["motion_stops_deg"]:
        stops = ", ".join(f"{e['deg']:.1f}" for e in s["motion_stops_deg"])
        rows.append((f"motion stops near ({unit})", stops))
    return table(rows)


def scene_columns(sw: SceneSweep, units: str | None) -> list[str]:
    """The CSV header of ``analyze SCENE``, units in brackets: the input angle, statuses,
    each point's position (and velocity, acceleration when computed), each link's angle
    (and angular velocity, acceleration)."""
    u = units or "length"
    first = "theta [deg]" if sw.input == "angle" else f"s [{u}]"  # a linear input's displacement
    cols = [first, "status [code]", "status_name", "nit [-]", "det [-]"]
    for n in sw.points:
        cols += [f"{n}_x [{u}]", f"{n}_y [{u}]"]
        if sw.velocities is not None:
            cols += [f"{n}_vx [{u}/s]", f"{n}_vy [{u}/s]"]
        if sw.accelerations is not None:
            cols += [f"{n}_ax [{u}/s^2]", f"{n}_ay [{u}/s^2]"]
    for n in sw.angles:
        cols += [f"{n}_angle [deg]"]
        if sw.angular_velocities is not None:
            cols += [f"{n}_omega [rad/s]"]
        if sw.angular_accelerations is not None:
            cols += [f"{n}_alpha [rad/s^2]"]
    return cols


def _write_scene_csv(path: Path, sw: SceneSweep, units: str | None) -> None:
    cols = scene_columns(sw, units)
    per_point = [a for a in (sw.coords, sw.velocity_array, sw.acceleration_array) if a is not None]
    per_link = [
        a for a in (sw.angular_velocity_array, sw.angular_acceleration_array) if a is not None
    ]
    theta = wrap_deg(sw.theta) if sw.input == "angle" else sw.theta
    link_deg = wrap_deg(sw.angle_array)

    def rows() -> Iterator[list[object]]:
        for i in range(len(sw)):
            code = int(sw.status[i])
            row: list[object] = [
                float(theta[i]), code, Status(code).name, int(sw.nit[i]), float(sw.det[i]),
            ]  # fmt: skip
            for j in range(len(sw.point_names)):
                for a in per_point:
                    row += [float(a[i, j, 0]), float(a[i, j, 1])]
            for j in range(len(sw.link_names)):
                row.append(float(link_deg[i, j]))
                row += [float(a[i, j]) for a in per_link]
            yield row

    write_csv(path, cols, rows())


def _run_scene(args: argparse.Namespace) -> int:
    """``planarkin analyze SCENE``."""
    refuse_fourbar_options(args, [("newton_at", "--newton-at")])
    t_start = time.perf_counter()
    sc = load_scene(args.scene)
    theta = scene_angles(sc, args.step)
    finite("--rpm", args.rpm)
    finite("--dpi", args.dpi, positive=True)
    # a linear input is driven at 1 length unit per second (--rpm is for cranks)
    omega = args.rpm * math.tau / 60 if sc.input_kind == "angle" else 1.0
    figures = {} if args.no_figures else SCENE_FIGURES
    sweep = functools.partial(
        sc.sweep, theta, tol=args.tol, max_iter=args.max_iter, omega=omega,
        predictor=scene_predictor(args),
    )  # fmt: skip
    with bar(3 + len(figures), "analyze", quiet=args.quiet) as b:
        sw = sweep()
        b.update()
        # timed warm, as the four-bar's sweep is (the first call also compiled the plan)
        t_sweep, n_runs = warm_median(sweep, runs=5)
        b.update()
        out: Path = args.out
        out.mkdir(parents=True, exist_ok=True)
        _write_scene_csv(out / RESULTS_CSV, sw, sc.units)
        b.update()
        files = [RESULTS_CSV, SUMMARY_JSON]
        skipped = []
        if figures:
            # the figures draw every link: sweep the whole scene for them
            whole = sweep(outputs="all")
            for name, draw, data in (
                ("scene_linkage.png", scene_fig.linkage, whole),
                ("scene_conditioning.png", scene_fig.conditioning, sw),
                ("scene_tracers.png", scene_fig.tracers, sw),
            ):
                drawn = draw(sc, data)
                if drawn is None:
                    skipped.append(name)
                else:
                    name = figure_file(name, args.format)
                    drawn.savefig(out / name, dpi=args.dpi)
                    files.append(name)
                b.update()
    summary = scene_summary(
        sc, sw, {"sweep_median": t_sweep, "total": time.perf_counter() - t_start}
    )
    summary["files"] = files
    (out / SUMMARY_JSON).write_text(json_text(summary) + "\n", encoding="utf-8")
    if args.json:
        print(json_text(summary))
    else:
        print(f"planarkin analyze: {sc.name or args.scene}")
        print(scene_table(summary))
        ms = 1e3 * summary["wall_time_s"]["sweep_median"]
        print(f"  sweep {ms:.3f} ms (median of {n_runs} warm runs)")
        print(f"  wrote {', '.join(str(out / f) for f in files)}")
        if skipped:
            print("  no tracer figure: the scene has no tracer point (a point on one link only)")
    return 0
