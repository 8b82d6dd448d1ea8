"""``planarkin analyze SCENE`` and ``planarkin animate SCENE``: any scene (a file or a
built-in name) swept, summarised, drawn and animated. Degrees on the command line and in
the outputs; the API underneath works in radians."""

from __future__ import annotations

import argparse
import csv
import json
import math
import time
from pathlib import Path
from typing import Any

import numpy as np

from .. import scenes
from .._types import Status
from ..cli import _jsonable
from ._model import Scene
from ._results import SceneSweep

RESULTS_CSV = "results.csv"
SUMMARY_JSON = "summary.json"
FIGURES = {
    "scene_linkage.png": "the linkage drawn at several input angles over its tracer paths",
    "scene_conditioning.png": "signed conditioning of each step and of the whole solve",
    "scene_tracers.png": "tracer point coordinates and speeds against the input angle",
}
#: Largest number of input angles a command sweeps (memory of the outputs stays small).
MAX_ANGLES = 10_000_000


def load_scene(spec: str) -> Scene:
    """A scene file (.json/.toml) or a built-in name."""
    p = Path(spec)
    if p.suffix in (".json", ".toml"):
        if not p.exists():
            raise ValueError(f"scene file {spec!r} does not exist")
        return Scene.load(p)
    if spec in scenes.names():
        return scenes.load(spec)
    raise ValueError(
        f"SCENE must be a .json/.toml file or a built-in name ({', '.join(scenes.names())}), "
        f"got {spec!r}"
    )


def angles(scene: Scene, step_deg: float) -> np.ndarray:
    """One full turn from the drawn angle in ``step_deg`` steps (both ends included)."""
    if not (math.isfinite(step_deg) and 0 < step_deg <= 360):
        raise ValueError(f"--step must be in (0, 360] deg, got {step_deg}")
    n = math.floor(360.0 / step_deg + 1e-9) + 1
    if n > MAX_ANGLES:
        raise ValueError(f"--step {step_deg} deg asks for {n} angles; at most {MAX_ANGLES}")
    return scene.input_angle + np.arange(n) * math.radians(step_deg)


def _runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """(start, stop) index ranges where ``mask`` is True."""
    d = np.diff(np.concatenate([[0], mask.astype(np.int8), [0]]))
    return list(zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1), strict=True))


def _none(x: float) -> float | None:
    return x if math.isfinite(x) else None


