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

__all__ = ["Cylinder", "Structure", "fourbar", "frame", "ground", "hull", "labels", "pose"]


@dataclass(frozen=True)
class Cylinder:
    """A prismatic pair between two moving links drawn as a hydraulic cylinder: the barrel
    (the guide) a tube from its closed end ``closed`` along the line, ``barrel`` long; the
    rod (the translating link) a bar from its pin ``pin`` back into the barrel, ``rod``
    long, ending in the piston. Both lengths are fixed by the drawn pose (and the pair's
    travel limits, when the scene has them) so that they overlap as a real cylinder's do."""

    #: the guide (barrel) and translating (rod) links, and the pair's line (two points)
    barrel_link: str
    rod_link: str
    line: tuple[str, str]
    #: +1 when the rod leaves the barrel in the line's direction (line[0] -> line[1])
    sign: float
    #: the barrel's closed end (a point of the barrel link) and the rod's outer pin
    closed: str
    pin: str
    barrel: float
    rod: float
    #: the tube's width (the rod is a third of it)
    width: float

    @classmethod
    def of(
        cls, pts: Mapping[str, Any], links: Mapping[str, tuple[str, ...]], rod_link: str,
        barrel_link: str, line: tuple[str, str], travel: Any = None,
    ) -> Cylinder | None:  # fmt: skip
        """The cylinder of a prismatic pair as drawn at ``pts``; ``travel`` its limits
        (lo, hi) on the displacement, when the scene has them. None when the drawing is
        degenerate (the line's points together)."""
        xy = {k: np.asarray(v, dtype=np.float64) for k, v in pts.items()}
        a, b = xy[line[0]], xy[line[1]]
        n = float(np.hypot(*(b - a)))
        if not n > 0:
            return None
        u = (b - a) / n
        tg = {p: float((xy[p] - a) @ u) for p in links[barrel_link]}
        tr = {p: float((xy[p] - a) @ u) for p in links[rod_link]}
        sign = 1.0 if np.mean(list(tr.values())) >= np.mean(list(tg.values())) else -1.0
        closed = min(tg, key=lambda p: sign * tg[p])
        pin = max(tr, key=lambda p: sign * tr[p])
        own = max(sign * (tg[p] - tg[closed]) for p in tg)
        e0 = sign * (tr[pin] - tg[closed])  # the pin's distance out from the closed end
        ext = np.ptp(np.array(list(xy.values())), axis=0).max()
        if travel is not None and len(travel) == 2 and all(map(math.isfinite, travel)):
            lo, hi = sorted(sign * float(v) for v in travel)
            # the piston at the closed end when fully retracted, at the mouth extended
            rod, barrel = e0 + lo, max(own, hi - lo)
        else:  # the piston half-way along the barrel as drawn
            barrel = own if own > 0 else 0.5 * e0
            rod = e0 - 0.5 * barrel
        if not (rod > 0 and barrel > 0):
            barrel, rod = 0.5 * abs(e0), 0.75 * abs(e0)
        return cls(barrel_link, rod_link, line, sign, closed, pin, barrel, rod,
                   0.05 * float(ext))  # fmt: skip


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
    #: Prismatic joints between two moving links, drawn as cylinders: name -> its shape.
    cylinders: Mapping[str, Cylinder] = field(default_factory=dict)
    #: Points on two or more links, and the pins in slots (the joints); the others are
    #: tracers, or helpers.
    joints: frozenset[str] = field(init=False)
    #: Points that only give a slot's or prismatic pair's line its direction (on one link,
    #: no joint): drawn as a small mark, never as a pivot or a tracer.
    helpers: frozenset[str] = field(init=False)

    def __post_init__(self) -> None:
        seen: dict[str, int] = {}
        for pts in self.links.values():
            for p in dict.fromkeys(pts):
                seen[p] = seen.get(p, 0) + 1
        pins = {v[0] for v in self.slots.values()}
        joints = frozenset(p for p, k in seen.items() if k > 1) | pins
        object.__setattr__(self, "joints", joints)
        lines = {p for v in (*self.slots.values(), *self.prismatic.values()) for p in v[2]}
        object.__setattr__(self, "helpers", frozenset(lines - joints))

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
        limits = d.get("limits") or {}
        cyl = {}
        for k, (rod, guide, line) in pris.items():
            if d["ground"] not in (rod, guide):
                travel = limits.get(k) if isinstance(limits.get(k), (list, tuple)) else None
                c = Cylinder.of(d["points"], links, rod, guide, line, travel)  # type: ignore[arg-type]
                if c is not None:
                    cyl[k] = c
        return cls(links, d["ground"], link, slots, pris, cyl)  # type: ignore[arg-type]

    def moving(self) -> list[tuple[str, tuple[str, ...]]]:
        """The links other than ground, in order."""
        return [(k, v) for k, v in self.links.items() if k != self.ground]

    def tracers(self) -> list[str]:
        """Points on one moving link only (coupler points), in order: not a joint, not a
        line's helper, not a point of a cylinder's barrel or rod (drawn as the cylinder)."""
        inside = {c for cy in self.cylinders.values() for c in (cy.barrel_link, cy.rod_link)}
        out = [
            p
            for k, pts in self.moving()
            for p in pts
            if p not in self.joints and p not in self.helpers and k not in inside
        ]
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
    tubes = {c for cy in st.cylinders.values() for c in (cy.barrel_link, cy.rod_link)}
    for name, names in st.moving():
        c = own[name] if color is None else color
        corners = np.array([pts.get(p, nan) for p in names]).reshape(-1, 2)
        around = hull(corners)
        outline = corners[around]
        if name in tubes and len(around) <= 2:
            continue  # a cylinder's barrel or rod in line: drawn as the cylinder
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
            ends = [names[k] for k in around]
            if len(around) == 2 and set(ends) != set(j):
                stroke(ends, c)  # a bar that reaches past its joints (a boom to its tip)
        elif len(around) == 2:  # its points in line: a bar between the outermost two
            stroke([names[k] for k in around], c)
    for chain in _chains(bars):
        stroke(chain, color, lab=label)
        label = None
    artists += _sliders(ax, st, pts, color, alpha, zorder, own)
    artists += _cylinders(ax, st, pts, color, input_color, alpha, zorder, own)
    if color is None:
        fixed = set(st.links[st.ground])
        at = np.array([pts[p] for p in pts if p in st.joints and p not in fixed]).reshape(-1, 2)
        at = at[np.isfinite(at).all(axis=1)]
        if len(at):
            artists.append(ax.plot(at[:, 0], at[:, 1], "o", mfc="white", mec="k", ms=ms,
                                   mew=1.2, alpha=alpha, zorder=zorder + 1)[0])  # fmt: skip
    # a moving line's direction point: a small cross, not a joint (ground's: by ground())
    fixed = set(st.links[st.ground])
    helpers = [pts.get(p, nan) for p in sorted(st.helpers) if p not in fixed]
    m = np.array(helpers).reshape(-1, 2)
    m = m[np.isfinite(m).all(axis=1)]
    if len(m) and color is None:
        artists.append(ax.plot(m[:, 0], m[:, 1], "+", color="0.35", ms=ms + 1, mew=1.0,
                               alpha=alpha, zorder=zorder + 1, gid="helper")[0])  # fmt: skip
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
    ax: Axes,
    st: Structure,
    pts: Mapping[str, np.ndarray],
    color: Any,
    alpha: float,
    zorder: float,
    own: Mapping[str, Any],
) -> list:
    """Slots as a guide rail (two lines along the guide's line, long enough to cover the
    points on it) with a slider block on the pin: on ground a grey rail past the points; on
    a moving guide (a slotted lever) the slot is part of that link, in its colour, closed
    at both ends and running from the guide's own points to the pin, so it never floats
    off its link. Prismatic joints on ground as a sleeve (an open rectangle on the guide's
    line) round the translating link's points; between two moving links, see
    :func:`_cylinders`."""
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

    for point, guide, (p, q) in st.slots.values():
        at, on = pts.get(point), line(p, q)
        if on is None or at is None or not np.isfinite(at).all():
            continue
        a, u = on
        nrm = np.array([-u[1], u[0]])
        foot = a + nrm * float(np.dot(at - a, nrm))  # the rail passes through the pin
        if guide == st.ground:
            s = [float(np.dot(v - a, u)) for v in (pts[p], pts[q], at)]
            lo, hi = min(s) - 3 * size, max(s) + 3 * size
            for side in (-0.9, 0.9):
                ends = np.array([foot + lo * u, foot + hi * u]) + side * size * nrm
                artists.append(ax.plot(*ends.T, "-", color=ink, lw=1.0, alpha=alpha,
                                       zorder=zorder - 1.5)[0])  # fmt: skip
        else:
            on_guide = [pts.get(k) for k in st.links.get(guide, ())]
            s = [
                float(np.dot(v - a, u)) for v in on_guide if v is not None and np.isfinite(v).all()
            ]
            s.append(float(np.dot(at - a, u)))
            lo, hi = min(s) - 1.6 * size, max(s) + 1.6 * size
            ring = np.array([foot + lo * u, foot + hi * u, foot + hi * u, foot + lo * u])
            ring += np.array([-1, -1, 1, 1])[:, None] * 0.9 * size * nrm
            c = own[guide] if color is None else color
            artists.append(ax.add_patch(Polygon(ring, closed=True, fill=False, ec=c, lw=1.4,
                                                alpha=alpha, zorder=zorder - 0.5,
                                                gid=f"slot:{guide}")))  # fmt: skip
        block = _box(at, u, 2.6 * size, 1.5 * size)
        artists.append(ax.add_patch(Polygon(block, closed=True, fc="white", ec=ink, lw=1.2,
                                            alpha=alpha, zorder=zorder + 0.5)))  # fmt: skip
    for name, (link, _guide, (p, q)) in st.prismatic.items():
        if name in st.cylinders:
            continue
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


