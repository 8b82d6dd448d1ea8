"""An atlas entry as a scene: the topology's points at an input angle (the Rust kernel's
closed form), carried onto the target by the placement's similarity (scale, turn,
shift), with the links, input and tracer each topology has."""

from __future__ import annotations

import copy
import math
from typing import Any

import numpy as np

from ..._kernel import atlas_pose
from ...scene import Scene

#: the tracer point of every topology's scene
TRACER = "P"
#: topology -> (links, extra entries of the scene)
_SHAPES: dict[str, tuple[dict[str, list[str]], dict[str, Any]]] = {
    "four-bar": (
        {
            "ground": ["O2", "O4"],
            "crank": ["O2", "A"],
            "coupler": ["A", "B", "P"],
            "rocker": ["O4", "B"],
        },
        {"output": {"link": "rocker", "pivot": "O4"}},
    ),
    "slider-crank": (
        {"ground": ["O2", "X"], "crank": ["O2", "A"], "coupler": ["A", "B", "P"]},
        {
            "output": {"slot": "slider"},
            "slots": {"slider": {"point": "B", "guide": "ground", "line": ["O2", "X"]}},
        },
    ),
    "watt2": (
        {
            "ground": ["O2", "O4", "O6"],
            "crank": ["O2", "A"],
            "coupler1": ["A", "B"],
            "ternary": ["O4", "B", "C"],
            "coupler2": ["C", "D", "P"],
            "rocker": ["O6", "D"],
        },
        {"output": {"link": "rocker", "pivot": "O6"}},
    ),
    "stephenson3": (
        {
            "ground": ["j3", "j7"],
            "crank": ["j7", "j6"],
            "T1": ["j1", "j2", "j3"],
            "T2": ["j4", "j5", "j6", "P"],
            "B1": ["j1", "j4"],
            "B2": ["j2", "j5"],
        },
        {"input": {"link": "crank", "pivot": "j7"}, "output": {"link": "T1", "pivot": "j3"}},
    ),
}


class NotAssembled(ValueError):
    """An atlas entry asked for a pose at an input angle where it does not assemble."""


def scene_dict(
    topology: str,
    params: np.ndarray,
    signs: np.ndarray,
    a: complex,
    b: complex,
    theta: float,
    *,
    name: str = "path design",
    description: str = "",
    units: str = "target units",
) -> dict[str, Any]:
    """The scene of an entry drawn at input angle ``theta`` (its own frame) and carried
    by z -> a z + b onto the target's frame. Raises ValueError where it does not assemble
    at ``theta``."""
    got = atlas_pose(
        topology,
        np.asarray(params, dtype=np.float64),
        np.asarray(signs, dtype=np.float64),
        float(theta),
    )
    if got is None:
        raise NotAssembled(f"theta: the {topology} does not assemble at {theta!r} rad")
    names, pts, _ = got
    z = a * (pts[:, 0] + 1j * pts[:, 1]) + b
    points = {n: [float(w.real), float(w.imag)] for n, w in zip(names, z, strict=True)}
    if topology == "slider-crank":
        x = a + b  # the slide line's direction from O2: +x of the entry's frame
        points["X"] = [float(x.real), float(x.imag)]
    # (a copy: a caller may edit the dict it gets without editing the template)
    links, extra = copy.deepcopy(_SHAPES[topology])
    return {
        "name": name,
        "description": description,
        "units": units,
        "points": points,
        "links": links,
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O2"},
        **extra,
        "outputs": [TRACER],
    }


def input_offset(a: complex) -> float:
    """What the placement adds to an entry's input angle: the turn of its similarity."""
    return math.atan2(a.imag, a.real)


def scene_of(topology: str, params, signs, a: complex, b: complex, theta: float, **kw) -> Scene:
    """:func:`scene_dict` as a Scene."""
    return Scene(scene_dict(topology, params, signs, a, b, theta, **kw))
