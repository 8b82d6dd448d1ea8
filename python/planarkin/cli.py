"""The ``planarkin`` command. ``analyze`` solves a crank sweep and writes a summary table,
the figures, a CSV of every crank angle and a JSON summary; ``animate`` writes the linkage
in motion as a GIF and a self-contained HTML page; ``tradeoff`` measures speed/accuracy.

Degrees on the command line and in the outputs; the API underneath works in radians.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import os
import sys
import time
from pathlib import Path
from typing import NamedTuple

import numpy as np

from . import plot, tradeoff
from ._types import MODES, PREDICTORS, Limits, Solution, Status, Sweep
from .fourbar import FourBar

#: The seeds' linkage: ground r1, crank r2, coupler r3, rocker r4.
DEFAULT_LINKS = (6.0, 2.0, 5.0, 5.0)
#: Coupler point: distance from the crank pin A, angle from the line A-B (degrees).
DEFAULT_COUPLER = (3.0, 30.0)
#: The seeds' convergence study: theta2 = 45 deg from the cold guess (80, 100) deg.
NEWTON_THETA2_DEG = 45.0
NEWTON_GUESS_DEG = {"open": (80.0, 100.0), "crossed": (-80.0, -100.0)}

RESULTS_CSV = "results.csv"
SUMMARY_JSON = "summary.json"
ANIMATION_GIF = "linkage.gif"
ANIMATION_HTML = "linkage.html"
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
    RESULTS_CSV: "one row per crank angle, every computed column (units in the header)",
    SUMMARY_JSON: "the summary table as data (also on stdout with --json)",
    **FIGURES,
}


class _Parser(argparse.ArgumentParser):
    """argparse with a one-line error (exit code 2) instead of usage + error."""

    def error(self, message: str) -> None:  # type: ignore[override]
        self.exit(2, f"planarkin: error: {message} (see '{self.prog} --help')\n")


def _linkage_options() -> _Parser:
    # a _Parser like the subcommands it is a parent of (argparse only copies its arguments)
    p = _Parser(add_help=False)
    g = p.add_argument_group("linkage and sweep")
    g.add_argument(
        "--links",
        nargs=4,
        type=float,
        metavar=("R1", "R2", "R3", "R4"),
        default=DEFAULT_LINKS,
        help="link lengths: ground, crank (input), coupler, rocker "
        "(default: %(default)s, the seeds' linkage)",
    )
    g.add_argument(
        "--mode", choices=MODES, default="open", help="assembly mode (default: %(default)s)"
    )
    g.add_argument(
        "--step",
        type=float,
        default=1.0,
        metavar="DEG",
        help="crank-angle step; the sweep runs 0..360 deg (default: %(default)s)",
    )
    g.add_argument(
        "--tol",
        type=float,
        default=1e-9,
        help="Newton tolerance on max(|f1|, |f2|) / longest link and on the next Newton "
        "correction in rad (default: %(default)s)",
    )
    g.add_argument(
        "--max-iter",
        type=int,
        default=100,
        metavar="N",
        help="Newton iterations per crank angle (default: %(default)s)",
    )
    g.add_argument(
        "--predictor",
        choices=PREDICTORS,
        default="quadratic",
        help="continuation predictor along the sweep (default: %(default)s)",
    )
    g.add_argument(
        "--rpm",
        type=float,
        default=100.0,
        help="constant crank speed, rev/min; omega2 = rpm * 2 pi / 60 rad/s, "
        "alpha2 = 0 (default: %(default)s)",
    )
    g.add_argument(
        "--coupler",
        nargs=2,
        type=float,
        metavar=("P", "DELTA"),
        default=DEFAULT_COUPLER,
        help="coupler point at distance P from the crank pin A, at DELTA deg from "
        "the coupler line A-B (default: %(default)s)",
    )
    return p


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="planarkin",
        description="Planar four-bar linkage kinematics (Rust core). Run 'planarkin analyze' "
        "for the seeds' linkage, or give your own with --links.",
    )
    from . import __version__

    parser.add_argument("--version", action="version", version=f"planarkin {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    common = _linkage_options()

    a = sub.add_parser(
        "analyze",
        parents=[common],
        help="sweep, summary table, figures, CSV and JSON",
        description="Solve the crank sweep, print a summary table and write figures "
        f"(PNG), {RESULTS_CSV} and {SUMMARY_JSON} into the output folder.",
        epilog="files written:\n"
        + "".join(f"  {k:34}{v}\n" for k, v in _FILES.items())
        + "\nAngles are in degrees; omega in rad/s, alpha in rad/s^2; lengths in the unit of "
        "--links.",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    a.add_argument(
        "scene",
        nargs="?",
        metavar="SCENE",
        help="a scene file (.json/.toml) or built-in scene name to analyze instead of the "
        "four-bar given by --links (see 'planarkin scenes'); then --links, --mode, "
        "--predictor, --coupler and --newton-at do not apply",
    )
    a.add_argument(
        "--out",
        type=Path,
        default=Path("figures"),
        metavar="DIR",
        help="output folder (default: %(default)s)",
    )
    a.add_argument(
        "--dpi", type=float, default=300.0, help="figure resolution (default: %(default)s)"
    )
    a.add_argument(
        "--newton-at",
        type=float,
        default=NEWTON_THETA2_DEG,
        metavar="DEG",
        help="crank angle of the convergence study, solved from the seeds' cold "
        "guess (80, 100) deg, mirrored for crossed (default: %(default)s)",
    )
    a.add_argument("--no-figures", action="store_true", help="write the CSV and JSON only")
    a.add_argument(
        "--json", action="store_true", help="print the JSON summary to stdout instead of the table"
    )
    a.set_defaults(func=run_analyze)

    m = sub.add_parser(
        "animate",
        parents=[common],
        help="the linkage in motion: GIF and HTML",
        description=f"Write {ANIMATION_GIF} and {ANIMATION_HTML} (self-contained, with play "
        "controls) of the linkage moving through the sweep with its coupler curve traced.",
    )
    m.add_argument(
        "scene",
        nargs="?",
        metavar="SCENE",
        help="a scene file (.json/.toml) or built-in scene name to animate instead of the "
        "four-bar given by --links",
    )
    m.add_argument(
        "--out",
        type=Path,
        default=Path("figures"),
        metavar="DIR",
        help="output folder (default: %(default)s)",
    )
    m.add_argument("--frames", type=int, default=72, help="frames (default: %(default)s)")
    m.add_argument(
        "--fps", type=float, default=12.0, help="frames per second (default: %(default)s)"
    )
    m.add_argument(
        "--dpi", type=float, default=80.0, help="frame resolution (default: %(default)s)"
    )
    m.set_defaults(func=run_animate)

    sc = sub.add_parser("scenes", help="list the built-in scenes")
    sc.set_defaults(func=run_scenes)

    c = sub.add_parser(
        "circuits",
        help="every assembly of a scene at an input angle, grouped by circuit",
        description="Find every real assembly of SCENE at --theta (default: as drawn), trace "
        "each circuit through its dead points, and write circuits.json and circuits.png "
        "(input angle against the output angle for every circuit, turning points marked, "
        "and the linkage drawn in each assembly).",
    )
    c.add_argument("scene", metavar="SCENE", help="a scene file (.json/.toml) or built-in name")
    c.add_argument("--theta", type=float, default=None, metavar="DEG", help="input angle")
    c.add_argument("--out", type=Path, default=Path("figures"), metavar="DIR",
                   help="output folder (default: %(default)s)")  # fmt: skip
    c.add_argument("--dpi", type=float, default=150.0, help="figure resolution")
    c.add_argument("--no-figures", action="store_true", help="write circuits.json only")
    c.add_argument("--json", action="store_true", help="print the JSON instead of the table")
    c.set_defaults(func=run_circuits)

    y = sub.add_parser(
        "synthesize",
        help="defect-free synthesis of a double butterfly (seed 003): ackermann",
        description="Synthesize a double butterfly by multistart SLSQP on the true linkage's "
        "error, verify it, and write design.json, report.json and the seed's figures.",
    )
    from .synthesis import cli as synthesis_cli

    synthesis_cli.add_arguments(y)
    y.set_defaults(func=synthesis_cli.run_synthesize)

    t = sub.add_parser("tradeoff", help="measure the speed/accuracy trade-off")
    tradeoff.add_arguments(t)
    t.set_defaults(func=tradeoff.run)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``planarkin`` console script; returns the exit code."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except ValueError as e:
        print(f"planarkin: error: {e}", file=sys.stderr)
        return 2
    except OSError as e:
        print(f"planarkin: error: {e}", file=sys.stderr)
        return 1
    except MemoryError as e:
        print(f"planarkin: error: out of memory: {e}", file=sys.stderr)
        return 1


# --- shared ------------------------------------------------------------------------------


def _finite(name: str, value: float, *, positive: bool = False) -> float:
    if not math.isfinite(value) or (positive and value <= 0):
        raise ValueError(f"{name} must be finite{' and > 0' if positive else ''}, got {value}")
    return value


#: Most crank angles a command sweeps: every one becomes a CSV row and plotted points.
MAX_POINTS = 10_000_000


def crank_angles(step_deg: float) -> np.ndarray:
    """0..360 deg in ``step_deg`` steps (360 included when the step divides it), radians.
    With the default 1 deg step this is exactly ``planarkin.DEFAULT_THETA2``. At most
    :data:`MAX_POINTS` angles (ValueError naming ``--step`` beyond)."""
    step = _finite("--step", step_deg, positive=True)
    if step > 360:
        raise ValueError(f"--step must be <= 360 deg, got {step}")
    n = math.floor(360.0 / step + 1e-9) + 1
    if n > MAX_POINTS:
        raise ValueError(
            f"--step {step:g} deg gives {n} crank angles; at most {MAX_POINTS} "
            f"(--step >= {360 / (MAX_POINTS - 1):.3g})"
        )
    return np.arange(n) * (step * math.tau / 360)


def _setup(args: argparse.Namespace) -> tuple[FourBar, np.ndarray]:
    """The linkage and the crank angles, after checking the shared options."""
    fb = FourBar(*args.links)
    theta2 = crank_angles(args.step)
    _finite("--rpm", args.rpm)
    _finite("--coupler P", args.coupler[0])
    _finite("--coupler DELTA", args.coupler[1])
    _finite("--dpi", args.dpi, positive=True)
    return fb, theta2


def _max_abs(x: object) -> float | None:
    """Largest finite |x|, or None when there is none."""
    a = np.abs(np.asarray(x, dtype=np.float64))
    a = a[np.isfinite(a)]
    return float(a.max()) if a.size else None


def _wrap(x: np.ndarray) -> np.ndarray:
    return np.remainder(x + math.pi, math.tau) - math.pi


def _jsonable(x: object) -> object:
    """NaN/inf -> None, NumPy scalars -> Python, recursively (strict JSON)."""
    if isinstance(x, dict):
        return {k: _jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_jsonable(v) for v in x]
    if isinstance(x, np.generic):
        x = x.item()
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


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
        u = plot.unwrap_deg(t)
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
            [math.degrees(a), math.degrees(b)] for a, b in plot.unreachable_spans(sweep, limits)
        ],
        "unsolved_deg": unsolved,
        "newton": {
            "theta2_deg": args.newton_at,
            "guess_deg": list(guess),
            "status": sol.status.name,
            "nit": sol.nit,
            "residual": sol.residual,
            "history": sol.history.tolist(),
            "order": plot.convergence_order(sol.history),
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


def _write_csv(path: Path, columns: dict) -> None:
    with path.open("w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(columns)
        for row in zip(*columns.values(), strict=True):
            w.writerow([_cell(v) for v in row])


def _cell(v: object) -> str:
    """The shortest text that reads back to the same float (or the int, or the name)."""
    if isinstance(v, str):
        return v
    return repr(v.item() if isinstance(v, np.generic) else v)


def _figures(res: Analysis, args: argparse.Namespace) -> dict:
    """File name -> a function drawing that figure."""
    sweep, limits = res.sweep, res.limits
    p, delta = args.coupler[0], math.radians(args.coupler[1])
    guess_deg = NEWTON_GUESS_DEG[sweep.mode]
    guess = (math.radians(guess_deg[0]), math.radians(guess_deg[1]))
    builders = {
        "figure_a_position_analysis.png": lambda: plot.position(sweep, limits=limits),
        "figure_combined_positions.png": lambda: plot.positions_combined(sweep, limits=limits),
        "figure_b_convergence.png": lambda: plot.convergence(res.newton, guess=guess, tol=args.tol),
        "figure_c_velocity.png": lambda: plot.velocity(sweep, limits=limits),
        "figure_d_acceleration.png": lambda: plot.acceleration(sweep, limits=limits),
        "figure_e_transmission_angle.png": lambda: plot.transmission(sweep, limits=limits),
        "figure_f_coupler_curve.png": lambda: plot.coupler_curve(sweep, p, delta, limits=limits),
        "figure_g_linkage.png": lambda: plot.linkage(sweep, p, delta),
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
        figs = [f for f in summary["files"] if f.endswith(".png")]
        data = [f for f in summary["files"] if not f.endswith(".png")]
        what = ", ".join(data) + (f" and {len(figs)} figures (PNG)" if figs else "")
        add("written", f"{summary['out']}{os.sep}: {what}")
    width = max(len(k) for k, _ in rows) + 2
    head = f"planarkin analyze: four-bar ({L['r1']:g}, {L['r2']:g}, {L['r3']:g}, {L['r4']:g})"
    return head + "\n" + "\n".join(f"  {k:<{width}}{v}" for k, v in rows)


def run_circuits(args: argparse.Namespace) -> int:
    from .scene import cli as scene_cli

    return scene_cli.run_circuits(args)


def run_scenes(args: argparse.Namespace) -> int:
    from . import scenes

    for name in scenes.names():
        sc = scenes.load(name)
        print(f"{name:20s} {len(sc.links)} links, {len(sc.points)} points: {sc.name}")
    return 0


def warm_median(fn, *, runs: int = 51, budget_s: float = 0.25) -> tuple[float, int]:
    """Median seconds of ``fn()`` over warm calls (after one call that is not timed: the
    first pays for first-touch memory and caches), as the README's timings are taken: up
    to ``runs`` calls, fewer when they would take more than ``budget_s`` in all.
    Returns (median, number of timed calls)."""
    fn()
    times: list[float] = []
    spent = 0.0
    while len(times) < runs and (len(times) < 3 or spent < budget_s):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
        spent += times[-1]
    return float(np.median(times)), len(times)


def run_analyze(args: argparse.Namespace) -> int:
    if args.scene is not None:
        from .scene import cli as scene_cli

        return scene_cli.run_analyze(args)
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
    _write_csv(out / RESULTS_CSV, res.columns)
    files = [RESULTS_CSV, SUMMARY_JSON]
    if not args.no_figures:
        for name, draw in _figures(res, args).items():
            draw().savefig(out / name, dpi=args.dpi)
            files.append(name)
    summary = res.summary
    summary["wall_time_s"] = {
        "sweep": t_sweep,
        "sweep_runs": n_runs,
        "total": time.perf_counter() - t_start,
    }
    summary["out"] = str(out)
    summary["files"] = files
    text = json.dumps(_jsonable(summary), indent=2, allow_nan=False)
    (out / SUMMARY_JSON).write_text(text + "\n", encoding="utf-8")
    print(text if args.json else format_table(summary))
    return 0


# --- animate -----------------------------------------------------------------------------


def run_animate(args: argparse.Namespace) -> int:
    if args.scene is not None:
        from .scene import cli as scene_cli

        return scene_cli.run_animate(args)
    from matplotlib.animation import PillowWriter

    fb, theta2 = _setup(args)
    if args.frames < 1:
        raise ValueError(f"--frames must be >= 1, got {args.frames}")
    _finite("--fps", args.fps, positive=True)
    sweep = fb.sweep(
        theta2, mode=args.mode, tol=args.tol, max_iter=args.max_iter, predictor=args.predictor
    )
    p, delta = args.coupler[0], math.radians(args.coupler[1])
    # a crank that cannot turn fully rocks between its toggles (and the mode switches)
    path = plot.rocking(fb, fb.limits(args.mode), sweep, points=len(theta2) // 2 + 1)
    anim = plot.animation(path, p, delta, frames=args.frames, fps=args.fps, dpi=args.dpi)
    out: Path = args.out
    out.mkdir(parents=True, exist_ok=True)
    anim.save(str(out / ANIMATION_GIF), writer=PillowWriter(fps=args.fps))
    r = ", ".join(f"{x:g}" for x in fb.lengths)
    page = plot.animation_html(
        anim, fps=args.fps, title=f"planarkin four-bar ({r}), {args.mode} mode"
    )
    (out / ANIMATION_HTML).write_text(page, encoding="utf-8")
    n = len(plot.animation_frames(path, args.frames))
    how = "" if len(path) == 1 else ", the crank rocking between its toggles"
    print(f"planarkin animate: four-bar ({r}), {args.mode} mode{how}, {n} frames")
    print(f"  wrote {out / ANIMATION_GIF} and {out / ANIMATION_HTML}")
    return 0
