"""The one animator: a linkage moving through a sweep (a four-bar's, played as the scene
it is, or any scene's) as a matplotlib animation, saved as a GIF and as a self-contained
HTML page that plays on load. Poses are drawn by the one drawer (``draw``)."""

from __future__ import annotations

import html
import math
import re
import tempfile
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.animation import FuncAnimation, HTMLWriter, PillowWriter
from matplotlib.figure import Figure

from .._status import Status
from ..fourbar import COUPLER_POINT, Sweep
from ..scene import Scene, SceneSweep
from . import draw
from .degrees import wrapped
from .figures.fourbar import pose_points
from .figures.scene import ground_size, tracer_names
from .fonts import clean
from .titles import fit_titles

__all__ = [
    "animation",
    "fourbar",
    "fourbar_frames",
    "html_page",
    "motion",
    "save",
    "scene",
    "scene_frames",
]

_TRACE = "tab:purple"


def animation(
    st: draw.Structure,
    points: Mapping[str, np.ndarray],
    theta: np.ndarray,
    status: np.ndarray,
    frames: Sequence[int],
    *,
    ground: Mapping[str, Any],
    ground_size: float,
    title: str,
    symbol: str = "θ",
    shown: Callable[[float], str] | None = None,
    notes: Sequence[str] | None = None,
    tracers: Sequence[str] = (),
    fps: float = 12,
    dpi: float = 80,
    figsize: tuple[float, float] = (6.0, 4.8),
) -> FuncAnimation:
    """The linkage ``st`` moving through ``points`` (name -> (N, 2)) at the indices
    ``frames``: the ground (points ``ground``) drawn once, each tracer's whole path faint
    and its path so far in colour, the pose redrawn each frame (the input link red, the
    rest blue), and a label "``symbol`` = input" with ``notes[i]`` and the status where it
    is not CONVERGED; ``shown(value)`` writes the input (default: an angle in degrees,
    wrapped to (-180, 180])."""
    write = shown or (lambda v: f"{wrapped(v):6.1f}°")
    fig = Figure(figsize=figsize, dpi=dpi, layout="constrained")
    ax = fig.subplots()
    for p in tracers:
        ax.plot(points[p][:, 0], points[p][:, 1], color="0.8", lw=1.0, zorder=1)
    draw.ground(ax, st, ground, ground_size)
    traces = {p: ax.plot([], [], color=_TRACE, lw=1.8, zorder=2)[0] for p in tracers}
    label = ax.text(0.02, 0.97, "", transform=ax.transAxes, va="top", family="monospace")
    ax.set_title(title, fontsize="medium")
    ax.grid(True, alpha=0.3)
    draw.frame(ax, *points.values(), list(ground.values()))
    fit_titles(fig)
    drawn: list = []

    def draw_frame(i: int) -> list:
        for a in drawn:
            a.remove()
        drawn.clear()
        xy = {n: v[i] for n, v in points.items()}
        drawn.extend(draw.pose(ax, st, xy, color="tab:blue", input_color="tab:red",
                               tracer_color=_TRACE, lw=3, ms=5, star=12, fill_alpha=0.25,
                               zorder=4))  # fmt: skip
        for p, line in traces.items():
            seen = points[p][: i + 1]
            line.set_data(seen[:, 0], seen[:, 1])
        code = Status(int(status[i]))
        state = "" if code == Status.CONVERGED else "  " + code.name.lower().replace("_", " ")
        note = f"  {notes[i]}" if notes is not None else ""
        label.set_text(f"{symbol} = {write(float(theta[i]))}{note}{state}")
        return [*drawn, *traces.values(), label]

    return FuncAnimation(fig, draw_frame, frames=list(frames), interval=1000.0 / fps, blit=False)


# --- the four-bar, played as the scene it is ---------------------------------------------


def _parts(sweep: Sweep | Sequence[Sweep]) -> list[Sweep]:
    return [sweep] if isinstance(sweep, Sweep) else list(sweep)


def fourbar_frames(sweep: Sweep | Sequence[Sweep], frames: int) -> np.ndarray:
    """Indices, into the sweeps played one after another (their points concatenated), of
    the points that :func:`fourbar` shows: at most ``frames``, evenly spaced; a single
    sweep that closes the circle does not repeat its first pose."""
    parts = _parts(sweep)
    t2 = np.concatenate([np.asarray(p.theta2) for p in parts]) if parts else np.empty(0)
    n = len(t2)
    closes = len(parts) == 1 and n > 1 and math.isclose(abs(t2[-1] - t2[0]), math.tau)
    idx = np.unique(np.linspace(0, n - 1 if closes else n, frames, endpoint=False).astype(int))
    return idx[idx < n]


