"""The ``planarkin`` command: ``main()`` builds the parser from the command modules (one
per subcommand: analyze, animate, atlas, circuits, export, forces, scenes, synthesize,
tradeoff, web; analyze's two variants in analyze_fourbar and analyze_scene, synthesize's
path problem in synthesize_path) and turns what goes wrong
into one line on stderr: a bad option or input (exit 2), a file that cannot be written or a
missing optional extra (1), Ctrl-C (130)."""

from __future__ import annotations

import argparse
import sys

from ... import __version__
from ..fonts import use as use_fonts
from . import (
    analyze,
    animate,
    atlas,
    circuits,
    export,
    forces,
    scenes,
    synthesize,
    tradeoff,
    web,
)
from ._common import Parser

__all__ = ["build_parser", "main"]

#: The subcommands, in the order ``--help`` lists them.
COMMANDS = (analyze, animate, scenes, export, circuits, forces, synthesize, atlas, tradeoff, web)


def build_parser() -> argparse.ArgumentParser:
    parser = Parser(
        prog="planarkin",
        description="Planar linkage kinematics with a Rust core: four-bars (--links), any "
        "planar linkage as a scene (a file or a built-in: 'planarkin scenes'), its circuits, "
        "the synthesis of double butterflies and of linkages tracing a path. Run 'planarkin "
        "analyze' for the textbook four-bar, 'planarkin analyze jansen' for a scene.",
    )
    parser.add_argument("--version", action="version", version=f"planarkin {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for command in COMMANDS:
        command.add_parser(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``planarkin`` console script; returns the exit code."""
    try:
        args = build_parser().parse_args(argv)
        use_fonts()
        return int(args.func(args) or 0)
    except KeyboardInterrupt:
        print("planarkin: interrupted", file=sys.stderr)
        return 130
    except ValueError as e:
        print(f"planarkin: error: {e}", file=sys.stderr)
        return 2
    except OSError as e:
        print(f"planarkin: error: {e}", file=sys.stderr)
        return 1
    except ImportError as e:  # an optional extra that is not installed: its pip command
        print(f"planarkin: error: {e}", file=sys.stderr)
        return 1
    except MemoryError as e:
        print(f"planarkin: error: out of memory: {e}", file=sys.stderr)
        return 1