def _cylinders(
    ax: Axes,
    st: Structure,
    pts: Mapping[str, np.ndarray],
    color: Any,
    input_color: Any,
    alpha: float,
    zorder: float,
    own: Mapping[str, Any],
) -> list:
    """Each :class:`Cylinder` at this pose: the barrel a filled tube from its closed end
    along the pair's line, the rod a bar from its pin back into the barrel, ending in the
    piston (a cross bar); the rod and the barrel overlap as a real cylinder's do. The
    barrel's patch has the gid ``barrel:NAME``, the rod's line ``rod:NAME``."""
    artists: list = []
    for name, cy in st.cylinders.items():
        need = [pts.get(k) for k in (cy.closed, cy.pin, *cy.line)]
        if any(v is None or not np.isfinite(v).all() for v in need):
            continue
        closed, pin, a, b = (np.asarray(v, dtype=np.float64) for v in need)
        d = b - a
        n = float(np.hypot(*d))
        if not n > 0:
            continue
        w = cy.sign * d / n  # out of the barrel, towards the rod's pin
        nrm = np.array([-w[1], w[0]])
        # the tube on the line through the pin (the pair keeps its offset)
        base = closed + nrm * float(np.dot(pin - closed, nrm))
        tube = _box(base + 0.5 * cy.barrel * w, w, cy.barrel, cy.width)
        cb = own[cy.barrel_link] if color is None else color
        cr = own[cy.rod_link] if color is None else color
        if input_color is not None and st.input == cy.rod_link:
            cr = input_color
        artists.append(ax.add_patch(Polygon(tube, closed=True, fc=to_rgba(cb, 0.35 * alpha),
                                            ec=to_rgba(cb, alpha), lw=1.4, zorder=zorder - 0.5,
                                            gid=f"barrel:{name}")))  # fmt: skip
        piston = pin - cy.rod * w
        (rod,) = ax.plot(*np.array([pin, piston]).T, "-", color=cr, lw=2.2, alpha=alpha,
                         zorder=zorder + 0.2, solid_capstyle="butt", gid=f"rod:{name}")  # fmt: skip
        cross = np.array([piston - 0.42 * cy.width * nrm, piston + 0.42 * cy.width * nrm])
        artists += [rod, ax.plot(*cross.T, "-", color=cr, lw=2.6, alpha=alpha,
                                 zorder=zorder + 0.2, gid=f"piston:{name}")[0]]  # fmt: skip
    return artists


