"""Statics and inverse dynamics along a sweep, vectorised over its rows: the loads (and
d'Alembert's inertia forces) gathered per link, one batched dense Newton-Euler solve for
every reaction and the input effort, the same effort by virtual work through the sweep's
velocity map, the energies and the checks. A kernel of the forces subject."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from .._status import Status
from ._results import Forces
from ._structure import Structure
from ._units import inertia_factor

__all__ = ["solve"]

_TAU = 2 * np.pi
#: A point whose scale-free conditioning (the sweep's ``det``) is below this is taken to be
#: at a dead point: an effort there is amplified by more than 1e5 over the loads' scale,
#: and its value says only how near the sampled point lies to the dead point (a linear
#: input's default stroke ends at 1e-6, where the kinematics still converge).
DEAD_POINT = 1e-5


def _cross(r: np.ndarray, f: np.ndarray) -> np.ndarray:
    return r[..., 0] * f[..., 1] - r[..., 1] * f[..., 0]


def _perp(w: np.ndarray, r: np.ndarray) -> np.ndarray:
    """w x r for a planar angular rate w (n,) and vectors r (n, 2)."""
    return np.stack((-w * r[:, 1], w * r[:, 0]), axis=-1)


def _profile(entry: Mapping[str, Any], key: str, theta: np.ndarray, angle: bool) -> np.ndarray:
    """A load's value at every input value: constant, or its table over the input
    (linear in between; over a turn, periodically, for an angle input; held at the ends
    for a displacement)."""
    v = np.asarray(entry[key], dtype=np.float64)
    xs = entry.get("input")
    n = len(theta)
    if xs is None:
        return np.broadcast_to(v, (n, *v.shape)).copy()
    xs = np.asarray(xs, dtype=np.float64)
    period = _TAU if angle else None
    if v.ndim == 1:
        return np.interp(theta, xs, v, period=period)
    return np.stack([np.interp(theta, xs, v[:, i], period=period) for i in range(2)], axis=-1)


class _Tally:
    """Loads on links (force and moment about each link's reference point), their
    generalised force through the unit-rate velocity map, and their power."""

    def __init__(self, st: Structure, P: np.ndarray, V1: np.ndarray, V: np.ndarray) -> None:
        n = P.shape[0]
        self.st, self.P, self.V1, self.V = st, P, V1, V
        self.F = np.zeros((n, st.nm + 1, 2), dtype=P.dtype)
        self.M = np.zeros((n, st.nm + 1), dtype=P.dtype)
        z = np.zeros(n, dtype=P.dtype)  # complex along a complex step (see effort)
        self.gen = z.copy()  # sum of generalised forces (virtual power at unit rate)
        self.gabs = z.copy()  # sum of their magnitudes (the check's scale)
        self.power = z.copy()  # power of the applied loads (actual rate)
        self.pabs = z.copy()

    def force(self, link: int, pos: np.ndarray, f: np.ndarray, v1: np.ndarray, v: np.ndarray,
              work: bool = True) -> None:  # fmt: skip
        self.F[:, link] += f
        self.M[:, link] += _cross(pos - self.P[:, self.st.ref[link]], f)
        g = np.einsum("ij,ij->i", f, v1)
        self.gen += g
        self.gabs += np.abs(g)
        if work:
            p = np.einsum("ij,ij->i", f, v)
            self.power += p
            self.pabs += np.abs(p)

    def couple(self, link: int, t: np.ndarray, w1: np.ndarray, w: np.ndarray,
               work: bool = True) -> None:  # fmt: skip
        self.M[:, link] += t
        g = t * w1
        self.gen += g
        self.gabs += np.abs(g)
        if work:
            p = t * w
            self.power += p
            self.pabs += np.abs(p)


def solve(
    st: Structure,
    data: Mapping[str, Any],
    sweep: Any,
    loads: Mapping[str, Any] | None,
    units: dict[str, str | None],
    omega: np.ndarray | None,
    alpha: np.ndarray | None,
) -> Forces:
    """Forces along ``sweep`` (every point reported, velocities at a nonzero ``rate``;
    accelerations too for dynamics). ``omega`` (N,) the input's rate and ``alpha`` its
    rate of change for dynamics; None for statics."""
    out = _run(st, data, sweep, loads, units, omega, alpha)
    assert isinstance(out, Forces)
    return out


def effort(
    st: Structure,
    data: Mapping[str, Any],
    sweep: Any,
    loads: Mapping[str, Any] | None,
    units: dict[str, str | None],
    coords: np.ndarray,
    drawn: np.ndarray,
) -> np.ndarray:
    """The statics input effort (N,) at the poses ``coords`` (N, points, 2, scene order)
    of a drawing ``drawn`` (points, 2): both may be complex, every step being analytic in
    them (a complex step differentiates it exactly). NaN where ``sweep`` is not solved."""
    out = _run(st, data, sweep, loads, units, None, None, coords=coords, drawn=drawn)
    assert isinstance(out, np.ndarray)
    return out


def _run(
    st: Structure,
    data: Mapping[str, Any],
    sweep: Any,
    loads: Mapping[str, Any] | None,
    units: dict[str, str | None],
    omega: np.ndarray | None,
    alpha: np.ndarray | None,
    *,
    coords: np.ndarray | None = None,
    drawn: np.ndarray | None = None,
) -> Forces | np.ndarray:
    """:func:`solve`, or with ``coords`` given :func:`effort`."""
    dynamic = omega is not None
    theta = np.asarray(sweep.theta)
    n = len(theta)
    col = {p: i for i, p in enumerate(sweep.point_names)}
    idx = np.array([col[p] for p in st.point_names], dtype=np.intp)
    rate = float(sweep.rate)
    P = sweep.coords[:, idx] if coords is None else coords
    V1 = sweep.velocity_array[:, idx] / rate
    lcol = {k: i for i, k in enumerate(sweep.link_names)}
    lk = np.array([lcol[name] for name in st.link_names[: st.nm]], dtype=np.intp)
    W1 = np.zeros((n, st.nm + 1))
    W1[:, : st.nm] = sweep.angular_velocity_array[:, lk] / rate
    w = np.zeros(n) if omega is None else np.broadcast_to(omega, (n,)).astype(np.float64)
    al = np.zeros(n) if alpha is None else np.broadcast_to(alpha, (n,)).astype(np.float64)
    if dynamic:
        A1 = sweep.acceleration_array[:, idx] / rate**2
        Acc = w[:, None, None] ** 2 * A1 + al[:, None, None] * V1
        Al1 = np.zeros((n, st.nm + 1))
        Al1[:, : st.nm] = sweep.angular_acceleration_array[:, lk] / rate**2
        Wa = w[:, None] ** 2 * Al1 + al[:, None] * W1
    else:
        Acc = np.zeros_like(P)
        Wa = np.zeros((n, st.nm + 1))
    V = w[:, None, None] * V1
    Wl = w[:, None] * W1
    angle = st.input_kind == "angle"
    cu = inertia_factor(units)
    links: Mapping[str, tuple[str, ...]] = data["links"]
    lidx = {k: i for i, k in enumerate(st.link_names)}
    pidx = {p: i for i, p in enumerate(st.point_names)}
    moving = st.link_names[: st.nm]

    def carrier(p: str) -> int:
        return next((lidx[k] for k in moving if p in links[k]), st.nm)

    t = _Tally(st, P, V1, V)
    u, nrm = st.directions(P)

    def along(j: int, pt: int) -> tuple[np.ndarray, np.ndarray]:
        """Rate of the displacement along line j of point pt relative to its guide: at
        unit input rate and at the actual rate."""
        g, a, _ = st.lines[j]
        r = P[:, pt] - P[:, a]
        rel1 = V1[:, pt] - V1[:, a] - _perp(W1[:, g], r)
        s1 = np.einsum("ij,ij->i", u[:, j], rel1)
        return s1, w * s1

    z = np.zeros(n, dtype=P.dtype)
    kin, pot, dpot, dpabs, dkin, dkabs = (z.copy() for _ in range(6))  # dpot: d(pot)/dt
    L = loads or {}
    for e in L.get("forces", []):
        if "point" in e:
            p = pidx[e["point"]]
            f = _profile(e, "force", theta, angle)
            t.force(carrier(e["point"]), P[:, p], f, V1[:, p], V[:, p])
            continue
        kind = "slot" if "slot" in e else "prismatic"
        j, pt, holder = (st.slot_of if kind == "slot" else st.prismatic_of)[e[kind]]
        mag = _profile(e, "force", theta, angle)
        fu = mag[:, None] * u[:, j]
        # the actuator pushes the moving part along the line and the guide back
        s1, s = along(j, pt)
        t.F[:, holder] += fu
        t.M[:, holder] += _cross(P[:, pt] - P[:, st.ref[holder]], fu)
        g = st.lines[j][0]
        t.F[:, g] -= fu
        t.M[:, g] -= _cross(P[:, pt] - P[:, st.ref[g]], fu)
        t.gen += mag * s1
        t.gabs += np.abs(mag * s1)
        t.power += mag * s
        t.pabs += np.abs(mag * s)
    for e in L.get("torques", []):
        k = lidx[e["link"]]
        tq = _profile(e, "torque", theta, angle)
        t.couple(k, tq, W1[:, k], Wl[:, k])
    for e in L.get("springs", []):
        a, b = (pidx[x] for x in e["between"])
        d = P[:, b] - P[:, a]
        length = np.sqrt(d[:, 0] ** 2 + d[:, 1] ** 2)
        ev = d / length[:, None]
        stretch = length - e["free_length"]
        tension = e["preload"] + e["k"] * stretch
        f = tension[:, None] * ev
        ca, cb = carrier(e["between"][0]), carrier(e["between"][1])
        t.force(ca, P[:, a], f, V1[:, a], V[:, a], work=False)
        t.force(cb, P[:, b], -f, V1[:, b], V[:, b], work=False)
        pot += e["preload"] * stretch + 0.5 * e["k"] * stretch**2
        rate_d = np.einsum("ij,ij->i", ev, V[:, b] - V[:, a])
        dpot += tension * rate_d
        dpabs += np.abs(tension * rate_d)
    for e in L.get("dampers", []):
        a, b = (pidx[x] for x in e["between"])
        d = P[:, b] - P[:, a]
        ev = d / np.sqrt(d[:, 0] ** 2 + d[:, 1] ** 2)[:, None]
        tension = e["c"] * np.einsum("ij,ij->i", ev, V[:, b] - V[:, a])
        f = tension[:, None] * ev
        t.force(carrier(e["between"][0]), P[:, a], f, V1[:, a], V[:, a])
        t.force(carrier(e["between"][1]), P[:, b], -f, V1[:, b], V[:, b])
    gravity = L.get("gravity")
    masses = [(lidx[k], m) for k, m in L.get("masses", {}).items() if lidx[k] != st.nm]
    if masses:
        # every massed link at once: its centre is point a plus the arm c0 (drawn) turned
        # with the link (a point centre: a is that point and c0 is zero)
        ks = np.array([k for k, _ in masses], dtype=np.intp)
        ia: list[int] = []
        ib: list[int] = []
        ic: list[int] = []  # the drawn point whose coordinates the centre is given from
        c_at: list[tuple[float, float]] = []
        for k, m in masses:
            c, pts = m["center"], links[st.link_names[k]]
            if isinstance(c, str):
                ia.append(pidx[c])
                ib.append(pidx[pts[1] if pts[0] == c else pts[0]])
                ic.append(-1)
                c_at.append((0.0, 0.0))
            else:
                ia.append(pidx[pts[0]])
                ib.append(pidx[pts[1]])
                ic.append(pidx[pts[0]])
                c_at.append((float(c[0]), float(c[1])))
        ia_, ib_, ic_ = (np.array(v, dtype=np.intp) for v in (ia, ib, ic))
        D = drawn if drawn is not None else np.array([data["points"][p] for p in st.point_names])
        # the centre's arm from point a as drawn (zero for a point centre), turned with the
        # link: the turn's cosine and sine from the directions a -> b now and as drawn
        arm0 = np.where((ic_ >= 0)[:, None], np.array(c_at) - D[ia_], 0.0)
        e0 = D[ib_] - D[ia_]
        e0 = e0 / np.sqrt((e0**2).sum(axis=1))[:, None]
        d = P[:, ib_] - P[:, ia_]
        d = d / np.sqrt((d**2).sum(axis=2))[..., None]
        cs = d[..., 0] * e0[:, 0] + d[..., 1] * e0[:, 1]
        sn = e0[:, 0] * d[..., 1] - e0[:, 1] * d[..., 0]
        r = np.stack((cs * arm0[:, 0] - sn * arm0[:, 1], sn * arm0[:, 0] + cs * arm0[:, 1]), -1)
        rp = np.stack((-r[..., 1], r[..., 0]), axis=-1)  # k x r for a unit rate
        G = P[:, ia_] + r
        v1G = V1[:, ia_] + W1[:, ks, None] * rp
        vG = w[:, None, None] * v1G
        mass = cu * np.array([m["mass"] for _, m in masses])
        inertia = cu * np.array([m["inertia"] for _, m in masses])
        f = np.zeros_like(G)
        if gravity is not None:
            wg = mass[:, None] * np.asarray(gravity, dtype=np.float64)
            f += wg
            pw = np.einsum("nmj,mj->nm", vG, wg)
            pot -= np.einsum("nmj,mj->n", G, wg)
            dpot -= pw.sum(axis=1)
            dpabs += np.abs(pw).sum(axis=1)
        tq = np.zeros((n, len(ks)), dtype=P.dtype)
        if dynamic:
            aG = Acc[:, ia_] + Wa[:, ks, None] * rp - (Wl[:, ks] ** 2)[..., None] * r
            # d'Alembert: the inertia force and couple as loads (no power: they are the
            # kinetic energy's rate of change, tallied apart)
            f -= mass[:, None] * aG
            tq = -inertia * Wa[:, ks]
            kin += 0.5 * (mass * np.einsum("nmj,nmj->nm", vG, vG) + inertia * Wl[:, ks] ** 2).sum(1)
            dk_t = mass * np.einsum("nmj,nmj->nm", aG, vG)
            dk_r = inertia * Wa[:, ks] * Wl[:, ks]
            dkin += (dk_t + dk_r).sum(axis=1)
            dkabs += (np.abs(dk_t) + np.abs(dk_r)).sum(axis=1)
        # links are distinct: plain fancy-index adds
        t.F[:, ks] += f
        t.M[:, ks] += _cross(G - P[:, st.ref[ks]], f) + tq
        g = np.einsum("nmj,nmj->n", f, v1G) + (tq * W1[:, ks]).sum(axis=1)
        t.gen += g
        t.gabs += (np.abs(np.einsum("nmj,nmj->nm", f, v1G)) + np.abs(tq * W1[:, ks])).sum(1)

    size = st.size
    status = np.asarray(sweep.status).astype(np.int8).copy()
    det = np.asarray(sweep.det)
    dead = (status == Status.CONVERGED) & ~(np.abs(det) >= DEAD_POINT)
    status[dead] = Status.SINGULAR
    ok = status == Status.CONVERGED
    ncol = len(st.columns)
    x = np.full((n, ncol), np.nan, dtype=P.dtype)
    Afull = st.matrix(P if ok.all() else P[ok])
    A = Afull[:, : 3 * st.nm]
    rhs = -np.concatenate((t.F[ok, : st.nm], t.M[ok, : st.nm, None] / size), axis=-1)
    if ok.any():
        x[ok] = st.solve(A, rhs.reshape(len(A), -1))
    if coords is not None:
        return x[:, -1]
    if ok.any():
        # a block singular to rounding although the sweep's conditioning is not small
        bad = ok & ~np.isfinite(x).all(axis=1)
        if bad.any():
            status[bad] = Status.SINGULAR
            x[bad] = np.nan
            keep = ~bad[ok]
            ok = ok & ~bad
            Afull = Afull[keep]
    ground = np.full((n, 3), np.nan)
    ground[ok] = np.einsum("irk,ik->ir", Afull[:, 3 * st.nm :], x[ok])
    q_ne = x[:, -1]
    q_vw = np.where(ok, -t.gen, np.nan)

    reactions: dict[tuple[str, str], np.ndarray] = {}
    normal: dict[str, np.ndarray] = {}
    moment: dict[str, np.ndarray] = {}
    for c, (kind, name, link) in enumerate(st.columns):
        if kind == "pin" and (name, link) not in reactions:
            reactions[(name, link)] = x[:, c : c + 2]
        elif kind == "normal":
            normal[name] = x[:, c]
        elif kind == "moment":
            moment[name] = x[:, c]

    checks: dict[str, float] = {}
    scale_vw = float(np.max((t.gabs + np.abs(q_ne))[ok], initial=0.0))
    res = np.abs(q_vw - q_ne)[ok]
    checks["virtual_work"] = float(res.max() / scale_vw) if scale_vw > 0 and res.size else 0.0
    p_in = q_ne * w
    if dynamic:
        resid = (p_in + t.power - dpot - dkin)[ok]
        scale_e = float(np.max((np.abs(p_in) + t.pabs + dpabs + dkabs)[ok], initial=0.0))
        checks["energy"] = float(np.abs(resid).max() / scale_e) if scale_e > 0 else 0.0
    check = max(checks.values()) if checks else 0.0

    ma = None
    out = data.get("output")
    if out is not None:
        if "link" in out:
            rate1 = W1[:, lidx[out["link"]]]
        else:
            kind = "slot" if "slot" in out else "prismatic"
            j, pt, _ = (st.slot_of if kind == "slot" else st.prismatic_of)[out[kind]]
            rate1 = along(j, pt)[0]
        with np.errstate(divide="ignore", invalid="ignore"):
            ma = np.where(ok, 1.0 / rate1, np.nan)

    nan = np.where(ok, 0.0, np.nan)
    return Forces(
        kind="dynamics" if dynamic else "statics",
        theta=theta,
        input_kind="angle" if angle else "displacement",
        status=status,
        input=q_ne,
        input_virtual_work=q_vw,
        reactions=reactions,
        normal=normal,
        moment=moment,
        mechanical_advantage=ma,
        shaking_force=ground[:, :2],
        shaking_moment=ground[:, 2] * size,
        kinetic_energy=kin + nan,
        potential_energy=pot + nan,
        input_power=p_in,
        check=check,
        checks=checks,
        units=units,
        omega=w if dynamic else None,
        alpha=al if dynamic else None,
    )
