"""``planarkin animate``: a four-bar (``--links``) or any SCENE in motion, written as
linkage.gif and linkage.html (self-contained, with play controls), or with ``--format``
as one of gif, html, mp4, webm (video: the ``video`` extra). A four-bar crank that cannot
turn fully rocks between its toggles."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from matplotlib.animation import PillowWriter

from ...fourbar.analysis import rocking
from .. import animate, video
from ..progress import bar
from ._common import (
    finite,
    fourbar_setup,
    linkage_options,
    load_scene,
    out_argument,
    quiet_argument,
    refuse_fourbar_options,
    scene_angles,
    scene_argument,
    scene_predictor,
)

ANIMATION_GIF = "linkage.gif"
ANIMATION_HTML = "linkage.html"
#: ``--format``: what ``animate`` writes (default: the GIF and the page).
FORMATS = ("gif", "html", "mp4", "webm")


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Registers ``animate``."""
    m = sub.add_parser(
        "animate",
        parents=[linkage_options(rpm=False)],
        help="the linkage in motion: GIF and HTML",
        description=f"Write {ANIMATION_GIF} and {ANIMATION_HTML} (self-contained, with play "
        "controls) of a four-bar (--links) or of a SCENE moving through its sweep, its "
        "coupler curve (tracer paths) traced.",
    )
    scene_argument(m, "animate")
    out_argument(m)
    m.add_argument("--frames", type=int, default=72, help="frames (default: %(default)s)")
    m.add_argument(
        "--fps", type=float, default=12.0, help="frames per second (default: %(default)s)"
    )
    m.add_argument(
        "--dpi", type=float, default=80.0, help="frame resolution (default: %(default)s)"
    )
    m.add_argument(
        "--format",
        choices=FORMATS,
        help="write only linkage.FORMAT: gif, html (a page with play controls), mp4 or webm "
        '(video: pip install "planarkin[video]"); default: linkage.gif and linkage.html',
    )
    quiet_argument(m)
    m.set_defaults(func=run)
    return m


def _check(args: argparse.Namespace) -> None:
    if args.frames < 1:
        raise ValueError(f"--frames must be >= 1, got {args.frames}")
    finite("--fps", args.fps, positive=True)
    if args.format in video.CODECS:
        video.ffmpeg()  # a missing extra says so before any frame is drawn


def run(args: argparse.Namespace) -> int:
    """``planarkin animate [SCENE]``; returns the exit code."""
    return _run_scene(args) if args.scene is not None else _run_fourbar(args)


def _save(anim: object, args: argparse.Namespace, title: str, frames: int) -> str:
    """Writes the animation in the asked format(s); returns "FILE" or "FILE and FILE"."""
    fmt = args.format
    out: Path = args.out
    out.mkdir(parents=True, exist_ok=True)
    gif, page = out / ANIMATION_GIF, out / ANIMATION_HTML
    if fmt is None:
        # each frame is drawn twice: once for the GIF, once for the page
        with bar(2 * frames, "animate", quiet=args.quiet, unit="frame") as b:
            animate.save(anim, gif, page, fps=args.fps, title=title,  # type: ignore[arg-type]
                         progress=lambda i, n: b.update())  # fmt: skip
        return f"{gif} and {page}"
    path = out / f"linkage.{fmt}"
    with bar(frames, "animate", quiet=args.quiet, unit="frame") as b:
        tick = lambda i, n: b.update()  # noqa: E731
        if fmt == "gif":
            anim.save(str(path), writer=PillowWriter(fps=args.fps), progress_callback=tick)  # type: ignore[attr-defined]
        elif fmt == "html":
            page_text = animate.html_page(anim, fps=args.fps, title=title, progress=tick)  # type: ignore[arg-type]
            path.write_text(page_text, encoding="utf-8")
        else:
            video.save(anim, path, fps=args.fps, progress=tick)  # type: ignore[arg-type]
    return str(path)


def _run_fourbar(args: argparse.Namespace) -> int:
    fb, theta2 = fourbar_setup(args)
    _check(args)
    sweep = fb.sweep(
        theta2, mode=args.mode, tol=args.tol, max_iter=args.max_iter, predictor=args.predictor
    )
    p, delta = args.coupler[0], math.radians(args.coupler[1])
    # a crank that cannot turn fully rocks between its toggles (and the mode switches)
    path = rocking(fb, fb.limits(args.mode), sweep, points=len(theta2) // 2 + 1)
    anim = animate.fourbar(path, p, delta, frames=args.frames, fps=args.fps, dpi=args.dpi)
    r = ", ".join(f"{x:g}" for x in fb.lengths)
    n = len(animate.fourbar_frames(path, args.frames))
    wrote = _save(anim, args, f"planarkin four-bar ({r}), {args.mode} mode", n)
    how = "" if len(path) == 1 else ", the crank rocking between its toggles"
    print(f"planarkin animate: four-bar ({r}), {args.mode} mode{how}, {n} frames")
    print(f"  wrote {wrote}")
    return 0


def _run_scene(args: argparse.Namespace) -> int:
    refuse_fourbar_options(args)
    sc = load_scene(args.scene)
    _check(args)
    finite("--dpi", args.dpi, positive=True)
    theta = scene_angles(sc, args.step)
    # every link drawn: the whole scene swept (a cylinder's barrel and rod too)
    sw = sc.sweep(theta, outputs="all", tol=args.tol, max_iter=args.max_iter,
                  predictor=scene_predictor(args))  # fmt: skip
    anim = animate.scene(sc, sw, frames=args.frames, fps=args.fps, dpi=args.dpi)
    _, points, _, rocks = animate.motion(sc, sw)
    n = len(animate.scene_frames(points, args.frames))
    wrote = _save(anim, args, f"planarkin: {sc.name or args.scene}", n)
    how = ", rocking between its dead points (the input cannot turn fully)" if rocks else ""
    if rocks and sc.input_kind == "displacement":
        how = ", out and back across its stroke"
    what = "input angles" if sc.input_kind == "angle" else "input displacements"
    print(f"planarkin animate: {sc.name or args.scene}, {int(sw.success.sum())} of {len(sw)} "
          f"{what} solved{how}")  # fmt: skip
    print(f"  wrote {wrote}")
    return 0
