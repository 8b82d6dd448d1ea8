"""The result of a force analysis over a sweep (statics or inverse dynamics): the input
effort, every joint reaction, the shaking force and moment, the energies, the built-in
checks and a summary. Plain data: nothing here reaches the kernel."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._angles import wrapped
from .._results import status_counts
from .._status import Status

__all__ = ["EffortGradient", "Forces"]


@dataclass(frozen=True, eq=False, repr=False)
class Forces:
    """Forces along a sweep, in the scene's units (``units``: length, force, mass).

    ``input`` is the effort that drives the motion: for an angle input the torque on the
    input link about its pivot (positive counter-clockwise), for a linear input the force
    along the guide's line (positive from ``line[0]`` towards ``line[1]``). NaN where the
    sweep's point is not solved or lies at a dead point, with ``status`` saying which.
    """

    #: "statics" or "dynamics".
    kind: str
    #: (N,) the input coordinate (angles in radians, or displacements).
    theta: np.ndarray
    #: "angle" or "displacement".
    input_kind: str
    #: (N,) int8 status of each point: the sweep's, SINGULAR at a dead point.
    status: np.ndarray
    #: (N,) the input effort by Newton-Euler (torque, or force along the guide).
    input: np.ndarray
    #: (N,) the same by virtual work through the exact velocity map.
    input_virtual_work: np.ndarray
    #: (joint, link) -> (N, 2): the force the joint's first link (scene order) exerts on
    #: ``link`` at the joint.
    reactions: dict[tuple[str, str], np.ndarray]
    #: slot or prismatic pair -> (N,): the guide's force on the moving part along the
    #: line's unit normal (its direction turned +90 degrees).
    normal: dict[str, np.ndarray]
    #: prismatic pair -> (N,): the guide's moment on the moving link (counter-clockwise).
    moment: dict[str, np.ndarray]
    #: (N,) output effort per unit input effort (the inverse of the output's velocity
    #: ratio: d input / d output); None when the scene declares no output.
    mechanical_advantage: np.ndarray | None
    #: (N, 2) the force the moving links exert on the ground (through every ground joint and
    #: the input's reaction) and (N,) its moment about the ground's first point.
    shaking_force: np.ndarray
    shaking_moment: np.ndarray
    #: (N,) kinetic and potential (gravity and springs) energy, force x length units.
    kinetic_energy: np.ndarray
    potential_energy: np.ndarray
    #: (N,) the input's power (dynamics; zeros for statics).
    input_power: np.ndarray
    #: Largest relative residual of the checks (``checks``), over solved points.
    check: float
    #: Each check's largest relative residual: "virtual_work" (virtual work against
    #: Newton-Euler), "energy" (dynamics: input power against the rate of change of the
    #: energies minus the other loads' power).
    checks: dict[str, float]
    #: The unit system: length, force, mass (names; None where not stated).
    units: dict[str, str | None]
    #: (N,) input rate and its rate of change (dynamics), None for statics.
    omega: np.ndarray | None = field(default=None)
    alpha: np.ndarray | None = field(default=None)

    @property
    def success(self) -> np.ndarray:
        """(N,) True where the effort was found."""
        return self.status == Status.CONVERGED

    @property
    def effort_unit(self) -> str:
        """The input effort's unit: force x length for an angle input, force otherwise."""
        f, length = self.units["force"] or "force", self.units["length"] or "length"
        return f"{f}*{length}" if self.input_kind == "angle" else f

    def reaction_magnitudes(self) -> dict[tuple[str, str], np.ndarray]:
        """(joint, link) -> (N,) magnitude of each pin reaction."""
        return {k: np.hypot(v[:, 0], v[:, 1]) for k, v in self.reactions.items()}

    def peaks(self) -> dict[tuple[str, str], tuple[float, float]]:
        """(joint, link) -> (largest reaction magnitude, the input value where it is)."""
        out = {}
        for k, m in self.reaction_magnitudes().items():
            if np.isfinite(m).any():
                i = int(np.nanargmax(m))
                out[k] = (float(m[i]), float(self.theta[i]))
            else:
                out[k] = (float("nan"), float("nan"))
        return out

    @property
    def peak_input(self) -> float:
        """Largest |input effort| over solved points (NaN if none)."""
        ok = np.isfinite(self.input)
        return float(np.abs(self.input[ok]).max()) if ok.any() else float("nan")

    @property
    def rms_input(self) -> float:
        """Root mean square of the input effort over solved points (NaN if none)."""
        ok = np.isfinite(self.input)
        return float(np.sqrt(np.mean(self.input[ok] ** 2))) if ok.any() else float("nan")

    def summary(self) -> str:
        """A few lines: peak and RMS effort, the largest pin reaction, the checks."""
        u = self.effort_unit
        n = len(self.theta)
        counts = ", ".join(f"{k}={v}" for k, v in status_counts(self.status).items())
        lines = [
            f"{self.kind}: {int(self.success.sum())}/{n} points ({counts})",
            f"input effort: peak {self.peak_input:.6g} {u}, RMS {self.rms_input:.6g} {u}",
        ]
        peaks = self.peaks()
        if peaks:
            (j, link), (m, t) = max(peaks.items(), key=lambda kv: np.nan_to_num(kv[1][0]))
            at = f"{wrapped(t):.1f} deg" if self.input_kind == "angle" else f"{t:.6g}"
            lines.append(
                f"largest pin reaction: {m:.6g} {self.units['force'] or ''} at joint {j} "
                f"(on {link}), input {at}"
            )
        lines.append(
            "checks (largest relative residual): "
            + ", ".join(f"{k} {v:.2e}" for k, v in self.checks.items())
        )
        return "\n".join(lines)

    def __str__(self) -> str:
        return self.summary()

    def __repr__(self) -> str:
        return (
            f"<Forces {self.kind}, {len(self.theta)} points, peak input "
            f"{self.peak_input:.4g} {self.effort_unit}, check {self.check:.1e}>"
        )


@dataclass(frozen=True, eq=False)
class EffortGradient:
    """The peak (largest |input effort| over the sweep's points) or RMS input effort of a
    statics sweep and its exact derivatives by free drawn coordinates (at fixed absolute
    input values): an objective or constraint for synthesis. The peak's derivative is the
    one at the point where it is reached (the peak over the sampled points)."""

    #: The free coordinates, as given: "A.x", "A.y".
    free: tuple[str, ...]
    #: "peak" or "rms".
    measure: str
    #: The measure's value (effort units).
    value: float
    #: (F,) its derivatives by the free coordinates.
    gradient: np.ndarray
    #: (N,) the input effort and (N, F) its derivatives at every point (NaN where unsolved).
    input: np.ndarray
    input_gradient: np.ndarray
