"""``planarkin circuits SCENE``: every real assembly of a scene at one input angle,
grouped by circuit (each traced through its dead points), written as circuits.json and
drawn as circuits.png (or .svg, .pdf); at an input the linkage cannot reach, the inputs
it can reach instead."""

from __future__ import annotations

import argparse
import math
import textwrap
import time
from pathlib import Path
from typing import Any

import numpy as np

from ..._results import true_runs
from ...scene import Circuit, Scene
from ..degrees import wrapped
from ..figures.circuits import circuits
from ..progress import bar
from ._common import (
    figure_arguments,
    figure_file,
    finite,
    json_text,
    load_scene,
    out_argument,
    plural,
    quiet_argument,
)

CIRCUITS_JSON = "circuits.json"
CIRCUITS_PNG = "circuits.png"
#: Input angles tried for the reachable ranges when --theta is out of reach (5 deg apart).
REACH_STEP_DEG = 5.0

#: What the words of the table mean (``--help``, the table and the README say the same).
GLOSSARY = (
    "An assembly is one way the linkage can be put together at the input angle. A circuit "
    "is the set of assemblies one continuous motion connects: the linkage cannot get from "
    "one circuit to another without being taken apart. A turning point is an input angle "
    "where the motion on a circuit must reverse (a dead point: two links in line); a "
    "circuit without one lets the input turn fully. An assembly's label has one token per "
    "plan step: a dyad's side, + or - (the sign of its triangle's angle at the point it "
    "solves), or a group's elbows in parentheses (the sign of the angle at each of its "
    "joints), with a letter a, b, ... where two assemblies share the signs. A label is "
    "read at --theta: it changes where one of those angles passes through 0, so the same "
    "assembly can carry another label at another --theta."
)


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Registers ``circuits``."""
    c = sub.add_parser(
        "circuits",
        help="every assembly of a scene at an input angle, grouped by circuit",
        description="Find every real assembly of SCENE at --theta (default: as drawn), trace "
        f"each circuit through its dead points, and write {CIRCUITS_JSON} and a figure "
        "(one panel per circuit: input angle against the output angle, turning points "
        "marked; the linkage drawn in each assembly).",
        epilog=GLOSSARY,
    )
    c.add_argument("scene", metavar="SCENE", help="a scene file (.json/.toml) or built-in name")
    c.add_argument(
        "--theta",
        type=float,
        default=None,
        metavar="DEG",
        help="input angle in degrees, or for a linear input its displacement from the drawn "
        "pose in the scene's length unit (default: as drawn)",
    )
    out_argument(c)
    figure_arguments(c, 150.0)
    c.add_argument("--no-figures", action="store_true", help=f"write {CIRCUITS_JSON} only")
    c.add_argument("--json", action="store_true", help="print the JSON instead of the table")
    quiet_argument(c)
    c.set_defaults(func=run)
    return c


def reachable(sc: Scene, *, quiet: bool = False) -> list[tuple[float, float]]:
    """The input ranges (degrees, in (-180, 180]) where ``sc`` has some assembly, on a
    grid of :data:`REACH_STEP_DEG` (each range from its first to its last grid angle)."""
    grid = np.arange(-180.0 + REACH_STEP_DEG, 180.0 + 1e-9, REACH_STEP_DEG)
    has = np.zeros(len(grid), dtype=bool)
    with bar(len(grid), "circuits: reachable inputs", quiet=quiet, unit="angle") as b:
        for i, d in enumerate(grid):
            has[i] = len(sc.assemblies(math.radians(float(d)))) > 0
            b.update()
    runs = true_runs(has)
    # a range through 180 deg is one range: from its start to its end past 180
    if len(runs) > 1 and runs[0][0] == 0 and runs[-1][1] == len(grid):
        (a, b_), *mid, (c, _) = runs
        return [(float(grid[i]), float(grid[j - 1])) for i, j in mid] + [
            (float(grid[c]), float(grid[b_ - 1]) + 360.0)
        ]
    return [(float(grid[i]), float(grid[j - 1])) for i, j in runs]


def reachable_linear(sc: Scene, *, quiet: bool = False) -> list[tuple[float, float]]:
    """A linear input's ranges (scene units, from the drawn pose) where ``sc`` has some
    assembly, on a grid of 801 values over four sizes of the drawing each way."""
    pts = np.array(list(sc.points.values()), dtype=float)
    size = float(np.ptp(pts, axis=0).max())
    grid = np.linspace(-4.0 * size, 4.0 * size, 801)
    has = np.zeros(len(grid), dtype=bool)
    with bar(len(grid), "circuits: reachable inputs", quiet=quiet, unit="value") as b:
        for i, s in enumerate(grid):
            has[i] = len(sc.assemblies(float(s))) > 0
            b.update()
    return [(float(grid[i]), float(grid[j - 1])) for i, j in true_runs(has)]


def run(args: argparse.Namespace) -> int:
    """``planarkin circuits SCENE``: every assembly at an input angle, grouped by circuit."""
    sc = load_scene(args.scene)
    if sc.input_kind == "displacement":
        return run_linear(sc, args)
    theta = sc.input_angle if args.theta is None else math.radians(args.theta)
    if not math.isfinite(theta):
        raise ValueError(f"--theta must be finite, got {args.theta}")
    finite("--dpi", args.dpi, positive=True)
    figure = not args.no_figures
    with bar(2 + figure, "circuits", quiet=args.quiet) as b:
        t0 = time.perf_counter()
        found = sc.circuits(theta)
        wall = time.perf_counter() - t0
        b.update()
        counts = sc.assemblies(theta).complex_counts
        b.update()
        reach = None if found else reachable(sc, quiet=args.quiet)
        rows: list[dict[str, Any]] = []
        for k, c in enumerate(found):
            lo, hi = (math.degrees(v) for v in shown_range(c, theta))
            rows.append({
                "circuit": k + 1,
                "assemblies": [{"label": a.label, "det": a.det} for a in c.assemblies],
                "full_turn": c.full_turn,
                "net_turn_deg": math.degrees(c.net_turn),
                "turning_points_deg": [wrapped(v) for v in c.turning_points],
                "input_range_deg": [lo, hi],
                "closed": c.trace.closed,
                "trace_points": len(c.trace),
            })  # fmt: skip
        summary = {
            "scene": sc.name,
            "theta_deg": wrapped(theta),
            "assemblies": sum(len(c.assemblies) for c in found),
            "group_complex_solutions": counts,
            "circuits": rows,
            "reachable_deg": None if reach is None else [list(r) for r in reach],
            "glossary": GLOSSARY,
            "wall_time_s": wall,
        }
        out: Path = args.out
        out.mkdir(parents=True, exist_ok=True)
        (out / CIRCUITS_JSON).write_text(json_text(summary) + "\n", encoding="utf-8")
        files = [CIRCUITS_JSON]
        if figure:
            name = figure_file(CIRCUITS_PNG, args.format)
            circuits(sc, found, theta, reachable=reach).savefig(out / name, dpi=args.dpi)
            files.append(name)
            b.update()
    if args.json:
        print(json_text(summary))
        return 0
    at = summary["theta_deg"]
    print(f"planarkin circuits: {sc.name or args.scene} at theta = {at:.3f} deg")
    if not found:
        where = "; ".join(f"{a:.1f} to {b:.1f}" for a, b in reach or []) or "none found"
        print(f"  no assembly at theta = {at:.3f} deg: the linkage cannot be put together "
              f"there; it has assemblies for theta in (deg, {REACH_STEP_DEG:g} deg grid): "
              f"{where}")  # fmt: skip
    else:
        n = sum(len(c.assemblies) for c in found)
        print(f"  {plural(n, 'real assembly', 'real assemblies')} on "
              f"{plural(len(rows), 'circuit')}"
              + (f"; complex solutions of its groups: {counts}" if counts else ""))  # fmt: skip
    for r in rows:
        labels = ", ".join(f"{a['label']} (det {a['det']:+.3g})" for a in r["assemblies"])
        lo, hi = r["input_range_deg"]
        kind = (
            "input turns fully"
            if r["full_turn"]
            else f"input rocks between {lo:.2f} and {hi:.2f} deg"
        )
        if not r["full_turn"] and (hi > 180 or lo <= -180):
            kind += " (a continuous range through 180 deg)"
        tps = ", ".join(f"{v:.4f}" for v in r["turning_points_deg"]) or "none"
        print(f"  circuit {r['circuit']}: {labels}; {kind}; turning points (deg): {tps}")
    if found:
        print("  " + "\n  ".join(textwrap.wrap(GLOSSARY, 88)))
    print(f"  {1e3 * wall:.1f} ms; wrote {', '.join(str(out / f) for f in files)}")
    return 0


def shown_range(c: Circuit, theta: float) -> tuple[float, float]:
    """A circuit's input range (radians, continuous) in the turn that holds ``theta``."""
    shift = math.tau * round((theta - math.radians(wrapped(theta))) / math.tau)
    return c.range[0] - shift, c.range[1] - shift


