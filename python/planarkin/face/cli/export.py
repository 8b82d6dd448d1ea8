"""``planarkin export SCENE --to FILE``: the scene in another tool's format, picked by the
suffix: a cutting sheet (``.dxf``, ``.svg``: every link and the ground as a part, pin
holes, labels, a scale bar, 1:1), a MuJoCo model (``.xml``: the link tree, its loops
closed by equality constraints, the input a position actuator), a Pyslvs project
(``.pyslvs``)."""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from ...interop import dxf, mujoco, pyslvs, sheet, svg
from ._common import finite, load_scene

SUFFIXES = (".dxf", ".svg", ".xml", ".pyslvs")


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Registers ``export``."""
    e = sub.add_parser(
        "export",
        help="a scene as a cutting sheet (DXF, SVG), a MuJoCo model or a Pyslvs project",
        description="Write SCENE (a scene file or built-in name) in another tool's format, "
        "picked by the suffix of --to: .dxf or .svg (a cutting sheet: each link and the "
        "ground as a part with its pin holes, labels and a scale bar, 1:1 in the scene's "
        'unit; DXF needs pip install "planarkin[dxf]"), .xml (a MuJoCo model, closed loops '
        "as equality constraints), .pyslvs (a Pyslvs project).",
    )
    e.add_argument("scene", metavar="SCENE", help="a scene file or built-in scene name")
    e.add_argument("--to", type=Path, required=True, metavar="FILE",
                   help=f"the file to write ({', '.join(SUFFIXES)})")  # fmt: skip
    for flag, what in (
        ("--width", "bar width of the parts (default: 6%% of the scene's size)"),
        ("--hole", "pin hole diameter (default: 40%% of the width)"),
        ("--margin", "gap between parts and round the sheet (default: half the width)"),
    ):
        e.add_argument(flag, type=float, metavar="L", help=f"sheets: {what}")
    e.add_argument("--force", action="store_true", help="replace an existing file")
    e.set_defaults(func=run)
    return e


def run(args: argparse.Namespace) -> int:
    """Writes the scene in the format of --to's suffix; returns the exit code."""
    path: Path = args.to
    if path.suffix not in SUFFIXES:
        raise ValueError(f"--to must end in {', '.join(SUFFIXES)}, got {str(path)!r}")
    if path.exists() and not args.force:
        raise ValueError(f"--to {str(path)!r} exists (--force replaces it)")
    sizes = {k: getattr(args, k) for k in ("width", "hole", "margin")}
    for k, v in sizes.items():
        if v is not None:
            finite(f"--{k}", v, positive=True)
    if path.suffix not in (".dxf", ".svg") and any(v is not None for v in sizes.values()):
        raise ValueError("--width, --hole and --margin are for .dxf and .svg sheets")
    sc = load_scene(args.scene)
    t0 = time.perf_counter()
    if path.suffix in (".dxf", ".svg"):
        sh = sheet.layout(sc, **sizes)
        (dxf if path.suffix == ".dxf" else svg).write(sh, path)
        w, h = sh.size
        what = f"a cutting sheet of {len(sh.parts)} parts, {w:.4g} x {h:.4g} {sh.units}"
    elif path.suffix == ".xml":
        mujoco.write(sc, path)
        what = "a MuJoCo model"
    else:
        path.write_text(pyslvs.dumps(sc), encoding="utf-8")
        what = "a Pyslvs project"
    ms = (time.perf_counter() - t0) * 1e3
    print(f"planarkin export: wrote {path} ({what}; {ms:.0f} ms)")
    return 0
