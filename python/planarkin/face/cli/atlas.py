"""``planarkin atlas build|info``: an atlas of normalised coupler curves built as Dask
tasks (:func:`planarkin.atlas.build`: resumable, a finished shard is kept; progress per
shard on a terminal; Ctrl-C exits 130 keeping the finished shards), and what an atlas
folder holds (its manifest)."""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

from ..progress import Stages
from ._common import json_text, quiet_argument, table

#: the topologies an atlas is built for (as ``synthesize path --topology`` names them)
TOPOLOGIES = ("four-bar", "slider-crank", "watt2", "stephenson3")


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Registers ``atlas`` and its two actions."""
    a = sub.add_parser(
        "atlas",
        help="atlases of coupler curves for path synthesis: build, info",
        description="Build an atlas of normalised coupler curves (shards as Dask tasks, on "
        "this machine or a cluster; resumable) or show what an atlas folder holds. "
        "'planarkin synthesize path --atlas DIR' draws its candidates from one.",
    )
    actions = a.add_subparsers(dest="action", required=True, metavar="ACTION")
    b = actions.add_parser(
        "build",
        help="build (or resume building) an atlas into a folder",
        description="Build an atlas of SIZE linkages of one topology into --out, shard by "
        "shard as Dask tasks (a LocalCluster on this machine, or --scheduler). The same "
        "seed gives the same atlas, bit for bit, whatever the workers; a shard already "
        "finished in --out is not recomputed, so running the command again resumes it.",
    )
    b.add_argument("--topology", choices=TOPOLOGIES, required=True, help="the linkages")
    b.add_argument("--size", type=int, required=True, metavar="N", help="linkages in the atlas")
    b.add_argument("--out", type=Path, required=True, metavar="DIR", help="the atlas folder")
    b.add_argument(
        "--scheduler",
        default=None,
        metavar="ADDRESS",
        help="a Dask scheduler address (default: a LocalCluster on this machine)",
    )
    b.add_argument("--seed", type=int, default=0, help="random seed (default: %(default)s)")
    b.add_argument(
        "--shard-size",
        type=int,
        default=None,
        metavar="N",
        help="linkages per shard (default: the atlas's own)",
    )
    quiet_argument(b)
    b.set_defaults(func=build)
    i = actions.add_parser(
        "info",
        help="what an atlas folder holds (its manifest)",
        description="Print an atlas's manifest: topology, size, seed, version, shards.",
    )
    i.add_argument("dir", type=Path, metavar="DIR", help="the atlas folder")
    i.add_argument("--json", action="store_true", help="print the manifest as JSON")
    i.set_defaults(func=info)
    return a


def _check(args: argparse.Namespace) -> None:
    if args.size < 1:
        raise ValueError(f"--size must be >= 1, got {args.size}")
    if args.shard_size is not None and args.shard_size < 1:
        raise ValueError(f"--shard-size must be >= 1, got {args.shard_size}")
    if args.out.exists() and not args.out.is_dir():
        raise ValueError(f"--out {str(args.out)!r} is a file, not a folder")


def build(args: argparse.Namespace) -> int:
    """``planarkin atlas build``; returns the exit code."""
    _check(args)
    from ...atlas import build as build_atlas

    t0 = time.perf_counter()
    shards = Stages("atlas build", args.quiet, unit="shard")
    try:
        atlas = build_atlas(
            args.topology,
            args.size,
            str(args.out),
            seed=args.seed,
            scheduler=args.scheduler,
            shard_size=args.shard_size,
            progress=lambda done, total: shards("", done, total),
        )
    except KeyboardInterrupt:
        shards.close()
        kept = f" ({shards.done} finished shards kept)" if shards.done else ""
        print(f"planarkin: interrupted; the atlas in {args.out} is incomplete{kept}: run the "
              "same command again to resume", file=sys.stderr)  # fmt: skip
        return 130
    shards.close()
    wall = time.perf_counter() - t0
    m = dict(atlas.manifest)
    n = m.get("size", args.size)
    rate = f", {n / wall:,.0f} linkages/s" if wall > 0 and isinstance(n, int) else ""
    print(f"planarkin atlas build: {n} {args.topology} linkages in {args.out} "
          f"({wall:.1f} s{rate})")  # fmt: skip
    return 0


def info(args: argparse.Namespace) -> int:
    """``planarkin atlas info``; returns the exit code."""
    if not args.dir.is_dir():
        raise ValueError(f"atlas folder {str(args.dir)!r} does not exist")
    from ...atlas import open as open_atlas

    m = dict(open_atlas(str(args.dir)).manifest)
    if args.json:
        print(json_text(m))
        return 0
    print(f"atlas {args.dir}")
    print(table([(k, _shown(v)) for k, v in m.items()]))
    return 0


def _shown(v: object) -> str:
    """A manifest value in a line: a list or dict by its length when long."""
    if isinstance(v, float):
        return f"{v:.6g}" if math.isfinite(v) else str(v)
    if isinstance(v, (list, tuple, dict)) and len(v) > 6:
        return f"({len(v)} {'entries' if isinstance(v, dict) else 'items'})"
    return str(v)
