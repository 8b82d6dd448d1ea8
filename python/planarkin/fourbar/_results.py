"""The four-bar's plain result types (Solution, Sweep, BatchSweep, Limits, Grashof) and
its names as a scene. Nothing here reaches the kernel: the NumPy reference builds the
same objects on its own, so parity tests compare two independent implementations."""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from functools import cached_property
from typing import Protocol

import numpy as np

from .._angles import TAU
from .._results import StatusResult, SweepResult
from .._status import Status

#: The four-bar drawn as a scene: point and link names as in the built-in ``fourbar``
#: scene (O2 the crank's ground pivot at the origin, O4 = (r1, 0), A the crank pin, B the
#: rocker pin). ``Sweep.points``/``Sweep.angles`` and ``FourBar.to_scene`` use them.
POINTS = ("O2", "O4", "A", "B")
LINKS: dict[str, tuple[str, ...]] = {
    "ground": ("O2", "O4"),
    "crank": ("O2", "A"),
    "coupler": ("A", "B"),
    "rocker": ("O4", "B"),
}
#: The name of a coupler point (a tracer on the coupler) in ``FourBar.to_scene``.
COUPLER_POINT = "P"


@dataclass(frozen=True)
class Solution:
    """One crank angle solved by Newton-Raphson (scipy's vocabulary: success, status, nit)."""

    theta2: float
    #: Coupler angle in (-pi, pi]; NaN unless converged.
    theta3: float
    #: Rocker angle in (-pi, pi]; NaN unless converged.
    theta4: float
    success: bool
    status: Status
    #: Newton steps taken.
    nit: int
    #: Dimensionless residual max(|f1|, |f2|) / longest link at the last evaluation
    #: (the returned angles add the last Newton correction to that iterate).
    residual: float
    #: Residual per iteration (length nit + 1) when asked for with ``history=True``.
    history: np.ndarray | None = field(default=None, compare=False)

    @property
    def message(self) -> str:
        """One line saying how the solve ended (the status's message)."""
        return self.status.message


