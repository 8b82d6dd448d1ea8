"""The other ways a user would solve a dyadic scene, for the scene benchmarks: a vectorized
NumPy chain of circle intersections (every input angle at once, as a user would hand-chain
it), and pylinkage (numba) built from the same scene. Both peel the scene the same way:
a link with two known points carries its others; a point reached by two links from two
known points is a circle intersection, on its drawn side."""

from __future__ import annotations

import math

import numpy as np


def _chain_order(d: dict) -> list[tuple]:
    """The solving order: ("crank", p) | ("rigid", p, a, b) | ("dyad", p, a, b)."""
    pts = {k: np.asarray(v, dtype=float) for k, v in d["points"].items()}
    on = {p: [ls for ls in d["links"].values() if p in ls] for p in pts}
    known = set(d["links"][d["ground"]])
    order: list[tuple] = []
    for p in d["links"][d["input"]["link"]]:
        if p not in known:
            order.append(("crank", p))
            known.add(p)
    remaining = [p for p in pts if p not in known]
    while remaining:
        for p in remaining:
            rigid = [ls for ls in on[p] if sum(q in known for q in ls) >= 2]
            if rigid:
                a, b = [q for q in rigid[0] if q in known][:2]
                order.append(("rigid", p, a, b))
                break
            ks = list(dict.fromkeys(next(q for q in ls if q in known) for ls in on[p]
                                    if any(q in known for q in ls)))  # fmt: skip
            if len(ks) >= 2:
                order.append(("dyad", p, ks[0], ks[1]))
                break
        else:
            raise ValueError(f"not dyadic: no chain for {remaining}")
        known.add(order[-1][1])
        remaining.remove(order[-1][1])
    return order


class NumpyChain:
    """Every input angle at once: positions as (N, 2) arrays, circle intersections with
    NumPy, the side of each dyad taken from the drawing."""

    def __init__(self, d: dict) -> None:
        self.d = d
        self.pts = {k: np.asarray(v, dtype=float) for k, v in d["points"].items()}
        self.order = _chain_order(d)
        piv = d["input"]["pivot"]
        tip = next(p for p in d["links"][d["input"]["link"]] if p != piv)
        u = self.pts[tip] - self.pts[piv]
        self.theta0 = math.atan2(u[1], u[0])
        self.piv = piv

    def run(self, theta: np.ndarray) -> dict[str, np.ndarray]:
        pts = self.pts
        n = len(theta)
        out = {k: np.broadcast_to(pts[k], (n, 2)) for k in self.d["links"][self.d["ground"]]}
        c, s = np.cos(theta - self.theta0), np.sin(theta - self.theta0)
        for step in self.order:
            p = step[1]
            if step[0] == "crank":
                v = pts[p] - pts[self.piv]
                out[p] = pts[self.piv] + np.stack([c * v[0] - s * v[1], s * v[0] + c * v[1]], -1)
                continue
            a, b = step[2], step[3]
            if step[0] == "rigid":
                za, zb, zp = (complex(*pts[q]) for q in (a, b, p))
                m = (zp - za) / (zb - za)
                pa, pb = out[a], out[b]
                dx, dy = pb[:, 0] - pa[:, 0], pb[:, 1] - pa[:, 1]
                out[p] = np.stack([pa[:, 0] + m.real * dx - m.imag * dy,
                                   pa[:, 1] + m.imag * dx + m.real * dy], -1)  # fmt: skip
                continue
            r1 = float(np.hypot(*(pts[p] - pts[a])))
            r2 = float(np.hypot(*(pts[p] - pts[b])))
            u0, v0 = pts[b] - pts[a], pts[p] - pts[a]
            side = np.sign(u0[0] * v0[1] - u0[1] * v0[0])
            pa, pb = out[a], out[b]
            u = pb - pa
            dd = np.einsum("ij,ij->i", u, u)
            dist = np.sqrt(dd)
            along = (r1 * r1 - r2 * r2 + dd) / (2 * dist)
            h = np.sqrt(r1 * r1 - along * along)
            e = u / dist[:, None]
            out[p] = (
                pa + along[:, None] * e + (side * h)[:, None] * np.stack([-e[:, 1], e[:, 0]], -1)
            )
        return out


class PylinkageScene:
    """The scene built in pylinkage 1.3 (Ground, Crank, RRRDyad, FixedDyad) in the same
    order, started at the drawn pose one step before the drawn angle, stepped 1 degree per
    step by its numba ``step_fast``."""

    def __init__(self, d: dict, n: int = 361, step: float = math.tau / 360) -> None:
        from pylinkage.actuators import Crank
        from pylinkage.components import Ground
        from pylinkage.dyads import FixedDyad, RRRDyad
        from pylinkage.simulation import Linkage

        pts = {k: np.asarray(v, dtype=float) for k, v in d["points"].items()}
        self.n, self.step = n, step
        comp: dict[str, object] = {}
        for k in d["links"][d["ground"]]:
            comp[k] = Ground(*pts[k], name=k)
        order = _chain_order(d)
        piv = d["input"]["pivot"]
        names = list(comp)
        crank = None
        for st in order:
            p = st[1]
            if st[0] == "crank":
                if crank is None:
                    r = float(np.hypot(*(pts[p] - pts[piv])))
                    crank = Crank(anchor=comp[piv], radius=r, angular_velocity=step, name=p)
                    comp[p] = crank.output
                    self.crank_tip = p
                else:  # another point of the input link: fixed on crank pivot -> tip
                    comp[p] = _fixed(FixedDyad, comp, pts, p, piv, self.crank_tip)
            elif st[0] == "rigid":
                comp[p] = _fixed(FixedDyad, comp, pts, p, st[2], st[3])
            else:
                a, b = st[2], st[3]
                comp[p] = RRRDyad(comp[a], comp[b],
                                  distance1=float(np.hypot(*(pts[p] - pts[a]))),
                                  distance2=float(np.hypot(*(pts[p] - pts[b]))),
                                  x=float(pts[p][0]), y=float(pts[p][1]), name=p)  # fmt: skip
            names.append(p)
        objs = [crank if (crank is not None and k == self.crank_tip) else comp[k] for k in names]
        self.linkage = Linkage(objs, name=d.get("name") or "scene")
        self.names = names
        self.pts = pts
        self.piv = piv
        self.linkage.compile()
        self.run()  # numba compiles (or loads its cache) on the first call

    def _reset(self) -> None:
        c, s = math.cos(-self.step), math.sin(-self.step)
        coords = []
        for k in self.names:
            v = self.pts[k] - self.pts[self.piv]
            turned = self.pts[self.piv] + [c * v[0] - s * v[1], s * v[0] + c * v[1]]
            coords.append(tuple(turned) if k == self.crank_tip else tuple(self.pts[k]))
        self.linkage.set_coords(coords)

    def run(self) -> np.ndarray:
        """One sweep of ``n`` steps: (n, joints, 2), joints in ``self.names`` order."""
        self._reset()
        return self.linkage.step_fast(iterations=self.n)


def _fixed(fixed_cls, comp, pts, p, a, b):
    u, v = pts[b] - pts[a], pts[p] - pts[a]
    ang = math.atan2(u[0] * v[1] - u[1] * v[0], u[0] * v[0] + u[1] * v[1])
    return fixed_cls(comp[a], comp[b], distance=float(np.hypot(*v)), angle=ang, name=p)
