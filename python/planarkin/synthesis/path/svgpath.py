"""SVG path data (the ``d`` attribute) read as one curve and sampled by arc length: lines,
quadratic and cubic Béziers (smooth forms too), elliptical arcs and ``Z``; every sample
lies on the curve (the parameter found by Newton on the exact arc length), not on a chord.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

__all__ = ["SvgCurve", "parse", "sample", "transform", "transformed"]

#: Gauss-Legendre nodes and weights on [0, 1] (7 points): arc lengths of the segments.
_GL_X, _GL_W = np.polynomial.legendre.leggauss(7)
_GL_X, _GL_W = (_GL_X + 1.0) / 2.0, _GL_W / 2.0
#: Knots per segment of the arc-length table that Newton starts from.
_KNOTS = 65

_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_WORD = re.compile(r"[^\s,]+")
#: How many numbers each command takes per repetition.
_ARITY = {"m": 2, "l": 2, "h": 1, "v": 1, "c": 6, "s": 4, "q": 4, "t": 2, "a": 7, "z": 0}


@dataclass(frozen=True)
class _Segment:
    """One piece of the curve: its point and its derivative at parameters t in [0, 1]."""

    at: Callable[[np.ndarray], np.ndarray]
    d: Callable[[np.ndarray], np.ndarray]


@dataclass(frozen=True)
class SvgCurve:
    """The pieces of one SVG subpath, in order, and whether it was closed by ``Z``."""

    segments: tuple[_Segment, ...]
    closed: bool


def _line(p0: np.ndarray, p1: np.ndarray) -> _Segment:
    return _Segment(lambda t: p0 + t[:, None] * (p1 - p0), lambda t: np.tile(p1 - p0, (len(t), 1)))


def _quad(p0: np.ndarray, p1: np.ndarray, p2: np.ndarray) -> _Segment:
    def at(t: np.ndarray) -> np.ndarray:
        t = t[:, None]
        return (1 - t) ** 2 * p0 + 2 * (1 - t) * t * p1 + t**2 * p2

    def d(t: np.ndarray) -> np.ndarray:
        t = t[:, None]
        return 2 * (1 - t) * (p1 - p0) + 2 * t * (p2 - p1)

    return _Segment(at, d)


def _cubic(p0: np.ndarray, p1: np.ndarray, p2: np.ndarray, p3: np.ndarray) -> _Segment:
    def at(t: np.ndarray) -> np.ndarray:
        t = t[:, None]
        u = 1 - t
        return u**3 * p0 + 3 * u * u * t * p1 + 3 * u * t * t * p2 + t**3 * p3

    def d(t: np.ndarray) -> np.ndarray:
        t = t[:, None]
        u = 1 - t
        return 3 * u * u * (p1 - p0) + 6 * u * t * (p2 - p1) + 3 * t * t * (p3 - p2)

    return _Segment(at, d)


def _arc(
    p0: np.ndarray, rx: float, ry: float, phi_deg: float, large: bool, sweep: bool, p1: np.ndarray
) -> _Segment | None:
    """The SVG arc from p0 to p1 (SVG 1.1, appendix F.6.5: endpoint to centre form); radii
    too small are scaled up as the specification says; None for a zero-radius arc (a
    line, which the caller draws)."""
    rx, ry = abs(rx), abs(ry)
    if rx == 0 or ry == 0:
        return None
    phi = math.radians(phi_deg % 360.0)
    c, s = math.cos(phi), math.sin(phi)
    dx, dy = (p0 - p1) / 2.0
    x1, y1 = c * dx + s * dy, -s * dx + c * dy
    lam = (x1 / rx) ** 2 + (y1 / ry) ** 2
    if lam > 1:
        rx, ry = rx * math.sqrt(lam), ry * math.sqrt(lam)
    num = rx * rx * ry * ry - rx * rx * y1 * y1 - ry * ry * x1 * x1
    den = rx * rx * y1 * y1 + ry * ry * x1 * x1
    k = math.sqrt(max(0.0, num / den))
    if large == sweep:
        k = -k
    cx1, cy1 = k * rx * y1 / ry, -k * ry * x1 / rx
    mid = (p0 + p1) / 2.0
    centre = np.array([c * cx1 - s * cy1, s * cx1 + c * cy1]) + mid
    a0 = math.atan2((y1 - cy1) / ry, (x1 - cx1) / rx)
    a1 = math.atan2((-y1 - cy1) / ry, (-x1 - cx1) / rx)
    da = a1 - a0
    if sweep and da < 0:
        da += math.tau
    elif not sweep and da > 0:
        da -= math.tau
    rot = np.array([[c, -s], [s, c]])

    def at(t: np.ndarray) -> np.ndarray:
        a = a0 + t * da
        return centre + np.stack([rx * np.cos(a), ry * np.sin(a)], axis=1) @ rot.T

    def d(t: np.ndarray) -> np.ndarray:
        a = a0 + t * da
        return da * np.stack([-rx * np.sin(a), ry * np.cos(a)], axis=1) @ rot.T

    return _Segment(at, d)


_TRANSFORM = re.compile(r"\s*(matrix|translate|scale|rotate|skewX|skewY)\s*\(([^)]*)\)\s*,?")


def transform(text: str) -> np.ndarray:
    """The 2 x 3 affine matrix [[a, c, e], [b, d, f]] of an SVG ``transform`` attribute
    (matrix, translate, scale, rotate (about a point too), skewX, skewY; applied right to
    left as SVG says)."""
    m = np.eye(3)
    pos = 0
    for found in _TRANSFORM.finditer(text):
        if text[pos : found.start()].strip(" ,"):
            break
        pos = found.end()
        name = found.group(1)
        try:
            v = [float(x) for x in re.split(r"[\s,]+", found.group(2).strip()) if x]
        except ValueError:
            raise ValueError(f"SVG transform: cannot read {found.group(0).strip()!r}") from None
        counts = {"matrix": (6,), "translate": (1, 2), "scale": (1, 2), "rotate": (1, 3),
                  "skewX": (1,), "skewY": (1,)}  # fmt: skip
        if len(v) not in counts[name]:
            raise ValueError(f"SVG transform: {name} takes {' or '.join(map(str, counts[name]))} "
                             f"numbers, got {len(v)}")  # fmt: skip
        if name == "matrix":
            a, b, c, d, e, f = v
            step = np.array([[a, c, e], [b, d, f], [0, 0, 1]])
        elif name == "translate":
            step = np.array([[1, 0, v[0]], [0, 1, v[1] if len(v) > 1 else 0.0], [0, 0, 1]])
        elif name == "scale":
            sy = v[1] if len(v) > 1 else v[0]
            step = np.diag([v[0], sy, 1.0])
        elif name == "rotate":
            r = math.radians(v[0])
            cx, cy = (v[1], v[2]) if len(v) == 3 else (0.0, 0.0)
            c, s = math.cos(r), math.sin(r)
            rot = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
            to = np.array([[1, 0, cx], [0, 1, cy], [0, 0, 1]])
            back = np.array([[1, 0, -cx], [0, 1, -cy], [0, 0, 1]])
            step = to @ rot @ back
        else:
            k = math.tan(math.radians(v[0]))
            step = np.array([[1, k, 0], [0, 1, 0], [0, 0, 1]]) if name == "skewX" else (
                np.array([[1, 0, 0], [k, 1, 0], [0, 0, 1]]))  # fmt: skip
        m = m @ step
    if text[pos:].strip(" ,"):
        raise ValueError(f"SVG transform: cannot read {text[pos:].strip()!r}")
    return m[:2]


def transformed(curve: SvgCurve, m: np.ndarray) -> SvgCurve:
    """The curve under the affine map ``m`` (2 x 3): each piece's points and derivatives
    mapped (exact for every kind of piece; arc lengths are then measured on the map)."""
    lin, off = m[:, :2], m[:, 2]

    def piece(seg: _Segment) -> _Segment:
        return _Segment(lambda t: seg.at(t) @ lin.T + off, lambda t: seg.d(t) @ lin.T)

    return SvgCurve(tuple(piece(s) for s in curve.segments), curve.closed)


def _tokens(d: str) -> list[str | float]:
    """Commands and numbers; an arc's two flags are read as one character each, so the
    compact form that minifiers write ("a1 1 0 00 1 1") reads as SVG says."""
    out: list[str | float] = []
    pos, n = 0, len(d)
    cmd, k = "", 0
    while True:
        while pos < n and d[pos] in " \t\r\n,":
            pos += 1
        if pos >= n:
            return out
        c = d[pos]
        if c in "MmLlHhVvCcSsQqTtAaZz":
            out.append(c)
            cmd, k = c.lower(), 0
            pos += 1
            continue
        if cmd == "a" and k % 7 in (3, 4):
            if c not in "01":
                bad = _WORD.match(d, pos)
                raise ValueError(f"SVG path: an arc flag must be 0 or 1, got "
                                 f"{bad.group() if bad else c} (character {pos})")  # fmt: skip
            out.append(float(c))
            pos, k = pos + 1, k + 1
            continue
        m = _NUMBER.match(d, pos)
        if m is None:
            bad = _WORD.match(d, pos)
            raise ValueError(f"SVG path: cannot read {bad.group() if bad else c!r} at "
                             f"character {pos}")  # fmt: skip
        out.append(float(m.group()))
        pos, k = m.end(), k + 1


def _flag(v: float, at: str) -> bool:
    if v not in (0.0, 1.0):
        raise ValueError(f"SVG path: an arc flag must be 0 or 1, got {v:g} ({at})")
    return bool(v)


def parse(d: str) -> SvgCurve:
    """The segments of the path data ``d`` (one subpath: a second one that draws is an
    error, as is anything after ``Z``)."""
    toks = _tokens(d)
    if not toks:
        raise ValueError("SVG path: the path data is empty")
    if not isinstance(toks[0], str) or toks[0] not in "Mm":
        raise ValueError("SVG path: the path data must start with M or m")
    segs: list[_Segment] = []
    cur = start = np.zeros(2)
    ctrl: np.ndarray | None = None  # the last control point, for S/s and T/t
    last = ""
    closed = False
    i = 0
    while i < len(toks):
        cmd = toks[i]
        if not isinstance(cmd, str):
            raise ValueError(f"SVG path: a number {cmd:g} where a command was expected")
        i += 1
        if closed:
            raise ValueError(f"SVG path: {cmd!r} after Z (a second subpath); give one curve")
        op, rel = cmd.lower(), cmd.islower()
        n = _ARITY[op]
        if op == "z":
            if np.any(cur != start):
                segs.append(_line(cur, start))
            cur, closed, ctrl, last = start, True, None, op
            continue
        first = True
        while True:
            args = toks[i : i + n]
            if len(args) < n or any(isinstance(a, str) for a in args):
                if first:
                    raise ValueError(f"SVG path: {cmd!r} needs {n} numbers")
                break
            if not first and i < len(toks) and isinstance(toks[i], str):
                break
            i += n
            v = np.array(args, dtype=np.float64)
            base = cur if rel else np.zeros(2)
            if op == "m":
                if first:
                    if segs:
                        raise ValueError(
                            "SVG path: a second subpath (M after drawing); give one curve"
                        )
                    cur = start = base + v
                    first = False
                    op = "l"  # further pairs after M are lines (SVG 1.1, 8.3.2)
                    continue
                new = base + v
                segs.append(_line(cur, new))
                cur = new
            elif op == "l":
                new = base + v
                segs.append(_line(cur, new))
                cur = new
            elif op in "hv":
                new = cur.copy()
                k = 0 if op == "h" else 1
                new[k] = (cur[k] if rel else 0.0) + v[0]
                segs.append(_line(cur, new))
                cur = new
            elif op == "c":
                p1, p2, p3 = base + v[0:2], base + v[2:4], base + v[4:6]
                segs.append(_cubic(cur, p1, p2, p3))
                cur, ctrl = p3, p2
            elif op == "s":
                p1 = 2 * cur - ctrl if last in "cs" and ctrl is not None else cur
                p2, p3 = base + v[0:2], base + v[2:4]
                segs.append(_cubic(cur, p1, p2, p3))
                cur, ctrl = p3, p2
            elif op == "q":
                p1, p2 = base + v[0:2], base + v[2:4]
                segs.append(_quad(cur, p1, p2))
                cur, ctrl = p2, p1
            elif op == "t":
                p1 = 2 * cur - ctrl if last in "qt" and ctrl is not None else cur
                p2 = base + v
                segs.append(_quad(cur, p1, p2))
                cur, ctrl = p2, p1
            else:  # "a"
                new = base + v[5:7]
                where = f"arc to ({new[0]:g}, {new[1]:g})"
                arc = _arc(cur, v[0], v[1], v[2], _flag(v[3], where), _flag(v[4], where), new)
                segs.append(arc if arc is not None else _line(cur, new))
                cur = new
            last = op
            first = False
        last = op
    return SvgCurve(tuple(segs), closed)


def _table(seg: _Segment) -> tuple[np.ndarray, np.ndarray]:
    """Knots in t and the arc length from t = 0 to each (Gauss-Legendre on each span)."""
    t = np.linspace(0.0, 1.0, _KNOTS)
    h = np.diff(t)
    x = (t[:-1, None] + h[:, None] * _GL_X[None, :]).ravel()
    speed = np.hypot(*seg.d(x).T).reshape(len(h), len(_GL_X))
    return t, np.concatenate([[0.0], np.cumsum(h * (speed @ _GL_W))])


def _length(seg: _Segment, t0: np.ndarray, t1: np.ndarray) -> np.ndarray:
    """Arc length from t0 to t1 (arrays; spans shorter than a knot span)."""
    h = t1 - t0
    x = (t0[:, None] + h[:, None] * _GL_X[None, :]).ravel()
    speed = np.hypot(*seg.d(x).T).reshape(len(h), len(_GL_X))
    return h * (speed @ _GL_W)


def _at_length(seg: _Segment, knots: tuple[np.ndarray, np.ndarray], s: np.ndarray) -> np.ndarray:
    """The parameters t where the arc length from t = 0 is ``s``: Newton from the table."""
    t_k, s_k = knots
    j = np.clip(np.searchsorted(s_k, s, side="right") - 1, 0, len(t_k) - 2)
    t = t_k[j] + (s - s_k[j]) / np.maximum(s_k[j + 1] - s_k[j], 1e-300) * (t_k[j + 1] - t_k[j])
    for _ in range(8):
        f = s_k[j] + _length(seg, t_k[j], t) - s
        v = np.hypot(*seg.d(t).T)
        step = np.where(v > 0, f / np.maximum(v, 1e-300), 0.0)
        t = np.clip(t - step, t_k[j], t_k[j + 1])
        if np.all(np.abs(f) <= 1e-15 * max(1.0, float(s_k[-1]))):
            break
    return t


def sample(curve: SvgCurve, m: int) -> np.ndarray:
    """``m`` points at equal arc length along the curve: from its start to its end (both
    included) when open; from its start, ``m`` steps round, the start not repeated, when
    closed. Zero-length pieces are skipped."""
    segs = []
    for seg in curve.segments:
        table = _table(seg)
        if table[1][-1] > 0:
            segs.append((seg, table))
    if not segs:
        raise ValueError("SVG path: the path has no length (it draws nothing)")
    lengths = np.array([tb[1][-1] for _, tb in segs])
    ends = np.concatenate([[0.0], np.cumsum(lengths)])
    total = ends[-1]
    s = np.arange(m) * (total / m) if curve.closed else np.linspace(0.0, total, m)
    which = np.clip(np.searchsorted(ends, s, side="right") - 1, 0, len(segs) - 1)
    out = np.empty((m, 2))
    for k, (seg, table) in enumerate(segs):
        sel = which == k
        if np.any(sel):
            local = np.clip(s[sel] - ends[k], 0.0, lengths[k])
            out[sel] = seg.at(_at_length(seg, table, local))
    return out
