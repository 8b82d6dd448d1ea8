"""Plain result types of scenes: plan steps and sweeps (NumPy arrays made in Rust)."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field

import numpy as np

from .._types import Status


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
class SceneSweep:
    """A scene solved at N input angles. Arrays come from the Rust kernel; the dicts hold
    views into them (no copies). NaN wherever a point or link is not solved."""

    plan: Plan
    #: (N,) input angles (radians).
    theta: np.ndarray
    #: name -> (N, 2) positions, scene units.
    points: dict[str, np.ndarray]
    #: link -> (N,) angles in (-pi, pi].
    angles: dict[str, np.ndarray]
    #: (N,) int8: the first failing step's status, or CONVERGED.
    status: np.ndarray
    #: (N,) Newton steps spent reaching each angle (group steps only).
    nit: np.ndarray
    #: (N,) signed, scale-free conditioning of the whole solve: the product of the steps'.
    det: np.ndarray
    #: (N,) for LIMIT angles, the input angle (radians) of the dead point that stops the
    #: motion on the circuit followed (where continuation last converged); NaN elsewhere.
    limit: np.ndarray
    #: (N, steps) each step's signed conditioning (a dyad's sine of its angle at the
    #: solved point; a group's Hadamard ratio det J / prod |columns|).
    step_det: np.ndarray
    #: (N, steps) int8 status of each step.
    step_status: np.ndarray
    #: name -> (N,) int8 status of each reported point.
    point_status: dict[str, np.ndarray]
    #: name -> (N, 2) velocities (scene units per time) when ``omega`` was given.
    velocities: dict[str, np.ndarray] | None = None
    #: link -> (N,) angular velocities when ``omega`` was given.
    angular_velocities: dict[str, np.ndarray] | None = None
    #: (N, P, 2) all reported positions in one array (``points`` are views of it).
    coords: np.ndarray = field(default_factory=lambda: np.empty((0, 0, 2)))

    @classmethod
    def build(cls, plan, theta, pts, ang, status, nit, det, limit, step_status, step_det, pstat, vel):  # noqa: ANN001, ANN206, E501
        names, links = plan.points, plan.links
        v = w = None
        if vel is not None:
            v = {n: vel[0][:, j] for j, n in enumerate(names)}
            w = {n: vel[1][:, j] for j, n in enumerate(links)}
        return cls(
            plan=plan,
            theta=theta,
            points={n: pts[:, j] for j, n in enumerate(names)},
            angles={n: ang[:, j] for j, n in enumerate(links)},
            status=status,
            nit=nit,
            det=det,
            limit=limit,
            step_det=step_det,
            step_status=step_status,
            point_status={n: pstat[:, j] for j, n in enumerate(names)},
            velocities=v,
            angular_velocities=w,
            coords=pts,
        )

    @property
    def success(self) -> np.ndarray:
        """(N,) bool: every step converged."""
        return self.status == Status.CONVERGED

    def __len__(self) -> int:
        return len(self.theta)

    def statuses(self) -> dict[str, int]:
        """Count of angles per status name (only statuses that occur)."""
        codes, counts = np.unique(self.status, return_counts=True)
        return {Status(int(c)).name: int(k) for c, k in zip(codes, counts, strict=True)}

    def __repr__(self) -> str:
        n = len(self.theta)
        ok = int(np.count_nonzero(self.success))
        return (
            f"SceneSweep({n} angles, {ok} converged, {len(self.plan)} steps, "
            f"points {list(self.points)[:6]}{'...' if len(self.points) > 6 else ''})"
        )
