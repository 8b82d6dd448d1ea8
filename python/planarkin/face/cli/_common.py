"""Plumbing the ``planarkin`` commands share (they import it, never each other): the
parser with one-line errors, the one limit on points (MAX_POINTS), input angles from
``--step``, the four-bar's options and their defaults, scenes by file or name, CSV/JSON
writing and the key-value table. Degrees on the command line; radians underneath."""

from __future__ import annotations

import argparse
import csv
import json
import math
import time
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..._args import MODES, PREDICTORS
from ...fourbar import FourBar
from ...interop import pyslvs
from ...scene import Scene
from ...scene import builtin as scenes
from ...scene.report import input_axis

#: The file formats every figure can be written in (``--format``): SVG and PDF are vector
#: (papers, laser cutters), PNG at ``--dpi``.
FORMATS = ("png", "svg", "pdf")

#: The data files ``analyze`` writes, whichever its variant (four-bar or SCENE).
RESULTS_CSV = "results.csv"
SUMMARY_JSON = "summary.json"

#: Most input angles a command sweeps: every one becomes a CSV row and plotted points.
MAX_POINTS = 10_000_000

#: The input speeds when none is given: a crank's (rev/min, ``--rpm``) and a linear
#: input's (length units per second, ``--speed``).
DEFAULT_RPM = 100.0
DEFAULT_SPEED = 1.0
#: The seeds' linkage: ground r1, crank r2, coupler r3, rocker r4.
DEFAULT_LINKS = (6.0, 2.0, 5.0, 5.0)
#: Coupler point: distance from the crank pin A, angle from the line A-B (degrees).
DEFAULT_COUPLER = (3.0, 30.0)
#: The four-bar's own options (argparse dest -> flag) and their defaults; they default to
#: None on the command line so that one given with a SCENE is seen (and refused).
FOURBAR_OPTIONS = {
    "links": ("--links", DEFAULT_LINKS),
    "mode": ("--mode", "open"),
    "predictor": ("--predictor", "quadratic"),
    "coupler": ("--coupler", DEFAULT_COUPLER),
}
#: The values of those options that a SCENE takes as well.
SCENE_VALUES = {"predictor": ("closed-form",)}


class Parser(argparse.ArgumentParser):
    """argparse with a one-line error (exit code 2) instead of usage + error."""

    def error(self, message: str) -> None:  # type: ignore[override]
        self.exit(2, f"planarkin: error: {message} (see '{self.prog} --help')\n")


def linkage_options(*, rpm: bool) -> Parser:
    """The options of a sweep (``analyze``, ``animate``): the four-bar's own and those
    that apply to a SCENE as well; ``rpm`` adds the crank speed (velocities)."""
    # a Parser like the subcommands it is a parent of (argparse only copies its arguments)
    p = Parser(add_help=False)
    g = p.add_argument_group("linkage and sweep")
    links = " ".join(f"{v:g}" for v in DEFAULT_LINKS)
    g.add_argument(
        "--links",
        nargs=4,
        type=float,
        metavar=("R1", "R2", "R3", "R4"),
        help="four-bar link lengths: ground, crank (input), coupler, rocker "
        f"(default: {links}, the textbook linkage)",
    )
    g.add_argument("--mode", choices=MODES, help="four-bar assembly mode (default: open)")
    g.add_argument(
        "--step",
        type=float,
        default=1.0,
        metavar="DEG",
        help="input-angle step; the sweep runs one full turn (default: %(default)s)",
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
        help="Newton iterations per input angle (default: %(default)s)",
    )
    g.add_argument(
        "--predictor",
        choices=PREDICTORS,
        help="four-bar continuation predictor along the sweep (default: quadratic); with a "
        "SCENE, closed-form only: every angle on its own, on the drawn sides (default: the "
        "drawn circuit followed)",
    )
    if rpm:
        g.add_argument(
            "--rpm",
            type=float,
            help="constant speed of an input that turns, rev/min; omega2 = rpm * 2 pi / 60 "
            f"rad/s, alpha2 = 0 (default: {DEFAULT_RPM:g}); an error for a linear input",
        )
        g.add_argument(
            "--speed",
            type=float,
            metavar="V",
            help="constant speed of a SCENE's linear input (a slot or prismatic pair, e.g. a "
            "cylinder's extension), in the scene's length units per second (default: "
            f"{DEFAULT_SPEED:g}); an error for an input that turns",
        )
    p_, d_ = DEFAULT_COUPLER
    g.add_argument(
        "--coupler",
        nargs=2,
        type=float,
        metavar=("P", "DELTA"),
        help="four-bar coupler point at distance P from the crank pin A, at DELTA deg "
        f"from the coupler line A-B (default: {p_:g} {d_:g})",
    )
    return p


