"""Cutting sheets, format-free: every moving link and the ground as a part to cut (a
rounded bar between two pins, a convex hull with rounded corners for a plate), its pin
holes, laid out without overlaps at 1:1 in scene units, with a scale bar. ``dxf`` and
``svg`` write a ``Sheet``; each part's ``place`` maps scene coordinates onto the sheet."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..scene import Scene
from ._lines import helpers

#: Units DXF and SVG know, by the names a scene's ``units`` may give (else: mm).
UNITS = ("mm", "cm", "m", "in")

Point = tuple[float, float]


@dataclass(frozen=True)
class Part:
    """One link to cut. ``outline``: the closed outline as (x, y, bulge) vertices, DXF's
    LWPOLYLINE convention (bulge = tan of a quarter of the arc to the next vertex, 0 for a
    straight edge, > 0 counter-clockwise); ``holes``: point name -> centre (every joint
    and tracer the link carries; not the helper points that only hold a line); ``slots``:
    slot name -> its cut outline, over the pin's travel; ``label``: where the name goes,
    ``label_size`` its height. All on the sheet. ``angle``, ``shift``: the placement,
    sheet = R(angle) scene + shift."""

    name: str
    outline: tuple[tuple[float, float, float], ...]
    holes: dict[str, Point]
    slots: dict[str, tuple[tuple[float, float, float], ...]]
    label: Point
    label_size: float
    angle: float
    shift: Point

    def place(self, p: Sequence[float]) -> Point:
        """A point of the scene's drawn pose, where it lies on the sheet."""
        c, s = math.cos(self.angle), math.sin(self.angle)
        return (c * p[0] - s * p[1] + self.shift[0], s * p[0] + c * p[1] + self.shift[1])


@dataclass(frozen=True)
class Sheet:
    """The laid-out parts; ``size`` (width, height) of the sheet from (0, 0); ``scale``:
    the scale bar's start, end (on the sheet) and its length as labelled."""

    parts: tuple[Part, ...]
    size: Point
    units: str
    width: float
    hole: float
    margin: float
    scale: tuple[Point, Point, float]
    title: str


def hull(points: Sequence[Point]) -> list[Point]:
    """The convex hull, counter-clockwise, without collinear points (two points where all
    are collinear; Andrew's monotone chain)."""
    pts = sorted(set(points))
    if len(pts) <= 2:
        return pts

    def cross(o: Point, a: Point, b: Point) -> float:
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lo: list[Point] = []
    hi: list[Point] = []
    for p in pts:
        while len(lo) >= 2 and cross(lo[-2], lo[-1], p) <= 0:
            lo.pop()
        lo.append(p)
    for p in reversed(pts):
        while len(hi) >= 2 and cross(hi[-2], hi[-1], p) <= 0:
            hi.pop()
        hi.append(p)
    out = lo[:-1] + hi[:-1]
    return out if len(out) >= 2 else pts[:1] + pts[-1:]


def rounded(poly: Sequence[Point], r: float) -> list[tuple[float, float, float]]:
    """The hull grown by ``r`` (its Minkowski sum with a disc): offset edges joined by arcs
    of radius ``r`` around each vertex; two points give a rounded bar."""
    n = len(poly)
    normals = []
    for i in range(n):
        (x0, y0), (x1, y1) = poly[i], poly[(i + 1) % n]
        d = math.hypot(x1 - x0, y1 - y0)
        normals.append(((y1 - y0) / d, -(x1 - x0) / d))  # outward for a CCW polygon
    out: list[tuple[float, float, float]] = []
    for i in range(n):
        (nx, ny), (mx, my) = normals[i], normals[(i + 1) % n]
        a, b = poly[i], poly[(i + 1) % n]
        turn = math.atan2(nx * my - ny * mx, nx * mx + ny * my)
        if turn <= 0:  # two points: the far end turns by pi
            turn += 2 * math.pi
        out.append((a[0] + r * nx, a[1] + r * ny, 0.0))
        out.append((b[0] + r * nx, b[1] + r * ny, math.tan(turn / 4)))
    return out


def _frame(poly: list[Point]) -> float:
    """The rotation that lays the part flattest: the hull edge direction giving the lowest
    bounding box (a bar lies along its axis)."""
    best, angle = math.inf, 0.0
    for i in range(len(poly)):
        (x0, y0), (x1, y1) = poly[i], poly[(i + 1) % len(poly)]
        a = -math.atan2(y1 - y0, x1 - x0)
        c, s = math.cos(a), math.sin(a)
        ys = [s * x + c * y for x, y in poly]
        if max(ys) - min(ys) < best - 1e-12:
            best, angle = max(ys) - min(ys), a
    return angle


def _scale(length: float) -> float:
    """A round length (1, 2 or 5 times a power of ten) at most ``length``."""
    k = 10 ** math.floor(math.log10(length))
    return max(m * k for m in (1, 2, 5) if m * k <= length)


