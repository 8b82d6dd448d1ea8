"""Scenes the force tests share: a four-bar worked by hand and a pendulum."""

from __future__ import annotations

import planarkin as pk

__all__ = ["FOURBAR", "pendulum"]

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
