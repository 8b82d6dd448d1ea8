"""Forces through the Rust kernel: the scene's structure and loads described once as plain
indices and tables (a ``ForceModel``, cached on the structure per loads), then one call per
sweep that solves every row. The NumPy solve (``_solve``) is the reference it is tested
against. A kernel of the forces subject."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from .. import _kernel
from ._results import Forces
from ._structure import Structure
from ._units import inertia_factor

__all__ = ["Native", "native"]

#: A spring or damper as the kernel takes it: points, their links, rate, free length, preload.
_Element = tuple[int, int, int, int, float, float, float]


def _table(e: Mapping[str, Any], key: str) -> tuple[list[float], list[float]]:
    xs = e.get("input")
    values = np.asarray(e[key], dtype=np.float64).ravel().tolist()
    return ([] if xs is None else [float(x) for x in xs]), values


class Native:
    """A scene's ``ForceModel`` under one set of loads, with what turns its output into a
    :class:`Forces`: the columns each reaction reads."""

    def __init__(
        self,
        st: Structure,
        data: Mapping[str, Any],
        loads: Mapping[str, Any] | None,
        units: dict[str, str | None],
    ) -> None:
        self.st = st
        self.loads = loads
        links: Mapping[str, tuple[str, ...]] = data["links"]
        lidx = {k: i for i, k in enumerate(st.link_names)}
        pidx = {p: i for i, p in enumerate(st.point_names)}
        moving = st.link_names[: st.nm]

        def carrier(p: str) -> int:
            return next((lidx[k] for k in moving if p in links[k]), st.nm)

        L = loads or {}
        point_forces = []
        line_forces = []
        for e in L.get("forces", []):
            if "point" in e:
                point_forces.append((carrier(e["point"]), pidx[e["point"]], _table(e, "force")))
                continue
            kind = "slot" if "slot" in e else "prismatic"
            j, pt, holder = (st.slot_of if kind == "slot" else st.prismatic_of)[e[kind]]
            line_forces.append((j, pt, holder, _table(e, "force")))
        torques = [(lidx[e["link"]], _table(e, "torque")) for e in L.get("torques", [])]

        def element(e: Mapping[str, Any], spring: bool) -> _Element:
            a, b = e["between"]
            if spring:
                rate, free, pre = e["k"], e["free_length"], e["preload"]
            else:
                rate, free, pre = e["c"], 0.0, 0.0
            return (pidx[a], pidx[b], carrier(a), carrier(b), float(rate), float(free), float(pre))

        springs = [element(e, True) for e in L.get("springs", [])]
        dampers = [element(e, False) for e in L.get("dampers", [])]
        g = L.get("gravity")
        gravity = None if g is None else (float(g[0]), float(g[1]))
        cu = inertia_factor(units)
        drawn = {p: np.asarray(data["points"][p], dtype=np.float64) for p in st.point_names}
        masses = []
        for name, m in L.get("masses", {}).items():
            k = lidx[name]
            if k == st.nm:
                continue
            c, pts = m["center"], links[name]
            if isinstance(c, str):
                a, b = c, (pts[1] if pts[0] == c else pts[0])
                arm = (0.0, 0.0)
            else:
                a, b = pts[0], pts[1]
                arm = (float(c[0] - drawn[a][0]), float(c[1] - drawn[a][1]))
            e0 = drawn[b] - drawn[a]
            e0 = e0 / math.sqrt(float(e0 @ e0))
            masses.append(
                (k, pidx[a], pidx[b], arm, (float(e0[0]), float(e0[1])),
                 cu * float(m["mass"]), cu * float(m["inertia"]))
            )  # fmt: skip
        output: tuple[bool, int, int] | None = None
        out = data.get("output")
        if out is not None:
            if "link" in out:
                output = (True, lidx[out["link"]], 0)
            else:
                kind = "slot" if "slot" in out else "prismatic"
                j, pt, _ = (st.slot_of if kind == "slot" else st.prismatic_of)[out[kind]]
                output = (False, j, pt)
        self.model = _kernel.ForceModel(
            len(st.point_names),
            st.nm,
            st.size,
            st.ref.tolist(),
            [
                (int(k), int(c), float(s), int(p), int(d), max(int(j), 0))
                for k, c, s, p, d, j in zip(
                    st.f_link, st.f_col, st.f_sign, st.f_pt, st.f_kind, st.f_line, strict=True
                )
            ],
            [
                (int(k), int(c), float(s))
                for k, c, s in zip(st.c_link, st.c_col, st.c_sign, strict=True)
            ],
            [tuple(int(v) for v in line) for line in st.lines],  # type: ignore[misc]
            [(r.tolist(), c.tolist(), p.tolist()) for r, c, p in st.blocks],
            point_forces,
            line_forces,
            torques,
            springs,
            dampers,
            gravity,
            masses,
            2 * math.pi if st.input_kind == "angle" else None,
            output,
        )
        pins: list[tuple[tuple[str, str], int]] = []
        normal: list[tuple[str, int]] = []
        moment: list[tuple[str, int]] = []
        seen: set[tuple[str, str]] = set()
        for c, (kind, name, link) in enumerate(st.columns):
            if kind == "pin" and (name, link) not in seen:
                seen.add((name, link))
                pins.append(((name, link), c))
            elif kind == "normal":
                normal.append((name, c))
            elif kind == "moment":
                moment.append((name, c))
        self.pins, self.normal, self.moment = pins, normal, moment
        self._maps: dict[tuple[tuple[str, ...], tuple[str, ...]], tuple[list[int], list[int]]] = {}

    def _maps_of(self, sweep: Any) -> tuple[list[int], list[int]]:
        key = (tuple(sweep.point_names), tuple(sweep.link_names))
        m = self._maps.get(key)
        if m is None:
            col = {p: i for i, p in enumerate(key[0])}
            lcol = {k: i for i, k in enumerate(key[1])}
            m = (
                [col[p] for p in self.st.point_names],
                [lcol[k] for k in self.st.link_names[: self.st.nm]],
            )
            self._maps[key] = m
        return m

    def run(
        self,
        sweep: Any,
        units: dict[str, str | None],
        omega: np.ndarray | None,
        alpha: np.ndarray | None,
    ) -> Forces:
        """Statics (``omega`` None) or inverse dynamics along ``sweep`` (every point, with
        velocities at a nonzero rate; accelerations for dynamics)."""
        pmap, lmap = self._maps_of(sweep)
        dynamic = omega is not None
        theta = sweep.theta
        x, status, q_vw, ground, kin, pot, p_in, ma, c_vw, c_e = self.model.run(
            theta,
            sweep.status,
            sweep.det,
            sweep.coords,
            sweep.velocity_array,
            sweep.acceleration_array if dynamic else None,
            sweep.angular_velocity_array,
            sweep.angular_acceleration_array if dynamic else None,
            pmap,
            lmap,
            float(sweep.rate),
            omega,
            alpha,
        )
        checks = {"virtual_work": c_vw}
        if c_e is not None:
            checks["energy"] = c_e
        return Forces(
            kind="dynamics" if dynamic else "statics",
            theta=theta,
            input_kind="angle" if self.st.input_kind == "angle" else "displacement",
            status=status,
            input=x[:, -1],
            input_virtual_work=q_vw,
            reactions={k: x[:, c : c + 2] for k, c in self.pins},
            normal={k: x[:, c] for k, c in self.normal},
            moment={k: x[:, c] for k, c in self.moment},
            mechanical_advantage=ma,
            shaking_force=ground[:, :2],
            shaking_moment=ground[:, 2] * self.st.size,
            kinetic_energy=kin,
            potential_energy=pot,
            input_power=p_in,
            check=max(checks.values()),
            checks=checks,
            units=units,
            omega=omega,
            alpha=alpha,
        )


def native(
    st: Structure,
    data: Mapping[str, Any],
    loads: Mapping[str, Any] | None,
    units: dict[str, str | None],
) -> Native:
    """The kernel's model of ``st`` under ``loads``: made once per loads object (the
    scene's own loads are one object for its lifetime) and kept on the structure."""
    cached = st.cache.get("native")
    if cached is None or cached.loads is not loads:
        cached = Native(st, data, loads, units)
        st.cache["native"] = cached
    return cached
