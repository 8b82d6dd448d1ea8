"""The one linkage drawer: a pose of any linkage (a scene, or a four-bar drawn as the
scene it is) and its ground onto matplotlib axes. The figures and the animator of both
halves call it; nothing else in planarkin draws links."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from matplotlib import colormaps
from matplotlib.axes import Axes
from matplotlib.colors import to_rgba
from matplotlib.figure import Figure
from matplotlib.patches import Polygon, Rectangle

from ..fourbar import COUPLER_POINT, LINKS
from .fonts import clean

__all__ = ["Structure", "fourbar", "frame", "ground", "hull", "labels", "pose"]


@dataclass(frozen=True)
class Structure:
    """What the drawer needs of a linkage: its links (name -> the points it carries, in
    order), which one is ground and which the input."""

    links: Mapping[str, tuple[str, ...]]
    ground: str
    input: str
    #: Pins in slots: name -> (point, guide link, (line point, line point)).
    slots: Mapping[str, tuple[str, str, tuple[str, str]]] = field(default_factory=dict)
    #: Prismatic joints: name -> (translating link, guide link, (line point, line point)).
    prismatic: Mapping[str, tuple[str, str, tuple[str, str]]] = field(default_factory=dict)
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
        return cls.from_dict(scene.to_dict())

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> Structure:
        """The structure of a scene in the file format (``Scene.to_dict()``), slots and
        prismatic joints included when it has them."""
        inp = d["input"]
        link = inp.get("link")
        if link is None:  # a linear input: the slot's point's link or the translating link
            if "slot" in inp:
                point = d["slots"][inp["slot"]]["point"]
                link = next(k for k, v in d["links"].items() if point in v and k != d["ground"])
            else:
                link = d["prismatic"][inp["prismatic"]]["link"]
        slots = {
            k: (v["point"], v["guide"], tuple(v["line"])) for k, v in d.get("slots", {}).items()
        }
        pris = {
            k: (v["link"], v["guide"], tuple(v["line"])) for k, v in d.get("prismatic", {}).items()
        }
        links = {k: tuple(v) for k, v in d["links"].items()}
        return cls(links, d["ground"], link, slots, pris)  # type: ignore[arg-type]

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
        corners = np.array([pts.get(p, nan) for p in names]).reshape(-1, 2)
        around = hull(corners)
        outline = corners[around]
        if len(around) > 2:
            # a plate: its outline (the convex hull of its points) never crosses itself
            edge = input_color if name == apart else c
            patch = Polygon(outline, closed=True, fc=to_rgba(c, fill_alpha * alpha),
                            ec=to_rgba(edge, alpha), lw=0.6 * lw, zorder=zorder - 1)  # fmt: skip
            artists.append(ax.add_patch(patch))
        j = _joints_of(st, names)
        if name == apart and len(around) <= 2:
            stroke(j if len(j) >= 2 else list(names), input_color)
        elif len(j) == 2 and color is None:
            stroke(j, c)
        elif len(j) == 2:
            bars.append((j[0], j[1]))  # a chain through the joints (the plate round it)
        elif len(around) == 2:  # its points in line: a bar between the outermost two
            stroke([names[k] for k in around], c)
    for chain in _chains(bars):
        stroke(chain, color, lab=label)
        label = None
    artists += _sliders(ax, st, pts, color, alpha, zorder)
    if color is None:
        fixed = set(st.links[st.ground])
        at = np.array([pts[p] for p in pts if p in st.joints and p not in fixed]).reshape(-1, 2)
        at = at[np.isfinite(at).all(axis=1)]
        if len(at):
            artists.append(ax.plot(at[:, 0], at[:, 1], "o", mfc="white", mec="k", ms=ms,
                                   mew=1.2, alpha=alpha, zorder=zorder + 1)[0])  # fmt: skip
    for p in st.tracers():
        v = pts.get(p, nan)
        if np.isfinite(v).all():
            c = next(own[k] for k, names in st.moving() if p in names) if color is None else color
            artists.append(ax.plot(*v, "*", color=c if tracer_color is None else tracer_color,
                                   ms=star, alpha=alpha, zorder=zorder + 1)[0])  # fmt: skip
    return artists


def hull(points: np.ndarray) -> list[int]:
    """Indices of the convex hull of the finite rows of ``points`` ((n, 2)), counter-
    clockwise (Andrew's monotone chain): a link's outline, which never crosses itself
    whatever order its points are listed in. Two indices when they are all in line."""
    ok = [i for i in range(len(points)) if np.isfinite(points[i]).all()]
    if len(ok) < len(points):
        return []  # a link with an unsolved point is left out
    order = sorted(ok, key=lambda i: (points[i][0], points[i][1]))
    uniq: list[int] = []
    for i in order:
        if not uniq or not np.array_equal(points[uniq[-1]], points[i]):
            uniq.append(i)
    if len(uniq) <= 2:
        return uniq

    def cross(o: int, a: int, b: int) -> float:
        (ox, oy), (ax_, ay), (bx, by) = points[o], points[a], points[b]
        return float((ax_ - ox) * (by - oy) - (ay - oy) * (bx - ox))

    def half(seq: list[int]) -> list[int]:
        out: list[int] = []
        for i in seq:
            while len(out) >= 2 and cross(out[-2], out[-1], i) <= 0:
                out.pop()
            out.append(i)
        return out

    lower, upper = half(uniq), half(uniq[::-1])
    return lower[:-1] + upper[:-1]


def _box(centre: np.ndarray, u: np.ndarray, length: float, width: float) -> np.ndarray:
    """Corners of a rectangle centred at ``centre``, ``length`` along unit ``u``."""
    n = np.array([-u[1], u[0]])
    a, b = 0.5 * length * u, 0.5 * width * n
    return np.array([centre - a - b, centre + a - b, centre + a + b, centre - a + b])


def _sliders(
    ax: Axes, st: Structure, pts: Mapping[str, np.ndarray], color: Any, alpha: float, zorder: float
) -> list:
    """Slots as a guide rail (two lines along the guide's line, long enough to cover the
    points on it) with a slider block on the pin; prismatic joints as a sleeve (an open
    rectangle on the guide's line) round the translating link's points."""
    artists: list = []
    size = _scale(pts)
    ink = "0.25" if color is None else color

    def line(p: str, q: str) -> tuple[np.ndarray, np.ndarray] | None:
        a, b = pts.get(p), pts.get(q)
        if a is None or b is None or not (np.isfinite(a).all() and np.isfinite(b).all()):
            return None
        d = b - a
        n = float(np.hypot(*d))
        return (a, d / n) if n > 0 else None

    for point, _guide, (p, q) in st.slots.values():
        at, on = pts.get(point), line(p, q)
        if on is None or at is None or not np.isfinite(at).all():
            continue
        a, u = on
        s = [float(np.dot(v - a, u)) for v in (pts[p], pts[q], at)]
        lo, hi = min(s) - 3 * size, max(s) + 3 * size
        nrm = np.array([-u[1], u[0]])
        foot = a + nrm * float(np.dot(at - a, nrm))  # the rail passes through the pin
        for side in (-0.9, 0.9):
            ends = np.array([foot + lo * u, foot + hi * u]) + side * size * nrm
            artists.append(ax.plot(*ends.T, "-", color=ink, lw=1.0, alpha=alpha,
                                   zorder=zorder - 1.5)[0])  # fmt: skip
        block = _box(at, u, 2.6 * size, 1.5 * size)
        artists.append(ax.add_patch(Polygon(block, closed=True, fc="white", ec=ink, lw=1.2,
                                            alpha=alpha, zorder=zorder + 0.5)))  # fmt: skip
    for link, _guide, (p, q) in st.prismatic.values():
        on = line(p, q)
        carried = np.array([pts.get(k, np.full(2, np.nan)) for k in st.links.get(link, ())])
        if on is None or not len(carried) or not np.isfinite(carried).all():
            continue
        a, u = on
        c = carried.mean(axis=0)
        s = (carried - c) @ u
        length = max(float(np.ptp(s)) * 0.6, 4 * size)
        corners = _box(c, u, length, 2.2 * size)
        sleeve = corners[[3, 0, 1, 2]]  # open at the end the link leaves through
        artists.append(ax.plot(*sleeve.T, "-", color=ink, lw=1.6, alpha=alpha,
                               zorder=zorder - 0.5)[0])  # fmt: skip
    return artists


def _scale(pts: Mapping[str, np.ndarray]) -> float:
    """3% of the extent of the finite points: the size of the symbols."""
    xy = np.array([v for v in pts.values() if np.isfinite(v).all()]).reshape(-1, 2)
    return 0.03 * float(np.ptp(xy, axis=0).max()) if len(xy) > 1 else 1.0


def ground(ax: Axes, st: Structure, xy: Mapping[str, Any], size: float) -> list:
    """Draws the ground link once, as an engineer does: a thin line through its points
    and, under each, a pivot on a support triangle (of height 1.6 ``size``) standing on a
    hatched base. Returns the artists."""
    g = np.array([xy[p] for p in st.links[st.ground]], dtype=np.float64)
    g = g[np.isfinite(g).all(axis=1)]
    around = hull(g)
    ring = g[around + around[:1]] if len(around) > 2 else g[around]
    artists: list = [ax.plot(*ring.T, color="0.45", ls="-.", lw=1.0, zorder=1)[0]]
    for gx, gy in g:
        base = gy - 1.6 * size
        tri = np.array([[gx, gy], [gx - size, base], [gx + size, base]])
        artists.append(ax.add_patch(Polygon(tri, closed=True, fc="0.85", ec="0.2", lw=1.0,
                                            zorder=2)))  # fmt: skip
        artists.append(ax.plot([gx - 1.6 * size, gx + 1.6 * size], [base, base], color="0.2",
                               lw=1.2, zorder=2)[0])  # fmt: skip
        artists.append(ax.add_patch(Rectangle((gx - 1.6 * size, base - 0.7 * size),
                                              3.2 * size, 0.7 * size, fill=False, lw=0,
                                              hatch="////", ec="0.35", zorder=2)))  # fmt: skip
    artists.append(ax.plot(*g.T, "o", mfc="white", mec="k", mew=1.2, ms=6, zorder=6)[0])
    return artists


def labels(ax: Axes, xy: Mapping[str, Any], names: list[str], *, fontsize: float = 8) -> list:
    """Names the points ``names`` of a pose, each label set off from its point away from
    the pose's centre, in the first of eight directions where it overlaps no label placed
    before (checked on the drawn extents). Returns the annotations."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    fig = ax.get_figure(root=True)
    assert isinstance(fig, Figure)
    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    fig.draw_without_rendering()  # the layout settled, so extents are final
    renderer = canvas.get_renderer()
    pts = {n: np.asarray(xy[n], dtype=np.float64) for n in names if n in xy}
    pts = {n: v for n, v in pts.items() if np.isfinite(v).all()}
    if not pts:
        return []
    centre = np.mean(list(pts.values()), axis=0)
    placed: list = []
    boxes: list = []
    marks = [ax.transData.transform(v) for v in pts.values()]
    for n, v in pts.items():
        d = v - centre
        a0 = math.atan2(d[1], d[0]) if np.hypot(*d) > 0 else math.pi / 4
        best, best_hits = None, None
        for k in (0, 1, -1, 2, -2, 3, -3, 4):
            a = a0 + k * math.pi / 4
            off = (9 * math.cos(a), 9 * math.sin(a))
            t = ax.annotate(clean(n, "?"), (float(v[0]), float(v[1])), xytext=off,
                            textcoords="offset points", ha="center", va="center",
                            fontsize=fontsize, zorder=8, annotation_clip=False)  # fmt: skip
            t.set_in_layout(False)
            e = t.get_window_extent(renderer)
            hits = sum(e.overlaps(b) for b in boxes) + sum(
                e.x0 - 2 < m[0] < e.x1 + 2 and e.y0 - 2 < m[1] < e.y1 + 2 for m in marks
            )
            if best_hits is None or hits < best_hits:
                if best is not None:
                    best.remove()
                best, best_hits = t, hits
            else:
                t.remove()
            if hits == 0:
                break
        assert best is not None
        boxes.append(best.get_window_extent(renderer))
        placed.append(best)
    return placed


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
