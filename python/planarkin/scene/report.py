"""The reports of a scene as plain data: a sweep's summary and CSV columns (``planarkin
analyze SCENE``), its circuits at one input (``planarkin circuits``). Angle and linear
inputs go through one code path over an :class:`InputAxis`, which says how the input's
values are shown (degrees wrapped to (-180, 180], or displacements as they are)."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Sequence
from typing import Any

import numpy as np

from .._angles import rpm, wrap_deg, wrapped
from .._results import true_runs
from .._status import Status
from . import output as declared_output
from ._model import Scene
from ._results import Circuit, SceneSweep

__all__ = [
    "REACH_STEP_DEG",
    "InputAxis",
    "circuits_summary",
    "columns",
    "input_axis",
    "output_summary",
    "reachable",
    "rows",
    "summary",
]

#: Input angles tried for the reachable ranges of an angle input (5 deg apart).
REACH_STEP_DEG = 5.0
#: A linear input's reachable ranges: this many values over four drawing sizes each way.
REACH_LINEAR = 801


class InputAxis:
    """An angle input: radians underneath, shown in degrees wrapped to (-180, 180]; the
    base of :class:`LinearAxis`, whose methods say where a linear input differs."""

    #: "angle" or "displacement" (``Scene.input_kind``, ``SceneSweep.input``)
    kind = "angle"
    #: the unit the values are shown in
    unit = "deg"
    #: the CSV column's symbol
    symbol = "theta"
    #: what the JSON keys of shown values end with
    key = "_deg"
    #: whether the input's values go round (a range can run through 180 deg)
    wraps = True

    @property
    def column(self) -> str:
        return f"{self.symbol} [{self.unit}]"

    def shown(self, values: object) -> np.ndarray:
        """The input's values as the reports show them."""
        return wrap_deg(values)

    def value(self, v: float) -> float:
        """One input value as the reports show it."""
        return float(self.shown(v))

    def from_user(self, v: float) -> float:
        """A value as a user gives it (degrees) to the input (radians)."""
        return math.radians(v)

    def drawn(self, scene: Scene) -> float:
        """The input at the drawn pose."""
        return scene.input_angle

    def sweep(self, scene: Scene, n: int, step_deg: float) -> np.ndarray:
        """``n`` inputs of a sweep: one turn from the drawn angle in ``step_deg`` steps."""
        return scene.input_angle + np.arange(n) * math.radians(step_deg)

    #: the command-line option that sets the input's rate, and its default
    rate_option = "--rpm"
    rate_default = 100.0

    def rate(self, given: float) -> float:
        """The input's rate (omega, rad/s) when it is driven at ``given`` rpm."""
        return given * math.tau / 60

    def head(self, scene: Scene, at: float) -> dict[str, Any]:
        """The circuits report's entries naming the input ``at``: the same three keys for
        both input kinds (``input_kind``, ``input_unit``, ``input``: the value in that
        unit), and this kind's former key (``theta_deg``)."""
        v = self.value(at)
        return {"input_kind": self.kind, "input_unit": self.unit, "input": v, "theta_deg": v}

    def circuit(self, c: Circuit, at: float) -> dict[str, Any]:
        """A circuit's motion: its net turn, turning points and input range, shown in the
        turn that holds ``at``."""
        shift = math.tau * round((at - math.radians(wrapped(at))) / math.tau)
        lo, hi = _range(c)
        return {
            "net_turn_deg": math.degrees(c.net_turn),
            "turning_points_deg": [wrapped(v) for v in c.turning_points],
            "input_range_deg": [math.degrees(lo - shift), math.degrees(hi - shift)],
        }

    def reach_grid(self, scene: Scene) -> np.ndarray:
        """The shown input values :func:`reachable` tries."""
        return np.arange(-180.0 + REACH_STEP_DEG, 180.0 + 1e-9, REACH_STEP_DEG)

    def summary(self, scene: Scene, sw: SceneSweep) -> dict[str, Any]:
        """A sweep summary's entries on the input: the drawn angle, or the stroke."""
        return {"drawn_input_deg": wrapped(scene.input_angle), "stroke": None}

    def speed(self, omega: float, unit: str) -> dict[str, Any]:
        """A sweep summary's input speed: omega and rpm, or a linear speed."""
        return {"omega_rad_s": omega, "rpm": rpm(omega), "speed": None, "speed_value": None}


