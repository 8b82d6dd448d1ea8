"""What a path synthesis returns: ranked designs with their true errors and defects."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class PathError:
    """Distances from the target's points to the design's coupler curve (the traced arc),
    divided by the target's size: the largest and the root mean square."""

    max: float
    rms: float


@dataclass(frozen=True)
class Defects:
    """True where the design has that defect: ``circuit`` (the target's points lie on more
    than one circuit), ``branch`` (a dead point inside the traced arc), ``order`` (the
    input does not reach the points in the target's order)."""

    circuit: bool
    branch: bool
    order: bool

    @property
    def any(self) -> bool:
        """Any of the three."""
        return self.circuit or self.branch or self.order
