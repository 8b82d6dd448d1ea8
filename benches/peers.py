"""The other ways a user would solve the four-bar, written the way they would write them,
for the benchmarks to put beside planarkin: the seed report's Newton-Raphson loop (plain
``math``, and as printed with NumPy scalars), a vectorized NumPy Newton-Raphson over a
batch, and pylinkage (numba) set up on the same linkage.

Every Newton here uses planarkin's convergence criterion, max(|f1|, |f2|) / longest link
< tol, so iteration counts and accuracy are comparable.
"""

from __future__ import annotations

import math

import numpy as np
from planarkin.reference import closed_form_vectorized

SEED = (6.0, 2.0, 5.0, 5.0)
#: The seed report's first guess at theta2 = 0 (open mode, "from the geometry").
SEED_GUESS = (math.radians(80.0), math.radians(100.0))
TAU = 2.0 * math.pi


# --- the seed report's algorithm, plain Python ------------------------------------------


def math_newton(r1, r2, r3, r4, theta2, guess, tol=1e-9, max_iter=100):
    """One crank angle by Newton-Raphson with Cramer's rule (the seed's Algorithm 1),
    in plain ``math``. Returns (theta3, theta4, converged, iterations)."""
    scale = max(r1, r2, r3, r4)
    c2, s2 = math.cos(theta2), math.sin(theta2)
    t3, t4 = guess
    for k in range(max_iter + 1):
        s3, c3 = math.sin(t3), math.cos(t3)
        s4, c4 = math.sin(t4), math.cos(t4)
        f1 = r2 * c2 + r3 * c3 - r4 * c4 - r1
        f2 = r2 * s2 + r3 * s3 - r4 * s4
        if max(abs(f1), abs(f2)) / scale < tol:
            return t3, t4, True, k
        if k == max_iter:
            break
        j11, j12, j21, j22 = -r3 * s3, r4 * s4, r3 * c3, -r4 * c4
        det = j11 * j22 - j12 * j21
        if abs(det) < 1e-9 * r3 * r4:  # the seed's singularity check, made dimensionless
            break
        t3 += (-f1 * j22 + f2 * j12) / det
        t4 += (-j11 * f2 + j21 * f1) / det
    return t3, t4, False, max_iter


def math_sweep(r1, r2, r3, r4, theta2, guess=SEED_GUESS, tol=1e-9, max_iter=100):
    """The seed's sweep: each angle starts from the previous solution (zeroth-order
    continuation). Returns lists theta3, theta4 (wrapped to (-pi, pi]) and iterations."""
    t3o, t4o, nito = [], [], []
    g = guess
    for t2 in theta2:
        t3, t4, ok, k = math_newton(r1, r2, r3, r4, t2, g, tol, max_iter)
        nito.append(k)
        if ok:
            t3o.append(math.atan2(math.sin(t3), math.cos(t3)))
            t4o.append(math.atan2(math.sin(t4), math.cos(t4)))
            g = (t3, t4)
        else:
            t3o.append(math.nan)
            t4o.append(math.nan)
    return t3o, t4o, nito


def seed_as_printed(r1, r2, r3, r4, theta2_deg, guess=SEED_GUESS, tol=1e-9, max_iter=100):
    """The seed report's code as printed (NumPy scalar functions inside a Python loop,
    degrees in, previous solution as the next guess), with planarkin's criterion."""
    scale = max(r1, r2, r3, r4)
    out3, out4 = [], []
    cur = guess
    for d in theta2_deg:
        theta2 = np.radians(d)
        theta3, theta4 = cur
        ok = False
        for _ in range(max_iter + 1):
            f1 = r2 * np.cos(theta2) + r3 * np.cos(theta3) - r4 * np.cos(theta4) - r1
            f2 = r2 * np.sin(theta2) + r3 * np.sin(theta3) - r4 * np.sin(theta4)
            if max(abs(f1), abs(f2)) / scale < tol:
                ok = True
                break
            J11 = -r3 * np.sin(theta3)
            J12 = r4 * np.sin(theta4)
            J21 = r3 * np.cos(theta3)
            J22 = -r4 * np.cos(theta4)
            det = J11 * J22 - J12 * J21
            if abs(det) < 1e-9:
                break
            theta3 += ((-f1) * J22 - (-f2) * J12) / det
            theta4 += (J11 * (-f2) - J21 * (-f1)) / det
        if ok:
            out3.append(np.degrees(theta3))
            out4.append(np.degrees(theta4))
            cur = (theta3, theta4)
        else:
            out3.append(None)
            out4.append(None)
    return out3, out4


# --- vectorized NumPy Newton-Raphson over a batch ----------------------------------------


def _wrap(a):
    return np.pi - np.mod(np.pi - a, TAU)