class LinearAxis(InputAxis):
    """A linear input (a slot or prismatic pair): displacements from the drawn pose in the
    scene's length unit, shown as they are (no wrapping)."""

    kind = "displacement"
    symbol = "s"
    key = ""
    wraps = False

    def __init__(self, units: str | None) -> None:
        self.unit = units or "length"

    def shown(self, values: object) -> np.ndarray:
        return np.asarray(values, dtype=np.float64)

    def from_user(self, v: float) -> float:
        return float(v)

    def drawn(self, scene: Scene) -> float:
        return 0.0

    def sweep(self, scene: Scene, n: int, step_deg: float) -> np.ndarray:
        """``n`` displacements across the stroke, both dead points included."""
        lo, hi = scene.stroke()
        return np.linspace(lo, hi, n)

    rate_option = "--speed"
    rate_default = 1.0

    def rate(self, given: float) -> float:
        """The input's rate: ``given`` length units per second, as it is."""
        return float(given)

    def head(self, scene: Scene, at: float) -> dict[str, Any]:
        # the shared keys, then this kind's former ones (units, theta)
        v = float(at)
        shared = {"input_kind": self.kind, "input_unit": self.unit, "input": v}
        return {**shared, "units": scene.units, "theta": v}

    def circuit(self, c: Circuit, at: float) -> dict[str, Any]:
        return {"turning_points": [float(v) for v in c.turning_points], "input_range": _range(c)}

    def reach_grid(self, scene: Scene) -> np.ndarray:
        pts = np.array(list(scene.points.values()), dtype=float)
        size = float(np.ptp(pts, axis=0).max())
        return np.linspace(-4.0 * size, 4.0 * size, REACH_LINEAR)

    def summary(self, scene: Scene, sw: SceneSweep) -> dict[str, Any]:
        return {"drawn_input_deg": None, "stroke": [float(sw.theta[0]), float(sw.theta[-1])]}

    def speed(self, omega: float, unit: str) -> dict[str, Any]:
        return {"omega_rad_s": None, "rpm": None, "speed": f"{omega:g} {unit}/s",
                "speed_value": omega}  # fmt: skip


def _range(c: Circuit) -> list[float]:
    """A circuit's input range (continuous): where the input reverses, its ends are the
    turning points refined by bisection, never the nearest traced sample."""
    ends = [*c.range, *np.asarray(c.trace.turning_points, dtype=np.float64).tolist()]
    return [float(min(ends)), float(max(ends))]


def input_axis(kind: str, units: str | None = None) -> InputAxis:
    """The axis of an input of ``kind`` ("angle" or "displacement", in ``units``)."""
    return InputAxis() if kind == "angle" else LinearAxis(units)


def _none(x: float) -> float | None:
    return x if math.isfinite(x) else None


def _declared(
    scene: Scene, sw: SceneSweep
) -> tuple[declared_output.Declared, np.ndarray, np.ndarray | None] | None:
    """The declared output of ``scene`` along ``sw``: (what it is, its coordinate at every
    row, a slot's transmission angle or None); None without an output, or where the sweep
    does not report its points."""
    dec = declared_output.declared(scene)
    if dec is None or not all(p in sw.points for p in dec.points()):
        return None
    pts = sw.points
    return dec, declared_output.coordinate(dec, pts), declared_output.transmission(dec, pts)


def output_summary(scene: Scene, sw: SceneSweep) -> dict[str, Any] | None:
    """The declared output of a sweep as data (:func:`planarkin.scene.output.summary`):
    its extremes and the inputs where they occur (shown as the input axis shows them),
    swing or stroke, a crank's quick-return time ratio, a slot's least transmission
    angle; None when the scene declares no output."""
    got = _declared(scene, sw)
    if got is None:
        return None
    dec, _, _ = got
    axis = input_axis(scene.input_kind, scene.units)
    t = np.asarray(sw.theta, dtype=np.float64)
    ok = np.asarray(sw.success)
    rows = np.arange(len(t))
    turn = len(t) > 2 and math.isclose(float(t[-1] - t[0]), math.tau, rel_tol=0, abs_tol=1e-9)
    if scene.input_kind == "angle" and turn and not ok.all() and ok[0] and ok[-1]:
        # a turn whose middle is out of reach: the solved rows after the gap lead on to
        # those before it (the last row is the first again), so follow them in that order
        gap = np.flatnonzero(~ok)
        rows = np.concatenate([np.arange(gap[-1] + 1, len(t)), np.arange(1, gap[0])])
        t = np.where(rows < gap[0], t[rows] + math.tau, t[rows])
        ok = ok[rows]
    pts = {k: v[rows] for k, v in sw.points.items()}
    pts = {k: np.where(ok[:, None], v, np.nan) for k, v in pts.items()}
    y = declared_output.coordinate(dec, pts)
    mu = declared_output.transmission(dec, pts)
    return declared_output.summary(
        dec, t, y, mu, angle_input=scene.input_kind == "angle",
        shown=axis.value, unit=scene.units or "length",
    )  # fmt: skip


