"""What a synthesis aims at: a function (output rotation against input rotation), a path
with prescribed timing (points at given input angles) or a path of points alone (the
input free, in order); each checked at construction and with the scale its error is
measured in."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

__all__ = ["FunctionTarget", "PathPoints", "PathTarget", "Target"]


def _monotone(name: str, a: np.ndarray) -> None:
    # the seed's order constraint: the input moves one way through the design points
    d = np.diff(a)
    if a.ndim != 1 or a.size < 2 or not (np.all(d > 0) or np.all(d < 0)):
        raise ValueError(
            f"{name} must be a strictly monotone 1-D array of >= 2 input angles (order "
            "constraint: the input must pass the design points in order)"
        )


@dataclass(frozen=True)
class FunctionTarget:
    """Function generation: output rotations ``phi_out`` at input rotations ``phi_in``
    (radians from the drawn pose; the drawn pose itself is input 0, output 0), and the
    same on a dense grid for the branch constraint and verification (``dense_in``,
    ``dense_out``)."""

    phi_in: np.ndarray
    phi_out: np.ndarray
    dense_in: np.ndarray
    dense_out: np.ndarray
    #: the prescribed function itself (a picklable callable), for verification off the grid
    function: Callable[[np.ndarray], np.ndarray] | None = None

    def __post_init__(self) -> None:
        for name in ("phi_in", "phi_out", "dense_in", "dense_out"):
            a = np.asarray(getattr(self, name), dtype=np.float64)
            if a.ndim != 1 or not np.all(np.isfinite(a)):
                raise ValueError(f"{name} must be a 1-D array of finite angles (radians)")
            object.__setattr__(self, name, a)
        _monotone("phi_in", self.phi_in)
        _monotone("dense_in", self.dense_in)
        if self.phi_out.shape != self.phi_in.shape:
            raise ValueError(f"phi_out must have the shape of phi_in {self.phi_in.shape}")
        if self.dense_out.shape != self.dense_in.shape:
            raise ValueError(f"dense_out must have the shape of dense_in {self.dense_in.shape}")
        if np.ptp(self.phi_out) <= 0:
            raise ValueError("phi_out must not be constant (its range scales the objective)")

    @property
    def scale(self) -> float:
        """The prescribed output range (the objective's denominator)."""
        return float(np.ptp(self.phi_out))


@dataclass(frozen=True)
class PathTarget:
    """Path generation with prescribed timing: point ``point`` at ``xy`` (n, 2) at input
    rotations ``phi_in``; ``dense_in`` is the grid of the branch constraint."""

    point: str
    phi_in: np.ndarray
    xy: np.ndarray
    dense_in: np.ndarray

    def __post_init__(self) -> None:
        pi = np.asarray(self.phi_in, dtype=np.float64)
        xy = np.asarray(self.xy, dtype=np.float64)
        di = np.asarray(self.dense_in, dtype=np.float64)
        _monotone("phi_in", pi)
        _monotone("dense_in", di)
        if xy.shape != (pi.size, 2) or not np.all(np.isfinite(xy)):
            raise ValueError(f"xy must be finite points of shape ({pi.size}, 2), got {xy.shape}")
        object.__setattr__(self, "phi_in", pi)
        object.__setattr__(self, "xy", xy)
        object.__setattr__(self, "dense_in", di)

    @property
    def scale(self) -> float:
        """The size of the prescribed path (the larger side of its bounding box)."""
        return float(np.ptp(self.xy, axis=0).max())


@dataclass(frozen=True)
class PathPoints:
    """Path generation without prescribed timing: point ``point`` through ``xy`` (n, 2) in
    that order, at input values the optimizer chooses (design variables after the joint
    coordinates: input rotations, or displacements for a linear input, from the drawn
    pose) within ``span``, each at least ``order_margin`` past the one before (the order
    constraint); the branch constraint holds on ``dense`` inputs from the first point's to
    the last's. ``phi0``: where the optimizer starts them (default evenly in ``span``)."""

    point: str
    xy: np.ndarray
    span: tuple[float, float] = (-math.pi, math.pi)
    dense: int = 41
    order_margin: float = 1e-3
    phi0: np.ndarray | None = None

    def __post_init__(self) -> None:
        xy = np.asarray(self.xy, dtype=np.float64)
        if xy.ndim != 2 or xy.shape[1] != 2 or xy.shape[0] < 2 or not np.all(np.isfinite(xy)):
            raise ValueError(f"xy must be >= 2 finite points of shape (n, 2), got {xy.shape}")
        object.__setattr__(self, "xy", xy)
        lo, hi = (float(v) for v in self.span)
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
            raise ValueError(f"span must be two finite input values, low < high, got {self.span}")
        object.__setattr__(self, "span", (lo, hi))
        if int(self.dense) != self.dense or self.dense < 2:
            raise ValueError(f"dense must be an integer >= 2, got {self.dense}")
        if not (math.isfinite(self.order_margin) and self.order_margin > 0):
            raise ValueError(f"order_margin must be finite and > 0, got {self.order_margin}")
        if self.order_margin * (xy.shape[0] - 1) >= hi - lo:
            raise ValueError("order_margin leaves no room in span for the points in order")
        if self.phi0 is None:
            phi0 = np.linspace(lo, hi, xy.shape[0] + 2)[1:-1]
        else:
            phi0 = np.asarray(self.phi0, dtype=np.float64)
            if phi0.shape != (xy.shape[0],) or not np.all(np.isfinite(phi0)):
                raise ValueError(f"phi0 must be {xy.shape[0]} finite input values")
            if np.any(phi0 < lo) or np.any(phi0 > hi):
                raise ValueError(f"phi0 must lie within span {self.span}")
        object.__setattr__(self, "phi0", phi0)

    @property
    def n(self) -> int:
        """The number of points."""
        return int(self.xy.shape[0])

    @property
    def scale(self) -> float:
        """The size of the prescribed path (the larger side of its bounding box)."""
        return float(np.ptp(self.xy, axis=0).max()) or 1.0


#: any of the three
Target = FunctionTarget | PathTarget | PathPoints