def travel(sc: Scene) -> dict[str, tuple[Point, Point]]:
    """Slot name -> the ends of its pin's travel in the guide's drawn frame, from the scene's
    default sweep (the line through the drawn pin, parallel to the slot's line)."""
    if not sc.slots:
        return {}
    sw = sc.sweep(outputs=list(sc.points))
    ok = sw.success
    out = {}
    for name, (pin, _guide, (a, b)) in sc.slots.items():
        p, q, x = (sw.points[n][ok] for n in (a, b, pin))
        u = q - p
        s = np.einsum("ij,ij->i", x - p, u) / np.hypot(u[:, 0], u[:, 1])
        (ax, ay), (bx, by), (px, py) = sc.points[a], sc.points[b], sc.points[pin]
        d = math.hypot(bx - ax, by - ay)
        ux, uy = (bx - ax) / d, (by - ay) / d
        s0 = (px - ax) * ux + (py - ay) * uy
        lo, hi = (float(s.min()) - s0, float(s.max()) - s0) if len(s) else (0.0, 0.0)
        out[name] = ((px + lo * ux, py + lo * uy), (px + hi * ux, py + hi * uy))
    return out


def layout(
    sc: Scene,
    width: float | None = None,
    hole: float | None = None,
    margin: float | None = None,
) -> Sheet:
    """The scene's links as parts on a sheet: bars ``width`` wide (default: 6% of the
    scene's size), holes of diameter ``hole`` (40% of the width) at every point a link
    carries, ``margin`` between parts and round the sheet (half the width)."""
    pts = sc.points
    xs, ys = [p[0] for p in pts.values()], [p[1] for p in pts.values()]
    size = max(max(xs) - min(xs), max(ys) - min(ys))
    w = 0.06 * size if width is None else width
    d = 0.4 * w if hole is None else hole
    m = 0.5 * w if margin is None else margin
    for what, v in (("width", w), ("hole", d), ("margin", m)):
        if not (math.isfinite(v) and v > 0):
            raise ValueError(f"{what} must be a positive finite length, got {v!r}")
    if d >= w:
        raise ValueError(f"hole ({d:g}) must be smaller than width ({w:g})")
    units = sc.units if sc.units in UNITS else "mm"
    ends = travel(sc)
    skip = helpers(sc)
    shapes = []
    for name, on in sc.links.items():
        slot_ends = [e for n, e in ends.items() if sc.slots[n][1] == name]
        around = [pts[p] for p in on if p not in skip] + [q for e in slot_ends for q in e]
        poly = hull(around if len(hull(around)) >= 2 else [pts[p] for p in on])
        if len(poly) < 2:
            raise ValueError(f"links.{name}: its points coincide; a part needs two apart")
        a = _frame(poly)
        c, s = math.cos(a), math.sin(a)
        rot = [(c * x - s * y, s * x + c * y) for x, y in poly]
        lo = (min(p[0] for p in rot) - w / 2, min(p[1] for p in rot) - w / 2)
        hi = (max(p[0] for p in rot) + w / 2, max(p[1] for p in rot) + w / 2)
        shapes.append((name, on, poly, a, lo, hi))
    # shelves: tallest first, rows no wider than a square sheet would be
    area = sum((hi[0] - lo[0] + m) * (hi[1] - lo[1] + m) for *_, lo, hi in shapes)
    row_w = max(math.sqrt(area) * 1.2, *(hi[0] - lo[0] for *_, lo, hi in shapes))
    order = sorted(shapes, key=lambda t: -(t[5][1] - t[4][1]))
    parts: list[Part] = []
    x = y = m
    row_h = 0.0
    right = 0.0
    for name, on, poly, a, lo, hi in order:
        pw, ph = hi[0] - lo[0], hi[1] - lo[1]
        if x > m and x + pw > m + row_w:
            x, y, row_h = m, y + row_h + m, 0.0
        shift = (x - lo[0], y - lo[1])
        part = Part(name, (), {}, {}, (0.0, 0.0), 0.0, a, shift)
        verts = [part.place(p) for p in poly]
        centre = part.place(
            (sum(p[0] for p in poly) / len(poly), sum(p[1] for p in poly) / len(poly))
        )
        holes = {p: part.place(pts[p]) for p in on if p not in skip}
        slots = {
            n: tuple(rounded(hull([part.place(q) for q in e]), d / 2))
            for n, e in ends.items()
            if sc.slots[n][1] == name and math.dist(*e) > 0
        }
        # the name fits between the holes of a bar (a character is about 0.6 high)
        text = min(0.5 * w, 0.8 * (pw - w - d) / (0.6 * max(len(name), 1)))
        outline = tuple(rounded(verts, w / 2))
        parts.append(Part(name, outline, holes, slots, centre, max(text, 0.1 * w), a, shift))
        x += pw + m
        row_h = max(row_h, ph)
        right = max(right, x)
    bar = _scale(max(right - 2 * m, w) / 3)
    y_bar = y + row_h + m
    scale = ((m, y_bar), (m + bar, y_bar), bar)
    sheet_h = y_bar + 2 * w + m
    title = sc.name or "scene"
    return Sheet(tuple(parts), (max(right, m + bar + m), sheet_h), units, w, d, m, scale, title)
