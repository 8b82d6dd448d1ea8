"""``planarkin scenes``: the built-in scenes, one line each (name, size, title);
``--export NAME`` writes one to a file (JSON, TOML, or a Pyslvs project ``.pyslvs``) to
start a scene of one's own from; ``--import FILE.pyslvs`` reads a Pyslvs project into
scene JSON (printed, or written ``--to`` a file)."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from ...interop import pyslvs
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
        help="where --export writes (.json, .toml or .pyslvs; default: NAME.json here), or "
        "where --import writes its scene (.json or .toml; default: printed as JSON)",
    )
    sc.add_argument(
        "--import",
        dest="import_",
        type=Path,
        metavar="FILE",
        help="read a Pyslvs project (FILE.pyslvs: its mechanism and input) as a scene",
    )
    sc.add_argument("--force", action="store_true", help="let --to replace an existing file")
    sc.set_defaults(func=run)
    return sc


def run(args: argparse.Namespace) -> int:
    """Prints the built-in scenes, or exports one; returns the exit code."""
    if args.import_ is not None:
        return _import(args)
    if args.export is None:
        if args.to is not None:
            raise ValueError("--to needs --export NAME or --import FILE")
        for name in builtin.names():
            sc = builtin.load(name)
            print(f"{name:20s} {len(sc.links)} links, {len(sc.points)} points: {sc.name}")
        return 0
    sc = builtin.load(args.export)
    path: Path = args.to if args.to is not None else Path(f"{args.export}.json")
    if path.suffix not in (".json", ".toml", ".pyslvs"):
        raise ValueError(f"--to must end in .json, .toml or .pyslvs, got {str(path)!r}")
    if path.exists() and not args.force:
        raise ValueError(f"--to {str(path)!r} exists (--force replaces it)")
    if path.suffix == ".pyslvs":
        path.write_text(pyslvs.dumps(sc), encoding="utf-8")
        print(f"planarkin scenes: wrote {args.export!r} to {path} (a Pyslvs project)")
        return 0
    sc.save(path)
    print(f"planarkin scenes: wrote {args.export!r} to {path} (edit it, then "
          f"'planarkin analyze {path}')")  # fmt: skip
    return 0


def _import(args: argparse.Namespace) -> int:
    if args.export is not None:
        raise ValueError("--import and --export go one at a time")
    if args.import_.suffix != ".pyslvs":
        raise ValueError(f"--import must end in .pyslvs, got {str(args.import_)!r}")
    sc = pyslvs.load(args.import_)
    if args.to is None:
        print(json.dumps(sc.to_dict(), indent=2))
        return 0
    if args.to.suffix not in (".json", ".toml"):
        raise ValueError(f"--to must end in .json or .toml, got {str(args.to)!r}")
    if args.to.exists() and not args.force:
        raise ValueError(f"--to {str(args.to)!r} exists (--force replaces it)")
    sc.save(args.to)
    print(f"planarkin scenes: wrote {args.import_} as a scene to {args.to}")
    return 0
