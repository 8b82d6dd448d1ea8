"""A scene's declared output along a sweep or trace, as a designer reads it: its coordinate
from the points (an angle, or a slot's or prismatic pair's displacement), its extremes and
the inputs where they occur, its swing or stroke, a crank's quick-return time ratio and a
slider's transmission angle. Plain NumPy on results; nothing here solves."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = [
    "Declared",
    "columns",
    "coordinate",
    "declared",
    "extremes",
    "needs",
    "summary",
    "time_ratio",
    "transmission",
]


@dataclass(frozen=True)
class Declared:
    """What a scene's ``output`` entry names, as the points that locate it.

    ``kind`` is "angle" (a ground-pivoted link: the direction from ``pivot`` to ``tip``)
    or "displacement" (along a slot or prismatic pair: ``point`` measured along the line
    ``line`` of the guide, from the drawn pose). A slot's ``rod`` is the link reaching
    its point and ``rod_from`` that link's joint the rod's direction is measured from (the
    transmission angle)."""

    kind: str
    name: str
    link: str | None = None
    pivot: str | None = None
    tip: str | None = None
    point: str | None = None
    line: tuple[str, str] | None = None
    drawn: float = 0.0
    rod: str | None = None
    rod_from: str | None = None

    def points(self) -> list[str]:
        """The points the coordinate and the transmission angle are computed from."""
        names = [self.pivot, self.tip, self.point, self.rod_from, *(self.line or ())]
        return [p for p in dict.fromkeys(names) if p is not None]


def declared(scene: Any) -> Declared | None:
    """The declared output of ``scene`` (a :class:`planarkin.Scene`), None without one."""
    d = scene.to_dict()
    out = d.get("output")
    if not out:
        return None
    links = d["links"]
    pts = d["points"]
    if "link" in out:
        link, pivot = out["link"], out["pivot"]
        tip = next(q for q in links[link] if q != pivot)
        return Declared("angle", link, link=link, pivot=pivot, tip=tip)
    ((kind, name),) = out.items()
    if kind == "slot":
        spec = d["slots"][name]
        point, guide = spec["point"], spec["guide"]
        carriers = [k for k, v in links.items() if point in v and k != guide]
        rod = carriers[0] if carriers else None
        rod_from = None
        if rod is not None:
            # from the rod's joint with the rest of the linkage (a crank pin), else its
            # first other point
            joints = {p for k, v in links.items() if k != rod for p in v}
            others = [p for p in links[rod] if p != point]
            rod_from = next((p for p in others if p in joints), others[0] if others else None)
    else:
        spec = d["prismatic"][name]
        point, rod, rod_from = links[spec["link"]][0], None, None
    line = (spec["line"][0], spec["line"][1])
    s0 = _along(np.asarray(pts[point], float), np.asarray(pts[line[0]], float),
                np.asarray(pts[line[1]], float))  # fmt: skip
    return Declared("displacement", name, point=point, line=line, drawn=float(s0), rod=rod,
                    rod_from=rod_from)  # fmt: skip


def needs(scene: Any) -> list[str]:
    """The names a plan must report for the declared output to be known: the output link
    (its angle in ``sw.angles``), or the slot's point, its line's points and the rod (its
    transmission angle); empty without an output."""
    dec = declared(scene)
    if dec is None:
        return []
    names = [dec.link, dec.rod, *dec.points()]
    return [n for n in dict.fromkeys(names) if n is not None]


def _along(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The coordinate of ``p`` along the line a -> b (from a, unit length), row by row."""
    d = b - a
    u = d / np.hypot(d[..., 0], d[..., 1])[..., None]  # unit first: no overflow at any scale
    return ((p - a) * u).sum(axis=-1)


def coordinate(dec: Declared, points: Mapping[str, np.ndarray]) -> np.ndarray:
    """The output coordinate at every row of ``points`` (name -> (N, 2)): an angle in
    radians, unwrapped along the rows (NaN rows skipped), or a displacement from the
    drawn pose."""
    if dec.kind == "angle":
        assert dec.pivot is not None and dec.tip is not None
        v = np.asarray(points[dec.tip]) - np.asarray(points[dec.pivot])
        a = np.arctan2(v[:, 1], v[:, 0])
        ok = np.isfinite(a)
        a[ok] = np.unwrap(a[ok])
        return a
    assert dec.point is not None and dec.line is not None
    p, a, b = (np.asarray(points[k], dtype=np.float64) for k in (dec.point, *dec.line))
    return _along(p, a, b) - dec.drawn


