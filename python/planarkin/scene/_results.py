"""The scene's plain result types: plan steps, sweeps, assemblies, circuits and traces.
Nothing here reaches the kernel: the NumPy reference builds SceneSweep objects too."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from .._results import InputResult, SweepResult


@dataclass(frozen=True)
class Step:
    """One step of a plan."""

    #: "dyad" (circle intersection, closed form) or "group" (Newton on linked loops).
    kind: str
    #: Points it solves: the primary ones first, then those its links carry.
    points: tuple[str, ...]
    #: Links whose angles are its unknowns.
    unknowns: tuple[str, ...]


@dataclass(frozen=True)
class Plan:
    """The steps that solve the requested outputs, in order (iterable like a tuple)."""

    steps: tuple[Step, ...]
    #: The names asked for (None: everything).
    outputs: tuple[str, ...] | None
    #: Points a sweep reports: every point the plan reads or solves.
    points: tuple[str, ...]
    #: Links whose angles a sweep reports.
    links: tuple[str, ...]

    def __iter__(self) -> Iterator[Step]:
        return iter(self.steps)

    def __len__(self) -> int:
        return len(self.steps)

    def __getitem__(self, i: int) -> Step:
        return self.steps[i]

    def __str__(self) -> str:
        rows = [
            f"{i + 1}. {s.kind:5s} solves {', '.join(s.points)} "
            f"(unknown angles of {', '.join(s.unknowns)})"
            for i, s in enumerate(self.steps)
        ]
        return "\n".join(rows) if rows else "(nothing to solve: input and ground only)"


@dataclass(frozen=True, eq=False, repr=False)
class SceneSweep(SweepResult):
    """A scene solved at N input values (angles, or a linear input's displacements), by
    the kernel (``Scene.sweep``) or by the NumPy reference
    (``planarkin.reference.scene_sweep``). The dicts (``points``, ``angles``,
    ``point_status``, ``velocities``, ``angular_velocities``) hold views into the arrays
    (no copies), made on first access. NaN wherever a point or link is not solved.

    Besides the shared names (see :class:`planarkin._results.SweepResult`), its own: the
    plan, the per-step and per-point arrays and ``limit``. The reference solves every
    joint equation at once, with no plan: there ``plan``, ``limit``, ``step_status``,
    ``step_det`` and ``point_status_array`` are None, and ``det`` is the Hadamard ratio
    of its own Jacobian (same zeros and branch meaning, another number).
    """

    #: The steps solved (None: the reference, which has no plan).
    plan: Plan | None
    #: (N,) the input coordinate: angles (radians), or a linear input's displacements s
    #: from the drawn pose (scene units) when ``input_kind`` is "displacement".
    theta: np.ndarray
    #: (N, P, 2) every reported position, scene units (``points`` are views of it).
    coords: np.ndarray
    #: (N, L) link angles in (-pi, pi] (``angles`` are views of it).
    angle_array: np.ndarray
    #: (N,) int8: the first failing step's status, or CONVERGED.
    status: np.ndarray
    #: (N,) Newton steps spent reaching each angle (group steps only).
    nit: np.ndarray
    #: (N,) signed, scale-free conditioning of the whole solve: the product of the steps'.
    det: np.ndarray
    #: (N,) for LIMIT angles, the input angle (radians) of the dead point that stops the
    #: motion on the circuit followed (where continuation last converged); NaN elsewhere.
    #: None: not computed (the reference).
    limit: np.ndarray | None
    #: (N, steps) int8 status of each step (None: no plan).
    step_status: np.ndarray | None
    #: (N, steps) each step's signed conditioning (a dyad's sine of its angle at the
    #: solved point; a group's Hadamard ratio det J / prod |columns|); None: no plan.
    step_det: np.ndarray | None
    #: (N, P) int8 status of each reported point (None: not computed, the reference).
    point_status_array: np.ndarray | None
    #: (N, P, 2) velocities and (N, L) angular velocities when ``rate`` was given.
    velocity_array: np.ndarray | None = None
    angular_velocity_array: np.ndarray | None = None
    #: (N, P, 2) accelerations and (N, L) angular accelerations at constant ``rate``
    #: (None: not computed).
    acceleration_array: np.ndarray | None = field(default=None, kw_only=True)
    angular_acceleration_array: np.ndarray | None = field(default=None, kw_only=True)
    #: The input's rate behind the velocities (None: not given): its angular velocity
    #: (rad/s) for an angle input, its linear speed (scene units per second) for a linear
    #: one. ``omega`` is the same number (its former name, kept).
    rate: float | None = field(default=None, kw_only=True)
    #: "angle": ``theta`` holds input angles (radians); "displacement": a linear input's
    #: displacements from the drawn pose (scene units). ``input`` is the same (its former
    #: name, kept).
    input_kind: str = field(default="angle", kw_only=True)
    #: The scene's length unit (its ``units`` key; None: not named).
    units: str | None = field(default=None, kw_only=True)
    #: Where ``output`` comes from: the (N,) array, a function of (``point_names``,
    #: ``coords``) computing it on first access (the kernel's sweeps: nothing is spent on
    #: an output nobody reads), or None.
    output_source: np.ndarray | Callable[..., np.ndarray | None] | None = field(
        default=None, kw_only=True, repr=False
    )
    #: The names of the P reported points and of the L reported links, in array order.
    point_names: tuple[str, ...] = field(default=(), kw_only=True)
    link_names: tuple[str, ...] = field(default=(), kw_only=True)

    @classmethod
    def build(
        cls, plan, theta, pts, ang, status, nit, det, limit, step_status, step_det, pstat, vel,
        acc=None, rate=None, input_kind="angle", output=None, units=None,
    ):  # noqa: ANN001, ANN206, E501  # fmt: skip
        """From the kernel's arrays; ``vel`` and ``acc`` are (points, links) pairs or None;
        ``output`` the output coordinate, or a function of (``point_names``, ``coords``)
        computing it on first access.

        The fields go straight into the instance's dict, those left at their defaults not
        at all (the class holds the defaults): the dataclass's frozen ``__init__`` sets
        each of its 20 fields through ``object.__setattr__``, which costs more than a small
        sweep itself (about 4 us). Every field reads the same (a test checks them against
        ``dataclasses.fields``).
        """
        self = object.__new__(cls)
        d = self.__dict__
        d["plan"] = plan
        d["theta"] = theta
        d["coords"] = pts
        d["angle_array"] = ang
        d["status"] = status
        d["nit"] = nit
        d["det"] = det
        d["limit"] = limit
        d["step_status"] = step_status
        d["step_det"] = step_det
        d["point_status_array"] = pstat
        d["point_names"] = plan.points
        d["link_names"] = plan.links
        if vel is not None:
            d["velocity_array"], d["angular_velocity_array"] = vel
        if acc is not None:
            d["acceleration_array"], d["angular_acceleration_array"] = acc
        if rate is not None:
            d["rate"] = rate
        if input_kind != "angle":
            d["input_kind"] = input_kind
        if output is not None:
            d["output_source"] = output
        if units is not None:
            d["units"] = units
        return self

    @property
    def omega(self) -> float | None:
        """The input's rate (``rate``'s former name, kept: an angular velocity, or a
        linear input's speed)."""
        return self.rate

    @property
    def input(self) -> str:
        """The input's kind (``input_kind``'s former name, kept): "angle" or
        "displacement"."""
        return self.input_kind

    @cached_property
    def output(self) -> np.ndarray | None:
        """(N,) the scene's output coordinate (an angle, or a displacement along a slot or
        prismatic pair) at every input value; None when the scene names no output or the
        plan does not report its points."""
        src = self.output_source
        return src(self.point_names, self.coords) if callable(src) else src

    @staticmethod
    def _columns(a: np.ndarray | None, names: tuple[str, ...]) -> dict[str, np.ndarray] | None:
        """name -> the column of ``a`` (axis 1) for that name: views, no copies."""
        return None if a is None else {n: a[:, j] for j, n in enumerate(names)}

    @cached_property
    def points(self) -> dict[str, np.ndarray]:
        """name -> (N, 2) positions, scene units."""
        out = self._columns(self.coords, self.point_names)
        assert out is not None
        return out

    @cached_property
    def angles(self) -> dict[str, np.ndarray]:
        """link -> (N,) angles in (-pi, pi]."""
        out = self._columns(self.angle_array, self.link_names)
        assert out is not None
        return out

    @cached_property
    def point_status(self) -> dict[str, np.ndarray] | None:
        """name -> (N,) int8 status of each reported point (None: not computed)."""
        return self._columns(self.point_status_array, self.point_names)

    @cached_property
    def velocities(self) -> dict[str, np.ndarray] | None:
        """name -> (N, 2) velocities (scene units per time) when ``rate`` was given."""
        return self._columns(self.velocity_array, self.point_names)

    @cached_property
    def angular_velocities(self) -> dict[str, np.ndarray] | None:
        """link -> (N,) angular velocities when ``rate`` was given."""
        return self._columns(self.angular_velocity_array, self.link_names)

    @cached_property
    def accelerations(self) -> dict[str, np.ndarray] | None:
        """name -> (N, 2) accelerations (scene units per time squared) at constant
        ``rate``, when computed."""
        return self._columns(self.acceleration_array, self.point_names)

    @cached_property
    def angular_accelerations(self) -> dict[str, np.ndarray] | None:
        """link -> (N,) angular accelerations at constant ``rate``, when computed."""
        return self._columns(self.angular_acceleration_array, self.link_names)

    def _describe(self) -> str:
        k = 0 if self.plan is None else len(self.plan)
        steps = "no plan (reference)" if self.plan is None else f"{k} step{'' if k == 1 else 's'}"
        names = list(self.point_names)
        return f"{steps}, points {names[:6]}{'...' if len(names) > 6 else ''}"


class Assembly(dict):
    """One real assembly: a dict point name -> (x, y) holding every point of the scene,
    with its signed, scale-free conditioning ``det`` (the product of ``step_det``) and a
    mode ``label``: one token per plan step, a dyad's side ("+"/"-"), a group's elbows in
    parentheses (the sign of the angle at each of its joints, e.g. "(+-+-)", with a
    letter added where two solutions share them). A label changes only where a joint's two
    links fall in line, so it follows an assembly as the input angle moves."""

    det: float
    step_det: tuple[float, ...]
    label: str

    def __init__(self, points: dict, det: float, step_det: tuple[float, ...], label: str) -> None:
        super().__init__(points)
        self.det = det
        self.step_det = step_det
        self.label = label

    def __repr__(self) -> str:
        return f"Assembly({self.label!r}, det={self.det:.3g}, {len(self)} points)"


class Assemblies(list):
    """Every real assembly at one input angle (a list of :class:`Assembly`), with the
    number of finite complex solutions each group step has (``complex_counts``: one list
    per group step, one entry per homotopy call), the paths tracked for each
    (``paths``, the same shape: all runs together), the homotopy paths that failed, and
    ``continua``: branches where a dyad's two known points coincide with equal links, so
    its point can be anywhere on a circle (not listed: no finite set of assemblies)."""

    theta: float
    complex_counts: list[list[int]]
    paths: list[list[int]]
    failed_paths: int
    continua: int

    def __init__(
        self,
        items,  # noqa: ANN001
        theta: float,
        complex_counts,  # noqa: ANN001
        failed_paths: int,
        continua: int,
        *,
        paths: list[list[int]] | None = None,
    ) -> None:
        super().__init__(items)
        self.theta = theta
        self.complex_counts = complex_counts
        self.paths = [[] for _ in complex_counts] if paths is None else paths
        self.failed_paths = failed_paths
        self.continua = continua


@dataclass(frozen=True, eq=False, repr=False)
class Trace(InputResult):
    """A path traced through dead points (pseudo-arclength continuation): a result over
    the input (``theta``, ``input_kind``, ``units``, ``len()``, the shared repr) with the
    sweep's ``points`` and ``det``. Documented exception: no ``status``, ``nit`` or
    ``angles`` (every path point is a converged pose; the tracer keeps no iterations)."""

    #: (M,) input coordinate at each path point, continuous (not wrapped): an angle
    #: (radians) or a linear input's displacement (scene units).
    theta: np.ndarray
    #: name -> (M, 2) positions (views of ``coords``).
    points: dict[str, np.ndarray]
    #: (M,) the plan's signed conditioning along the path.
    det: np.ndarray
    #: Input values (continuous, like ``theta``) of the dead points passed (where the
    #: conditioning changes sign and the input reverses; a change point, where it goes on,
    #: is none), refined by bisection on the conditioning's sign, in path order. The path
    #: holds the pose at each of them.
    turning_points: np.ndarray
    #: The path came back to its start (its last point is the start again).
    closed: bool
    #: (M, P, 2) every point at every path point.
    coords: np.ndarray
    #: "angle" or "displacement", as :attr:`SceneSweep.input_kind`.
    input_kind: str = field(default="angle", kw_only=True)
    #: The scene's length unit (None: not named).
    units: str | None = field(default=None, kw_only=True)
    #: Input values (continuous, like ``theta``) where the path stops at a travel limit of
    #: the scene (``limits``), in path order: its two ends, or empty.
    limits: np.ndarray = field(default_factory=lambda: np.empty(0), kw_only=True)

    def _describe(self) -> str:
        k = len(self.turning_points)
        ends = ", stopped by limits at both ends" if len(self.limits) else ""
        how = "closed" if self.closed else "open"
        return f"{how}, {k} turning point{'' if k == 1 else 's'}{ends}"


@dataclass(frozen=True, eq=False, repr=False)
class Circuit:
    """The assemblies at one input angle that a traced circuit connects."""

    #: The assemblies at that angle on this circuit, in the order the trace meets them.
    assemblies: list[Assembly]
    #: Input angles (radians, wrapped to (-pi, pi]) of its dead points, in path order.
    turning_points: np.ndarray
    #: The input angle changes by a net +-2 pi (or more) once round: the input is a crank.
    full_turn: bool
    #: Net change of the input angle once round (NaN when the trace did not close).
    net_turn: float
    #: (lowest, highest) input angle on the path (continuous): where the input reverses,
    #: the refined turning points.
    range: tuple[float, float]
    trace: Trace

    def __repr__(self) -> str:
        return (
            f"Circuit({len(self.assemblies)} assemblies, {len(self.turning_points)} turning "
            f"points, {'full turn' if self.full_turn else 'rocking'})"
        )


@dataclass(frozen=True, eq=False, repr=False)
class SceneGradient:
    """Exact derivatives of a sweep by free drawn coordinates (``Scene.gradient``): each
    point's (x, y) and the output angle, by implicit differentiation of the whole linkage
    at every solved input angle (one factorisation per angle for all the coordinates).
    NaN where the sweep did not converge or the linkage is singular."""

    #: The free coordinates, as given: "A.x", "A.y".
    free: tuple[str, ...]
    #: The sweep the derivatives are taken along (every point reported).
    sweep: SceneSweep
    #: (N, P, 2, F): d(point p, x or y) / d(free f), points in ``sweep.point_names`` order.
    point_array: np.ndarray
    #: (N, F): d(output angle) / d(free f); None when the scene has no angle output.
    output: np.ndarray | None

    @cached_property
    def points(self) -> dict[str, np.ndarray]:
        """Point name -> (N, 2, F) derivatives (views)."""
        return {n: self.point_array[:, j] for j, n in enumerate(self.sweep.point_names)}

    def __repr__(self) -> str:
        n, p, _, f = self.point_array.shape
        return f"SceneGradient({n} angles, {p} points, by {f} coordinates: {', '.join(self.free)})"
