"""Scenes replayed in MuJoCo itself (the ``mujoco`` extra): ``solve`` moves the model's
input joint through the given input values and closes the loops with MuJoCo's own
equality residuals and Jacobians (Gauss-Newton from the last pose, so the drawn assembly
is followed); ``simulate`` drives the position actuator and steps the dynamics, as a user
would. Both return every site's path, to compare with the scene's sweep."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..scene import Scene
from ._extras import need
from .mujoco import build


class Replay:
    """A scene's MJCF model loaded in MuJoCo: ``model``, ``data``, the input joint's qpos
    and dof addresses, the drawn input value, and the scene's size (for tolerances)."""

    def __init__(self, sc: Scene, xml: str | None = None) -> None:
        self.mj: Any = need("mujoco", "mujoco", "a MuJoCo replay")
        built = build(sc)
        self.model: Any = self.mj.MjModel.from_xml_string(xml or built.xml)
        self.model.opt.jacobian = self.mj.mjtJacobian.mjJAC_DENSE
        self.data: Any = self.mj.MjData(self.model)
        j = self.model.joint(built.input_joint)
        self.iq, self.iv = int(j.qposadr[0]), int(j.dofadr[0])
        self.start = sc.input_angle if sc.input_kind == "angle" else 0.0
        xy = np.array(list(sc.points.values()))
        self.size = float(np.ptp(xy, axis=0).max())
        self.sites = list(built.sites)

    def _sites(self) -> np.ndarray:
        return np.array([self.data.site(s).xpos[:2] for s in self.sites])

    def _close(self, q: np.ndarray, free: np.ndarray, tol: float, max_iter: int) -> bool:
        m, d, mj = self.model, self.data, self.mj
        for _ in range(max_iter):
            d.qpos[:] = q
            mj.mj_forward(m, d)
            r = d.efc_pos[: d.nefc].copy()
            if np.abs(r).max(initial=0.0) <= tol * self.size:
                return True
            jac = np.ravel(d.efc_J)[: d.nefc * m.nv].reshape(d.nefc, m.nv)[:, free]
            q[free] += np.linalg.lstsq(jac, -r, rcond=None)[0]  # hinges, slides: qpos = dofs
        return False

    def solve(self, offsets: np.ndarray, tol: float = 1e-13, max_iter: int = 30) -> np.ndarray:
        """Sites' (N, S, 2) positions with the input joint at each offset from the drawn
        value in turn, continued from the drawn pose (a step that does not close is cut in
        halves, down to 1/64); NaN from the first offset that cannot be reached."""
        m = self.model
        free = np.array([i for i in range(m.nv) if i != self.iv])
        q = m.qpos0.copy()
        out = np.full((len(offsets), len(self.sites), 2), np.nan)
        for k, t in enumerate(np.asarray(offsets, dtype=float)):
            last = q.copy()
            for parts in (1, 2, 4, 8, 16, 32, 64):
                q = last.copy()
                ok = all(
                    self._set(q, last[self.iq] + (t - last[self.iq]) * i / parts)
                    and self._close(q, free, tol, max_iter)
                    for i in range(1, parts + 1)
                )
                if ok:
                    break
            if not ok:
                break
            out[k] = self._sites()
        return out

    def _set(self, q: np.ndarray, value: float) -> bool:
        q[self.iq] = value
        return True

    def replay(self, sw: Any, tol: float = 1e-13) -> dict[str, np.ndarray]:
        """Site name -> (N, 2) at a sweep's input values (``sw.theta``), reached the way the
        sweep reaches them: from the drawn pose forwards and backwards, over the values
        the sweep solved; NaN elsewhere."""
        t = np.asarray(sw.theta, dtype=float)
        ok = np.asarray(sw.success, dtype=bool)
        off = t - self.start
        if sw.input == "angle":  # from the drawn angle through a turn: back is -2 pi away
            fwd = np.arange(len(t))
            back = fwd[::-1]
            back_off = off - 2 * np.pi
        else:  # increasing s across the reachable interval, the drawn pose at s = 0
            fwd = np.flatnonzero(off >= 0)
            back = np.flatnonzero(off < 0)[::-1]
            back_off = off
        out = np.full((len(t), len(self.sites), 2), np.nan)
        for idx, values in ((fwd, off), (back, back_off)):
            run = idx[: np.argmin(ok[idx]) if not ok[idx].all() else len(idx)]
            todo = run[np.isnan(out[run, 0, 0])]
            if len(todo):
                out[todo] = self.solve(values[todo], tol)
        return {s: out[:, i] for i, s in enumerate(self.sites)}

    def simulate(self, offsets: np.ndarray, steps: int = 100) -> tuple[np.ndarray, np.ndarray]:
        """The dynamics, as a user would run them: the position actuator's target moved to
        each offset in turn, ``steps`` time steps at each. Returns the input joint's
        actual offsets (N,) and the sites' (N, S, 2) positions there (MuJoCo's soft
        constraints and the servo's lag: compare with the scene at the actual inputs)."""
        m, d, mj = self.model, self.data, self.mj
        mj.mj_resetData(m, d)
        got = np.empty(len(offsets))
        out = np.empty((len(offsets), len(self.sites), 2))
        for k, t in enumerate(np.asarray(offsets, dtype=float)):
            d.ctrl[0] = t
            for _ in range(steps):
                mj.mj_step(m, d)
            mj.mj_forward(m, d)
            got[k] = d.qpos[self.iq]
            out[k] = self._sites()
        return got, out