def transmission(dec: Declared, points: Mapping[str, np.ndarray]) -> np.ndarray | None:
    """A slot output's transmission angle (radians, in [0, pi/2]) at every row: the angle
    between the rod (the link reaching the slot's point, from its other joint to the
    point) and the slot's normal; pi/2 is a rod along the slot (all of its force drives
    the slider), 0 one across it (a dead point). None for other outputs."""
    if dec.kind != "displacement" or dec.rod_from is None or dec.point is None:
        return None
    assert dec.line is not None
    p, q, a, b = (np.asarray(points[k], dtype=np.float64)
                  for k in (dec.point, dec.rod_from, *dec.line))  # fmt: skip
    rod, along = p - q, b - a
    cos_to_line = np.abs((rod * along).sum(axis=1)) / (
        np.hypot(rod[:, 0], rod[:, 1]) * np.hypot(along[:, 0], along[:, 1])
    )
    # the angle to the normal is the complement of the angle to the line
    return np.arcsin(np.clip(cos_to_line, 0.0, 1.0))


def _vertex(x: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """The extreme (x, y) of the polynomial through the (three or five) points round a
    sampled extreme, the middle one: the parabola's vertex, then (five points) Newton on
    the quartic's slope from there, so the extreme is good to about the step's fourth
    power, not its square."""
    m = len(x) // 2
    x0 = float(x[m])
    h = x - x0
    mid = slice(m - 1, m + 2)
    c2, c1, _ = np.polyfit(h[mid], y[mid], 2)
    if c2 == 0:
        return x0, float(y[m])
    lo, hi = float(h[m - 1]), float(h[m + 1])
    dx = float(np.clip(-c1 / (2 * c2), lo, hi))
    poly = np.polyfit(h, y, len(x) - 1)
    slope, curve = np.polyder(poly), np.polyder(poly, 2)
    for _ in range(8 if len(x) == 5 else 0):
        c = float(np.polyval(curve, dx))
        if c == 0:
            break
        dx = float(np.clip(dx - float(np.polyval(slope, dx)) / c, lo, hi))
    return x0 + dx, float(np.polyval(poly, dx))


def extremes(
    t: np.ndarray, y: np.ndarray, *, cyclic: bool = False
) -> tuple[tuple[float, float], tuple[float, float]]:
    """((input, value) at the minimum, (input, value) at the maximum) of ``y`` over the
    finite rows, each refined by the parabola through it and its neighbours where it is
    not at an end (``cyclic``: the rows are one period, the ends neighbours, ``t`` then
    continued by its period across the seam)."""
    ok = np.isfinite(y) & np.isfinite(t)
    t, y = t[ok], y[ok]
    n = len(t)
    out = []
    for i in (int(np.argmin(y)), int(np.argmax(y))):
        if cyclic and n >= 5:
            period = float(t[-1] - t[0]) * n / (n - 1)
            k = np.arange(i - 2, i + 3)
            # the rows across the seam are a period on: continue t there
            x = t[k % n].astype(float) + period * np.floor_divide(k, n)
            out.append(_refined(x, y[k % n]))
        elif 2 <= i < n - 2:
            out.append(_refined(t[i - 2 : i + 3], y[i - 2 : i + 3]))
        elif 0 < i < n - 1:
            out.append(_refined(t[i - 1 : i + 2], y[i - 1 : i + 2]))
        else:
            out.append((float(t[i]), float(y[i])))
    return out[0], out[1]


def _refined(x: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """The sampled extreme in the middle of ``x``, refined (:func:`_vertex`) only where it
    is one: samples evenly spaced round it (no unsolved rows between) and the middle one
    beyond both neighbours. An extreme at the edge of a solved span (the motion stops
    there, at a dead point) is the sample itself."""
    m = len(x) // 2
    step = np.diff(x)
    even = bool(np.all(step > 0)) and float(step.max()) <= 1.01 * float(step.min())
    peak = (y[m] - y[m - 1]) * (y[m] - y[m + 1]) > 0
    if even and peak:
        return _vertex(x, y)
    if peak and len(x) == 5:
        return _refined(x[1:4], y[1:4])
    return float(x[m]), float(y[m])


def time_ratio(t: np.ndarray, y: np.ndarray) -> tuple[float, float, float] | None:
    """A crank's quick-return time ratio from one full turn of the input ``t`` (radians,
    increasing, every row solved, the last row the first again or not): the output ``y``
    must rise once and fall once. Returns (ratio >= 1, the input's travel while the output
    rises, while it falls), both in radians; None where the output does not go up and
    down once per turn."""
    t, y = np.asarray(t, dtype=np.float64), np.asarray(y, dtype=np.float64)
    if len(t) < 8 or not (np.isfinite(t).all() and np.isfinite(y).all()):
        return None
    if math.isclose(t[-1] - t[0], math.tau, rel_tol=0, abs_tol=1e-9):
        t, y = t[:-1], y[:-1]  # the last pose is the first
    step = np.diff(t)
    if not (step > 0).all() or not math.isclose(
        t[-1] - t[0] + float(step.mean()), math.tau, rel_tol=1e-6
    ):
        return None
    dy = np.diff(np.append(y, y[0]))
    signs = np.sign(dy[dy != 0])
    if len(signs) < 2 or int(np.count_nonzero(signs != np.roll(signs, 1))) != 2:
        return None
    (t_lo, _), (t_hi, _) = extremes(t, y, cyclic=True)
    rise = (t_hi - t_lo) % math.tau
    fall = math.tau - rise
    if min(rise, fall) <= 0:
        return None
    return max(rise, fall) / min(rise, fall), rise, fall


def summary(
    dec: Declared,
    t: np.ndarray,
    y: np.ndarray,
    mu: np.ndarray | None,
    *,
    angle_input: bool,
    shown: Any,
    unit: str,
) -> dict[str, Any]:
    """The declared output of a sweep as data: its name, kind and unit; its minimum and
    maximum with the inputs where they occur (shown as the input axis shows them); the
    lever's swing or the slider's stroke; a crank's quick-return time ratio; a slot's
    least transmission angle and where. ``t`` are the sweep's input values, ``y`` the
    output coordinate (radians or length), ``mu`` the transmission angle (radians)."""
    ok = np.isfinite(y)
    angle = dec.kind == "angle"
    out_unit = "deg" if angle else unit
    scale = math.degrees(1.0) if angle else 1.0
    res: dict[str, Any] = {
        "name": dec.name,
        "kind": dec.kind,
        "unit": out_unit,
        "min": None,
        "max": None,
        "swing_deg" if angle else "stroke": None,
        "turns_fully": False,
        "time_ratio": None,
        "time_ratio_input_deg": None,
        "transmission_angle_min_deg": None,
    }
    if ok.sum() < 3:
        return res
    full = (
        angle_input
        and bool(ok.all())
        and len(t) > 2
        and (math.isclose(float(t[-1] - t[0]), math.tau, rel_tol=0, abs_tol=1e-9))
    )
    tt, yy = np.asarray(t, dtype=np.float64), np.asarray(y, dtype=np.float64)
    if full:
        tt, yy = tt[:-1], yy[:-1]
    if angle and np.ptp(yy[np.isfinite(yy)]) >= math.tau - 1e-6:
        res["turns_fully"] = True  # no extremes: the output link turns round
        return res
    (t_lo, y_lo), (t_hi, y_hi) = extremes(tt, yy, cyclic=full)
    res["min"] = {"value": _shown_output(y_lo, angle), "input": float(shown(t_lo))}
    res["max"] = {"value": _shown_output(y_hi, angle), "input": float(shown(t_hi))}
    res["swing_deg" if angle else "stroke"] = (y_hi - y_lo) * scale
    if full:
        q = time_ratio(tt, yy)
        if q is not None:
            res["time_ratio"] = q[0]
            res["time_ratio_input_deg"] = {"rising": math.degrees(q[1]),
                                           "falling": math.degrees(q[2])}  # fmt: skip
    if mu is not None and np.isfinite(mu).any():
        m = np.asarray(mu, dtype=np.float64)
        i = int(np.nanargmin(m))
        res["transmission_angle_min_deg"] = math.degrees(float(m[i]))
        res["transmission_angle_min_input"] = float(shown(float(t[i])))
    return res


def _shown_output(v: float, angle: bool) -> float:
    if not angle:
        return float(v)
    d = math.degrees(v) % 360.0
    return d - 360.0 if d > 180.0 else d


def columns(dec: Declared, unit: str) -> Sequence[str]:
    """The CSV columns of the declared output: its coordinate, and a slot's transmission
    angle."""
    cols = [f"output_{dec.name} [{'deg' if dec.kind == 'angle' else unit}]"]
    if dec.kind == "displacement" and dec.rod_from is not None:
        cols.append("transmission_angle [deg]")
    return cols