def numpy_newton_batch(links, theta2, tol=1e-9, max_iter=100, predictor="quadratic"):
    """The best NumPy Newton-Raphson we could write for M linkages x N angles.

    A sweep is sequential in theta2 (continuation), so the loop runs over the N angles
    and every operation is vectorized over the M linkages. The first angle starts from
    the vectorized closed form; each next angle from a ``"tangent"`` or ``"quadratic"``
    prediction (the same predictors as planarkin). Newton stops per linkage when
    max(|f1|, |f2|) / longest link < tol; converged linkages are masked out of the step.
    No status logic (assembly, branch, singularity): the benchmark linkages are
    crank-rockers that assemble at every angle. Returns (theta3, theta4, nit), (M, N).
    """
    links = np.asarray(links, dtype=np.float64)
    theta2 = np.asarray(theta2, dtype=np.float64)
    m, n = links.shape[0], theta2.shape[0]
    r1, r2, r3, r4 = (np.ascontiguousarray(links[:, k]) for k in range(4))
    scale = links.max(axis=1)
    c2s, s2s = np.cos(theta2), np.sin(theta2)
    t3o = np.empty((n, m))
    t4o = np.empty((n, m))
    nito = np.zeros((n, m), dtype=np.uint32)
    x3, x4 = closed_form_vectorized(r1, r2, r3, r4, theta2[0])
    v3 = v4 = a3 = a4 = None
    for j in range(n):
        c2, s2 = c2s[j], s2s[j]
        if j > 0:
            h = theta2[j] - theta2[j - 1]
            if predictor == "quadratic":
                hh = 0.5 * h * h
                x3 = x3 + v3 * h + a3 * hh
                x4 = x4 + v4 * h + a4 * hh
            else:
                x3 = x3 + v3 * h
                x4 = x4 + v4 * h
        a = r2 * c2 - r1
        b = r2 * s2
        nit = nito[j]
        for it in range(max_iter + 1):
            s3, c3, s4, c4 = np.sin(x3), np.cos(x3), np.sin(x4), np.cos(x4)
            r3s3, r3c3, r4s4, r4c4 = r3 * s3, r3 * c3, r4 * s4, r4 * c4
            f1 = a + r3c3 - r4c4
            f2 = b + r3s3 - r4s4
            active = np.maximum(np.abs(f1), np.abs(f2)) >= tol * scale
            if it == max_iter or not active.any():
                break
            det = r3s3 * r4c4 - r4s4 * r3c3
            nit += active
            x3 = x3 + np.where(active, (f1 * r4c4 + f2 * r4s4) / det, 0.0)
            x4 = x4 + np.where(active, (f2 * r3s3 + f1 * r3c3) / det, 0.0)
        t3o[j] = x3
        t4o[j] = x4
        # dx/dtheta2 from the Jacobian at the solution: J v = (r2 s2, -r2 c2)
        det = r3s3 * r4c4 - r4s4 * r3c3
        v3 = (r2 * (c2 * r4s4 - s2 * r4c4)) / det
        v4 = (r2 * (c2 * r3s3 - s2 * r3c3)) / det
        if predictor == "quadratic":
            w3s, w4s = v3 * v3, v4 * v4
            b0 = r2 * c2 + r3c3 * w3s - r4c4 * w4s
            b1 = r2 * s2 + r3s3 * w3s - r4s4 * w4s
            a3 = -(b0 * r4c4 + b1 * r4s4) / det
            a4 = -(b1 * r3s3 + b0 * r3c3) / det
    return _wrap(t3o).T, _wrap(t4o).T, nito.T


# --- pylinkage (numba) ------------------------------------------------------------------


class PylinkageFourBar:
    """pylinkage's crank + RRR dyad set up as the four-bar r1..r4, started on the open
    mode, stepped 1 degree per step by its numba ``step_fast`` (361 points from 0 to 360
    degrees). ``angles()`` converts its joint positions to (theta3, theta4)."""

    def __init__(self, r1, r2, r3, r4, n=361, step=TAU / 360):
        from pylinkage.actuators import Crank
        from pylinkage.components import Ground
        from pylinkage.dyads import RRRDyad
        from pylinkage.simulation import Linkage

        self.r = (r1, r2, r3, r4)
        self.n = n
        self.step = step
        o2 = Ground(0.0, 0.0, name="O2")
        o4 = Ground(r1, 0.0, name="O4")
        crank = Crank(anchor=o2, radius=r2, angular_velocity=step, name="A")
        rocker = RRRDyad(crank.output, o4, distance1=r3, distance2=r4, name="B")
        self.linkage = Linkage([o2, o4, crank, rocker], name="four-bar")
        t3, t4 = closed_form_vectorized(r1, r2, r3, r4, 0.0)
        self.b0 = (r2 + r3 * math.cos(t3), r3 * math.sin(t3))
        self.linkage.compile()
        self.run()  # numba compiles (or loads its cache) on the first call
        from pylinkage.bridge.solver_conversion import update_solver_positions
        from pylinkage.solver.simulation import simulate

        self._reset()
        sd = self.linkage._solver_data
        update_solver_positions(sd, self.linkage)
        self._simulate = simulate
        self._args = (
            sd.constraints,
            sd.joint_types,
            sd.parent_indices,
            sd.constraint_offsets,
            sd.solve_order,
        )
        self._pos0 = sd.positions.copy()

    def _reset(self) -> None:
        r1, r2 = self.r[0], self.r[1]
        a = (r2 * math.cos(-self.step), r2 * math.sin(-self.step))
        self.linkage.set_coords([(0.0, 0.0), (r1, 0.0), a, self.b0])

    def kernel(self) -> np.ndarray:
        """pylinkage's numba simulation loop alone (``solver.simulation.simulate``), from
        the same start, without ``step_fast``'s Python bookkeeping."""
        return self._simulate(self._pos0.copy(), *self._args, self.n, 1.0)

    def run(self) -> np.ndarray:
        """One sweep: reset to one step before theta2 = 0 (each step rotates first),
        then ``step_fast``. Returns the (n, 4, 2) trajectory of O2, O4, A, B."""
        self._reset()
        return self.linkage.step_fast(iterations=self.n)

    def angles(self, traj: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        a, b = traj[:, 2], traj[:, 3]
        t3 = np.arctan2(b[:, 1] - a[:, 1], b[:, 0] - a[:, 0])
        t4 = np.arctan2(b[:, 1], b[:, 0] - self.r[0])
        return t3, t4


# --- linkages ---------------------------------------------------------------------------


def random_links(m: int, seed: int = 1) -> np.ndarray:
    """M random crank-rockers (see planarkin.fourbar.tradeoff.random_crank_rockers)."""
    from planarkin.fourbar.tradeoff import random_crank_rockers

    return random_crank_rockers(m, seed=seed)
