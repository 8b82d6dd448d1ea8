"""The built-in scenes with slots and prismatic pairs (slider-cranks, quick return, Scotch
yoke, hydraulic boom, trammel), their dimensions chosen here; ``SLIDERS`` names them."""

from __future__ import annotations

import math

import numpy as np

from .geometry import DEG, dist


def slider_crank(offset):
    r, rod, e, t0 = 40.0, 160.0, offset, 30 * DEG
    a = np.array([r * math.cos(t0), r * math.sin(t0)])
    b = np.array([a[0] + math.sqrt(rod * rod - (a[1] - e) ** 2), e])
    what = "centred" if e == 0 else f"offset (e = {e:g} mm)"
    along = "" if e == 0 else f" at {e:g} mm from it"
    return {
        "name": f"slider-crank, {what}",
        "description": (
            f"The slider-crank of engines, pumps and presses, {what}: crank O2-A r = {r:g} mm, "
            f"connecting rod A-B l = {rod:g} mm (r / l = 1/4, a usual engine ratio), the "
            f"piston pin B in a slot along the ground line O2 -> X{along}. "
            "Dimensions chosen here. Piston position x_B = r cos t + sqrt(l^2 - (r sin t - e)^2); "
            "output: its displacement along the slot from the drawn pose. Drawn at t = 30 deg."
        ),
        "units": "mm",
        "points": {"O2": [0.0, 0.0], "X": [1.0, 0.0], "A": a, "B": b},
        "links": {"ground": ["O2", "X"], "crank": ["O2", "A"], "rod": ["A", "B"]},
        "slots": {"piston": {"point": "B", "guide": "ground", "line": ["O2", "X"]}},
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O2"},
        "output": {"slot": "piston"},
    }


def inverted_slider_crank():
    d, r, t0 = 100.0, 40.0, 40 * DEG
    o4 = np.array([d, 0.0])
    a = np.array([r * math.cos(t0), r * math.sin(t0)])
    u = (a - o4) / dist(a, o4)
    c = o4 + 150.0 * u
    return {
        "name": "inverted slider-crank (oscillating cylinder)",
        "description": (
            "The inverted slider-crank of an oscillating cylinder: crank O2-A r = 40 mm, "
            "ground O2-O4 d = 100 mm, the cylinder pivoted at O4 with the crank pin A sliding "
            "along its axis O4 -> C (a block on the rocker). Dimensions chosen here. Cylinder "
            "angle atan2(r sin t, r cos t - d). Drawn at t = 40 deg."
        ),
        "units": "mm",
        "points": {"O2": [0.0, 0.0], "O4": o4, "A": a, "C": c},
        "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "cylinder": ["O4", "C"]},
        "slots": {"block": {"point": "A", "guide": "cylinder", "line": ["O4", "C"]}},
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O2"},
        "output": {"link": "cylinder", "pivot": "O4"},
    }


def whitworth():
    r, c, big_r, rod, t0 = 60.0, 30.0, 50.0, 150.0, 30 * DEG
    o4 = np.array([0.0, c])
    a = np.array([r * math.cos(t0), r * math.sin(t0)])
    u = (a - o4) / dist(a, o4)
    cc = o4 - big_r * u
    dd = np.array([cc[0] - math.sqrt(rod * rod - (cc[1] - c) ** 2), c])
    return {
        "name": "Whitworth quick return",
        "description": (
            "Whitworth's quick-return mechanism: crank O2-A r = 60 mm turning fully about O2, "
            "the slotted lever pivoted at O4, c = 30 mm above O2 (c < r: the lever turns "
            "fully too), the crank pin A sliding in the lever's slot; the lever's arm O4-C "
            "(50 mm, opposite the slot) drives the ram D through the rod C-D (150 mm), D "
            "sliding on the horizontal line through O4. Dimensions chosen here. The ram's "
            "strokes take crank angles pi + 2 asin(c/r) and pi - 2 asin(c/r): a time ratio "
            "of 2 here. Drawn at t = 30 deg."
        ),
        "units": "mm",
        "points": {"O2": [0.0, 0.0], "O4": o4, "X": [-1.0, c], "A": a, "C": cc, "D": dd},
        "links": {
            "ground": ["O2", "O4", "X"],
            "crank": ["O2", "A"],
            "lever": ["O4", "C"],
            "rod": ["C", "D"],
        },
        "slots": {
            "block": {"point": "A", "guide": "lever", "line": ["O4", "C"]},
            "ram": {"point": "D", "guide": "ground", "line": ["O4", "X"]},
        },
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O2"},
        "output": {"slot": "ram"},
    }


