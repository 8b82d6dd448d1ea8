"""A path target: points in order, closed, open or partial, with optional input values per
point (timing); read from an array, a CSV, a JSON file or an SVG path, and checked once,
at construction, with a one-line error naming the problem."""

from __future__ import annotations

import json
import math
import re
import xml.etree.ElementTree as ET
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from . import svgpath

__all__ = ["KINDS", "SVG_SAMPLES", "CurveTarget", "load_target"]

#: the kinds of target: the whole closed coupler curve, an open path, or part of a curve
KINDS = ("closed", "open", "partial")
#: points an SVG path is sampled into (equal arc length) unless ``svg_samples`` says
SVG_SAMPLES = 64
#: the names of the columns (CSV header) and keys (JSON) that hold input values, and the
#: factor to radians of each
_INPUT_NAMES = {"input": 1.0, "input_deg": math.pi / 180.0}
_INPUT_KEYS = {"inputs": 1.0, "inputs_deg": math.pi / 180.0}


def _frozen(a: np.ndarray) -> np.ndarray:
    a = np.array(a, dtype=np.float64, copy=True, order="C")
    a.flags.writeable = False
    return a


@dataclass(frozen=True, eq=False)
class CurveTarget:
    """``points`` (n, 2) in order; ``kind`` one of :data:`KINDS`; ``inputs`` (n,) input
    values per point (timing: radians for an input that turns, scene units for a linear
    one) or None (free). A closed target closes by itself: its last point does not repeat
    the first. Checked at construction: at least 3 points, all finite, no point repeating
    the one before it; a closed target that crosses itself is allowed."""

    points: np.ndarray
    kind: str = "closed"
    inputs: np.ndarray | None = None

    def __post_init__(self) -> None:
        try:
            pts = np.asarray(self.points, dtype=np.float64)
        except (TypeError, ValueError) as e:
            raise ValueError(f"points must be an (n, 2) array of numbers: {e}") from None
        if pts.ndim != 2 or pts.shape[1] != 2:
            raise ValueError(f"points must be an (n, 2) array of x, y, got shape {pts.shape}")
        n = len(pts)
        if n < 3:
            raise ValueError(f"a target needs at least 3 points, got {n}")
        bad = np.flatnonzero(~np.isfinite(pts).all(axis=1))
        if len(bad):
            i = int(bad[0])
            raise ValueError(f"points must be finite: point {i} is ({pts[i, 0]}, {pts[i, 1]})")
        same = np.flatnonzero((pts[1:] == pts[:-1]).all(axis=1))
        if len(same):
            i = int(same[0])
            raise ValueError(
                f"points {i} and {i + 1} are the same point ({pts[i, 0]:g}, {pts[i, 1]:g}): "
                "consecutive points must differ"
            )
        if not isinstance(self.kind, str) or self.kind not in KINDS:
            raise ValueError(f"kind must be one of {', '.join(KINDS)}, got {self.kind!r}")
        if self.kind == "closed" and np.array_equal(pts[0], pts[-1]):
            raise ValueError(
                "the last point repeats the first: a closed target closes by itself "
                "(drop the last point)"
            )
        object.__setattr__(self, "points", _frozen(pts))
        if self.inputs is not None:
            try:
                t = np.asarray(self.inputs, dtype=np.float64)
            except (TypeError, ValueError) as e:
                raise ValueError(f"inputs must be numbers: {e}") from None
            if t.shape != (n,):
                raise ValueError(f"inputs must hold one value per point ({n}), got shape {t.shape}")
            bad = np.flatnonzero(~np.isfinite(t))
            if len(bad):
                raise ValueError(f"inputs must be finite: inputs[{int(bad[0])}] is {t[bad[0]]}")
            object.__setattr__(self, "inputs", _frozen(t))

    def __len__(self) -> int:
        return len(self.points)

    def __repr__(self) -> str:
        timing = "timing given" if self.inputs is not None else "timing free"
        return f"CurveTarget({len(self)} points, {self.kind}, size {self.size:.4g}, {timing})"

    @property
    def size(self) -> float:
        """The diagonal of the points' bounding box: errors are divided by it."""
        return float(np.hypot(*np.ptp(self.points, axis=0)))

    @property
    def closed(self) -> bool:
        return self.kind == "closed"

    def _polyline(self) -> np.ndarray:
        """The points, the first appended again when closed (the closing segment)."""
        return np.vstack([self.points, self.points[:1]]) if self.closed else self.points

    def _cumulative(self) -> np.ndarray:
        """Arc length from the first point to each vertex of :meth:`_polyline`."""
        seg = np.hypot(*np.diff(self._polyline(), axis=0).T)
        return np.concatenate([[0.0], np.cumsum(seg)])

    @property
    def length(self) -> float:
        """The polyline's length through the points (round to the first when closed)."""
        return float(self._cumulative()[-1])

    def arc_fractions(self) -> np.ndarray:
        """Each point's arc-length position along the polyline through the points, as a
        fraction of its length: in [0, 1) for a closed target (the closing segment
        counted, so the first point is 0 and none is 1), from 0 to 1 (both ends) for an
        open or partial one."""
        s = self._cumulative()
        return s[: len(self)] / s[-1]

    def resampled(self, m: int) -> CurveTarget:
        """The target as ``m`` points at equal arc length along its polyline (linear
        between the given points): first to last point (both kept) when open or partial;
        from the first point round, ``m`` equal steps, when closed. Input values are
        interpolated the same way; a closed target's closing segment runs from the last
        input value to the first plus a full turn in the direction they run."""
        m = int(m)
        if m < 3:
            raise ValueError(f"m must be >= 3, got {m}")
        s = self._cumulative()
        total = s[-1]
        at = np.arange(m) * (total / m) if self.closed else np.linspace(0.0, total, m)
        poly = self._polyline()
        pts = np.column_stack([np.interp(at, s, poly[:, 0]), np.interp(at, s, poly[:, 1])])
        if not self.closed:
            pts[-1] = poly[-1]  # exactly the last point, not its rounded interpolation
        t = None
        if self.inputs is not None:
            vals = self.inputs
            if self.closed:
                turn = math.copysign(math.tau, float(vals[-1] - vals[0]) or 1.0)
                vals = np.append(vals, vals[0] + turn)
            t = np.interp(at, s, vals)
        return CurveTarget(pts, self.kind, t)

    def to_dict(self) -> dict[str, Any]:
        """Plain data (report.json's ``target``): points, kind, inputs (radians or None),
        size and length."""
        return {
            "points": self.points.tolist(),
            "kind": self.kind,
            "inputs": None if self.inputs is None else self.inputs.tolist(),
            "size": self.size,
            "length": self.length,
        }