def scene_argument(parser: argparse.ArgumentParser, what: str, *extra: str) -> None:
    """The optional SCENE of ``analyze`` and ``animate`` (instead of the four-bar);
    ``extra``: the command's own four-bar options, for the help."""
    flags = ", ".join([f for f, _ in FOURBAR_OPTIONS.values()] + list(extra))
    parser.add_argument(
        "scene",
        nargs="?",
        metavar="SCENE",
        help=f"a scene file (.json/.toml) or built-in scene name to {what} instead of the "
        f"four-bar of --links (see 'planarkin scenes'); the four-bar's own options ({flags}) "
        "are then an error",
    )


def parsed_options(args: argparse.Namespace, skip: Iterable[str] = ()) -> dict[str, Any]:
    """Every option as parsed (defaults included), by name, paths as text: what a command's
    report records of how it was run (the subcommand's own fields and ``skip`` left out)."""
    left_out = {"func", "command", *skip}
    return {
        k: str(val) if isinstance(val, Path) else val
        for k, val in sorted(vars(args).items())
        if k not in left_out
    }


def out_argument(parser: argparse.ArgumentParser, default: str = "figures") -> None:
    parser.add_argument(
        "--out",
        type=Path,
        default=Path(default),
        metavar="DIR",
        help="output folder (default: %(default)s)",
    )


def figure_arguments(parser: argparse.ArgumentParser, dpi: float) -> None:
    """``--dpi`` and ``--format`` of a command that writes figures."""
    parser.add_argument(
        "--dpi", type=float, default=dpi, help="figure resolution (default: %(default)s)"
    )
    format_argument(parser)


def format_argument(parser: argparse.ArgumentParser) -> None:
    """``--format png|svg|pdf`` of a command that writes figures."""
    parser.add_argument(
        "--format",
        choices=FORMATS,
        default="png",
        help="figure file format: png, svg or pdf (vector: papers, laser "
        "cutters) (default: %(default)s)",
    )


def quiet_argument(parser: argparse.ArgumentParser) -> None:
    """``--quiet``: no progress bar (one is drawn only when stderr is a terminal)."""
    parser.add_argument(
        "-q",
        "--quiet",
        action="store_true",
        help="no progress bar (one is shown on stderr only when it is a terminal; "
        "PLANARKIN_PROGRESS=1 shows it anyway)",
    )


def figure_file(name: str, fmt: str) -> str:
    """A figure's file name (listed with .png) in the format ``fmt``."""
    return str(Path(name).with_suffix(f".{fmt}"))


def plural(n: int, noun: str, nouns: str | None = None) -> str:
    """ "1 step", "2 steps" (``nouns``: an irregular plural)."""
    return f"{n} {noun if n == 1 else (nouns or noun + 's')}"


def refuse_fourbar_options(args: argparse.Namespace, extra: Iterable[tuple[str, str]] = ()) -> None:
    """ValueError (exit 2) when a four-bar option was given with a SCENE: it would be
    silently dropped. ``extra``: a command's own four-bar options as (dest, flag)."""
    flags = [(d, f) for d, (f, _) in FOURBAR_OPTIONS.items()] + list(extra)
    given = [f for d, f in flags if getattr(args, d, None) not in (None, *SCENE_VALUES.get(d, ()))]
    if given:
        what = f"{given[0]} does" if len(given) == 1 else f"{', '.join(given)} do"
        raise ValueError(
            f"{what} not apply to a scene (they set up the four-bar analyzed when no "
            "SCENE is given; a scene is solved as drawn)"
        )


def scene_predictor(args: argparse.Namespace) -> str:
    """A scene sweep's predictor: ``--predictor closed-form`` solves every angle on its own,
    each dyad and slider on its drawn side (plans with no group); by default the sweep
    follows the drawn circuit. The four-bar's other predictors are refused with the rest
    of its options (:func:`refuse_fourbar_options`)."""
    p = getattr(args, "predictor", None)
    return p if p in SCENE_VALUES["predictor"] else "continuation"


def finite(name: str, value: float, *, positive: bool = False) -> float:
    if not math.isfinite(value) or (positive and value <= 0):
        raise ValueError(f"{name} must be finite{' and > 0' if positive else ''}, got {value}")
    return value


def angle_count(step_deg: float, noun: str) -> int:
    """How many input angles one full turn in ``step_deg`` steps gives (360 included when
    the step divides it); ValueError naming ``--step`` beyond :data:`MAX_POINTS`."""
    step = step_deg
    if not (math.isfinite(step) and 0 < step <= 360):
        raise ValueError(f"--step must be in (0, 360] deg, got {step}")
    n = math.floor(360.0 / step + 1e-9) + 1
    if n > MAX_POINTS:
        raise ValueError(
            f"--step {step:g} deg gives {n} {noun}; at most {MAX_POINTS} "
            f"(--step >= {360 / (MAX_POINTS - 1):.3g})"
        )
    return n