def summarize(scene: Scene, sw: SceneSweep, wall: dict[str, float]) -> dict:
    """The summary table as data."""
    ok = sw.success
    deg = np.degrees(sw.theta)
    absdet = np.abs(sw.det[ok])
    # where the motion stops: the edges of the solved spans (to the sweep's resolution)
    edges = []
    for a, b in _runs(ok):
        if a > 0:
            edges.append({"deg": float(deg[a]), "det": float(sw.det[a]), "side": "start"})
        if b < len(ok):
            edges.append({"deg": float(deg[b - 1]), "det": float(sw.det[b - 1]), "side": "end"})
    return {
        "scene": scene.name,
        "description": scene.description,
        "links": len(scene.links),
        "joints": sum(len(v) - 1 for v in scene.joints.values()),
        "points": len(scene.points),
        "mobility": scene.mobility,
        "input": {"link": scene.input[0], "pivot": scene.input[1]},
        "drawn_input_deg": math.degrees(scene.input_angle),
        "outputs": list(sw.plan.outputs) if sw.plan.outputs is not None else "all",
        "plan": [
            {"kind": s.kind, "points": list(s.points), "unknowns": list(s.unknowns)}
            for s in sw.plan
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
        "dead_points_deg": sorted(
            {round(math.degrees(v), 9) for v in sw.limit if math.isfinite(v)}
        ),
        "wall_time_s": wall,
    }


def _table(s: dict) -> str:
    rows = [
        ("scene", s["scene"] or "(unnamed)"),
        ("links / joints / points", f"{s['links']} / {s['joints']} / {s['points']}"),
        ("mobility (Gruebler)", s["mobility"]),
        (
            "input",
            f"{s['input']['link']} at {s['input']['pivot']}, drawn at "
            f"{s['drawn_input_deg']:.3f} deg",
        ),  # fmt: skip
        ("outputs", ", ".join(s["outputs"]) if isinstance(s["outputs"], list) else "all"),
    ]
    for i, st in enumerate(s["plan"]):
        rows.append((f"plan step {i + 1}", f"{st['kind']}: {', '.join(st['points'])} "
                     f"(angles of {', '.join(st['unknowns'])})"))  # fmt: skip
    rows += [
        ("converged", f"{s['converged']} of {s['angles']} input angles"),
        ("statuses", ", ".join(f"{k}={v}" for k, v in s["statuses"].items())),
        (
            "Newton iterations",
            f"{s['nit_total']} total"
            + (
                f", {s['nit_mean_converged']:.3f} per solved angle"
                if s["nit_mean_converged"] is not None
                else ""
            ),
        ),  # fmt: skip
    ]
    if s["conditioning_min"] is not None:
        rows.append(
            ("|conditioning|", f"{s['conditioning_min']:.3g} .. {s['conditioning_max']:.3g}")
        )
    if s["dead_points_deg"]:
        dead = ", ".join(f"{v:.4f}" for v in s["dead_points_deg"])
        rows.append(("dead points met (deg)", dead + " (the input must reverse there)"))
    if s["motion_stops_deg"]:
        stops = ", ".join(f"{e['deg']:.1f}" for e in s["motion_stops_deg"])
        rows.append(("motion stops near (deg)", stops))
    w = max(len(k) for k, _ in rows)
    return "\n".join(f"  {k:<{w}}  {v}" for k, v in rows)


def _write_csv(path: Path, sw: SceneSweep) -> None:
    names = list(sw.points)
    cols = ["theta [deg]", "status [code]", "status_name", "nit [-]", "det [-]"]
    for n in names:
        cols += [f"{n}_x", f"{n}_y"]
        if sw.velocities is not None:
            cols += [f"{n}_vx", f"{n}_vy"]
    for n in sw.angles:
        cols += [f"{n}_angle [deg]"]
    with path.open("w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for i in range(len(sw)):
            row: list[object] = [
                repr(math.degrees(sw.theta[i])),
                int(sw.status[i]),
                Status(int(sw.status[i])).name,
                int(sw.nit[i]),
                repr(float(sw.det[i])),
            ]
            for n in names:
                row += [repr(float(v)) for v in sw.points[n][i]]
                if sw.velocities is not None:
                    row += [repr(float(v)) for v in sw.velocities[n][i]]
            row += [repr(math.degrees(sw.angles[n][i])) for n in sw.angles]
            w.writerow(row)


def run_analyze(args: argparse.Namespace) -> int:
    """``planarkin analyze SCENE``."""
    from .plot import conditioning, linkage, tracers

    t_start = time.perf_counter()
    sc = load_scene(args.scene)
    theta = angles(sc, args.step)
    omega = args.rpm * math.tau / 60
    sw = sc.sweep(theta, tol=args.tol, max_iter=args.max_iter, omega=omega)
    times = []
    for _ in range(5):  # a warm median: the first call also compiles the plan
        t0 = time.perf_counter()
        sc.sweep(theta, tol=args.tol, max_iter=args.max_iter, omega=omega)
        times.append(time.perf_counter() - t0)
    out: Path = args.out
    out.mkdir(parents=True, exist_ok=True)
    _write_csv(out / RESULTS_CSV, sw)
    files = [RESULTS_CSV, SUMMARY_JSON]
    if not args.no_figures:
        # the figures draw every link: sweep the whole scene for them
        whole = sc.sweep(theta, outputs="all", tol=args.tol, max_iter=args.max_iter, omega=omega)
        for name, draw, data in (
            ("scene_linkage.png", linkage, whole),
            ("scene_conditioning.png", conditioning, sw),
            ("scene_tracers.png", tracers, sw),
        ):
            draw(sc, data).savefig(out / name, dpi=args.dpi)
            files.append(name)
    summary = summarize(
        sc, sw, {"sweep_median": float(np.median(times)), "total": time.perf_counter() - t_start}
    )
    (out / SUMMARY_JSON).write_text(
        json.dumps(_jsonable(summary), indent=2, allow_nan=False) + "\n", encoding="utf-8"
    )
    if args.json:
        print(json.dumps(_jsonable(summary), indent=2, allow_nan=False))
    else:
        print(f"planarkin analyze: {sc.name or args.scene}")
        print(_table(summary))
        print(f"  sweep {1e3 * summary['wall_time_s']['sweep_median']:.3f} ms (warm median of 5)")
        print(f"  wrote {', '.join(str(out / f) for f in files)}")
    return 0


def run_animate(args: argparse.Namespace) -> int:
    """``planarkin animate SCENE``."""
    from matplotlib.animation import PillowWriter

    from ..plot import animation_html
    from .plot import animation

    sc = load_scene(args.scene)
    if args.frames < 1:
        raise ValueError(f"--frames must be >= 1, got {args.frames}")
    if not (math.isfinite(args.fps) and args.fps > 0):
        raise ValueError(f"--fps must be finite and > 0, got {args.fps}")
    sw = sc.sweep(angles(sc, args.step), tol=args.tol, max_iter=args.max_iter)
    anim = animation(sc, sw, frames=args.frames, fps=args.fps, dpi=args.dpi)
    out: Path = args.out
    out.mkdir(parents=True, exist_ok=True)
    gif, page = out / "linkage.gif", out / "linkage.html"
    anim.save(str(gif), writer=PillowWriter(fps=args.fps))
    page.write_text(
        animation_html(anim, fps=args.fps, title=f"planarkin: {sc.name or args.scene}"),
        encoding="utf-8",
    )
    print(f"planarkin animate: {sc.name or args.scene}, {int(sw.success.sum())} solved angles")
    print(f"  wrote {gif} and {page}")
    return 0


def run_circuits(args: argparse.Namespace) -> int:
    """``planarkin circuits SCENE``: every assembly at an input angle, grouped by circuit."""
    from .plot import circuits as draw

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
    (out / "circuits.json").write_text(
        json.dumps(_jsonable(summary), indent=2, allow_nan=False) + "\n", encoding="utf-8"
    )
    files = ["circuits.json"]
    if not args.no_figures:
        draw(sc, found, theta).savefig(out / "circuits.png", dpi=args.dpi)
        files.append("circuits.png")
    if args.json:
        print(json.dumps(_jsonable(summary), indent=2, allow_nan=False))
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