# --- loading -----------------------------------------------------------------------------


def load_target(
    source: Any,
    *,
    kind: str | None = None,
    timing: bool = False,
    svg_samples: int = SVG_SAMPLES,
) -> CurveTarget:
    """A :class:`CurveTarget` from ``source``: an (n, 2) or (n, 3) array or sequence (a
    third column: input values in radians), a CurveTarget, or a file: ``.csv`` (rows
    ``x,y[,input]``; an optional header naming the columns ``x``, ``y`` and ``input``
    (radians) or ``input_deg`` (degrees); ``#`` starts a comment), ``.json`` (an array of
    ``[x, y]`` or ``[x, y, input]``, or an object ``{"points": ..., "kind": ...,
    "inputs": ...}`` with ``inputs`` in radians or ``inputs_deg`` in degrees), ``.svg``
    (the ``d`` of the first ``<path>``, under the transforms on it and round it, or a file
    holding only path data). A string that is not a file and starts with ``M``/``m`` is
    read as SVG path data.

    An SVG path is sampled into ``svg_samples`` points at equal arc length (lines, Béziers
    and arcs; ``Z`` makes it closed); SVG's y axis points down, so y is negated: the target
    is the drawing as seen. ``kind``: None takes the data's word (SVG ``Z``, JSON
    ``kind``), else "closed" when the last point repeats the first (the repeat is
    dropped), else "open". ``timing``: keep the source's input values (an error when it
    has none); False leaves every point's input free (any values in the source are not
    used)."""
    if kind is not None and kind not in KINDS:
        raise ValueError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
    said: str | None = None  # the kind the data say
    inputs: np.ndarray | None = None
    if isinstance(source, CurveTarget):
        pts, inputs, said = source.points, source.inputs, source.kind
        where = "the target"
    elif isinstance(source, (str, Path)) and _is_path_data(source):
        pts, said = _svg_d(str(source), svg_samples)
        where = "the SVG path data"
    elif isinstance(source, (str, Path)):
        path = Path(source)
        where = str(path)
        if not path.is_file():
            raise ValueError(f"target file {where!r} does not exist")
        suffix = path.suffix.lower()
        if suffix == ".csv":
            pts, inputs = _csv(path)
        elif suffix == ".json":
            pts, inputs, said = _json(path)
        elif suffix == ".svg":
            pts, said = _svg_file(path, svg_samples)
        else:
            raise ValueError(f"a target file must be .csv, .json or .svg, got {where!r}")
    else:
        pts, inputs = _columns(source, "the target")
        where = "the target"
    if timing and inputs is None:
        raise ValueError(
            f"timing asked for, but {where} gives no input values (a third column 'input' "
            "in radians or 'input_deg' in degrees; JSON 'inputs' or 'inputs_deg')"
        )
    if not timing:
        inputs = None
    chosen = kind or said
    if len(pts) >= 2 and chosen in (None, "closed") and _same(pts[0], pts[-1], pts):
        pts = pts[:-1]
        inputs = None if inputs is None else inputs[:-1]
        chosen = "closed"
    return CurveTarget(pts, chosen or "open", inputs)