def crank_angles(step_deg: float) -> np.ndarray:
    """0..360 deg in ``step_deg`` steps (360 included when the step divides it), radians.
    With the default 1 deg step this is exactly ``planarkin.DEFAULT_THETA2``."""
    n = angle_count(step_deg, "crank angles")
    return np.arange(n) * (step_deg * math.tau / 360)


def scene_angles(scene: Scene, step_deg: float) -> np.ndarray:
    """One full turn from the drawn input angle in ``step_deg`` steps (both ends); for a
    linear input, as many displacements across its stroke (both dead points included)."""
    # its own formula (not crank_angles + the drawn angle): scene outputs keep their digits
    n = angle_count(step_deg, "input angles")
    return input_axis(scene.input_kind, scene.units).sweep(scene, n, step_deg)


def scene_rate(args: argparse.Namespace, scene: Scene) -> float:
    """The constant rate a SCENE's input is driven at: ``--rpm`` (rev/min, as omega in
    rad/s) for an input that turns, ``--speed`` (length units per second) for a linear
    one; the other option is an error naming the input, never silently ignored."""
    axis = input_axis(scene.input_kind, scene.units)
    linear = scene.input_kind == "displacement"
    wrong, right = ("--rpm", "--speed") if linear else ("--speed", "--rpm")
    if getattr(args, wrong.lstrip("-"), None) is not None:
        kind, name = scene.input
        what = f"is linear ({kind} {name!r}, in {axis.unit})" if linear else f"turns ({kind!r})"
        raise ValueError(f"{wrong} does not apply to scene {scene.name or '(unnamed)'!r}: its "
                         f"input {what}; give its speed with {right}")  # fmt: skip
    given = getattr(args, right.lstrip("-"), None)
    value = axis.rate_default if given is None else given
    finite(right, value)
    return axis.rate(value)


def fourbar_setup(args: argparse.Namespace) -> tuple[FourBar, np.ndarray]:
    """The four-bar and its crank angles: fills in the four-bar options' defaults, then
    checks the options every four-bar command shares (ValueError naming the option)."""
    for dest, (_, default) in FOURBAR_OPTIONS.items():
        if getattr(args, dest, None) is None:
            setattr(args, dest, default)
    fb = FourBar(*args.links)
    theta2 = crank_angles(args.step)
    if getattr(args, "speed", None) is not None:
        raise ValueError("--speed is for a SCENE's linear input; the four-bar's crank turns "
                         "at --rpm")  # fmt: skip
    if hasattr(args, "rpm"):
        if args.rpm is None:
            args.rpm = DEFAULT_RPM
        finite("--rpm", args.rpm)
    finite("--coupler P", args.coupler[0])
    finite("--coupler DELTA", args.coupler[1])
    finite("--dpi", args.dpi, positive=True)
    return fb, theta2


def load_scene(spec: str) -> Scene:
    """A scene file (.json/.toml, or a Pyslvs project .pyslvs) or a built-in name."""
    p = Path(spec)
    if p.suffix in (".json", ".toml", ".pyslvs"):
        if not p.exists():
            raise ValueError(f"scene file {spec!r} does not exist")
        return pyslvs.load(p) if p.suffix == ".pyslvs" else Scene.load(p)
    if spec in scenes.names():
        return scenes.load(spec)
    raise ValueError(
        f"SCENE must be a .json/.toml file or a built-in name ({', '.join(scenes.names())}), "
        f"got {spec!r}"
    )


def jsonable(x: object) -> object:
    """NaN/inf -> None, NumPy arrays -> lists, NumPy scalars -> Python, recursively
    (strict JSON)."""
    if isinstance(x, np.ndarray):
        x = x.tolist()
    if isinstance(x, dict):
        return {k: jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [jsonable(v) for v in x]
    if isinstance(x, np.generic):
        x = x.item()
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


def json_text(data: object) -> str:
    """Strict JSON (no NaN), indented, as the summary files hold it."""
    return json.dumps(jsonable(data), indent=2, allow_nan=False)


def write_csv(path: Path, header: Iterable[str], rows: Iterable[Iterable[object]]) -> None:
    """One header line, then the rows, each value as :func:`cell` writes it."""
    with path.open("w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(header)
        for row in rows:
            w.writerow([cell(v) for v in row])


def cell(v: object) -> str:
    """The shortest text that reads back to the same float (or the int, or the name)."""
    if isinstance(v, str):
        return v
    return repr(v.item() if isinstance(v, np.generic) else v)


def table(rows: Sequence[tuple[str, object]]) -> str:
    """Key-value rows, the keys padded to one width, each line indented by two spaces."""
    width = max(len(k) for k, _ in rows)
    return "\n".join(f"  {k:<{width}}  {v}" for k, v in rows)


def warm_median(
    fn: Callable[[], object], *, runs: int = 51, budget_s: float = 0.25
) -> tuple[float, int]:
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
