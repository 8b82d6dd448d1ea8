"""``planarkin forces SCENE``: statics (or, with ``--rpm`` / ``--speed``, inverse dynamics)
of a scene under its loads along its default sweep: a table (peak and RMS input effort,
each pin's peak reaction and the input where it peaks, the checks), forces.csv with units
in its header, forces.json, and figures (the input effort, the pin reactions, one pin's
force in polar form, the linkage with force arrows)."""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np

from ..._angles import wrap
from ...forces import Forces
from ...forces.report import columns, totals
from ...scene import Scene
from ..figures.forces import arrows, effort, polar, reactions
from ..progress import bar
from ._common import (
    figure_arguments,
    figure_file,
    finite,
    json_text,
    load_scene,
    out_argument,
    quiet_argument,
    table,
    write_csv,
)

FORCES_CSV = "forces.csv"
FORCES_JSON = "forces.json"
FIGURES = ("input_effort.png", "reactions.png", "pin_polar.png", "forces_drawn.png")
__all__ = ["FIGURES", "FORCES_CSV", "FORCES_JSON", "add_parser", "run"]


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Registers ``forces``."""
    c = sub.add_parser(
        "forces",
        help="input torque or force and every joint reaction of a scene under its loads",
        description="Statics of SCENE under its loads (the scene's 'loads' key) along its "
        "default sweep: the input torque (or a linear input's force) that holds every pose, "
        "and every pin's reaction, by Newton-Euler, checked by virtual work. With --rpm "
        "(an angle input) or --speed (a linear input): inverse dynamics at that constant "
        "rate (the links' inertia included), checked by the energy balance too. Writes "
        f"{FORCES_CSV} (units in the header), {FORCES_JSON} and figures.",
    )
    c.add_argument("scene", metavar="SCENE", help="a scene file (.json/.toml) or built-in name")
    rate = c.add_mutually_exclusive_group()
    rate.add_argument("--rpm", type=float, default=None, metavar="N",
                      help="input speed in revolutions per minute (an angle input)")  # fmt: skip
    rate.add_argument("--speed", type=float, default=None, metavar="V",
                      help="input speed in length units per second (a linear input)")  # fmt: skip
    c.add_argument("--pin", default=None, metavar="JOINT:LINK",
                   help="the pin of the polar figure (default: the largest force's)")  # fmt: skip
    c.add_argument("--at", type=float, default=None, metavar="DEG",
                   help="input of the arrows figure: degrees, or a linear input's displacement "
                   "(default: where the input effort peaks)")  # fmt: skip
    out_argument(c)
    figure_arguments(c, 120.0)
    c.add_argument("--no-figures", action="store_true", help="write the CSV and JSON only")
    c.add_argument("--json", action="store_true", help="print the JSON instead of the table")
    quiet_argument(c)
    c.set_defaults(func=run)
    return c


def _value(r: Forces, t: float) -> str:
    if r.input_kind == "angle":
        return f"{math.degrees(wrap(t)):.1f} deg"
    return f"{t:.6g} {r.units['length'] or ''}".rstrip()


def _summary(sc: Scene, r: Forces, args: argparse.Namespace, wall: float) -> dict:
    return {"scene": sc.name, "rpm": args.rpm, "speed": args.speed, **totals(r),
            "seconds": wall}  # fmt: skip


def run(args: argparse.Namespace) -> int:
    """``planarkin forces SCENE``."""
    sc = load_scene(args.scene)
    if sc.loads is None:
        raise ValueError(f"scene {sc.name or args.scene!r} has no 'loads': nothing to analyse")
    if args.rpm is not None and sc.input_kind != "angle":
        raise ValueError("--rpm needs an angle input; use --speed for a linear input")
    if args.speed is not None and sc.input_kind == "angle":
        raise ValueError("--speed needs a linear input; use --rpm for an angle input")
    finite("--dpi", args.dpi, positive=True)
    rate = None
    if args.rpm is not None:
        rate = finite("--rpm", args.rpm) * 2 * math.pi / 60
    elif args.speed is not None:
        rate = finite("--speed", args.speed)
    figure = not args.no_figures
    out: Path = args.out
    with bar(2 + 4 * figure, "forces", quiet=args.quiet) as b:
        t0 = time.perf_counter()
        sw = sc.sweep(outputs="all", rate=rate or 1.0)
        r = sc.statics(sw) if not rate else sc.dynamics(sw, omega=rate)
        wall = time.perf_counter() - t0
        b.update()
        summary = _summary(sc, r, args, wall)
        out.mkdir(parents=True, exist_ok=True)
        head, cols = columns(r)
        write_csv(out / FORCES_CSV, head, zip(*cols, strict=True))
        (out / FORCES_JSON).write_text(json_text(summary) + "\n", encoding="utf-8")
        files = [FORCES_CSV, FORCES_JSON]
        b.update()
        if figure:
            pin = _pin(r, args.pin)
            at = _index(sc, r, args.at)
            for name, make in zip(FIGURES, (
                lambda: effort(sc, r), lambda: reactions(sc, r),
                lambda: polar(sc, r, pin or ("", "")), lambda: arrows(sc, sw, r, at),
            ), strict=True):  # fmt: skip
                if name == FIGURES[2] and pin is None:
                    b.update()
                    continue  # no pin: no polar figure
                fn = figure_file(name, args.format)
                make().savefig(out / fn, dpi=args.dpi)
                files.append(fn)
                b.update()
    if args.json:
        print(json_text(summary))
        return 0
    e = r.effort_unit
    rows: list[tuple[str, object]] = [
        (
            "analysis",
            f"{r.kind}"
            + (f" at {args.rpm:g} rpm" if args.rpm else "")
            + (f" at {args.speed:g} {r.units['length'] or ''}/s" if args.speed else ""),
        ),  # fmt: skip
        ("solved", f"{summary['solved']}/{summary['points']} input values"),
        (
            "peak input",
            f"{r.peak_input:.6g} {e}"
            + (
                ""
                if summary["peak_input_at"] is None
                else f" at {_value(r, summary['peak_input_at'])}"
            ),
        ),  # fmt: skip
        ("RMS input", f"{r.rms_input:.6g} {e}"),
    ]
    for (j, k), (m, t) in r.peaks().items():
        rows.append((f"pin {j} on {k}", f"peak {m:.6g} {r.units['force']} at {_value(r, t)}"))
    for k, v in r.checks.items():
        rows.append((f"check: {k.replace('_', ' ')}", f"{v:.2e} (largest relative residual)"))
    print(f"planarkin forces: {sc.name or args.scene}")
    print(table(rows))
    print(f"  {1e3 * wall:.1f} ms; wrote {', '.join(str(out / f) for f in files)}")
    return 0


def _pin(r: Forces, spec: str | None) -> tuple[str, str] | None:
    if spec is None:
        peaks = r.peaks()
        if not peaks:
            return None
        return max(peaks, key=lambda k: np.nan_to_num(peaks[k][0]))
    joint, _, link = spec.partition(":")
    if (joint, link) not in r.reactions:
        known = ", ".join(f"{j}:{k}" for j, k in r.reactions)
        raise ValueError(f"--pin must be one of {known}, got {spec!r}")
    return (joint, link)


def _index(sc: Scene, r: Forces, at: float | None) -> int:
    ok = np.isfinite(r.input)
    if at is None:
        return int(np.nanargmax(np.abs(r.input))) if ok.any() else 0
    t = math.radians(finite("--at", at)) if r.input_kind == "angle" else finite("--at", at)
    if r.input_kind == "angle":
        d = np.abs((r.theta - t + math.pi) % (2 * math.pi) - math.pi)
    else:
        d = np.abs(r.theta - t)
    return int(np.argmin(np.where(ok, d, np.inf)))