def fourbar(
    sweep: Sweep | Sequence[Sweep],
    p: float,
    delta: float,
    *,
    frames: int = 72,
    fps: float = 12,
    dpi: float = 80,
) -> FuncAnimation:
    """A four-bar moving through the sweep with its coupler curve traced; several sweeps
    (e.g. :func:`planarkin.fourbar.analysis.rocking`) are played one after another, each
    frame labelled with its assembly mode. Save it with :func:`save`."""
    if frames < 1:
        raise ValueError(f"frames must be >= 1, got {frames}")
    parts = _parts(sweep)
    if not parts:
        raise ValueError("sweep: nothing to animate")
    each = [pose_points(s, p, delta) for s in parts]
    points = {n: np.concatenate([e[n] for e in each]) for n in each[0]}
    r = ", ".join(f"{x:g}" for x in parts[0].lengths)
    how = f"r = ({r})"
    if len(parts) > 1:
        how += ", crank rocking between its toggles"
    else:
        how += f", {parts[0].mode} mode"
    return animation(
        draw.fourbar(),
        points,
        np.concatenate([np.asarray(s.theta2) for s in parts]),
        np.concatenate([np.asarray(s.status) for s in parts]),
        fourbar_frames(parts, frames).tolist(),
        ground={"O2": (0.0, 0.0), "O4": (parts[0].lengths[0], 0.0)},
        ground_size=0.03 * max(parts[0].lengths),
        title=f"{how}, p = {p:g}, δ = {math.degrees(delta):g}°",
        symbol="θ2",
        notes=[s.mode for s in parts for _ in range(len(s.theta2))] if len(parts) > 1 else None,
        tracers=[COUPLER_POINT],
        fps=fps,
        dpi=dpi,
    )


# --- any scene ---------------------------------------------------------------------------


def scene(
    scene: Scene, sweep: SceneSweep, *, frames: int = 72, fps: float = 12, dpi: float = 80
) -> FuncAnimation:
    """The scene moving through the solved input values of the sweep (at most ``frames``,
    evenly spaced), its tracer points' paths traced, each frame labelled with its input
    (an angle in degrees, or a linear input's displacement in the scene's unit). Links
    whose points the sweep did not report are left out: sweep ``outputs="all"`` to draw
    every link (the command does). A linkage whose input cannot turn
    fully on the drawn circuit rocks between its dead points instead (:func:`motion`), as
    a four-bar's crank rocks between its toggles: never a jump across what it cannot
    reach."""
    if frames < 1:
        raise ValueError(f"frames must be >= 1, got {frames}")
    theta, points, status, rocks = motion(scene, sweep)
    if not len(theta):
        raise ValueError("the sweep solved no input angle: nothing to animate")
    st = draw.Structure.of(scene)
    drawn = scene.points
    name = clean(scene.name, "scene")
    unit = scene.units or "length"
    linear = scene.input_kind == "displacement"
    how = "out and back across its stroke" if linear else "rocking between its dead points"
    return animation(
        st,
        points,
        theta,
        status,
        scene_frames(points, frames),
        ground={p: drawn[p] for p in st.links[st.ground]},
        ground_size=ground_size(scene),
        title=f"{name}, {how}" if rocks else name,
        symbol="s" if linear else "θ",
        shown=(lambda v: f"{v:9.4g} {unit}") if linear else None,
        tracers=[p for p in tracer_names(scene, sweep) if p in points],
        fps=fps,
        dpi=dpi,
        figsize=(6.0, 5.2),
    )


def scene_frames(points: Mapping[str, np.ndarray], frames: int) -> list[int]:
    """Indices of at most ``frames`` poses of a motion (name -> (M, 2)), evenly spaced; a
    motion whose last pose is its first does not show it twice."""
    n = len(next(iter(points.values()))) if points else 0
    closes = n > 1 and all(np.allclose(v[0], v[-1], equal_nan=True) for v in points.values())
    idx = np.unique(np.linspace(0, n - 1 if closes else n, frames, endpoint=False).astype(int))
    return idx[idx < n].tolist()


def motion(
    scene: Scene, sweep: SceneSweep
) -> tuple[np.ndarray, dict[str, np.ndarray], np.ndarray, bool]:
    """The motion an animation plays: the sweep's solved poses in order when the input
    turns fully on the drawn circuit (every angle solved); else the drawn circuit traced
    through its dead points (``Scene.trace``), so the input rocks between them and the
    linkage moves continuously. A linear input (a cylinder) goes out across its solved
    stroke and back, as a cylinder does (never a jump from one end to the other). Returns
    (input values, name -> (M, 2) points, statuses, whether it rocks or goes back)."""
    ok = sweep.success
    if sweep.input_kind == "displacement" and ok.sum() > 2:
        out = np.flatnonzero(ok)
        out = out[np.argsort(sweep.theta[out], kind="stable")]
        keep = np.concatenate([out, out[-2:0:-1]])
        pts = {k: v[keep] for k, v in sweep.points.items()}
        return sweep.theta[keep], pts, sweep.status[keep], True
    if ok.all() or not ok.any():
        keep = np.flatnonzero(ok)
        pts = {k: v[keep] for k, v in sweep.points.items()}
        return sweep.theta[keep], pts, sweep.status[keep], False
    tr = scene.trace()
    status = np.full(len(tr), int(Status.CONVERGED), dtype=np.int8)
    return tr.theta, dict(tr.points), status, len(tr.turning_points) > 0