def _same(p: np.ndarray, q: np.ndarray, pts: np.ndarray) -> bool:
    """p and q equal, or apart by rounding only (1e-12 of the points' extent): a curve
    drawn back to its start in a file closes."""
    if not (np.isfinite(p).all() and np.isfinite(q).all()):
        return False
    ok = pts[np.isfinite(pts).all(axis=1)]
    extent = float(np.ptp(ok, axis=0).max()) if len(ok) else 0.0
    return bool(np.abs(p - q).max() <= 1e-12 * extent)


def _is_path_data(source: str | Path) -> bool:
    """A string (never a Path) that reads as SVG path data and names no file."""
    if isinstance(source, Path) or not re.match(r"\s*[Mm][\s\d.,+-]", source):
        return False
    try:
        return not Path(source).exists()
    except (OSError, ValueError):  # too long, or a NUL: no file name
        return True


def _columns(data: Any, where: str) -> tuple[np.ndarray, np.ndarray | None]:
    """Points and (a third column) input values in radians from an array-like."""
    try:
        a = np.asarray(data, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise ValueError(f"{where} must be an (n, 2) or (n, 3) array of numbers: {e}") from None
    if a.ndim != 2 or a.shape[1] not in (2, 3):
        raise ValueError(f"{where} must be an (n, 2) or (n, 3) array of numbers, got shape "
                         f"{a.shape}")  # fmt: skip
    return a[:, :2], (a[:, 2] if a.shape[1] == 3 else None)


def _csv(path: Path) -> tuple[np.ndarray, np.ndarray | None]:
    """Rows x,y[,input]; '#' comments and blank lines skipped; a first row that is not
    numbers is the header (x, y, input in radians or input_deg in degrees)."""
    rows: list[list[float]] = []
    names: list[str] | None = None
    width = 0
    for no, raw in enumerate(path.read_text(encoding="utf-8-sig").splitlines(), start=1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        cells = [c.strip() for c in re.split(r"[,;\t]|\s+", line) if c.strip() != ""]
        try:
            vals = [float(c) for c in cells]
        except ValueError:
            if rows or names is not None:
                raise ValueError(f"{path} line {no}: expected numbers, got {line!r}") from None
            names = [c.lower() for c in cells]
            _header(names, path, no)
            width = len(names)
            continue
        if not width:
            width = len(vals)
            if width not in (2, 3):
                raise ValueError(f"{path} line {no}: expected x,y or x,y,input, got {line!r}")
        if len(vals) != width:
            raise ValueError(f"{path} line {no}: expected {width} numbers, got {line!r}")
        rows.append(vals)
    if not rows:
        raise ValueError(f"{path}: no points (rows x,y[,input])")
    a = np.array(rows)
    if names is None:
        return a[:, :2], (a[:, 2] if width == 3 else None)
    x, y = a[:, names.index("x")], a[:, names.index("y")]
    inputs = None
    for name, to_rad in _INPUT_NAMES.items():
        if name in names:
            inputs = a[:, names.index(name)] * to_rad
    return np.column_stack([x, y]), inputs


def _header(names: list[str], path: Path, no: int) -> None:
    known = {"x", "y", *_INPUT_NAMES}
    unknown = [n for n in names if n not in known]
    if unknown:
        raise ValueError(f"{path} line {no}: unknown column {unknown[0]!r} (the columns are x, "
                         "y and input (radians) or input_deg (degrees))")  # fmt: skip
    for need in ("x", "y"):
        if need not in names:
            raise ValueError(f"{path} line {no}: the header has no column {need!r}")
    if len(set(names)) != len(names) or ("input" in names and "input_deg" in names):
        raise ValueError(f"{path} line {no}: a column is given twice in the header")


def _json(path: Path) -> tuple[np.ndarray, np.ndarray | None, str | None]:
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except json.JSONDecodeError as e:
        raise ValueError(f"{path}: not JSON ({e})") from None
    if isinstance(data, Sequence) and not isinstance(data, str):
        pts, inputs = _columns(data, f"{path}: the points")
        return pts, inputs, None
    if not isinstance(data, Mapping):
        raise ValueError(f"{path}: expected an array of points or an object with 'points'")
    known = {"points", "kind", "name", "description", "units", *_INPUT_KEYS}
    unknown = sorted(set(data) - known)
    if unknown:
        raise ValueError(f"{path}: unknown key {unknown[0]!r} (the keys are points, kind, "
                         "inputs (radians) or inputs_deg (degrees))")  # fmt: skip
    if "points" not in data:
        raise ValueError(f"{path}: the object has no 'points'")
    pts, inputs = _columns(data["points"], f"{path}: 'points'")
    given = [k for k in _INPUT_KEYS if k in data]
    if len(given) > 1 or (given and inputs is not None):
        raise ValueError(f"{path}: the input values are given twice (inputs, inputs_deg, or "
                         "a third number per point)")  # fmt: skip
    for k in given:
        try:
            inputs = np.asarray(data[k], dtype=np.float64) * _INPUT_KEYS[k]
        except (TypeError, ValueError):
            raise ValueError(f"{path}: {k!r} must be an array of numbers") from None
    kind = data.get("kind")
    if kind is not None and kind not in KINDS:
        raise ValueError(f"{path}: kind must be one of {', '.join(KINDS)}, got {kind!r}")
    return pts, inputs, kind


def _svg_d(d: str, m: int, where: np.ndarray | None = None) -> tuple[np.ndarray, str | None]:
    """Path data ``d`` sampled into ``m`` points, under the affine map ``where`` (2 x 3;
    the transforms round the path) when given, y negated."""
    m = int(m)
    if m < 3:
        raise ValueError(f"svg_samples must be >= 3, got {m}")
    curve = svgpath.parse(d)
    if where is not None:
        curve = svgpath.transformed(curve, where)
    pts = svgpath.sample(curve, m)
    pts[:, 1] = 0.0 - pts[:, 1]  # SVG's y points down: the target as the drawing is seen
    return pts, ("closed" if curve.closed else None)


def _svg_file(path: Path, m: int) -> tuple[np.ndarray, str | None]:
    text = path.read_text(encoding="utf-8")
    try:
        if not text.lstrip().startswith("<"):
            return _svg_d(text, m)
        try:
            root = ET.fromstring(text)
        except ET.ParseError as e:
            raise ValueError(f"not an SVG file ({e})") from None
        found = _first_path(root, np.eye(3)[:2])
        if found is None:
            raise ValueError("no <path> with a 'd' attribute")
        d, where = found
        return _svg_d(d, m, None if np.array_equal(where, np.eye(3)[:2]) else where)
    except ValueError as e:
        raise ValueError(f"{path}: {e}") from None


def _first_path(el: ET.Element, where: np.ndarray) -> tuple[str, np.ndarray] | None:
    """The ``d`` of the first <path> in document order, and the affine map of the
    transforms on it and the elements round it (outermost first)."""
    if el.get("transform"):
        step = np.vstack([svgpath.transform(el.get("transform", "")), [0.0, 0.0, 1.0]])
        where = where @ step
    if el.tag.rsplit("}", 1)[-1] == "path" and el.get("d"):
        return el.get("d", ""), where
    for child in el:
        found = _first_path(child, where)
        if found is not None:
            return found
    return None
