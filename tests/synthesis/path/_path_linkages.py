"""Closed forms of the linkages the path refinement and verification tests build their
targets from (independent of the scene solver): a four-bar's and an offset slider-crank's
coupler point at absolute crank angles, on a chosen assembly, and their scene files."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from _support import dyad_point


def fourbar_curve(
    o2: Any, o4: Any, r2: float, r3: float, r4: float, pu: float, pv: float,
    theta: Any, side: float = 1.0,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:  # fmt: skip
    """(A, B, P) at crank angles ``theta``: B where the circles about A (r3) and O4 (r4)
    meet, on ``side`` of A -> O4 (+1: left); P at (pu, pv) in the coupler's frame (A,
    along A -> B)."""
    o2, o4 = np.asarray(o2, float), np.asarray(o4, float)
    t = np.asarray(theta, float)
    a = o2 + r2 * np.stack([np.cos(t), np.sin(t)], -1)
    b = dyad_point(a, r3, np.broadcast_to(o4, a.shape), r4, side)
    u = (b - a) / r3
    w = np.stack([-u[:, 1], u[:, 0]], -1)
    return a, b, a + pu * u + pv * w


def fourbar_scene(
    o2: Any, o4: Any, r2: float, r3: float, r4: float, pu: float, pv: float,
    theta0: float, side: float = 1.0,
) -> dict[str, Any]:  # fmt: skip
    """The four-bar drawn at crank angle ``theta0`` on ``side``, tracer P."""
    a, b, p = fourbar_curve(o2, o4, r2, r3, r4, pu, pv, [theta0], side)
    return {
        "points": {
            "O2": [float(v) for v in o2],
            "O4": [float(v) for v in o4],
            "A": a[0].tolist(),
            "B": b[0].tolist(),
            "P": p[0].tolist(),
        },
        "links": {
            "ground": ["O2", "O4"],
            "crank": ["O2", "A"],
            "coupler": ["A", "B", "P"],
            "rocker": ["O4", "B"],
        },
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O2"},
    }


def transmission_sines(o2: Any, o4: Any, r2: float, r3: float, r4: float, theta: Any) -> np.ndarray:
    """|sin| of the four-bar's transmission angle (law of cosines on A, B, O4)."""
    a, _, _ = fourbar_curve(o2, o4, r2, r3, r4, 0.0, 0.0, theta)
    d2 = ((np.asarray(o4, float) - a) ** 2).sum(1)
    c = (r3**2 + r4**2 - d2) / (2 * r3 * r4)
    return np.sqrt(1 - c**2)  # type: ignore[no-any-return]


def slider_curve(
    o2: Any, gamma: float, e: float, r: float, rod: float, pu: float, pv: float, theta: Any
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(A, B, P) of an offset slider-crank: crank O2-A (r), rod A-B (``rod``), B on the line
    through O2 at angle ``gamma`` offset ``e`` to its left, ahead of A; P at (pu, pv) in
    the rod's frame."""
    o2 = np.asarray(o2, float)
    u = np.array([math.cos(gamma), math.sin(gamma)])
    n = np.array([-u[1], u[0]])
    t = np.asarray(theta, float)
    a = o2 + r * np.stack([np.cos(t), np.sin(t)], -1)
    sa, ha = (a - o2) @ u, (a - o2) @ n
    s = sa + np.sqrt(rod**2 - (e - ha) ** 2)
    b = o2 + s[:, None] * u + e * n
    w = (b - a) / rod
    wn = np.stack([-w[:, 1], w[:, 0]], -1)
    return a, b, a + pu * w + pv * wn


def slider_scene(
    o2: Any, gamma: float, e: float, r: float, rod: float, pu: float, pv: float, theta0: float
) -> dict[str, Any]:
    """The slider-crank drawn at ``theta0``: B in a slot on the ground line O2 -> X."""
    a, b, p = slider_curve(o2, gamma, e, r, rod, pu, pv, [theta0])
    x = np.asarray(o2, float) + 3.0 * np.array([math.cos(gamma), math.sin(gamma)])
    return {
        "points": {
            "O2": [float(v) for v in o2],
            "X": x.tolist(),
            "A": a[0].tolist(),
            "B": b[0].tolist(),
            "P": p[0].tolist(),
        },
        "links": {"ground": ["O2", "X"], "crank": ["O2", "A"], "rod": ["A", "B", "P"]},
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O2"},
        "slots": {"piston": {"point": "B", "guide": "ground", "line": ["O2", "X"]}},
    }


#: a Watt II six-bar drawn by hand: the four-bar O2-A-B-O4 drives, through its ternary
#: rocker O4-B-C, the four-bar O4-C-D-O6; the tracer P rides the second coupler C-D
WATT2 = {
    "points": {
        "O2": [0.0, 0.0],
        "A": [1.0, 0.3],
        "B": [3.5, 2.6],
        "O4": [4.0, 0.0],
        "C": [5.6, 2.4],
        "D": [7.4, 3.6],
        "O6": [8.0, 0.5],
        "P": [6.6, 4.6],
    },
    "links": {
        "ground": ["O2", "O4", "O6"],
        "crank": ["O2", "A"],
        "coupler1": ["A", "B"],
        "ternary": ["O4", "B", "C"],
        "coupler2": ["C", "D", "P"],
        "rocker2": ["O6", "D"],
    },
    "ground": "ground",
    "input": {"link": "crank", "pivot": "O2"},
}


def perturbed(data: dict[str, Any], scale: float, seed: int) -> dict[str, Any]:
    """The scene's drawn points each moved by a normal step of ``scale`` per coordinate."""
    rng = np.random.default_rng(seed)
    pts = {k: (np.array(v) + rng.normal(0.0, scale, 2)).tolist() for k, v in data["points"].items()}
    return {**data, "points": pts}