# --- saving: the GIF and the self-contained page -----------------------------------------


def save(
    anim: FuncAnimation,
    gif: Path,
    page: Path,
    *,
    fps: float,
    title: str,
    progress: Callable[[int, int], object] | None = None,
) -> None:
    """Writes the animation as a GIF and as a self-contained HTML page (:func:`html_page`);
    ``progress(frame, frames)`` is called after each frame drawn (twice over: GIF, page)."""
    # matplotlib's stub types fps as int; the writers take any positive number
    anim.save(str(gif), writer=PillowWriter(fps=fps), progress_callback=progress)  # type: ignore[arg-type]
    page.write_text(html_page(anim, fps=fps, title=title, progress=progress), encoding="utf-8")


def _svg(*shapes: str) -> str:
    """A 16 x 16 inline SVG icon in the button's text colour: no font needed."""
    return (
        '<svg viewBox="0 0 16 16" width="16" height="16" fill="currentColor" '
        'aria-hidden="true" style="vertical-align:middle">' + "".join(shapes) + "</svg>"
    )


_BAR = '<rect x="{}" y="3" width="2.5" height="10"/>'
_LEFT = '<polygon points="{},3 {},13 {},8"/>'  # a triangle pointing left
_ICONS = {  # matplotlib's Font Awesome classes -> inline SVG
    "fa-minus": _svg('<rect x="3" y="7" width="10" height="2.5"/>'),
    "fa-fast-backward": _svg(_BAR.format(1.5), _LEFT.format(9, 9, 4), _LEFT.format(14, 14, 9)),
    "fa-step-backward": _svg(_BAR.format(3), _LEFT.format(13, 13, 6)),
    "fa-play fa-flip-horizontal": _svg(_LEFT.format(12.5, 12.5, 3.5)),
    "fa-pause": _svg(_BAR.format(4), _BAR.format(9.5)),
    "fa-play": _svg('<polygon points="3.5,3 3.5,13 12.5,8"/>'),
    "fa-step-forward": _svg('<polygon points="3,3 3,13 10,8"/>', _BAR.format(10.5)),
    "fa-fast-forward": _svg(
        '<polygon points="2,3 2,13 7,8"/>', '<polygon points="7,3 7,13 12,8"/>', _BAR.format(12)
    ),
    "fa-plus": _svg('<rect x="3" y="6.75" width="10" height="2.5"/>',
                    '<rect x="6.75" y="3" width="2.5" height="10"/>'),
}  # fmt: skip


def html_page(
    anim: FuncAnimation,
    *,
    fps: float = 12,
    title: str = "planarkin",
    progress: Callable[[int, int], object] | None = None,
) -> str:
    """A self-contained HTML page (frames embedded as base64 PNG, play controls in plain
    JavaScript) for an animation, playing (looped) as soon as it loads. matplotlib's player
    loads its button icons from a web font; they are drawn as inline SVG instead, so the
    page needs no network and no particular font."""
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp, "anim.html")
        # matplotlib's stub types fps as int, but the writers take any positive number
        # (Animation.save itself passes fps=1000.0 / interval); a float fps is kept as is.
        writer = HTMLWriter(
            fps=fps,  # type: ignore[arg-type]
            embed_frames=True,
            default_mode="loop",
            embed_limit=1e6,
        )
        anim.save(str(path), writer=writer, progress_callback=progress)
        body = path.read_text(encoding="utf-8")
    body = re.sub(r"<link\b[^>]*\bhref=[\"']https?://[^>]*>", "", body)
    body = re.sub(
        r'<i class="fa ([^"]*)"></i>',
        lambda m: _ICONS.get(m.group(1).strip(), _svg('<circle cx="8" cy="8" r="3"/>')),
        body,
    )
    # start playing once matplotlib's player object exists (it is made in a timeout)
    names = sorted(set(re.findall(r"\b(anim[0-9a-f]{32})\s*=\s*new Animation", body)))
    autoplay = "".join(
        f'(function start() {{ var a = window["{n}"]; '
        "if (a) { a.play_animation(); } else { setTimeout(start, 10); } })();"
        for n in names
    )
    title = html.escape(title)
    return (
        '<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
        f"<title>{title}</title>\n<style>body{{font-family:sans-serif;margin:1.5em}}"
        ".anim-buttons button{min-width:2.6em;font-size:1em}</style>\n</head>\n<body>\n"
        f"<h3>{title}</h3>\n{body}\n<script>{autoplay}</script>\n</body>\n</html>\n"
    )
