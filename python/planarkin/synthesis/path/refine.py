"""Refinement of a placed candidate onto a path target: SLSQP on the scene's drawn
coordinates (and, timing free, each target point's input value) with the exact derivatives
of the poses (``pose_gradient``) and of the conditioning, under branch, order and the
user's constraints; then a least-squares polish kept only where the constraints still hold."""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.optimize import least_squares, minimize

from ...scene import Scene
from ..pool import blas_held_to_one_thread
from .model import DET_FLOOR, SWEEP_TOL, PathModel, _check
from .results import PathError
from .targets import CurveTarget

#: SLSQP's iterations and its absolute tolerance on the objective (the polish goes on)
MAX_ITER = 100
FTOL = 1e-13
#: SLSQP hands over to the polish once its best feasible objective has fallen by less than
#: STALL_DROP (relative) over STALL_ITER iterations: on a target no design traces exactly
#: the objective levels off and SLSQP's own test (an absolute FTOL) would use every
#: iteration
STALL_ITER, STALL_DROP = 15, 1e-4
#: the polish's relative tolerances, most evaluations and their rounds: a short arc's fit
#: is ill-conditioned (singular values over six decades on 10 points of a third of a
#: coupler curve), where Levenberg-Marquardt needs about 300 to reach 1e-16 of the size;
#: a round that does not take the objective below POLISH_DROP of its start ends it
POLISH_TOL, POLISH_NFEV, POLISH_ROUND, POLISH_DROP = 1e-12, 1000, 100, 0.8


@dataclass(frozen=True)
class Refined:
    """A refined design: ``scene`` (drawn at the refined coordinates), ``tracer``,
    ``inputs`` (the input value per target point, absolute, in the target's order),
    ``error`` at those inputs as the model measured it (:func:`~.verify.verify` measures
    the real linkage again), ``feasible`` (every constraint holds at the end), ``polished``
    (the least-squares polish was kept), SLSQP's ``iterations``, the model's
    ``evaluations`` (sweeps), ``seconds`` and SLSQP's ``message``."""

    scene: Scene
    tracer: str
    inputs: np.ndarray
    error: PathError
    feasible: bool
    polished: bool
    iterations: int
    evaluations: int
    seconds: float
    message: str


