"""Tolerance sensitivity by linearisation: the true error's median and 95th percentile over
the motion when every joint coordinate of the drawing gets Gaussian noise of standard
deviation sigma, from the exact derivatives of the output by every joint coordinate (one
factorisation per angle), with the noise drawn many times at the cost of a matrix
product. ``verify.tolerance_sensitivity`` samples the same by re-sweeping noisy linkages
(the check: the two agree where sigma is small). :func:`robust_start` optimises a design
for it: the tolerance-aware objective."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ..scene import Scene
from .exact import subgrid
from .problem import FunctionTarget, Problem, output_from_drawn
from .start import FD_STEP, Cache, resolve_gradient


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


def p95_objective(
    problem: Problem,
    sigma: float,
    samples: int = 200,
    seed: int = 0,
    grid: int = 101,
    measure: str = "p95",
) -> Callable[[np.ndarray], float]:
    """The tolerance-aware objective of design vectors of ``problem`` (a function target
    on an angle output): the linearised 95th percentile of the true max error (over a
    subgrid of ``grid`` points of the dense grid, in units of the target's scale) under
    Gaussian noise of standard deviation ``sigma`` on every joint coordinate, the same
    ``samples`` draws for every design (common random numbers: the objective is a
    deterministic function of the design). Infinite where the linkage does not move
    through the range."""
    t = problem.target
    if not isinstance(t, FunctionTarget):
        raise ValueError("the tolerance-aware objective needs a function target")
    if not (math.isfinite(sigma) and sigma > 0):
        raise ValueError(f"sigma must be finite and > 0, got {sigma}")
    phi = t.dense_in[subgrid(t.dense_in.size, grid)]
    out = np.interp(phi, t.dense_in, t.dense_out) if t.function is None else t.function(phi)
    n = 2 * len(problem.space.points)
    noise = np.random.default_rng(seed).standard_normal((samples, n))

    def f(x: np.ndarray) -> float:
        try:
            sc = problem.scene(x)
            sw, jac = output_jacobian(sc, phi)
        except ValueError:
            return math.inf
        if not np.all(sw.status == 0) or not np.all(np.isfinite(jac)):
            return math.inf
        e = output_from_drawn(sc, sw.output) - out
        if measure == "rms":  # the expected mean square over the range, in closed form
            return float(np.sqrt(np.mean(e**2) + sigma**2 * np.mean(jac**2) * n) / t.scale)
        worst = np.max(np.abs(e[None, :] + sigma * noise @ jac.T), axis=1)
        return float(np.percentile(worst, 95) / t.scale)

    return f


def robust_start(
    problem: Problem,
    x0: np.ndarray,
    sigma: float,
    budget: float,
    *,
    maxiter: int = 40,
    samples: int = 200,
    seed: int = 0,
    measure: str = "p95",
) -> tuple[np.ndarray, dict[str, Any]]:
    """SLSQP from a design ``x0`` on the tolerance-aware objective (:func:`p95_objective`
    at ``sigma``, forward differences of it) under every constraint of ``problem`` (exact
    derivatives where available) and the nominal true error within ``budget`` (in units
    of the target's scale) on the dense grid. Returns the best feasible iterate (``x0``
    when none improved on it) and scipy's words; the caller verifies it."""
    from scipy.optimize import minimize

    f = p95_objective(problem, sigma, samples, seed, measure=measure)
    box = max(float(np.max(problem.upper - problem.lower)), 1e-300)
    h = FD_STEP * 10 * box
    cache = Cache(problem, problem.grid(), FD_STEP * box, resolve_gradient(problem, "auto"))
    cache.fix_dense(x0)
    lo, hi = problem.lower, problem.upper
    f0 = f(x0)
    if not math.isfinite(f0):
        raise ValueError("x0 does not move through the range (no tolerance objective)")

    # SLSQP, the differences and keep() ask at one iterate up to three times
    seen: dict[bytes, float] = {}

    def fun(x: np.ndarray) -> float:
        k = np.asarray(x, dtype=np.float64).tobytes()
        if k not in seen:
            if len(seen) > 4 * x.size:
                seen.clear()
            v = f(x)
            seen[k] = v / f0 if math.isfinite(v) else 1e3
        return seen[k]

    def jac(x: np.ndarray) -> np.ndarray:
        v = fun(x)
        g = np.zeros_like(x)
        for j in range(x.size):
            xj = x.copy()
            xj[j] += h if xj[j] + h <= hi[j] else -h
            g[j] = (fun(xj) - v) / (xj[j] - x[j])
        return g

    def cons(x: np.ndarray) -> np.ndarray:
        d = cache.dense(x)
        return np.concatenate(
            [budget - d[:-1], budget + d[:-1], [budget - abs(d[-1])], cache.cons(x)]
        )

    def cons_jac(x: np.ndarray) -> np.ndarray:
        d = cache.dense(x)
        jd = cache.jac(x, dense=True).dense
        return np.vstack([-jd[:-1], jd[:-1], -np.sign(d[-1]) * jd[-1:], cache.cons_jac(x)])

    # SLSQP's iterates may leave the feasible set on the way (and it may end outside it):
    # the best iterate that satisfies every constraint is the one returned
    best = [1.0, np.clip(x0, lo, hi)]

    def keep(xk: np.ndarray) -> None:
        xk = np.clip(xk, lo, hi)
        if np.all(cons(xk) >= -1e-9) and fun(xk) < best[0]:
            best[:] = [fun(xk), xk.copy()]

    res = minimize(
        fun,
        best[1],
        jac=jac,
        method="SLSQP",
        bounds=list(zip(lo, hi, strict=True)),
        constraints=[{"type": "ineq", "fun": cons, "jac": cons_jac}],
        options={"maxiter": maxiter, "ftol": 1e-9},
        callback=keep,
    )
    keep(res.x)
    x = best[1]
    return x, {
        "phase": "robust",
        "status": int(res.status),
        "success": bool(res.success),
        "message": str(res.message),
        "nit": int(res.nit),
        "sigma": sigma,
        "p95_start": f0 * problem.target.scale,
        "p95_end": f(x) * problem.target.scale,
    }