def run_linear(sc: Scene, args: argparse.Namespace) -> int:
    """``planarkin circuits`` for a scene driven by a slot or prismatic pair: the input is a
    displacement from the drawn pose, in the scene's length unit (no wrapping)."""
    unit = sc.units or "length units"
    s = 0.0 if args.theta is None else float(args.theta)
    if not math.isfinite(s):
        raise ValueError(f"--theta must be finite, got {args.theta}")
    finite("--dpi", args.dpi, positive=True)
    figure = not args.no_figures
    with bar(2 + figure, "circuits", quiet=args.quiet) as b:
        t0 = time.perf_counter()
        found = sc.circuits(s)
        wall = time.perf_counter() - t0
        b.update()
        counts = sc.assemblies(s).complex_counts
        b.update()
        reach = None if found else reachable_linear(sc, quiet=args.quiet)
        rows: list[dict[str, Any]] = []
        for k, c in enumerate(found):
            rows.append({
                "circuit": k + 1,
                "assemblies": [{"label": a.label, "det": a.det} for a in c.assemblies],
                "full_turn": c.full_turn,
                "turning_points": [float(v) for v in c.turning_points],
                # the traced range, its turning points (refined by bisection) included
                "input_range": [
                    float(min([c.range[0], *c.turning_points])),
                    float(max([c.range[1], *c.turning_points])),
                ],
                "closed": c.trace.closed,
                "trace_points": len(c.trace),
            })  # fmt: skip
        summary = {
            "scene": sc.name,
            "input_kind": "displacement",
            "units": sc.units,
            "theta": s,
            "assemblies": sum(len(c.assemblies) for c in found),
            "group_complex_solutions": counts,
            "circuits": rows,
            "reachable": None if reach is None else [list(r) for r in reach],
            "glossary": GLOSSARY,
            "wall_time_s": wall,
        }
        out: Path = args.out
        out.mkdir(parents=True, exist_ok=True)
        (out / CIRCUITS_JSON).write_text(json_text(summary) + "\n", encoding="utf-8")
        files = [CIRCUITS_JSON]
        if figure:
            name = figure_file(CIRCUITS_PNG, args.format)
            circuits(sc, found, s, reachable=reach).savefig(out / name, dpi=args.dpi)
            files.append(name)
            b.update()
    if args.json:
        print(json_text(summary))
        return 0
    print(f"planarkin circuits: {sc.name or args.scene} at input = {s:.6g} {unit} "
          "(a displacement from the drawn pose)")  # fmt: skip
    if not found:
        where = "; ".join(f"{a:.6g} to {b:.6g}" for a, b in reach or []) or "none found"
        print(f"  no assembly at input = {s:.6g} {unit}: the linkage cannot be put together "
              f"there; it has assemblies for inputs in ({unit}): {where}")  # fmt: skip
    else:
        n = sum(len(c.assemblies) for c in found)
        print(f"  {plural(n, 'real assembly', 'real assemblies')} on "
              f"{plural(len(rows), 'circuit')}"
              + (f"; complex solutions of its groups: {counts}" if counts else ""))  # fmt: skip
    for r in rows:
        labels = ", ".join(f"{a['label']} (det {a['det']:+.3g})" for a in r["assemblies"])
        lo, hi = r["input_range"]
        tps = ", ".join(f"{v:.6g}" for v in r["turning_points"]) or "none"
        print(f"  circuit {r['circuit']}: {labels}; input moves between {lo:.6g} and "
              f"{hi:.6g} {unit}; turning points ({unit}): {tps}")  # fmt: skip
    if found:
        print("  " + "\n  ".join(textwrap.wrap(GLOSSARY, 88)))
    print(f"  {1e3 * wall:.1f} ms; wrote {', '.join(str(out / f) for f in files)}")
    return 0