def _polish(model: PathModel, u: np.ndarray, deadline: float) -> np.ndarray:
    """Least squares from ``u`` with the exact Jacobian (Levenberg-Marquardt, or a trust
    region where there are fewer residuals than variables), in rounds of POLISH_ROUND
    evaluations while each round takes the objective below POLISH_DROP of its start (an
    ill-conditioned exact fit crawls at about that rate before it converges; a round that
    gains less is at a minimum it cannot fit better) and time is left."""
    method = "lm" if 2 * model.n >= model.nu else "trf"
    x = np.array(u)
    for _ in range(POLISH_NFEV // POLISH_ROUND):
        if time.perf_counter() >= deadline:
            break
        f0 = model.objective(x)
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                ls = least_squares(
                    model.residuals,
                    x,
                    jac=lambda v: model.jacobians(v)["r"],
                    method=method,
                    xtol=POLISH_TOL,
                    ftol=POLISH_TOL,
                    gtol=1e-15,
                    max_nfev=POLISH_ROUND,
                )
        except (ValueError, np.linalg.LinAlgError):
            break
        f = model.objective(ls.x)
        if f < f0:
            x = ls.x
        if ls.status != 0 or not f < POLISH_DROP * f0:
            break  # converged by its own test, or no longer converging
    return x


def _drawn_at_start(sc: Scene, t: float) -> Scene:
    """``sc`` drawn at input ``t`` (the traced arc's first point), where it solves there:
    the design's file then starts where its path does, and sweeps from its drawing follow
    the arc (the drawing's place along the motion is free in the refinement)."""
    try:
        sw = sc.sweep(t, outputs="all", tol=SWEEP_TOL)
    except ValueError:
        return sc
    if sw.status[0] != 0 or not np.all(np.isfinite(sw.coords[0])):
        return sc
    d = sc.to_dict()
    d["points"] = {
        p: [float(x), float(y)] for p, (x, y) in zip(sw.point_names, sw.coords[0], strict=True)
    }
    try:
        return Scene.from_dict(d)
    except ValueError:
        return sc


def refine(
    scene: Scene,
    tracer: str,
    target: CurveTarget,
    inputs: Any,
    *,
    min_transmission: float | None = None,
    box: Any = None,
    max_link_ratio: float | None = None,
    full_turn: bool = False,
    time_limit: float | None = None,
    max_iter: int = MAX_ITER,
    timing_offset: bool = True,
) -> Refined:
    """Refines ``scene`` (placed on ``target``, in its frame and units) so that its point
    ``tracer`` passes the target's points: least squares of their distances to the tracer at
    their input values (``inputs``, the scene's absolute input angles, one per target point: the
    start; timing free each is a variable; given, the target's inputs turned by one common
    offset, a variable too unless ``timing_offset`` is False: then they are the scene's input
    values as they are), over the target's size squared. SLSQP with exact derivatives over every
    drawn coordinate (the drawing's own place along its motion is a null direction the solvers
    tolerate: it changes no curve), under: the conditioning keeps its sign and stays >=
    ``DET_FLOOR`` (and >= sin(``min_transmission``), degrees) on samples of the traced arc
    (between consecutive inputs; closed or ``full_turn``, the whole turn), the inputs strictly
    monotone in the target's order (spanning less than a turn), fixed pivots inside ``box``
    ((xmin, xmax), (ymin, ymax)), link dimensions within ``max_link_ratio`` of each other, and
    for a four-bar that must turn fully, its transmission floor where the crank lies along the
    ground (exactly the whole turn's, and Grashof's condition with a margin). Then a least-
    squares polish (exact Jacobian), kept only if the constraints still hold. ``time_limit``
    (seconds) stops SLSQP early. OpenBLAS is held to one thread meanwhile
    (:func:`~planarkin.synthesis.pool.blas_held_to_one_thread`)."""
    with blas_held_to_one_thread():
        return _refine(
            scene,
            tracer,
            target,
            inputs,
            min_transmission=min_transmission,
            box=box,
            max_link_ratio=max_link_ratio,
            full_turn=full_turn,
            time_limit=time_limit,
            max_iter=max_iter,
            timing_offset=timing_offset,
        )


def _refine(
    scene: Scene,
    tracer: str,
    target: CurveTarget,
    inputs: Any,
    *,
    min_transmission: float | None,
    box: Any,
    max_link_ratio: float | None,
    full_turn: bool,
    time_limit: float | None,
    max_iter: int,
    timing_offset: bool,
) -> Refined:
    start = time.perf_counter()
    floor = DET_FLOOR
    if min_transmission is not None:
        mt = float(min_transmission)
        _check(0.0 <= mt < 90.0, "min_transmission", f"must be in [0, 90) degrees, got {mt!r}")
        floor = max(floor, math.sin(math.radians(mt)))
    _check(
        isinstance(max_iter, int) and max_iter >= 0,
        "max_iter",
        f"must be an integer >= 0, got {max_iter!r}",
    )
    if time_limit is not None:
        _check(
            math.isfinite(float(time_limit)) and float(time_limit) > 0,
            "time_limit",
            f"must be a positive number of seconds, got {time_limit!r}",
        )
    model = PathModel(
        scene,
        tracer,
        target,
        inputs,
        floor=floor,
        box=box,
        max_link_ratio=max_link_ratio,
        full_turn=full_turn,
        timing_offset=timing_offset,
    )
    deadline = math.inf if time_limit is None else start + float(time_limit)
    best: dict[str, Any] = {"u": model.u0, "f": math.inf}

    def keep(u: np.ndarray) -> None:
        f = model.objective(u)
        if f < best["f"] and model.feasible(u):
            best["u"], best["f"] = np.array(u), f

    keep(model.u0)

    history: list[float] = []

    def stop(intermediate_result: Any) -> None:
        keep(intermediate_result.x)
        history.append(best["f"])
        if time.perf_counter() > deadline:
            raise StopIteration
        if len(history) > STALL_ITER:
            before = history[-1 - STALL_ITER]
            if math.isfinite(before) and history[-1] > (1 - STALL_DROP) * before:
                raise StopIteration

    def fun(u: np.ndarray) -> float:
        return model.objective(u)

    def jac(u: np.ndarray) -> np.ndarray:
        return np.asarray(2.0 * model.jacobians(u)["r"].T @ model.residuals(u))

    cons = {
        "type": "ineq",
        "fun": model.constraints,
        "jac": lambda u: model.jacobians(u)["cons"],
    }
    iterations, message = 0, "no iterations asked"
    u = model.u0
    if max_iter > 0:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            res = minimize(
                fun,
                model.u0,
                jac=jac,
                method="SLSQP",
                constraints=[cons],
                bounds=model.bounds(),
                options={"maxiter": max_iter, "ftol": FTOL},
                callback=stop,
            )
        iterations, message, u = int(res.nit), str(res.message), res.x
        keep(u)
    u = best["u"] if math.isfinite(best["f"]) else u
    polished = False
    if np.all(model.values(u)["ok"]):
        x = _polish(model, u, deadline)
        if model.objective(x) < model.objective(u) and (model.feasible(x) or not model.feasible(u)):
            u, polished = x, True
    feasible = model.feasible(u)
    r = model.residuals(u).reshape(-1, 2)
    d = np.hypot(r[:, 0], r[:, 1])
    err = PathError(float(d.max()), float(np.sqrt(np.mean(d**2))))
    whole = scene.to_dict()
    whole.pop("lengths", None)  # the refined drawing is an exact pose
    out_scene = _drawn_at_start(model.scene_at(u, whole), float(model.inputs(u)[0]))
    return Refined(
        scene=out_scene,
        tracer=tracer,
        inputs=model.inputs(u),
        error=err,
        feasible=feasible,
        polished=polished,
        iterations=iterations,
        evaluations=model.evaluations,
        seconds=time.perf_counter() - start,
        message=message,
    )