def summary(scene: Scene, sw: SceneSweep, wall: dict[str, float]) -> dict:
    """A sweep of ``scene`` as data: the scene, its plan, what converged, conditioning,
    where the motion stops and the dead points met (input values as the axis shows them;
    the keys keep "deg" for a linear input's displacements too)."""
    plan, limit = sw.plan, sw.limit
    assert plan is not None and limit is not None  # a kernel sweep has both
    ok = sw.success
    axis = input_axis(scene.input_kind, scene.units)
    shown = axis.shown(sw.theta)
    absdet = np.abs(sw.det[ok])
    # where the motion stops: the edges of the solved spans (to the sweep's resolution)
    edges = []
    for a, b in true_runs(ok):
        if a > 0:
            edges.append({"deg": float(shown[a]), "det": float(sw.det[a]), "side": "start"})
        if b < len(ok):
            edges.append({"deg": float(shown[b - 1]), "det": float(sw.det[b - 1]), "side": "end"})
    dead = sorted({round(axis.value(float(v)), 9) for v in limit if math.isfinite(v)})
    omega = sw.omega
    unit = scene.units or "length"
    return {
        "scene": scene.name,
        "description": scene.description,
        "units": scene.units,
        "links": len(scene.links),
        "joints": sum(len(v) - 1 for v in scene.joints.values()),
        "points": len(scene.points),
        "mobility": scene.mobility,
        "input": scene.to_dict()["input"],
        "input_kind": scene.input_kind,
        **axis.summary(scene, sw),
        "input_speed": None
        if omega is None
        else {
            **axis.speed(omega, unit),
            "constant": True,
            "velocity_unit": f"{unit}/s",
            "acceleration_unit": f"{unit}/s^2",
        },
        "outputs": list(plan.outputs) if plan.outputs is not None else "all",
        "plan": [
            {"kind": s.kind, "points": list(s.points), "unknowns": list(s.unknowns)} for s in plan
        ],
        "points_solved": list(sw.points),
        "angles": len(sw),
        "converged": int(ok.sum()),
        "statuses": sw.statuses(),
        "nit_total": int(sw.nit.sum()),
        "nit_mean_converged": _none(float(sw.nit[ok].mean())) if ok.any() else None,
        "conditioning_min": float(absdet.min()) if ok.any() else None,
        "conditioning_max": float(absdet.max()) if ok.any() else None,
        "motion_stops_deg": edges,
        "dead_points_deg": dead,
        "output": output_summary(scene, sw),
        "wall_time_s": wall,
    }


def columns(sw: SceneSweep, units: str | None, scene: Scene | None = None) -> list[str]:
    """The CSV header of a sweep, units in brackets: the input (an angle, or a linear
    input's displacement), statuses, each point's position (and velocity, acceleration
    when computed), each link's angle (and angular velocity, acceleration); with the
    ``scene``, its declared output last (its coordinate, a slot's transmission angle)."""
    u = units or "length"
    cols = [
        input_axis(sw.input_kind, units).column,
        "status [code]",
        "status_name",
        "nit [-]",
        "det [-]",
    ]
    for n in sw.points:
        cols += [f"{n}_x [{u}]", f"{n}_y [{u}]"]
        if sw.velocities is not None:
            cols += [f"{n}_vx [{u}/s]", f"{n}_vy [{u}/s]"]
        if sw.accelerations is not None:
            cols += [f"{n}_ax [{u}/s^2]", f"{n}_ay [{u}/s^2]"]
    for n in sw.angles:
        cols += [f"{n}_angle [deg]"]
        if sw.angular_velocities is not None:
            cols += [f"{n}_omega [rad/s]"]
        if sw.angular_accelerations is not None:
            cols += [f"{n}_alpha [rad/s^2]"]
    got = None if scene is None else _declared(scene, sw)
    if got is not None:
        cols += list(declared_output.columns(got[0], u))
    return cols