def _scale(pts: Mapping[str, np.ndarray]) -> float:
    """3% of the extent of the finite points: the size of the symbols."""
    xy = np.array([v for v in pts.values() if np.isfinite(v).all()]).reshape(-1, 2)
    return 0.03 * float(np.ptp(xy, axis=0).max()) if len(xy) > 1 else 1.0


def ground(ax: Axes, st: Structure, xy: Mapping[str, Any], size: float) -> list:
    """Draws the ground link once, as an engineer does: a thin line through its points
    and, under each, a pivot on a support triangle (of height 1.6 ``size``) standing on a
    hatched base; a point that only gives a slot's line its direction (a helper) is a
    small cross. Returns the artists."""
    g = np.array([xy[p] for p in st.links[st.ground]], dtype=np.float64)
    g = g[np.isfinite(g).all(axis=1)]
    around = hull(g)
    ring = g[around + around[:1]] if len(around) > 2 else g[around]
    artists: list = [ax.plot(*ring.T, color="0.45", ls="-.", lw=1.0, zorder=1)[0]]
    # a point that only gives a slot's line its direction is no pivot: a small cross
    mark = [p for p in st.links[st.ground] if p in st.helpers]
    at = np.array([xy[p] for p in mark], dtype=np.float64).reshape(-1, 2)
    if len(at):
        artists.append(ax.plot(*at.T, "+", color="0.35", ms=7, mew=1.2, zorder=6,
                               gid="helper")[0])  # fmt: skip
    pivots = [p for p in dict.fromkeys(st.links[st.ground]) if p not in st.helpers]
    g = np.array([xy[p] for p in pivots], dtype=np.float64).reshape(-1, 2)
    g = g[np.isfinite(g).all(axis=1)]
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
