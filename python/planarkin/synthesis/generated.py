"""The seed's generated output in closed form: loops 1 and 2 as half-angle solutions
(two dyads) from the prescribed input and output, loop 3 with the output link split into
the prescribed output and a generated one, theta* = 2 atan2(c2 +- sqrt(c1^2 + c2^2 - c3^2),
c1 + c3). One sign per loop: 8 branch combinations. Vectorised over design points."""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._angles import wrap_array
from .topology import Template

#: The 8 sign combinations (loop 1, loop 2, loop 3), +1 or -1 on the half-angle root.
SIGN_COMBINATIONS = tuple(itertools.product((1, -1), repeat=3))


def half_angle(
    c1: np.ndarray, c2: np.ndarray, c3: np.ndarray, sign: int
) -> tuple[np.ndarray, np.ndarray]:
    """x with c1 cos x + c2 sin x = c3 (the root of ``sign``), and the dimensionless
    radicand (c1^2 + c2^2 - c3^2) / (c1^2 + c2^2), negative where no real x exists. Where
    the radicand is negative, x is that of a zero radicand (finite, never NaN)."""
    n2 = c1 * c1 + c2 * c2
    rad = (n2 - c3 * c3) / np.where(n2 > 0, n2, 1.0)
    root = np.sqrt(np.maximum(n2 - c3 * c3, 0.0))
    x = 2.0 * np.arctan2(c2 + sign * root, c1 + c3)
    return x, rad


def _rot(v: np.ndarray, a: np.ndarray) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.stack([c * v[0] - s * v[1], s * v[0] + c * v[1]], axis=-1)


def _unit(a: np.ndarray) -> np.ndarray:
    return np.stack([np.cos(a), np.sin(a)], axis=-1)


@dataclass(frozen=True)
class Generated:
    """Generated outputs at the design points for one sign combination."""

    #: (n,) generated output rotation theta* (radians, from the drawn pose).
    theta: np.ndarray
    #: (n, 3) dimensionless radicands of the three loops (>= 0: assemblable).
    radicand: np.ndarray
    #: (n,) k = d theta* / d theta_out at fixed input (k = 1 is a dead point of the real
    #: linkage); the true error is about the generated one divided by 1 - k.
    k: np.ndarray
    signs: tuple[int, int, int]