def rows(sw: SceneSweep, scene: Scene | None = None) -> Iterator[list[object]]:
    """The CSV rows of a sweep, one per input value, in :func:`columns` order (the same
    ``scene``: its declared output last, an angle in degrees in (-180, 180])."""
    got = None if scene is None else _declared(scene, sw)
    extra: list[np.ndarray] = []
    if got is not None:
        dec, y, mu = got
        extra.append(wrap_deg(y) if dec.kind == "angle" else y)
        if mu is not None:
            extra.append(np.degrees(mu))
    per_point = [a for a in (sw.coords, sw.velocity_array, sw.acceleration_array) if a is not None]
    per_link = [
        a for a in (sw.angular_velocity_array, sw.angular_acceleration_array) if a is not None
    ]
    theta = input_axis(sw.input_kind).shown(sw.theta)
    link_deg = wrap_deg(sw.angle_array)
    for i in range(len(sw)):
        code = int(sw.status[i])
        row: list[object] = [
            float(theta[i]), code, Status(code).name, int(sw.nit[i]), float(sw.det[i]),
        ]  # fmt: skip
        for j in range(len(sw.point_names)):
            for a in per_point:
                row += [float(a[i, j, 0]), float(a[i, j, 1])]
        for j in range(len(sw.link_names)):
            row.append(float(link_deg[i, j]))
            row += [float(a[i, j]) for a in per_link]
        row += [float(e[i]) for e in extra]
        yield row


def reachable(
    scene: Scene, axis: InputAxis, progress: Callable[[], object] | None = None
) -> list[tuple[float, float]]:
    """The input ranges (shown values) where ``scene`` has some assembly, on the axis'
    :meth:`~InputAxis.reach_grid` (each range from its first to its last grid value; an
    angle's range through 180 deg is one range, its end past 180). ``progress()`` is
    called after each grid value."""
    grid = axis.reach_grid(scene)
    has = np.zeros(len(grid), dtype=bool)
    for i, v in enumerate(grid):
        has[i] = len(scene.assemblies(axis.from_user(float(v)))) > 0
        if progress is not None:
            progress()
    runs = true_runs(has)
    if axis.wraps and len(runs) > 1 and runs[0][0] == 0 and runs[-1][1] == len(grid):
        (a, b), *mid, (c, _) = runs
        return [(float(grid[i]), float(grid[j - 1])) for i, j in mid] + [
            (float(grid[c]), float(grid[b - 1]) + 360.0)
        ]
    return [(float(grid[i]), float(grid[j - 1])) for i, j in runs]


def circuits_summary(
    scene: Scene,
    axis: InputAxis,
    at: float,
    found: Sequence[Circuit],
    counts: object,
    reach: list[tuple[float, float]] | None,
    glossary: str,
    wall: float,
) -> dict[str, Any]:
    """The circuits of ``scene`` at the input ``at`` as data: each circuit's assemblies
    and motion, the complex solutions of its groups (``counts``), and where there is no
    assembly, the ``reach``-able ranges."""
    circuits = [
        {
            "circuit": k + 1,
            "assemblies": [{"label": a.label, "det": a.det} for a in c.assemblies],
            "full_turn": c.full_turn,
            **axis.circuit(c, at),
            "closed": c.trace.closed,
            "trace_points": len(c.trace),
            # where the scene's travel limits stop the motion (in the input's unit)
            "limits": [axis.value(v) for v in c.trace.limits],
        }
        for k, c in enumerate(found)
    ]
    return {
        "scene": scene.name,
        **axis.head(scene, at),
        "assemblies": sum(len(c.assemblies) for c in found),
        "group_complex_solutions": counts,
        "circuits": circuits,
        f"reachable{axis.key}": None if reach is None else [list(r) for r in reach],
        "glossary": glossary,
        "wall_time_s": wall,
    }
