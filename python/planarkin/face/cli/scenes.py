"""``planarkin scenes``: the built-in scenes, one line each (name, size, title);
``--export NAME`` writes one to a file (JSON or TOML) to start a scene of one's own from."""

from __future__ import annotations

import argparse
from pathlib import Path

from ...scene import builtin


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Registers ``scenes``."""
    sc = sub.add_parser(
        "scenes",
        help="list the built-in scenes, or export one to a file",
        description="List the built-in scenes; with --export NAME, write that scene to a file "
        "(NAME.json, or --to FILE: .json or .toml) to edit into a scene of your own.",
    )
    sc.add_argument("--export", metavar="NAME", help="the built-in scene to write to a file")
    sc.add_argument(
        "--to",
        type=Path,
        metavar="FILE",
        help="where --export writes (.json or .toml; default: NAME.json here)",
    )
    sc.add_argument("--force", action="store_true", help="let --export replace an existing file")
    sc.set_defaults(func=run)
    return sc


def run(args: argparse.Namespace) -> int:
    """Prints the built-in scenes, or exports one; returns the exit code."""
    if args.export is None:
        if args.to is not None:
            raise ValueError("--to needs --export NAME")
        for name in builtin.names():
            sc = builtin.load(name)
            print(f"{name:20s} {len(sc.links)} links, {len(sc.points)} points: {sc.name}")
        return 0
    sc = builtin.load(args.export)
    path: Path = args.to if args.to is not None else Path(f"{args.export}.json")
    if path.suffix not in (".json", ".toml"):
        raise ValueError(f"--to must end in .json or .toml, got {str(path)!r}")
    if path.exists() and not args.force:
        raise ValueError(f"--to {str(path)!r} exists (--force replaces it)")
    sc.save(path)
    print(f"planarkin scenes: wrote {args.export!r} to {path} (edit it, then "
          f"'planarkin analyze {path}')")  # fmt: skip
    return 0
