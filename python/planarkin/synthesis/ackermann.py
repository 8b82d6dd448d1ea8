"""The seed's example 2: Ackermann steering by a double butterfly of type II (ground the
ternary carrying both kingpins). Lengths in wheelbases; kingpins at (-0.3, 0), (0.3, 0)."""

from __future__ import annotations

import math

import numpy as np

from .problem import DesignSpace, FunctionTarget, Problem
from .topology import STEERING_LEVER, Template

#: track / wheelbase
TRACK = 0.6
#: inner and outer wheel angles at full lock (degrees)
INNER_DEG = 61.0
OUTER_DEG = math.degrees(math.atan(1.0 / (1.0 / math.tan(math.radians(INNER_DEG)) + TRACK)))
#: the compact box: every joint within |x|, |y| <= BOX (wheelbases)
BOX = 0.35
#: the smallest |conditioning| allowed over the range (well away from a dead point)
DET_MARGIN = 0.1
KINGPINS = {"KL": (-TRACK / 2, 0.0), "KR": (TRACK / 2, 0.0)}


def right_steer(delta_l: object, track: float = TRACK) -> np.ndarray:
    """Ackermann's right wheel angle for left wheel angles ``delta_l`` (radians, counter-
    clockwise positive): cot(outer) - cot(inner) = track / wheelbase."""
    d = np.asarray(delta_l, dtype=np.float64)
    out = np.zeros_like(d)
    pos, neg = d > 0, d < 0
    out[pos] = np.arctan(1.0 / (1.0 / np.tan(d[pos]) + track))
    out[neg] = -np.arctan(1.0 / (1.0 / np.tan(-d[neg]) - track))
    return out


def target(n: int = 31, dense: int = 1001) -> FunctionTarget:
    """The 31 design points over the steering range (-40.903 to 61 deg of the left
    knuckle) and the dense grid of 1001 angles (the branch constraint, the envelope, the
    minimax phase and the verification)."""
    if n < 2:
        raise ValueError(f"n must be >= 2, got {n}")
    if dense < 2:
        raise ValueError(f"dense must be >= 2, got {dense}")
    lo, hi = -math.radians(OUTER_DEG), math.radians(INNER_DEG)
    pi = np.linspace(lo, hi, n)
    di = np.linspace(lo, hi, dense)
    return FunctionTarget(pi, right_steer(pi), di, right_steer(di), right_steer)


def space(
    template: Template = STEERING_LEVER, box: float = BOX, min_link: float = 0.03
) -> DesignSpace:
    """Every joint but the kingpins free within the box."""
    free = tuple(p for p in template.point_names if p not in KINGPINS)
    pts = {p: KINGPINS.get(p, (0.0, 0.0)) for p in template.point_names}
    return DesignSpace(template, pts, free, -box, box, min_link)


def problem(
    objective: str = "true",
    det_margin: float = DET_MARGIN,
    envelope: bool = True,
    **kw: object,
) -> Problem:
    """The steering problem: every joint within the box as drawn and (``envelope``) over
    the whole steering range; the seed's objectives keep the closed forms assemblable."""
    return Problem(
        space(),
        target(**kw),  # type: ignore[arg-type]
        det_margin=det_margin,
        objective=objective,
        closed_form=objective != "true",
        envelope=((-BOX, -BOX), (BOX, BOX)) if envelope else None,
    )


def mirror_sampler(sp: DesignSpace):  # type: ignore[no-untyped-def]
    """Random mirror-symmetric lever designs (the steering function is mirror symmetric):
    O and H on the axis, P/Q, U/V, R/S mirror pairs; a little asymmetric noise."""
    b = float(sp.upper[0])
    pairs = {"Q": "P", "V": "U", "S": "R"}

    def draw(rng: np.random.Generator) -> np.ndarray:
        pts: dict[str, tuple[float, float]] = {}
        for p in ("P", "U", "R"):
            pts[p] = (rng.uniform(-b, b), rng.uniform(-b, b))
        for q, p in pairs.items():
            pts[q] = (-pts[p][0], pts[p][1])
        for p in ("O", "H"):
            pts[p] = (0.0, rng.uniform(-b, b))
        x = np.array([pts[p][i] for p in sp.free for i in (0, 1)])
        return np.clip(x + rng.normal(0, 0.002, x.size), sp.lower, sp.upper)

    return draw
