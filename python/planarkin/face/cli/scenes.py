"""``planarkin scenes``: the built-in scenes, one line each (name, size, title)."""

from __future__ import annotations

import argparse

from ...scene import builtin


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Registers ``scenes``."""
    sc = sub.add_parser("scenes", help="list the built-in scenes")
    sc.set_defaults(func=run)
    return sc


def run(args: argparse.Namespace) -> int:
    """Prints the built-in scenes; returns the exit code."""
    for name in builtin.names():
        sc = builtin.load(name)
        print(f"{name:20s} {len(sc.links)} links, {len(sc.points)} points: {sc.name}")
    return 0
