"""The FourBar: normalises and broadcasts arguments at the boundary, calls the Rust kernel
(whose validating constructors check the values: one rule, in one place) and wraps its
arrays in the plain result objects of ``_results``; ``to_scene`` draws it as a Scene."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from .. import _kernel
from .._args import as_angles, as_float, as_i64, as_str, check_guess, crank_rates, sweep_inputs
from .._status import Status
from ._results import COUPLER_POINT, LINKS, Grashof, Limits, Solution, Sweep

if TYPE_CHECKING:
    from ..scene import Scene


def _broadcast(**arrays: object) -> tuple[tuple[int, ...], list[np.ndarray]]:
    """Broadcasts named array-likes; returns the shape and flat contiguous float64 arrays."""
    conv = [as_angles(name, a) for name, a in arrays.items()]
    try:
        b = np.broadcast_arrays(*conv)
    except ValueError:
        shapes = ", ".join(f"{n} {a.shape}" for n, a in zip(arrays, conv, strict=True))
        raise ValueError(f"shapes do not broadcast: {shapes}") from None
    shape = b[0].shape
    return shape, [np.ascontiguousarray(x).ravel() for x in b]


class _KernelGeometry:
    """The lazy ``det`` and ``points`` of FourBar.sweep results, by the kernel (no NumPy
    trigonometry in the API: the same kernels that draw the coupler curve)."""

    def branch(self, theta3: np.ndarray, theta4: np.ndarray) -> np.ndarray:
        return _kernel.transmission(theta3, theta4)[1]

    def pins(
        self, lengths: tuple[float, float, float, float], theta2: np.ndarray, theta3: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        core = _kernel.FourBar(*lengths)
        # A is the coupler point at p = 0; with theta3 = 0 it stays finite where the loop
        # does not close (p * cos(NaN) would be NaN): the crank is always placed
        ax, ay = core.coupler_point(theta2, np.zeros_like(theta2), 0.0, 0.0)
        bx, by = core.coupler_point(theta2, theta3, lengths[2], 0.0)
        return np.column_stack((ax, ay)), np.column_stack((bx, by))


_KERNEL_GEOMETRY = _KernelGeometry()


def _shaped(shape: tuple[int, ...], *arrays: np.ndarray) -> tuple:
    """Reshapes flat results back; 0-d results become Python floats."""
    if shape == ():
        return tuple(float(a[0]) for a in arrays)
    return tuple(a.reshape(shape) for a in arrays)


class FourBar:
    """A four-bar linkage: r1 ground, r2 crank (input), r3 coupler, r4 rocker (output).

    Ground pivots O2 = (0, 0) and O4 = (r1, 0); angles in radians, counter-clockwise
    from +x. Lengths must be finite and > 0 (ValueError naming the parameter otherwise).
    """

    __slots__ = ("_core",)

    #: How :meth:`to_scene` makes a Scene of the data it draws: set by ``planarkin.scene``
    #: when it is imported (``import planarkin`` imports both subjects). The scene subject
    #: imports this one (``Scene.as_fourbar``); the way back is this hook, not an import,
    #: so the two subjects form no import circle.
    scene_from_dict: ClassVar[Callable[[dict[str, Any]], Scene] | None] = None

    def __init__(self, r1: float, r2: float, r3: float, r4: float) -> None:
        r = [
            as_float(n, v) for n, v in zip(("r1", "r2", "r3", "r4"), (r1, r2, r3, r4), strict=True)
        ]
        self._core = _kernel.FourBar(*r)

    @property
    def lengths(self) -> tuple[float, float, float, float]:
        """(r1, r2, r3, r4)"""
        return self._core.lengths

    r1 = property(lambda self: self.lengths[0], doc="Ground length.")
    r2 = property(lambda self: self.lengths[1], doc="Crank (input) length.")
    r3 = property(lambda self: self.lengths[2], doc="Coupler length.")
    r4 = property(lambda self: self.lengths[3], doc="Rocker (output) length.")

    def __repr__(self) -> str:
        return "FourBar(r1={!r}, r2={!r}, r3={!r}, r4={!r})".format(*self.lengths)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, FourBar) and self.lengths == other.lengths

    def __hash__(self) -> int:
        return hash(self.lengths)

    def grashof(self) -> Grashof:
        """Grashof condition and Barker class. S + L = P + Q is decided exactly on the
        binary values of the lengths (error-free sums, no tolerance)."""
        return Grashof(*self._core.grashof())

    def limits(self, mode: str = "open") -> Limits:
        """Limit positions on ``mode`` from the closed form: toggles (where a crank that
        cannot turn fully stops), all dead points, the assemblable crank-angle intervals
        and the rocker's extreme angles."""
        mode = as_str("mode", mode)
        toggles, dead, intervals, full, rocker = self._core.limits(mode)
        (t2min, t4min), (t2max, t4max) = rocker if rocker else ((None, None), (None, None))
        return Limits(
            mode, np.array(toggles), np.array(dead), tuple(intervals), full,
            t4min, t2min, t4max, t2max,
        )  # fmt: skip

    def solve(
        self,
        theta2: float,
        *,
        mode: str = "open",
        guess: tuple[float, float] | None = None,
        tol: float = 1e-9,
        max_iter: int = 100,
        history: bool = False,
    ) -> Solution:
        """Newton-Raphson at one crank angle.

        Starts from ``guess`` (theta3, theta4) or, by default, the closed form of
        ``mode``. Converged when max(|f1|, |f2|) / longest link < ``tol`` and the next
        Newton correction max|J^-1 F| (radians) < ``tol``; a point where rounding keeps that
        correction above ``tol`` is PRECISION_LOSS. That last correction is applied to the
        returned angles (error quadratic in it); ``nit`` and ``residual`` are those of the
        last evaluation. A point that converges on the other mode is BRANCH_JUMP; angles
        are NaN unless CONVERGED.
        ``history=True`` records the residual at every iterate.
        """
        t2 = as_float("theta2", theta2)
        mode = as_str("mode", mode)
        tol, max_iter = as_float("tol", tol), as_i64("max_iter", max_iter)
        g = check_guess(guess)
        t3, t4, st, nit, res, hist = self._core.solve(t2, mode, g, tol, max_iter, bool(history))
        status = Status(st)
        return Solution(t2, t3, t4, status == Status.CONVERGED, status, nit, res, hist)

    def sweep(
        self,
        theta2: object = None,
        *,
        mode: str = "open",
        guess: tuple[float, float] | None = None,
        tol: float = 1e-9,
        max_iter: int = 100,
        predictor: str = "quadratic",
        method: str = "newton",
        omega2: float | None = None,
        alpha2: float | None = None,
    ) -> Sweep:
        """Solves every crank angle in order, by continuation (default: 0..360 deg in 1 deg
        steps).

        Each point starts from a prediction off the last converged point: ``"previous"``
        (the seeds' continuation), ``"tangent"`` (first order) or ``"quadratic"`` (second
        order, the default: about one Newton step per point). The first point, and any
        point whose continuation fails, starts from the closed form of ``mode``, so a
        sweep never follows the other assembly mode. ``"closed-form"`` starts every point
        from the closed form of ``mode`` at its own angle and verifies it by Newton (with
        the mode check): no continuation, the points independent of each other (on the
        SIMD path, 4 angles at a time). ``omega2`` fills omega3/omega4, and ``alpha2``
        (with omega2) alpha3/alpha4.

        ``method="closed-form"`` solves every point by the four-bar's closed form instead:
        the same statuses and velocities, no iterations (``nit`` 0, ``residual`` NaN: not
        computed); faster, but only the four-bar has one.
        """
        a = sweep_inputs(theta2, mode, tol, max_iter, predictor, method)
        g = check_guess(guess)
        w2, a2 = crank_rates(omega2, alpha2)
        t3, t4, st, nit, res, w, acc = self._core.sweep(
            a.theta2, a.mode, g, a.tol, a.max_iter, a.predictor, a.method, w2, a2
        )
        # the rates' fields only where asked for (left out, they keep their defaults)
        rates = {} if w is None else {
            "omega2": w2, "omega3": w[0], "omega4": w[1],
            "alpha2": a2, "alpha3": acc[0] if acc else None, "alpha4": acc[1] if acc else None,
        }  # fmt: skip
        return Sweep.build(
            self._core.lengths, a.mode, a.theta2, t3, t4, st, nit, res,
            method=a.method, geometry=_KERNEL_GEOMETRY, **rates,
        )  # fmt: skip

    def closed_form(self, theta2: object, mode: str = "open") -> tuple:
        """Closed-form (theta3, theta4) of ``mode``, broadcast over ``theta2``; NaN where
        the linkage cannot assemble (or the position is indeterminate)."""
        mode = as_str("mode", mode)
        shape, (t2,) = _broadcast(theta2=theta2)
        t3, t4, _ = self._core.closed_form(t2, mode)
        return _shaped(shape, t3, t4)

    def closed_form_status(self, theta2: object, mode: str = "open") -> np.ndarray:
        """Status of the closed form at each crank angle (CONVERGED, SINGULAR at dead
        points, NOT_ASSEMBLABLE, NON_FINITE), as an int8 array shaped like ``theta2``."""
        mode = as_str("mode", mode)
        shape, (t2,) = _broadcast(theta2=theta2)
        return self._core.closed_form(t2, mode)[2].reshape(shape)

    def velocity(self, theta2: object, theta3: object, theta4: object, omega2: object) -> tuple:
        """(omega3, omega4) from J [w3, w4] = -dF/dtheta2 omega2, broadcast over the inputs.
        NaN at a dead point (|sin(theta4 - theta3)| below the singular threshold)."""
        shape, arrs = _broadcast(theta2=theta2, theta3=theta3, theta4=theta4, omega2=omega2)
        w3, w4, _ = self._core.velocity(*arrs)
        return _shaped(shape, w3, w4)

    def acceleration(
        self, theta2: object, theta3: object, theta4: object, omega2: object, alpha2: object = 0.0
    ) -> tuple:
        """(alpha3, alpha4): the loop differentiated twice, same Jacobian, broadcast.
        NaN at a dead point."""
        shape, arrs = _broadcast(
            theta2=theta2, theta3=theta3, theta4=theta4, omega2=omega2, alpha2=alpha2
        )
        a3, a4, _ = self._core.acceleration(*arrs)
        return _shaped(shape, a3, a4)

    def coupler_point(self, theta2: object, theta3: object, p: float, delta: float) -> tuple:
        """(x, y) of the coupler point at distance ``p`` from the crank pin A, at angle
        ``delta`` from the coupler line A-B; broadcast over theta2, theta3."""
        p = as_float("p", p)
        delta = as_float("delta", delta)
        shape, (t2, t3) = _broadcast(theta2=theta2, theta3=theta3)
        x, y = self._core.coupler_point(t2, t3, p, delta)
        return _shaped(shape, x, y)

    def coupler_curve(self, sweep: Sweep, p: float, delta: float) -> tuple:
        """Coupler-point curve (x, y) over a sweep of this linkage (NaN where unsolved).
        ValueError when ``sweep`` is not a Sweep, or is one of another linkage."""
        if not isinstance(sweep, Sweep):
            raise ValueError(
                f"sweep must be a Sweep (from FourBar.sweep), got {type(sweep).__name__}"
            )
        if tuple(sweep.lengths) != self.lengths:
            raise ValueError(
                f"sweep is of another linkage: lengths {tuple(sweep.lengths)}, this "
                f"linkage {self.lengths}"
            )
        return self.coupler_point(sweep.theta2, sweep.theta3, p, delta)

    @staticmethod
    def transmission_angle(theta3: object, theta4: object) -> object:
        """Transmission angle: the acute angle between coupler and rocker, in [0, pi/2]."""
        shape, (t3, t4) = _broadcast(theta3=theta3, theta4=theta4)
        return _shaped(shape, _kernel.transmission(t3, t4)[0])[0]

    @staticmethod
    def det(theta3: object, theta4: object) -> object:
        """sin(theta4 - theta3) = -det J / (r3 r4), the ``det`` of a sweep: > 0 open, < 0
        crossed, 0 at a dead point."""
        shape, (t3, t4) = _broadcast(theta3=theta3, theta4=theta4)
        return _shaped(shape, _kernel.transmission(t3, t4)[1])[0]

    @staticmethod
    def branch_indicator(theta3: object, theta4: object) -> object:
        """Deprecated alias of :meth:`det` (its former name, kept; the same numbers)."""
        return FourBar.det(theta3, theta4)

    def _repr_svg_(self) -> str | None:
        """A notebook's picture: the linkage as :meth:`to_scene` draws it (None when it
        cannot assemble)."""
        try:
            return self.to_scene()._repr_svg_()
        except ValueError:
            return None

    def _repr_png_(self) -> bytes | None:
        """The same picture as PNG (None when it cannot assemble)."""
        try:
            return self.to_scene()._repr_png_()
        except ValueError:
            return None

    def to_scene(
        self,
        theta2: float | None = None,
        *,
        mode: str = "open",
        coupler: tuple[float, float] | None = None,
    ) -> Scene:
        """This linkage as a :class:`planarkin.Scene`, with the built-in ``fourbar``
        scene's names: points O2 = (0, 0), O4 = (r1, 0), the crank pin A and the rocker pin
        B; links ground, crank, coupler, rocker; input the crank at O2, output the rocker
        at O4. ``coupler`` = (p, delta) adds the coupler point P at distance p from A, at
        angle delta (radians) from the line A -> B (the CLI's ``--coupler``, in radians).

        It is drawn at crank angle ``theta2`` on ``mode``, and the drawing chooses the
        circuit its sweeps follow: by default at 0, or in the middle of the first
        assemblable interval when 0 cannot assemble. ValueError when the linkage cannot
        assemble there (or anywhere) or sits at a dead point there.
        :meth:`planarkin.Scene.as_fourbar` goes the other way.
        """
        mode = as_str("mode", mode)
        if theta2 is None:
            t2 = 0.0
            if self.closed_form_status(t2, mode) == Status.NOT_ASSEMBLABLE:
                intervals = self.limits(mode).intervals
                if not intervals:
                    raise ValueError(f"{self!r} cannot be assembled at any crank angle")
                lo, hi = intervals[0]
                t2 = 0.5 * (lo + hi)
        else:
            t2 = as_float("theta2", theta2)
        status = Status(int(self.closed_form_status(t2, mode)))
        if status != Status.CONVERGED:
            raise ValueError(
                f"cannot draw {self!r} at theta2 = {t2!r} on the {mode} mode: {status.message}"
            )
        t3, _ = self.closed_form(t2, mode)
        r1, _, r3, _ = self.lengths

        def on_coupler(p: float, delta: float) -> list[float]:
            # the kernel's coupler-point formula places A (p = 0), B (p = r3) and P alike
            return [float(v) for v in self.coupler_point(t2, t3, p, delta)]

        points = {"O2": [0.0, 0.0], "O4": [r1, 0.0], "A": on_coupler(0.0, 0.0),
                  "B": on_coupler(r3, 0.0)}  # fmt: skip
        links = {k: list(v) for k, v in LINKS.items()}
        if coupler is not None:
            try:
                p, delta = coupler
            except (TypeError, ValueError):
                raise ValueError(f"coupler must be a pair (p, delta), got {coupler!r}") from None
            p, delta = as_float("coupler p", p), as_float("coupler delta", delta)
            if not (math.isfinite(p) and math.isfinite(delta)):
                raise ValueError(f"coupler must be finite, got {coupler!r}")
            points[COUPLER_POINT] = on_coupler(p, delta)
            links["coupler"].append(COUPLER_POINT)
        if FourBar.scene_from_dict is None:  # only where planarkin.scene was never imported
            raise RuntimeError("FourBar.to_scene needs planarkin.scene: import planarkin")
        return FourBar.scene_from_dict({
            "name": "four-bar ({:g}, {:g}, {:g}, {:g})".format(*self.lengths),
            "points": points,
            "links": links,
            "ground": "ground",
            "input": {"link": "crank", "pivot": "O2"},
            "output": {"link": "rocker", "pivot": "O4"},
        })  # fmt: skip