class Geometry(Protocol):
    """Computes a sweep's lazy members from its angles: the kernel's for
    ``FourBar.sweep``, NumPy's for ``planarkin.reference.sweep``."""

    def branch(self, theta3: np.ndarray, theta4: np.ndarray) -> np.ndarray:
        """sin(theta4 - theta3) at each point."""
        ...

    def pins(
        self, lengths: tuple[float, float, float, float], theta2: np.ndarray, theta3: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """The crank pin A (finite wherever theta2 is) and the rocker pin B, (N, 2) each."""
        ...


@dataclass(frozen=True, eq=False, repr=False)
class Sweep(SweepResult):
    """A crank sweep: one entry per crank angle, NaN angles wherever status != CONVERGED.

    Besides the shared names (``theta`` is ``theta2``), its own: ``theta3``/``theta4``,
    ``residual``, ``omega2..alpha4``, ``lengths``, ``mode``, ``method``. ``det`` is the
    branch indicator sin(theta4 - theta3) (> 0 open, < 0 crossed, 0 at a dead point),
    ``points`` O2, O4, A, B and ``angles`` crank, coupler, rocker (the built-in fourbar
    scene's names, O2 at the origin, O4 at (r1, 0)); the three are computed on first
    access, so a sweep costs nothing for them until they are read.
    """

    lengths: tuple[float, float, float, float]
    mode: str
    theta2: np.ndarray
    theta3: np.ndarray
    theta4: np.ndarray
    status: np.ndarray
    nit: np.ndarray
    residual: np.ndarray
    omega2: float | None = None
    omega3: np.ndarray | None = None
    omega4: np.ndarray | None = None
    alpha2: float | None = None
    alpha3: np.ndarray | None = None
    alpha4: np.ndarray | None = None
    #: "newton" or "closed-form" (no iterations; residual not computed, NaN).
    method: str = "newton"
    #: What computes ``det`` and ``points``; set by whoever made the sweep (the kernel or
    #: the reference). None: they are not available.
    geometry: Geometry | None = field(default=None, kw_only=True, compare=False)

    _points_name = "crank angles"
    _symbol = "theta2"

    @classmethod
    def build(
        cls, lengths, mode, theta2, theta3, theta4, status, nit, residual,
        method="newton", geometry=None, **rest,
    ):  # noqa: ANN001, ANN003, ANN206  # fmt: skip
        """The same instance as ``Sweep(...)`` with these arguments, built faster: the
        fields go straight into the instance's dict, those left at their defaults not at
        all (the class holds the defaults). The dataclass's frozen ``__init__`` sets each
        of its 17 fields through ``object.__setattr__``, which costs a sixth of a
        361-point sweep (about 4 us); ``method`` and ``geometry`` are parameters of their
        own, so the common call builds no dict of keywords. A test checks every field
        against the dataclass's.
        """
        if rest and not _SWEEP_FIELDS.issuperset(rest):
            extra = sorted(rest.keys() - _SWEEP_FIELDS)
            raise TypeError(f"Sweep.build() got unexpected keyword arguments {extra}")
        self = object.__new__(cls)
        d = self.__dict__
        d["lengths"], d["mode"], d["theta2"] = lengths, mode, theta2
        d["theta3"], d["theta4"], d["status"] = theta3, theta4, status
        d["nit"], d["residual"] = nit, residual
        d["method"], d["geometry"] = method, geometry
        if rest:
            d.update(rest)
        return self

    @property
    def theta(self) -> np.ndarray:
        """The input coordinate: the crank angles theta2."""
        return self.theta2

    _svg_links = tuple(v for k, v in LINKS.items() if k != "ground")
    _svg_ground = LINKS["ground"]

    def _describe(self) -> str:
        return f"{self.lengths}, {self.mode} mode, {self.method}"

    def _geometry(self, what: str) -> Geometry:
        if self.geometry is None:
            raise ValueError(
                f"this Sweep has no {what}: it was built without a geometry (sweeps from "
                "FourBar.sweep and planarkin.reference.sweep have one)"
            )
        return self.geometry

    @cached_property
    def det(self) -> np.ndarray:
        """(N,) sin(theta4 - theta3): the branch indicator, > 0 open, < 0 crossed, 0 at a
        dead point (what a scene sweep reports as ``det`` for the same four-bar)."""
        return self._geometry("det").branch(self.theta3, self.theta4)

    @cached_property
    def points(self) -> dict[str, np.ndarray]:
        """name -> (N, 2): the ground pivots O2 = (0, 0) and O4 = (r1, 0), the crank pin A
        and the rocker pin B (NaN where unsolved; A wherever theta2 is finite)."""
        a, b = self._geometry("points").pins(self.lengths, self.theta2, self.theta3)
        n = len(self.theta2)
        return {
            "O2": np.zeros((n, 2)),
            "O4": np.tile([self.lengths[0], 0.0], (n, 1)),
            "A": a,
            "B": b,
        }

    @cached_property
    def angles(self) -> dict[str, np.ndarray]:
        """link -> (N,): crank theta2 (as given), coupler theta3, rocker theta4 (radians,
        measured from the ground line O2 -> O4)."""
        return {"crank": self.theta2, "coupler": self.theta3, "rocker": self.theta4}


#: The keyword fields of :class:`Sweep` (for :meth:`Sweep.build`).
_SWEEP_FIELDS = frozenset(f.name for f in fields(Sweep))


@dataclass(frozen=True)
class Grashof:
    """Grashof condition and Barker class (Norton, Design of Machinery, Table 2-4)."""

    #: "grashof", "change-point" or "non-grashof"
    condition: str
    #: Barker code: GCRR, GCCC, GRCR, GRRC, RRR1-4, SCCC, SCRR, SRCR, SRRC, S2X, S3X
    barker: str
    #: crank-rocker, double-crank, rocker-crank, double-rocker, change-point, triple-rocker
    kind: str
    description: str
    s: float
    l: float  # noqa: E741 - the textbook's name
    p: float
    q: float

    @property
    def is_grashof(self) -> bool:
        """S + L < P + Q (decided exactly on the float inputs)."""
        return self.condition == "grashof"


@dataclass(frozen=True, eq=False)
class Limits:
    """Limit positions on one assembly mode, from the closed form (radians)."""

    mode: str
    #: Crank angles in (-pi, pi], sorted, where det J = 0 and the crank stops.
    #: Empty when the crank turns fully.
    toggles: np.ndarray
    #: Every crank angle where det J = 0: the toggles, plus the change points a fully
    #: turning crank passes through (where the two modes meet).
    dead_points: np.ndarray
    #: Assemblable crank-angle intervals (start, end), counter-clockwise, start in
    #: [-pi, pi]; end may exceed pi when an interval contains theta2 = pi.
    intervals: tuple[tuple[float, float], ...]
    #: The crank turns a full revolution.
    full_rotation: bool
    #: The rocker's interval on this mode: it sweeps counter-clockwise from rocker_min
    #: (wrapped to (-pi, pi]) to rocker_max = rocker_min + swing, which is never below
    #: rocker_min (it exceeds pi when the interval contains 180 deg); with the crank
    #: angles where they occur. None when the output turns fully (or never assembles).
    rocker_min: float | None
    rocker_min_theta2: float | None
    rocker_max: float | None
    rocker_max_theta2: float | None

    @property
    def rocker_swing(self) -> float | None:
        """Rocker swing angle: rocker_max - rocker_min."""
        if self.rocker_min is None or self.rocker_max is None:
            return None
        return self.rocker_max - self.rocker_min

    def assemblable(self, theta2: object) -> np.ndarray:
        """Boolean mask: crank angles inside an assemblable interval."""
        t = np.asarray(theta2, dtype=np.float64)
        inside = np.zeros(t.shape, dtype=bool)
        for a, b in self.intervals:
            inside |= a + np.mod(t - a, TAU) <= b
        return inside


@dataclass(frozen=True, eq=False, repr=False)
class BatchSweep(StatusResult):
    """Sweeps of M linkages over N crank angles: (M, N) arrays, row i the sweep of
    ``links[i]``. The shared names, with one documented exception: ``theta`` is the (N,)
    crank angles every linkage shares (not repeated M times), while ``status``,
    ``success``, ``nit``, ``det`` and each of ``points`` (M, N, 2) and ``angles`` (M, N)
    have a first axis per linkage; ``theta`` broadcasts against them. ``statuses()`` and
    ``summary()`` count all M x N points; ``len()`` is M, the number of sweeps."""

    links: np.ndarray
    mode: str
    theta2: np.ndarray
    theta3: np.ndarray
    theta4: np.ndarray
    status: np.ndarray
    nit: np.ndarray
    residual: np.ndarray
    method: str = "newton"
    #: What computes ``det`` and ``points`` (as :attr:`Sweep.geometry`); None: they are
    #: not available.
    geometry: Geometry | None = field(default=None, kw_only=True, compare=False)

    _points_name = "crank angles"
    _symbol = "theta2"

    @property
    def theta(self) -> np.ndarray:
        """The input coordinate: the (N,) crank angles theta2 (shared by every linkage)."""
        return self.theta2

    def __len__(self) -> int:
        """M, the number of linkages (of sweeps)."""
        return len(self.links)

    def _describe(self) -> str:
        return f"{len(self.links)} linkages, {self.mode} mode, {self.method}"

    def _geometry(self, what: str) -> Geometry:
        if self.geometry is None:
            raise ValueError(
                f"this BatchSweep has no {what}: it was built without a geometry (batches "
                "from sweep_batch have one)"
            )
        return self.geometry

    @cached_property
    def det(self) -> np.ndarray:
        """(M, N) sin(theta4 - theta3), as :attr:`Sweep.det` for each linkage."""
        t3, t4 = np.ascontiguousarray(self.theta3), np.ascontiguousarray(self.theta4)
        return self._geometry("det").branch(t3.ravel(), t4.ravel()).reshape(t3.shape)

    @cached_property
    def points(self) -> dict[str, np.ndarray]:
        """name -> (M, N, 2): O2, O4, A and B of each linkage, as :attr:`Sweep.points`."""
        g = self._geometry("points")
        m, n = self.theta3.shape
        out = {k: np.empty((m, n, 2)) for k in ("A", "B")}
        for i, r in enumerate(self.links):
            lengths = (float(r[0]), float(r[1]), float(r[2]), float(r[3]))
            out["A"][i], out["B"][i] = g.pins(lengths, self.theta2, self.theta3[i])
        o4 = np.zeros((m, n, 2))
        o4[:, :, 0] = np.asarray(self.links)[:, :1]
        return {"O2": np.zeros((m, n, 2)), "O4": o4, **out}

    @cached_property
    def angles(self) -> dict[str, np.ndarray]:
        """link -> (M, N): crank theta2 (broadcast, read-only), coupler theta3, rocker
        theta4."""
        crank = np.broadcast_to(self.theta2, self.theta3.shape)
        return {"crank": crank, "coupler": self.theta3, "rocker": self.theta4}
