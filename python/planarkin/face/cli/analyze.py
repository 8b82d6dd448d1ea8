"""``planarkin analyze``: the command's options and help, and the dispatch to its two
variants, one file each: a four-bar (``--links``, :mod:`.analyze_fourbar`) or any SCENE
(:mod:`.analyze_scene`). Degrees on the command line and in the outputs; radians
underneath."""

from __future__ import annotations

import argparse

from ...fourbar.report import NEWTON_THETA2_DEG
from . import analyze_fourbar, analyze_scene
from ._common import (
    RESULTS_CSV,
    SUMMARY_JSON,
    figure_arguments,
    linkage_options,
    out_argument,
    quiet_argument,
    scene_argument,
)

_FILES = {
    RESULTS_CSV: "one row per input angle, every computed column (units in the header)",
    SUMMARY_JSON: "the summary table as data (also on stdout with --json)",
    **analyze_fourbar.FIGURES,
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
        + "".join(f"  {k:34}{v}\n" for k, v in analyze_scene.FIGURES.items())
        + "\nAngles are in degrees, in (-180, 180]; omega in rad/s, alpha in rad/s^2; lengths "
        "in the unit of --links (or the scene's 'units'); the input turns at --rpm (a "
        "SCENE's linear input moves at --speed, its displacements in the scene's unit).",
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
    variant = analyze_scene if args.scene is not None else analyze_fourbar
    return variant.run(args)
