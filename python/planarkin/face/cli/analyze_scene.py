"""``planarkin analyze SCENE``: any scene swept, reported by :mod:`planarkin.scene.report`
(angle and linear inputs alike, over the input's axis), printed as a table, written as
results.csv and summary.json, and drawn (:data:`FIGURES`)."""

from __future__ import annotations

import argparse
import functools
import time
from collections.abc import Callable
from pathlib import Path

from ...forces import report as forces_report
from ...scene import report
from ..figures import scene as scene_fig
from ..progress import bar
from ._common import (
    RESULTS_CSV,
    SUMMARY_JSON,
    figure_file,
    finite,
    json_text,
    load_scene,
    refuse_fourbar_options,
    scene_angles,
    scene_predictor,
    scene_rate,
    table,
    warm_median,
    write_csv,
)

#: The figures of ``planarkin analyze SCENE``.
FIGURES = {
    "scene_linkage.png": "the linkage as drawn, every point named, beside several poses",
    "scene_conditioning.png": "signed conditioning of each step and of the whole solve",
    "scene_tracers.png": "tracer point coordinates and speeds (only if it has tracers)",
}

#: The table's words for each kind of input: what its values are called, the input (from
#: the summary), and its speed (from the summary's input_speed).
_WORDS: dict[str, tuple[str, Callable[[dict], str], Callable[[dict], str]]] = {
    "angle": (
        "input angles",
        lambda s: (
            f"{s['input']['link']} at {s['input']['pivot']}, drawn at "
            f"{s['drawn_input_deg']:.3f} deg"
        ),
        lambda v: f"omega = {v['omega_rad_s']:.4f} rad/s ({v['rpm']:g} rpm, constant)",
    ),
    "displacement": (
        "input values",
        lambda s: (
            "displacement along {} {!r} from the drawn pose, stroke {:.6g} to {:.6g} "
            "(its dead points)".format(*next(iter(s["input"].items())), *s["stroke"])
        ),
        lambda v: f"{v['speed']} (constant)",
    ),
}


def scene_table(s: dict) -> str:
    """The summary table of ``planarkin analyze SCENE`` (ASCII only)."""
    what, drive, speed_words = _WORDS[s["input_kind"]]
    rows = [
        ("scene", s["scene"] or "(unnamed)"),
        ("links / joints / points", f"{s['links']} / {s['joints']} / {s['points']}"),
        ("mobility (Gruebler)", s["mobility"]),
        ("input", drive(s)),
    ]
    speed = s["input_speed"]
    if speed is not None:
        rows.append(
            ("input speed", f"{speed_words(speed)}; velocities in {speed['velocity_unit']}")
        )
    rows.append(("outputs", ", ".join(s["outputs"]) if isinstance(s["outputs"], list) else "all"))
    for i, st in enumerate(s["plan"]):
        rows.append((f"plan step {i + 1}", f"{st['kind']}: {', '.join(st['points'])} "
                     f"(angles of {', '.join(st['unknowns'])})"))  # fmt: skip
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
    unit = report.input_axis(s["input_kind"], s["units"]).unit
    if s["dead_points_deg"]:
        dead = ", ".join(f"{v:.4f}" for v in s["dead_points_deg"])
        rows.append((f"dead points met ({unit})", dead + " (the input must reverse there)"))
    if s["motion_stops_deg"]:
        stops = ", ".join(f"{e['deg']:.1f}" for e in s["motion_stops_deg"])
        rows.append((f"motion stops near ({unit})", stops))
    rows += _output_rows(s.get("output"), unit)
    return table(rows)


def _output_rows(o: dict | None, unit: str) -> list[tuple[str, object]]:
    """The table's rows on the declared output: its swing or stroke between its extremes
    (with the inputs where they occur), a crank's quick-return ratio, a slot's least
    transmission angle."""
    if o is None:
        return []
    what = f"output {o['name']!r}"
    if o["turns_fully"]:
        return [(what, "turns fully (no extremes)")]
    if o["min"] is None:
        return [(what, "not solved")]
    u = o["unit"]
    lo, hi = o["min"], o["max"]
    ends = (f"{lo['value']:.4f} {u} at {lo['input']:.4f} {unit} .. "
            f"{hi['value']:.4f} {u} at {hi['input']:.4f} {unit}")  # fmt: skip
    if o["kind"] == "angle":
        rows: list[tuple[str, object]] = [(f"{what} swing", f"{o['swing_deg']:.4f} deg: {ends}")]
    else:
        rows = [(f"{what} stroke", f"{o['stroke']:.6g} {u}: {ends}")]
    if o["time_ratio"] is not None:
        t = o["time_ratio_input_deg"]
        words = (f"{o['time_ratio']:.4f} (the output rises over {t['rising']:.2f} deg of "
                 f"input, falls over {t['falling']:.2f} deg)")  # fmt: skip
        rows.append(("quick-return time ratio", words))
    if o["transmission_angle_min_deg"] is not None:
        rows.append(("transmission angle, least", f"{o['transmission_angle_min_deg']:.3f} deg "
                     f"at {o['transmission_angle_min_input']:.4f} {unit} (rod against the "
                     "slot's normal; 90 is ideal)"))  # fmt: skip
    return rows


def run(args: argparse.Namespace) -> int:
    """``planarkin analyze SCENE``; returns the exit code."""
    refuse_fourbar_options(args, [("newton_at", "--newton-at")])
    t_start = time.perf_counter()
    sc = load_scene(args.scene)
    theta = scene_angles(sc, args.step)
    finite("--dpi", args.dpi, positive=True)
    # --rpm for an input that turns, --speed for a linear one: the other is an error
    rate = scene_rate(args, sc)
    figures = {} if args.no_figures else FIGURES
    sweep = functools.partial(
        sc.sweep, theta, tol=args.tol, max_iter=args.max_iter, rate=rate,
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
        write_csv(out / RESULTS_CSV, report.columns(sw, sc.units, sc), report.rows(sw, sc))
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
    summary = report.summary(
        sc, sw, {"sweep_median": t_sweep, "total": time.perf_counter() - t_start}
    )
    if sc.loads is not None:
        # a scene with loads: its statics along the same input values (forces.csv)
        r = sc.statics(sc.sweep(theta, outputs="all", rate=1.0))
        head, cols = forces_report.columns(r)
        write_csv(out / "forces.csv", head, zip(*cols, strict=True))
        files.insert(2, "forces.csv")
        summary["forces"] = forces_report.totals(r)
    summary["files"] = files
    (out / SUMMARY_JSON).write_text(json_text(summary) + "\n", encoding="utf-8")
    if args.json:
        print(json_text(summary))
    else:
        print(f"planarkin analyze: {sc.name or args.scene}")
        print(scene_table(summary))
        if "forces" in summary:
            f = summary["forces"]
            print(f"  statics under its loads: peak input {f['peak_input']:.6g} "
                  f"{f['effort_unit']}, RMS {f['rms_input']:.6g}; virtual work check "
                  f"{f['checks']['virtual_work']:.1e} (planarkin forces for more)")  # fmt: skip
        ms = 1e3 * summary["wall_time_s"]["sweep_median"]
        print(f"  sweep {ms:.3f} ms (median of {n_runs} warm runs)")
        print(f"  wrote {', '.join(str(out / f) for f in files)}")
        if skipped:
            print("  no tracer figure: the scene has no tracer point (a point on one link only)")
    return 0
