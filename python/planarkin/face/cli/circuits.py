"""``planarkin circuits SCENE``: every real assembly of a scene at one input angle,
grouped by circuit (each traced through its dead points), written as circuits.json and
drawn as circuits.png."""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path
from typing import Any

from ..figures.circuits import circuits
from ._common import json_text, load_scene, out_argument

CIRCUITS_JSON = "circuits.json"
CIRCUITS_PNG = "circuits.png"


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Registers ``circuits``."""
    c = sub.add_parser(
        "circuits",
        help="every assembly of a scene at an input angle, grouped by circuit",
        description="Find every real assembly of SCENE at --theta (default: as drawn), trace "
        f"each circuit through its dead points, and write {CIRCUITS_JSON} and {CIRCUITS_PNG} "
        "(input angle against the output angle for every circuit, turning points marked, "
        "and the linkage drawn in each assembly).",
    )
    c.add_argument("scene", metavar="SCENE", help="a scene file (.json/.toml) or built-in name")
    c.add_argument("--theta", type=float, default=None, metavar="DEG", help="input angle")
    out_argument(c)
    c.add_argument("--dpi", type=float, default=150.0, help="figure resolution")
    c.add_argument("--no-figures", action="store_true", help=f"write {CIRCUITS_JSON} only")
    c.add_argument("--json", action="store_true", help="print the JSON instead of the table")
    c.set_defaults(func=run)
    return c


def run(args: argparse.Namespace) -> int:
    """``planarkin circuits SCENE``: every assembly at an input angle, grouped by circuit."""
    sc = load_scene(args.scene)
    theta = sc.input_angle if args.theta is None else math.radians(args.theta)
    if not math.isfinite(theta):
        raise ValueError(f"--theta must be finite, got {args.theta}")
    t0 = time.perf_counter()
    found = sc.circuits(theta)
    wall = time.perf_counter() - t0
    counts = sc.assemblies(theta).complex_counts
    rows: list[dict[str, Any]] = []
    for k, c in enumerate(found):
        rows.append({
            "circuit": k + 1,
            "assemblies": [{"label": a.label, "det": a.det} for a in c.assemblies],
            "full_turn": c.full_turn,
            "net_turn_deg": math.degrees(c.net_turn),
            "turning_points_deg": [math.degrees(v) for v in c.turning_points],
            "input_range_deg": [math.degrees(v) for v in c.range],
            "closed": c.trace.closed,
            "trace_points": len(c.trace),
        })  # fmt: skip
    summary = {
        "scene": sc.name,
        "theta_deg": math.degrees(theta),
        "assemblies": sum(len(c.assemblies) for c in found),
        "group_complex_solutions": counts,
        "circuits": rows,
        "wall_time_s": wall,
    }
    out: Path = args.out
    out.mkdir(parents=True, exist_ok=True)
    (out / CIRCUITS_JSON).write_text(json_text(summary) + "\n", encoding="utf-8")
    files = [CIRCUITS_JSON]
    if not args.no_figures:
        circuits(sc, found, theta).savefig(out / CIRCUITS_PNG, dpi=args.dpi)
        files.append(CIRCUITS_PNG)
    if args.json:
        print(json_text(summary))
        return 0
    print(f"planarkin circuits: {sc.name or args.scene} at theta = {math.degrees(theta):.3f} deg")
    print(f"  {summary['assemblies']} real assemblies"
          + (f"; complex solutions of its groups: {counts}" if counts else ""))  # fmt: skip
    for r in rows:
        labels = ", ".join(f"{a['label']} (det {a['det']:+.3g})" for a in r["assemblies"])
        kind = "input turns fully" if r["full_turn"] else "input rocks"
        tps = ", ".join(f"{v:.4f}" for v in r["turning_points_deg"]) or "none"
        print(f"  circuit {r['circuit']}: {labels}; {kind}; turning points (deg): {tps}")
    print(f"  {1e3 * wall:.1f} ms; wrote {', '.join(str(out / f) for f in files)}")
    return 0
