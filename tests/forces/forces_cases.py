"""Scenes the force tests share: a four-bar worked by hand, a pendulum, and loads of
every kind for any scene."""

from __future__ import annotations

import numpy as np
import planarkin as pk

__all__ = ["FOURBAR", "pendulum", "random_loads"]

FOURBAR = {
    "name": "hand-worked four-bar",
    "points": {"O2": [0, 0], "O4": [4, 0], "A": [0, 2], "B": [4, 3], "C": [2, 2.5]},
    "links": {
        "ground": ["O2", "O4"],
        "crank": ["O2", "A"],
        "coupler": ["A", "B", "C"],
        "rocker": ["O4", "B"],
    },
    "ground": "ground",
    "input": {"link": "crank", "pivot": "O2"},
    "output": {"link": "rocker", "pivot": "O4"},
}


def pendulum(**loads) -> pk.Scene:
    return pk.Scene.from_dict(
        {
            "points": {"O": [0.0, 0.0], "X": [1.0, 0.0], "P": [0.8, 0.6], "G": [0.4, 0.3]},
            "links": {"ground": ["O", "X"], "arm": ["O", "P", "G"]},
            "ground": "ground",
            "input": {"link": "arm", "pivot": "O"},
            "loads": loads,
        }
    )


def random_loads(sc: pk.Scene, rng: np.random.Generator) -> dict:
    """Loads of every kind on a scene: a force at each moving point, a torque on each
    moving link, a spring and a damper between two points of different links, a mass on
    every moving link (centre at drawn coordinates), gravity, and a force along every slot
    and prismatic pair."""
    pts = sc.points
    size = float(np.ptp(np.array(list(pts.values())), axis=0).max())
    moving = [k for k in sc.links if k != sc.ground]
    ground_pts = set(sc.links[sc.ground])
    free = [p for p in pts if p not in ground_pts]
    a, b = sc.links[moving[0]][-1], sc.links[moving[-1]][-1]
    loads = {
        "forces": [{"point": p, "force": rng.normal(size=2).tolist()} for p in free]
        + [{"slot": s, "force": float(rng.normal())} for s in sc.slots]
        + [{"prismatic": s, "force": float(rng.normal())} for s in sc.prismatic],
        "torques": [{"link": k, "torque": float(rng.normal()) * size} for k in moving],
        "springs": [{"between": [a, b], "k": 3.0 / size, "free_length": 0.5 * size,
                     "preload": 0.3}] if a != b else [],
        "dampers": [{"between": [a, b], "c": 0.2 / size}] if a != b else [],
        "gravity": [0.3, -1.0],
        "masses": {
            k: {"mass": float(rng.uniform(0.5, 2)),
                "center": (np.mean([pts[p] for p in sc.links[k]], axis=0)
                           + 0.1 * size * rng.normal(size=2)).tolist(),
                "inertia": float(rng.uniform(0.01, 0.1)) * size**2}
            for k in moving
        },
    }  # fmt: skip
    return loads
