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

from ...scene import Scene
from ...scene.report import (
    REACH_STEP_DEG,
    InputAxis,
    circuits_summary,
    input_axis,
    reachable,
)
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
__all__ = ["CIRCUITS_JSON", "CIRCUITS_PNG", "GLOSSARY", "REACH_STEP_DEG", "add_parser", "run"]

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


class _AngleWords:
    """How the table speaks of an angle input (degrees, wrapped)."""

    unit = "deg"
    #: the progress bar's unit while the reachable inputs are searched
    step = "angle"
    #: the format of the reachable ranges' ends
    ends = ".1f"

    def __init__(self, sc: Scene) -> None:
        self.reach_what = f"theta in (deg, {REACH_STEP_DEG:g} deg grid)"

    def at(self, v: float) -> str:
        return f"theta = {v:.3f} deg"

    def head(self, v: float) -> str:
        return self.at(v)

    def motion(self, r: dict) -> str:
        """A circuit's motion and turning points."""
        lo, hi = r["input_range_deg"]
        kind = (
            "input turns fully"
            if r["full_turn"]
            else f"input rocks between {lo:.4f} and {hi:.4f} deg"
        )
        if not r["full_turn"] and (hi > 180 or lo <= -180):
            kind += " (a continuous range through 180 deg)"
        tps = ", ".join(f"{v:.4f}" for v in r["turning_points_deg"]) or "none"
        return f"{kind}; turning points (deg): {tps}{_stops(r, '.4f', 'deg')}"


class _LinearWords(_AngleWords):
    """How the table speaks of a linear input: a displacement from the drawn pose in the
    scene's length unit."""

    step = "value"
    ends = ".6g"

    def __init__(self, sc: Scene) -> None:
        self.unit = sc.units or "length units"
        self.reach_what = f"inputs in ({self.unit})"

    def at(self, v: float) -> str:
        return f"input = {v:.6g} {self.unit}"

    def head(self, v: float) -> str:
        return self.at(v) + " (a displacement from the drawn pose)"

    def motion(self, r: dict) -> str:
        lo, hi = r["input_range"]
        tps = ", ".join(f"{v:.6g}" for v in r["turning_points"]) or "none"
        return (f"input moves between {lo:.6g} and {hi:.6g} {self.unit}; "
                f"turning points ({self.unit}): {tps}{_stops(r, '.6g', self.unit)}")  # fmt: skip


def _stops(r: dict, fmt: str, unit: str) -> str:
    """Where the scene's travel limits stop a circuit's motion, if they do."""
    if not r.get("limits"):
        return ""
    at = ", ".join(format(v, fmt) for v in r["limits"])
    return f"; stopped by the scene's limits at {at} {unit}"


#: The table's words for each kind of input.
_WORDS = {"angle": _AngleWords, "displacement": _LinearWords}


def run(args: argparse.Namespace) -> int:
    """``planarkin circuits SCENE``: every assembly at an input, grouped by circuit. The
    input is an angle, or for a scene driven by a slot or prismatic pair a displacement
    from the drawn pose in the scene's length unit (no wrapping)."""
    sc = load_scene(args.scene)
    axis, words = input_axis(sc.input_kind, sc.units), _WORDS[sc.input_kind](sc)
    at = axis.drawn(sc) if args.theta is None else axis.from_user(args.theta)
    if not math.isfinite(at):
        raise ValueError(f"--theta must be finite, got {args.theta}")
    finite("--dpi", args.dpi, positive=True)
    figure = not args.no_figures
    with bar(2 + figure, "circuits", quiet=args.quiet) as b:
        t0 = time.perf_counter()
        found = sc.circuits(at)
        wall = time.perf_counter() - t0
        b.update()
        counts = sc.assemblies(at).complex_counts
        b.update()
        reach = None if found else _reachable(sc, axis, words.step, args.quiet)
        summary = circuits_summary(sc, axis, at, found, counts, reach, GLOSSARY, wall)
        out: Path = args.out
        out.mkdir(parents=True, exist_ok=True)
        (out / CIRCUITS_JSON).write_text(json_text(summary) + "\n", encoding="utf-8")
        files = [CIRCUITS_JSON]
        if figure:
            name = figure_file(CIRCUITS_PNG, args.format)
            circuits(sc, found, at, reachable=reach).savefig(out / name, dpi=args.dpi)
            files.append(name)
            b.update()
    if args.json:
        print(json_text(summary))
        return 0
    shown = axis.value(at)
    print(f"planarkin circuits: {sc.name or args.scene} at {words.head(shown)}")
    if not found:
        f = words.ends
        where = "; ".join(f"{a:{f}} to {b:{f}}" for a, b in reach or []) or "none found"
        print(f"  no assembly at {words.at(shown)}: the linkage cannot be put together "
              f"there; it has assemblies for {words.reach_what}: {where}")  # fmt: skip
    else:
        n = summary["assemblies"]
        print(f"  {plural(n, 'real assembly', 'real assemblies')} on "
              f"{plural(len(found), 'circuit')}"
              + (f"; complex solutions of its groups: {counts}" if counts else ""))  # fmt: skip
    for r in summary["circuits"]:
        labels = ", ".join(f"{a['label']} (det {a['det']:+.3g})" for a in r["assemblies"])
        print(f"  circuit {r['circuit']}: {labels}; {words.motion(r)}")
    if found:
        print("  " + "\n  ".join(textwrap.wrap(GLOSSARY, 88)))
    print(f"  {1e3 * wall:.1f} ms; wrote {', '.join(str(out / f) for f in files)}")
    return 0


def _reachable(sc: Scene, axis: InputAxis, unit: str, quiet: bool) -> list[tuple[float, float]]:
    with bar(len(axis.reach_grid(sc)), "circuits: reachable inputs", quiet=quiet, unit=unit) as b:
        return reachable(sc, axis, b.update)