def scotch_yoke():
    r, t0 = 50.0, 25 * DEG
    a = np.array([r * math.cos(t0), r * math.sin(t0)])
    return {
        "name": "Scotch yoke",
        "description": (
            "The Scotch yoke: crank O2-A r = 50 mm; its pin A slides in the yoke's vertical "
            "slot Y1-Y2, and the yoke translates along the ground line O2 -> G (a prismatic "
            "pair). The yoke moves exactly r cos t (pure simple harmonic motion); output: its "
            "displacement from the drawn pose. Dimensions chosen here. Drawn at t = 25 deg."
        ),
        "units": "mm",
        "points": {
            "O2": [0.0, 0.0],
            "G": [1.0, 0.0],
            "A": a,
            "Y1": [a[0], -60.0],
            "Y2": [a[0], 60.0],
            "R": [a[0] + 120.0, 0.0],
        },
        "links": {"ground": ["O2", "G"], "crank": ["O2", "A"], "yoke": ["Y1", "Y2", "R"]},
        "slots": {"pin": {"point": "A", "guide": "yoke", "line": ["Y1", "Y2"]}},
        "prismatic": {"guide": {"link": "yoke", "guide": "ground", "line": ["O2", "G"]}},
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O2"},
        "output": {"prismatic": "guide"},
        "outputs": ["R"],
    }


def hydraulic_boom():
    o, c1, boom, e_at, t0 = np.array([0.0, 0.0]), np.array([600.0, -400.0]), 2000.0, 800.0, 30 * DEG
    u = np.array([math.cos(t0), math.sin(t0)])
    e, tip = e_at * u, boom * u
    ax = (e - c1) / dist(e, c1)
    return {
        "name": "hydraulic-cylinder boom",
        "description": (
            "A boom pivoted on the ground at O, lifted by a hydraulic cylinder: the barrel "
            "pivoted on the ground at C1 = (600, -400) mm, the rod pinned to the boom at E, "
            "800 mm from O; the boom's tip T at 2000 mm. The input is the cylinder's "
            "extension (a prismatic pair rod-in-barrel). The boom angle follows from the law "
            "of cosines in the triangle O-C1-E, |C1 E| being the drawn length plus the "
            "extension. Dimensions chosen here. Drawn with the boom at 30 deg. The cylinder "
            "(805 mm pin to pin as drawn) retracts to 605 mm and extends to 1105 mm: limits "
            "-200..300 mm on its extension; its barrel is 560 mm long and its rod 550 mm, so "
            "the piston stays in the barrel over the whole stroke."
        ),
        "units": "mm",
        "points": {
            "O": o,
            "C1": c1,
            "E": e,
            "T": tip,
            "C2": c1 + 560.0 * ax,
            "R": e - 550.0 * ax,
        },
        "links": {
            "ground": ["O", "C1"],
            "boom": ["O", "E", "T"],
            "barrel": ["C1", "C2"],
            "rod": ["R", "E"],
        },
        "prismatic": {"cylinder": {"link": "rod", "guide": "barrel", "line": ["C1", "C2"]}},
        "ground": "ground",
        "input": {"prismatic": "cylinder"},
        "output": {"link": "boom", "pivot": "O"},
        "outputs": ["T"],
        "limits": {"cylinder": [-200.0, 300.0]},
    }


def elliptic_trammel():
    big_l, p, a0 = 100.0, 40.0, 60.0
    a, b = np.array([a0, 0.0]), np.array([0.0, math.sqrt(big_l**2 - a0**2)])
    return {
        "name": "elliptic trammel",
        "description": (
            "The trammel of Archimedes: a bar A-B (100 mm) whose ends slide in two crossed "
            "slots (A along x, B along y). The input is A's displacement along its slot; the "
            "point P, 40 mm from A on the bar, draws the ellipse x^2 / 60^2 + y^2 / 40^2 = 1. "
            "Dimensions chosen here. Drawn with A at x = 60 mm."
        ),
        "units": "mm",
        "points": {
            "O": [0.0, 0.0],
            "X": [1.0, 0.0],
            "Y": [0.0, 1.0],
            "A": a,
            "B": b,
            "P": a + p / big_l * (b - a),
        },
        "links": {"ground": ["O", "X", "Y"], "bar": ["A", "B", "P"]},
        "slots": {
            "a": {"point": "A", "guide": "ground", "line": ["O", "X"]},
            "b": {"point": "B", "guide": "ground", "line": ["O", "Y"]},
        },
        "ground": "ground",
        "input": {"slot": "a"},
        "outputs": ["P"],
    }


SLIDERS = {
    "slider-crank": lambda: slider_crank(0.0),
    "slider-crank-offset": lambda: slider_crank(20.0),
    "inverted-slider-crank": inverted_slider_crank,
    "whitworth": whitworth,
    "scotch-yoke": scotch_yoke,
    "hydraulic-boom": hydraulic_boom,
    "elliptic-trammel": elliptic_trammel,
}
