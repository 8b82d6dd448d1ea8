"""Tolerance sensitivity by linearisation: the true error's median and 95th percentile over
the motion when every joint coordinate of the drawing gets Gaussian noise of standard
deviation sigma, from the exact derivatives of the output by every joint coordinate (one
factorisation per angle), with the noise drawn many times at the cost of a matrix
product. ``verify.tolerance_sensitivity`` samples the same by re-sweeping noisy linkages
(the check: the two agree where sigma is small)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..scene import Scene
from .problem import output_from_drawn


def output_jacobian(sc: Scene, phi_in: np.ndarray, tol: float = 1e-12) -> tuple[Any, np.ndarray]:
    """The sweep of ``sc`` at input rotations ``phi_in`` (from the drawn pose) and the
    exact derivatives (N, 2 P) of its output rotation, measured from the drawn output
    angle, by every joint coordinate (x then y of each point, in ``sc.points`` order)."""
    o = sc.output
    if o is None or "link" not in sc.to_dict()["output"]:
        raise ValueError("scene must have an angle output")
    names = list(sc.points)
    free = [f"{n}.{a}" for n in names for a in "xy"]
    g = sc.gradient(free, sc.input_angle + np.asarray(phi_in, dtype=np.float64), relative=True)
    assert g.output is not None
    link, pivot = o
    tip = next(q for q in sc.links[link] if q != pivot)
    e = np.subtract(sc.points[tip], sc.points[pivot])
    e2 = float(e @ e)
    da0 = np.zeros(2 * len(names))
    i, j = names.index(pivot), names.index(tip)
    da0[2 * j : 2 * j + 2] += (-e[1] / e2, e[0] / e2)
    da0[2 * i : 2 * i + 2] -= (-e[1] / e2, e[0] / e2)
    return g.sweep, g.output - da0


def linearized_tolerance(
    sc: Scene,
    phi_in: np.ndarray,
    phi_out: np.ndarray,
    sigmas: Sequence[float] = (1e-5, 1e-4),
    samples: int = 2000,
    seed: int = 0,
    noise: np.ndarray | None = None,
) -> list[dict[str, float]]:
    """Median and 95th percentile of the true max error (degrees) over ``phi_in`` when
    every joint coordinate gets Gaussian noise of standard deviation sigma (scene units):
    e + J delta at each angle, J the exact output derivatives, ``samples`` draws of delta
    (``seed``; or the unit draws ``noise`` (samples, 2 P), scaled by sigma)."""
    if samples < 1:
        raise ValueError(f"samples must be >= 1, got {samples}")
    sw, jac = output_jacobian(sc, phi_in)
    if not np.all(sw.status == 0) or not np.all(np.isfinite(jac)):
        raise ValueError("the linkage does not move through phi_in (no linearisation)")
    e = output_from_drawn(sc, sw.output) - np.asarray(phi_out, dtype=np.float64)
    if noise is None:
        noise = np.random.default_rng(seed).standard_normal((samples, jac.shape[1]))
    out = []
    for s in sigmas:
        if not (math.isfinite(s) and s > 0):
            raise ValueError(f"sigmas must be finite and > 0, got {s}")
        worst = np.degrees(np.max(np.abs(e[None, :] + s * noise @ jac.T), axis=1))
        out.append(
            {
                "sigma": float(s),
                "samples": int(noise.shape[0]),
                "median_max_error_deg": float(np.median(worst)),
                "p95_max_error_deg": float(np.percentile(worst, 95)),
            }
        )
    return out
