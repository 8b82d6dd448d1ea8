"""The one linkage drawer: a pose of any linkage (a scene, or a four-bar drawn as the
scene it is) and its ground onto matplotlib axes. The figures and the animator of both
halves call it; nothing else in planarkin draws links."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from matplotlib import colormaps
from matplotlib.axes import Axes
from matplotlib.patches import Polygon

from ..fourbar import COUPLER_POINT, LINKS

__all__ = ["Structure", "fourbar", "frame", "ground", "pose"]


@dataclass(frozen=True)
class Structure:
    """What the drawer needs of a linkage: its links (name -> the points it carries, in
    order), which one is ground and which the input."""

    links: Mapping[str, tuple[str, ...]]
    ground: str
    input: str
    #: Points on two or more links (the joints); the others are tracers.
    joints: frozenset[str] = field(init=False)

    def __post_init__(self) -> None:
        seen: dict[str, int] = {}
        for pts in self.links.values():
            for p in dict.fromkeys(pts):
                seen[p] = seen.get(p, 0) + 1
        object.__setattr__(self, "joints", frozenset(p for p, k in seen.items() if k > 1))

    @classmethod
    def of(cls, scene: Any) -> Structure:
        """The structure of a :class:`planarkin.Scene`."""
        return cls(scene.links, scene.ground, scene.input[0])

    def moving(self) -> list[tuple[str, tuple[str, ...]]]:
        """The links other than ground, in order."""
        return [(k, v) for k, v in self.links.items() if k != self.ground]

    def tracers(self) -> list[str]:
        """Points on one moving link only (coupler points), in order."""
        out = [p for _, pts in self.moving() for p in pts if p not in self.joints]
        return list(dict.fromkeys(out))


def fourbar(coupler: bool = True) -> Structure:
    """A four-bar as the scene it is (the built-in fourbar scene's names): ground O2-O4,
    crank O2-A (the input), coupler A-B carrying the coupler point P, rocker O4-B."""
    links = dict(LINKS)
    if coupler:
        links["coupler"] = (*links["coupler"], COUPLER_POINT)
    return Structure(links, "ground", "crank")


def _joints_of(st: Structure, pts: tuple[str, ...]) -> list[str]:
    return [p for p in dict.fromkeys(pts) if p in st.joints]


def _chains(bars: list[tuple[str, str]]) -> list[list[str]]:
    """Bars joined into polylines through the joints where exactly two of them meet: a
    four-bar's crank, coupler and rocker become the one line O2-A-B-O4."""
    at: dict[str, list[int]] = {}
    for i, (p, q) in enumerate(bars):
        at.setdefault(p, []).append(i)
        at.setdefault(q, []).append(i)
    used: set[int] = set()

    def extend(chain: list[str], i: int) -> None:
        while len(at[chain[-1]]) == 2:
            (k,) = (b for b in at[chain[-1]] if b != i)
            if k in used:
                return
            used.add(k)
            p, q = bars[k]
            chain.append(q if p == chain[-1] else p)
            i = k

    chains = []
    for i, (p, q) in enumerate(bars):
        if i in used:
            continue
        used.add(i)
        ahead, behind = [p, q], [q, p]
        extend(ahead, i)
        extend(behind, i)
        chains.append(behind[:1:-1] + ahead)
    return chains


def _finite_pieces(line: np.ndarray) -> list[np.ndarray]:
    """The pieces of a polyline between its non-finite points (two points or more)."""
    bad = np.flatnonzero(~np.isfinite(line).all(axis=1))
    pieces = np.split(line, bad)
    return [q for q in (p[np.isfinite(p).all(axis=1)] for p in pieces) if len(q) > 1]


def pose(
    ax: Axes,
    st: Structure,
    xy: Mapping[str, Any],
    *,
    color: Any = None,
    input_color: Any = None,
    tracer_color: Any = None,
    alpha: float = 1.0,
    fill_alpha: float = 0.3,
    lw: float = 2.5,
    ms: float = 5.0,
    star: float = 9.0,
    label: str | None = None,
    zorder: float = 3.0,
) -> list:
    """Draws one pose: ``xy`` maps point names to (x, y) (unsolved points NaN: what
    touches them is left out). A link with two joints is a bar, one with more is outlined
    through its joints, one with three points or more is filled; tracer points are stars;
    the ground is left to :func:`ground`. Returns the artists.

    ``color=None``: every link in its own colour, joints as open circles. A ``color``:
    the whole pose in it, the bars joined into chains through the joints where two meet
    (the first chain carries ``label``), joints as dots; ``input_color`` draws the input
    link apart in that colour (an animation's driver); ``tracer_color`` the stars.
    """
    artists: list = []
    cmap = colormaps["tab10"]
    pts = {p: np.asarray(v, dtype=np.float64) for p, v in xy.items()}
    nan = np.full(2, np.nan)
    own = {name: cmap(k % 10) for k, name in enumerate(st.links)}
    style = "-" if color is None else "-o"

    def stroke(names: list[str], c: Any, *, closed: bool = False, lab: str | None = None) -> None:
        line = np.array([pts.get(p, nan) for p in names])
        if closed:
            line = np.vstack([line, line[:1]])
        for piece in _finite_pieces(line):
            (ln,) = ax.plot(piece[:, 0], piece[:, 1], style, color=c, lw=lw, ms=ms, alpha=alpha,
                            zorder=zorder, label=lab)  # fmt: skip
            artists.append(ln)
            lab = None

    apart = st.input if input_color is not None else None
    bars = []
    for name, names in st.moving():
        c = own[name] if color is None else color
        if len(names) > 2:
            poly = np.array([pts.get(p, nan) for p in names])
            if np.isfinite(poly).all():
                patch = Polygon(poly, closed=True, fc=c, ec=c, alpha=fill_alpha * alpha,
                                zorder=zorder - 1)  # fmt: skip
                artists.append(ax.add_patch(patch))
        j = _joints_of(st, names)
        if name == apart:
            stroke(j, input_color)
        elif len(j) > 2:
            stroke(j, c, closed=True)
        elif len(j) == 2 and color is None:
            stroke(j, c)
        elif len(j) == 2:
            bars.append((j[0], j[1]))
    for chain in _chains(bars):
        stroke(chain, color, lab=label)
        label = None
    if color is None:
        fixed = set(st.links[st.ground])
        at = np.array([pts[p] for p in pts if p in st.joints and p not in fixed]).reshape(-1, 2)
        at = at[np.isfinite(at).all(axis=1)]
        if len(at):
            artists.append(ax.plot(at[:, 0], at[:, 1], "o", mfc="white", mec="k", ms=ms,
                                   alpha=alpha, zorder=zorder + 1)[0])  # fmt: skip
    for p in st.tracers():
        v = pts.get(p, nan)
        if np.isfinite(v).all():
            c = next(own[k] for k, names in st.moving() if p in names) if color is None else color
            artists.append(ax.plot(*v, "*", color=c if tracer_color is None else tracer_color,
                                   ms=star, alpha=alpha, zorder=zorder + 1)[0])  # fmt: skip
    return artists


def ground(ax: Axes, st: Structure, xy: Mapping[str, Any], size: float) -> list:
    """Draws the ground link once: a dashed line through its points, a hatched-style
    triangle (of height 1.6 ``size``) under each and a dot on each. Returns the artists."""
    g = np.array([xy[p] for p in st.links[st.ground]], dtype=np.float64)
    artists: list = [ax.plot(*g.T, color="0.35", ls="--", lw=1.2, zorder=1)[0]]
    for gx, gy in g:
        tri = np.array([[gx, gy], [gx - size, gy - 1.6 * size], [gx + size, gy - 1.6 * size]])
        artists.append(ax.add_patch(Polygon(tri, closed=True, fc="0.75", ec="0.2", lw=1.0,
                                            zorder=2)))  # fmt: skip
    artists.append(ax.plot(*g.T, "o", color="k", ms=5, zorder=5)[0])
    return artists


def frame(ax: Axes, *arrays: Any, pad: float = 0.08) -> None:
    """Fits the view to every finite point of ``arrays`` (any shapes of (x, y) pairs),
    equal aspect, with room below for the ground triangles."""
    pts = np.concatenate([np.asarray(a, dtype=np.float64).reshape(-1, 2) for a in arrays])
    pts = pts[np.isfinite(pts).all(axis=1)]
    if not len(pts):
        return
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    m = pad * float(max(hi - lo)) + 1e-12
    ax.set_xlim(lo[0] - m, hi[0] + m)
    ax.set_ylim(lo[1] - 2.5 * m, hi[1] + m)
    ax.set_aspect("equal", adjustable="box")
