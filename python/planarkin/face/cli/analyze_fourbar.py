"""``planarkin analyze`` of a four-bar (``--links``): the sweep, reported by
:mod:`planarkin.fourbar.report`, printed as a table, written as results.csv and
summary.json, and drawn (:data:`FIGURES`)."""

from __future__ import annotations

import argparse
import math
import os
import time
from pathlib import Path

import numpy as np

from ...fourbar import FourBar, Sweep
from ...fourbar.report import NEWTON_THETA2_DEG, Report, report
from ..figures import fourbar as fig
from ..progress import bar
from ._common import (
    RESULTS_CSV,
    SUMMARY_JSON,
    figure_file,
    fourbar_setup,
    json_text,
    table,
    warm_median,
    write_csv,
)

#: Figure file -> what it shows (listed in ``planarkin analyze --help``; drawn by ``figures``).
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


def setup(args: argparse.Namespace) -> tuple[FourBar, np.ndarray]:
    """The linkage and the crank angles, the four-bar options' defaults filled in."""
    if args.newton_at is None:
        args.newton_at = NEWTON_THETA2_DEG
    return fourbar_setup(args)


def analyze(fb: FourBar, sweep: Sweep, args: argparse.Namespace) -> Report:
    """The report of ``sweep`` with the command's options."""
    return report(
        fb,
        sweep,
        step_deg=args.step,
        tol=args.tol,
        max_iter=args.max_iter,
        predictor=args.predictor,
        rpm=args.rpm,
        coupler=args.coupler,
        newton_at_deg=args.newton_at,
    )


def figures(res: Report, args: argparse.Namespace) -> dict:
    """File name -> a function drawing that figure."""
    sweep, limits = res.sweep, res.limits
    p, delta = args.coupler[0], math.radians(args.coupler[1])
    builders = {
        "figure_a_position_analysis.png": lambda: fig.position(sweep, limits=limits),
        "figure_combined_positions.png": lambda: fig.positions_combined(sweep, limits=limits),
        "figure_b_convergence.png": lambda: fig.convergence(
            res.newton, guess=res.guess, tol=args.tol
        ),
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


def run(args: argparse.Namespace) -> int:
    """``planarkin analyze`` of a four-bar; returns the exit code."""
    t_start = time.perf_counter()
    fb, theta2 = setup(args)

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
        builders = figures(res, args)
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