class SeedPlan:
    """The closed form of a template drawn at ``points``: the input and output are
    rotated from the drawn pose by the prescribed angles."""

    def __init__(self, template: Template, points: Mapping[str, Sequence[float]]) -> None:
        self.t = template
        self.p0 = {n: np.asarray(points[n], dtype=np.float64) for n in template.point_names}
        self._drawn = self._drawn_signs()

    def _link_of(self, a: str, b: str, exclude: set[str] | None = None) -> str:
        for name, pts in self.t.links.items():
            if a in pts and b in pts and (exclude is None or name not in exclude):
                return name
        raise ValueError(f"template: no link carries both {a} and {b}")

    def _complete(self, known: dict[str, np.ndarray]) -> None:
        # rigid bodies: a link with two known points places all of its points
        changed = True
        while changed:
            changed = False
            for pts in self.t.links.values():
                k = [p for p in pts if p in known]
                if len(k) >= 2 and len(k) < len(pts):
                    a, b = k[0], k[1]
                    d0 = self.p0[b] - self.p0[a]
                    d1 = known[b] - known[a]
                    ang = np.arctan2(d1[..., 1], d1[..., 0]) - math.atan2(d0[1], d0[0])
                    for p in pts:
                        if p not in known:
                            known[p] = known[a] + _rot(self.p0[p] - self.p0[a], ang)
                    changed = True

    def _solve(
        self,
        phi_in: np.ndarray,
        phi_out: np.ndarray,
        signs: Sequence[int],
        follow: tuple[Mapping[str, np.ndarray], np.ndarray] | None = None,
    ) -> tuple[dict[str, np.ndarray], np.ndarray, np.ndarray, tuple[Any, Any, Any]]:
        # a sign 0 takes the root nearest the drawn pose at the first sample; ``follow``
        # (points and output rotation of a real linkage at each sample) takes, at each
        # sample and in each loop, the root nearest it (the signs are then arrays)
        t, p0 = self.t, self.p0
        n = phi_in.shape[0]
        known: dict[str, np.ndarray] = {}
        for p in t.links[t.ground]:
            known[p] = np.broadcast_to(p0[p], (n, 2)).copy()
        for (link, pivot), phi in ((t.input, phi_in), (t.output, phi_out)):
            for p in t.links[link]:
                if p != pivot:
                    known[p] = p0[pivot] + _rot(p0[p] - p0[pivot], phi)
        self._complete(known)
        rads = []
        used = []
        for (x, a, b), sign in zip(t.dyads, signs[:2], strict=True):
            ra = float(np.linalg.norm(p0[x] - p0[a]))
            rb = float(np.linalg.norm(p0[x] - p0[b]))
            d = known[a] - known[b]
            c1, c2 = 2 * ra * d[:, 0], 2 * ra * d[:, 1]
            c3 = rb * rb - ra * ra - (d * d).sum(axis=1)
            if follow is not None:
                near = [
                    np.linalg.norm(
                        known[a] + ra * _unit(half_angle(c1, c2, c3, sg)[0]) - follow[0][x], axis=1
                    )
                    for sg in (1, -1)
                ]
                sign = np.where(near[0] <= near[1], 1, -1)  # type: ignore[assignment]
            elif np.ndim(sign) == 0 and sign == 0:
                sign = min(
                    (1, -1),
                    key=lambda sg: float(
                        np.abs(
                            known[a][0] + ra * _unit(half_angle(c1, c2, c3, sg)[0])[0] - p0[x]
                        ).sum()
                    ),
                )
            ang, rad = half_angle(c1, c2, c3, sign)
            known[x] = known[a] + ra * _unit(ang)
            rads.append(rad)
            used.append(sign)
            self._complete(known)
        q, v, s = t.final
        pivot = t.output[1]
        h = p0[q] - p0[pivot]
        w = known[v] - known[q] + known[pivot] - known[s]
        length = float(np.linalg.norm(p0[v] - p0[s]))
        c1 = w[:, 0] * h[0] + w[:, 1] * h[1]
        c2 = w[:, 1] * h[0] - w[:, 0] * h[1]
        c3 = 0.5 * (length * length - (w * w).sum(axis=1) - h @ h)
        sign = signs[2]
        if follow is not None:
            off = [np.abs(wrap_array(half_angle(c1, c2, c3, sg)[0] - follow[1])) for sg in (1, -1)]
            sign = np.where(off[0] <= off[1], 1, -1)  # type: ignore[assignment]
        elif np.ndim(sign) == 0 and sign == 0:
            first = {sg: float(wrap_array(half_angle(c1, c2, c3, sg)[0][0])) for sg in (1, -1)}
            sign = min((1, -1), key=lambda sg: abs(first[sg]))
        th, rad = half_angle(c1, c2, c3, sign)
        rads.append(rad)
        used.append(sign)
        return known, wrap_array(th), np.stack(rads, axis=1), (used[0], used[1], used[2])

    def _drawn_signs(self) -> tuple[int, int, int]:
        # the signs whose solution is the drawn pose itself (zero input and output)
        z = np.zeros(1)
        return self._solve(z, z, (0, 0, 0))[3]

    @property
    def drawn_signs(self) -> tuple[int, int, int]:
        """The sign combination that reproduces the drawn pose."""
        return self._drawn

    def generated(
        self,
        phi_in: object,
        phi_out: object,
        signs: Sequence[int] | None = None,
        *,
        relative: bool = True,
        with_k: bool = True,
    ) -> Generated:
        """Generated output rotations at input rotations ``phi_in`` and prescribed output
        rotations ``phi_out`` (radians from the drawn pose). ``signs``: (s1, s2, s3) with
        each +1 or -1; with ``relative`` (default) relative to the drawn pose's signs
        (+1: the drawn branch of that loop), else the absolute half-angle roots. ``k`` is
        a central difference in the prescribed output (NaN without ``with_k``)."""
        pi = np.atleast_1d(np.asarray(phi_in, dtype=np.float64))
        po = np.atleast_1d(np.asarray(phi_out, dtype=np.float64))
        if pi.shape != po.shape or pi.ndim != 1:
            raise ValueError(f"phi_out must have the shape of phi_in {pi.shape}, got {po.shape}")
        if signs is None:
            signs = (1, 1, 1)
        if len(signs) != 3 or any(s not in (1, -1) for s in signs):
            raise ValueError(f"signs must be three of +1 / -1, got {signs!r}")
        sg = (
            tuple(int(s) * d for s, d in zip(signs, self._drawn, strict=True))
            if relative
            else tuple(signs)
        )
        _, th, rad, _ = self._solve(pi, po, sg)
        k = np.full(pi.shape, np.nan)
        if with_k:
            h = 1e-6
            _, th2, _, _ = self._solve(pi, po + h, sg)
            _, th1, _, _ = self._solve(pi, po - h, sg)
            k = wrap_array(th2 - th1) / (2 * h)
        return Generated(th, rad, k, (int(sg[0]), int(sg[1]), int(sg[2])))

    def follow(
        self,
        phi_in: object,
        phi_out: object,
        points: Mapping[str, object],
        theta: object,
    ) -> tuple[Generated, np.ndarray]:
        """The generated output on a real linkage's own roots: at each input rotation
        (``phi_in``, with prescribed outputs ``phi_out``), each loop takes the root nearest
        the real linkage there (``points``: name -> (n, 2) positions of the dyads' joints;
        ``theta``: (n,) its output rotation). Where the real linkage passes a loop's
        turning point (a radicand touching zero: the split mechanism's own dead point) the
        fixed signs of :meth:`generated` change root and stop describing it; this does
        not. Returns the Generated (``signs``: the drawn pose's, absolute; ``k`` from the
        same roots) and the (n, 3) absolute signs used at each input."""
        pi = np.atleast_1d(np.asarray(phi_in, dtype=np.float64))
        po = np.atleast_1d(np.asarray(phi_out, dtype=np.float64))
        th_ref = np.atleast_1d(np.asarray(theta, dtype=np.float64))
        if pi.shape != po.shape or pi.ndim != 1:
            raise ValueError(f"phi_out must have the shape of phi_in {pi.shape}, got {po.shape}")
        if th_ref.shape != pi.shape:
            raise ValueError(f"theta must have the shape of phi_in {pi.shape}, got {th_ref.shape}")
        ref: dict[str, np.ndarray] = {}
        for x, _, _ in self.t.dyads:
            if x not in points:
                raise ValueError(f"points must give the dyad joint {x!r}")
            ref[x] = np.asarray(points[x], dtype=np.float64).reshape(pi.size, 2)
        _, th, rad, used = self._solve(pi, po, (0, 0, 0), (ref, th_ref))
        signs = np.stack([np.broadcast_to(u, pi.shape) for u in used], axis=1)
        h = 1e-6
        th2 = self._solve(pi, po + h, tuple(signs.T))[1]  # type: ignore[arg-type]
        th1 = self._solve(pi, po - h, tuple(signs.T))[1]  # type: ignore[arg-type]
        k = wrap_array(th2 - th1) / (2 * h)
        return Generated(th, rad, k, self._drawn), signs.astype(np.int8)
