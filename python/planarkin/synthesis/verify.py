"""Verification of a design before it is returned: the true linkage swept through the
whole input range (status, branch, jumps), its true error, the generated error of the
seed's closed form, conditioning, link ratios and tolerance sensitivity."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from .._angles import wrap_array
from ..scene import Scene
from .generated import SeedPlan
from .problem import DesignSpace, FunctionTarget, Problem, link_lengths, output_from_drawn
from .topology import Template


def output_rotation(sc: Scene, phi_in: np.ndarray, tol: float = 1e-12) -> tuple[np.ndarray, Any]:
    """The true output rotation (from the drawn pose) at input rotations ``phi_in``, and
    the sweep (from the drawn pose to phi_in[0], then along phi_in)."""
    out = sc.output
    if out is None:
        raise ValueError("scene must have an output link")
    link, pivot = out
    pts = sc.points
    first = next(p for p in sc.links[link] if p != pivot)
    a0 = math.atan2(pts[first][1] - pts[pivot][1], pts[first][0] - pts[pivot][0])
    sw = sc.sweep(sc.input_angle + np.asarray(phi_in), outputs=[link], tol=tol)
    return wrap_array(sw.angles[link] - a0), sw


def sign_changes(det: np.ndarray) -> int:
    """Sign changes along a sweep (a failed angle counts as one)."""
    s = np.sign(np.where(np.isfinite(det), det, 0.0))
    return int(np.count_nonzero(s[1:] != s[:-1]))


def true_error(
    sc: Scene, phi_in: np.ndarray, phi_out: np.ndarray
) -> tuple[np.ndarray, dict[str, Any]]:
    """True output error (radians) of scene ``sc`` at ``phi_in`` against ``phi_out``, with
    the sweep's verdict: all converged, det sign changes, min |det|, largest output jump
    between neighbours relative to the input step."""
    rot, sw = output_rotation(sc, phi_in)
    err = rot - phi_out
    ok = bool(np.all(sw.status == 0))
    dphi = np.abs(np.diff(phi_in))
    jump = float(np.max(np.abs(wrap_array(np.diff(rot))) / dphi)) if ok and dphi.size else math.inf
    info = {
        "converged": ok,
        "det_sign_changes": sign_changes(sw.det),
        "min_abs_conditioning": float(np.nanmin(np.abs(sw.det))) if ok else 0.0,
        "max_output_rate": jump,
    }
    return err, info


def link_ratio(points: Mapping[str, Sequence[float]], template: Template) -> float:
    """Longest over shortest distance between two joints of one link."""
    ls = link_lengths(points, template)
    return float(ls.max() / ls.min())


def tolerance_sensitivity(
    sc: Scene,
    phi_in: np.ndarray,
    phi_out: np.ndarray,
    sigmas: Sequence[float] = (1e-5, 1e-4, 1e-3),
    samples: int = 200,
    seed: int = 0,
) -> list[dict[str, float]]:
    """Median and 95th percentile of the true max error (degrees) when every joint
    coordinate gets Gaussian noise of standard deviation sigma (scene units); a noisy
    linkage that fails to move through the range counts as infinite error."""
    if samples < 1:
        raise ValueError(f"samples must be >= 1, got {samples}")
    rng = np.random.default_rng(seed)
    d = sc.to_dict()
    names = list(d["points"])
    out = []
    for sigma in sigmas:
        if not (math.isfinite(sigma) and sigma >= 0):
            raise ValueError(f"sigmas must be finite and >= 0, got {sigma}")
        errs = []
        for _ in range(samples):
            dd = dict(d)
            dd["points"] = {
                n: [
                    d["points"][n][0] + rng.normal(0, sigma),
                    d["points"][n][1] + rng.normal(0, sigma),
                ]
                for n in names
            }
            try:
                e, info = true_error(Scene.from_dict(dd), phi_in, phi_out)
                errs.append(float(np.degrees(np.max(np.abs(e)))) if info["converged"] else math.inf)
            except ValueError:
                errs.append(math.inf)
        a = np.array(errs)
        out.append(
            {
                "sigma": float(sigma),
                "samples": samples,
                "median_max_error_deg": float(np.median(a)),
                "p95_max_error_deg": float(np.percentile(a, 95))
                if np.isfinite(a).sum()
                else math.inf,
                "failed": int(np.count_nonzero(~np.isfinite(a))),
            }
        )
    return out


def verify(problem: Problem, x: np.ndarray, dense: int = 1001) -> dict[str, Any]:
    """Every figure of a function-generation design: true error at the design points and
    on ``dense`` points over the range (``sweep_converged``: every point solved), the
    generated error of the seed's closed form on the linkage's own roots with k (and
    where, and with what error, the drawn signs held fixed would change root), branch and
    conditioning, link ratio, the bounding box as drawn and over the whole motion."""
    t = problem.target
    if not isinstance(t, FunctionTarget):
        raise ValueError("verify needs a function-generation target")
    sp = problem.space
    if not isinstance(sp, DesignSpace):
        raise ValueError("verify needs a double butterfly DesignSpace (any scene: verify_scene)")
    sc = sp.scene(x)
    pts = sp.points_of(x)
    e31, info31 = true_error(sc, t.phi_in, t.phi_out)
    lo, hi = float(t.dense_in[0]), float(t.dense_in[-1])
    grid = np.linspace(lo, hi, dense)
    interp_out = _dense_out(problem, grid)
    ed, infod = true_error(sc, grid, interp_out)
    plan = SeedPlan(sp.template, pts)
    # the seed's closed form on the real linkage's own roots: with the drawn signs fixed
    # it changes root where the linkage passes a loop's turning point, and would then
    # describe another mechanism (its error is kept, as the seed's objective would see it)
    fixed = plan.generated(t.phi_in, t.phi_out)
    dyad_joints = [x for x, _, _ in sp.template.dyads]
    real = sc.sweep(sc.input_angle + t.phi_in, outputs=dyad_joints, tol=1e-12)
    g, used = plan.follow(
        t.phi_in, t.phi_out, {n: real.points[n] for n in dyad_joints}, e31 + t.phi_out
    )
    changes = np.any(used != np.asarray(fixed.signs, dtype=np.int8), axis=1)
    eg = g.theta - t.phi_out
    xy = np.array(list(pts.values()))
    # every joint over the whole motion (the packaging envelope), on the dense grid
    motion = sc.sweep(sc.input_angle + grid, outputs="all", tol=1e-12).coords
    return {
        "generated_max_error_deg": float(np.degrees(np.max(np.abs(eg)))),
        "generated_rms_over_range": float(np.sqrt(np.mean(eg**2)) / t.scale),
        "generated_signs": list(fixed.signs),
        "generated_root_changes": int(np.count_nonzero(changes)),
        "generated_root_changes_deg": [float(v) for v in np.degrees(t.phi_in[changes])],
        "generated_fixed_signs_max_error_deg": float(
            np.degrees(np.max(np.abs(fixed.theta - t.phi_out)))
        ),
        "generated_min_radicand": float(np.min(g.radicand)),
        "k_range": [float(np.min(g.k)), float(np.max(g.k))],
        "corrected_max_error_deg": float(np.degrees(np.max(np.abs(eg / (1 - g.k))))),
        "true_max_error_deg": float(np.degrees(np.max(np.abs(e31)))),
        "true_rms_over_range": float(np.sqrt(np.mean(e31**2)) / t.scale),
        f"true_max_error_deg_{dense}": float(np.degrees(np.max(np.abs(ed)))),
        "design_points": int(t.phi_in.size),
        "dense_points": dense,
        "sweep_converged": bool(info31["converged"] and infod["converged"]),
        "det_sign_changes": int(infod["det_sign_changes"]),
        "min_abs_conditioning": float(infod["min_abs_conditioning"]),
        "max_output_rate": float(infod["max_output_rate"]),
        "link_ratio": link_ratio(pts, sp.template),
        "shortest_link": float(link_lengths(pts, sp.template).min()),
        "longest_link": float(link_lengths(pts, sp.template).max()),
        "max_abs_x": float(np.max(np.abs(xy[:, 0]))),
        "max_abs_y": float(np.max(np.abs(xy[:, 1]))),
        "motion_max_abs_x": float(np.nanmax(np.abs(motion[..., 0]))),
        "motion_max_abs_y": float(np.nanmax(np.abs(motion[..., 1]))),
    }


def _dense_out(problem: Problem, grid: np.ndarray) -> np.ndarray:
    t = problem.target
    assert isinstance(t, FunctionTarget)
    if t.function is not None:
        return np.asarray(t.function(grid), dtype=np.float64)
    return np.interp(grid, t.dense_in, t.dense_out)


def linear_sensitivity(
    sc: Scene, phi_in: np.ndarray, phi_out: np.ndarray, h: float = 1e-7
) -> float:
    """RMS over ``phi_in`` of the first-order output error (degrees) per unit of Gaussian
    noise on every joint coordinate: sqrt(mean_i sum_j (d e_i / d x_j)^2), forward
    differences of the true linkage. Times sigma, the expected RMS error under noise."""
    d = sc.to_dict()
    e0, _ = true_error(sc, phi_in, phi_out)
    rows = []
    for n in d["points"]:
        for k in (0, 1):
            dd = {**d, "points": {m: list(v) for m, v in d["points"].items()}}
            dd["points"][n][k] += h
            e1, _ = true_error(Scene.from_dict(dd), phi_in, phi_out)
            rows.append((e1 - e0) / h)
    j = np.array(rows)
    return float(np.degrees(np.sqrt(np.mean(np.sum(j**2, axis=0)))))


def verify_scene(problem: Problem, x: np.ndarray, dense: int = 1001) -> dict[str, Any]:
    """Every figure of a design of any scene, from the real linkage: its error at the
    design points (function: output rotation or displacement; path: the point's distance
    from each target point) and, for a function target, on ``dense`` inputs over the
    range; the sweep over the range (every point solved, the conditioning's sign changes
    and smallest size); the order (the design points' inputs strictly increasing); and
    the circuit, traced by the scene's tracer from the drawn pose through dead points: the
    range must be reached both ways from the drawn pose before any turning point, and
    the traced poses at the design points must be the swept ones (``circuit``)."""
    t = problem.target
    sc = problem.scene(x)
    phi = np.asarray(problem.inputs(x), dtype=np.float64)
    if isinstance(t, FunctionTarget):
        lo, hi = float(min(t.dense_in.min(), phi.min())), float(max(t.dense_in.max(), phi.max()))
    else:
        lo, hi = float(phi.min()), float(phi.max())
    lo, hi = min(lo, 0.0), max(hi, 0.0)  # the drawn pose is where the motion starts
    angle = sc.input_kind == "angle"
    base = sc.input_angle if angle else 0.0
    at = sc.sweep(base + phi, outputs="all", tol=1e-12)
    grid = np.linspace(lo, hi, dense)
    sw = sc.sweep(base + grid, outputs="all", tol=1e-12)
    scale = problem.target.scale
    out: dict[str, Any] = {"design_points": int(phi.size), "inputs": [float(v) for v in phi]}
    if isinstance(t, FunctionTarget):
        e = output_from_drawn(sc, at.output) - t.phi_out
        want = (
            np.asarray(t.function(grid), dtype=np.float64)
            if t.function is not None
            else np.interp(grid, t.dense_in, t.dense_out)
        )
        ed = output_from_drawn(sc, sw.output) - want
        out["max_error"] = float(np.max(np.abs(e)))
        out[f"max_error_{dense}"] = float(np.max(np.abs(ed)))
    else:
        e = np.hypot(*(at.points[t.point] - t.xy).T)
        out["max_error"] = float(np.max(e))
    out["max_error_relative"] = out["max_error"] / scale
    ok = bool(np.all(at.status == 0) and np.all(sw.status == 0))
    out["sweep_converged"] = ok
    out["det_sign_changes"] = sign_changes(sw.det)
    out["min_abs_conditioning"] = float(np.nanmin(np.abs(sw.det))) if ok else 0.0
    out["in_order"] = bool(np.all(np.diff(phi) > 0))
    out["circuit"] = _circuit(sc, lo, hi, phi, at.coords)
    out["verified"] = bool(
        ok
        and out["det_sign_changes"] == 0
        and out["in_order"]
        and out["circuit"]["one_branch"]
        and out["circuit"]["max_pose_distance"] <= 1e-3
    )
    return out


def _circuit(
    sc: Scene, lo: float, hi: float, phi: np.ndarray, coords: np.ndarray
) -> dict[str, Any]:
    # the tracer starts at the drawn pose with the input increasing and follows the
    # circuit through dead points until it closes: forwards it must reach hi, and
    # (closed) backwards from its end it must reach lo, before turning
    tr = sc.trace()
    th = tr.theta - tr.theta[0]
    d = np.diff(th)
    turn = np.flatnonzero(np.sign(d[1:]) * np.sign(d[:-1]) < 0) + 1
    first = int(turn[0]) if turn.size else th.size - 1
    last = int(turn[-1]) if turn.size else 0
    forward = float(np.max(th[: first + 1]))
    backward = float(np.min(th[last:] - th[-1])) if tr.closed else 0.0
    one_branch = hi <= forward + 1e-9 and lo >= backward - 1e-9
    size = float(np.ptp(coords[np.isfinite(coords).all(axis=(1, 2))], axis=(0, 1)).max()) or 1.0
    dist = 0.0
    if one_branch:
        for i, v in enumerate(phi):
            seg, rel = (slice(0, first + 1), th) if v >= 0 else (slice(last, th.size), th - th[-1])
            ts, cs = rel[seg], tr.coords[seg]
            k = int(np.clip(np.searchsorted(ts, v), 1, ts.size - 1))  # ts increases
            w = (v - ts[k - 1]) / (ts[k] - ts[k - 1]) if ts[k] != ts[k - 1] else 0.0
            pose = cs[k - 1] + w * (cs[k] - cs[k - 1])
            dist = max(dist, float(np.max(np.hypot(*(pose - coords[i]).T))) / size)
    return {
        "one_branch": bool(one_branch),
        "closed": bool(tr.closed),
        "turning_points": int(tr.turning_points.size),
        "reach": [backward, forward],
        "max_pose_distance": dist if one_branch else math.inf,
    }
