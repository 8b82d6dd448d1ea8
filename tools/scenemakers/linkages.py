"""The built-in four-, six- and eight-link scenes whose geometry is given (published
lengths or chosen by hand), each assembled by circle intersections at its drawn angle."""

from __future__ import annotations

import math

import numpy as np
from planarkin.reference import scene as ref

from .geometry import DEG, circles, dist, pick, rot


def _coupler_fourbar(o2, o4, a, b, p) -> dict:
    """The keys of a four-bar O2-A-B-O4 with a tracer P on its coupler (crank input,
    rocker output, P requested)."""
    return {
        "units": "arbitrary length units",
        "points": {"O2": o2, "O4": o4, "A": a, "B": b, "P": p},
        "links": {
            "ground": ["O2", "O4"],
            "crank": ["O2", "A"],
            "coupler": ["A", "B", "P"],
            "rocker": ["O4", "B"],
        },
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O2"},
        "output": {"link": "rocker", "pivot": "O4"},
        "outputs": ["P"],
    }


def fourbar():
    o2, o4 = np.array([0.0, 0.0]), np.array([6.0, 0.0])
    a = np.array([2.0, 0.0])
    b = pick(a, 5.0, o4, 5.0, key=lambda p: -p[1])  # open: B left of A -> O4 (above)
    u = (b - a) / dist(a, b)
    p = a + 3.0 * rot(u, 30 * DEG)
    return {
        "name": "four-bar (6, 2, 5, 5) with a coupler point",
        "description": (
            "The seed four-bar r = (6, 2, 5, 5) (ground, crank, coupler, rocker) of the "
            "two seed reports: a Grashof crank-rocker, drawn at theta2 = 0 in the open "
            "mode (B = (4, sqrt 21)). Coupler point P at distance 3 from A, 30 deg "
            "counter-clockwise from the line A -> B. The crank turns fully."
        ),
        **_coupler_fourbar(o2, o4, a, b, p),
    }


def watt2():
    o2, o4, o6 = np.array([0.0, 0.0]), np.array([6.0, 0.0]), np.array([13.0, 0.0])
    a = np.array([2.0, 0.0])
    b = pick(a, 5.0, o4, 5.0, key=lambda p: -p[1])
    c = o4 + 2.5 * rot((b - o4) / 5.0, -120 * DEG)
    d = pick(c, 6.0, o6, 5.5, key=lambda p: -p[1])
    return {
        "name": "Watt-II six-bar",
        "description": (
            "A Watt-II six-bar: two four-bars in series sharing the ground-pivoted ternary "
            "'ternary' (O4, B, C). First loop: the seed four-bar (ground O2-O4 6, crank 2, "
            "coupler 5, ternary side O4-B 5; Grashof crank-rocker). Second loop: ground "
            "O4-O6 7, ternary side O4-C 2.5 (at -120 deg from O4-B), coupler C-D 6, "
            "rocker O6-D 5.5: Grashof with the driving side O4-C shortest, so it "
            "assembles at every angle the first loop's rocker reaches. Dimensions are "
            "ours (chosen by hand), drawn at crank angle 0, both loops in the mode with B "
            "and D above. The crank turns fully."
        ),
        "units": "arbitrary length units",
        "points": {"O2": o2, "O4": o4, "O6": o6, "A": a, "B": b, "C": c, "D": d},
        "links": {
            "ground": ["O2", "O4", "O6"],
            "crank": ["O2", "A"],
            "coupler1": ["A", "B"],
            "ternary": ["O4", "B", "C"],
            "coupler2": ["C", "D"],
            "rocker": ["O6", "D"],
        },
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O2"},
        "output": {"link": "rocker", "pivot": "O6"},
        "outputs": ["D"],
    }


#: Theo Jansen's "holy numbers" (lengths of the Strandbeest leg).
JANSEN_HOLY = dict(
    a=38, b=41.5, c=39.3, d=40.1, e=55.8, f=39.4, g=36.7, h=65.7, i=49, j=50, k=61.9, l=7.8, m=15
)


def jansen():
    n = JANSEN_HOLY
    a, b, c, d, e, f, g, h, i, j, k, m = (n[x] for x in "abcdefghijkm")
    o = np.array([0.0, 0.0])
    z = np.array([-a, -n["l"]])
    mm = np.array([m, 0.0])  # crank pin at crank angle 0
    pb = pick(mm, j, z, b, key=lambda p: -p[1])  # upper joint
    pc = pick(mm, k, z, c, key=lambda p: p[1])  # lower joint
    pd = pick(pb, e, z, d, key=lambda p: p[0])  # outer corner of the upper triangle
    pe = pick(pd, f, pc, g, key=lambda p: p[0])  # outer corner of the lower triangle
    pf = pick(pe, h, pc, i, key=lambda p: p[1])  # foot
    return {
        "name": "Jansen's Strandbeest leg",
        "description": (
            "Theo Jansen's Strandbeest leg with his published 'holy numbers' a=38, b=41.5, "
            "c=39.3, d=40.1, e=55.8, f=39.4, g=36.7, h=65.7, i=49, j=50, k=61.9, l=7.8, "
            "m=15: crank axle O at the origin, fixed pivot Z at (-a, -l), crank O-M (m), "
            "M-B (j) and Z-B (b) to the upper joint, M-C (k) and Z-C (c) to the lower "
            "joint, upper triangle Z-B-D (b = Z-B, d = Z-D, e = B-D), bar D-E (f), lower "
            "triangle C-E-foot (g = C-E, h = E-foot, i = C-foot). Drawn at crank angle 0 in the "
            "standard walking assembly (B above, C below, D and E outboard, foot "
            "down), computed by circle intersections. The crank turns fully."
        ),
        "units": "Jansen's units (lengths as published)",
        "points": {"O": o, "Z": z, "M": mm, "B": pb, "C": pc, "D": pd, "E": pe, "foot": pf},
        "links": {
            "ground": ["O", "Z"],
            "crank": ["O", "M"],
            "j": ["M", "B"],
            "k": ["M", "C"],
            "upper": ["Z", "B", "D"],
            "c": ["Z", "C"],
            "f": ["D", "E"],
            "lower": ["C", "E", "foot"],
        },
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O"},
        "outputs": ["foot"],
    }


#: The Klann leg of shift-dynamics/shift-models (klann_linkage/klann_linkage.json and
#: leg.obj), in that model's frames: fixed pivots, body frame points, initial joint angles.
KLANN = {
    "P1": (-0.233, 0.616),  # first rocker's fixed pivot
    "P2": (-0.59, -0.176),  # second rocker's fixed pivot
    "crank": 0.268,
    "rocker1": 0.5176,
    "rocker2": 0.3206244,
    "rod": ((-0.59, 0.0), (-1.099, 0.116)),  # rocker-2 joint, leg joint (crank pin at 0)
    "leg": ((-0.8966114, 0.0), (-1.629715, -0.423306)),  # rod joint, foot (rocker-1 at 0)
    "q": (3.532, 2.4919, 2.4979),  # crank, crank->rod, ground->rocker-1 initial angles
}


def klann():
    kl = KLANN
    p1, p2 = np.array(kl["P1"]), np.array(kl["P2"])
    rod_r2, rod_leg = (np.array(v) for v in kl["rod"])
    leg_rod, leg_foot = (np.array(v) for v in kl["leg"])
    # the model's own pose (its joint angles are rounded): only to choose the sides
    q_crank, q_rod, q_r1 = kl["q"]
    m0 = kl["crank"] * np.array([math.cos(q_crank), math.sin(q_crank)])
    r2_model = m0 + rot(rod_r2, q_crank + q_rod)
    lo_model = p1 + kl["rocker1"] * np.array([math.cos(q_r1), math.sin(q_r1)])
    # exact assembly at the model's crank angle, sides from the model's pose
    o = np.array([0.0, 0.0])
    m = m0
    r2 = pick(m, float(np.hypot(*rod_r2)), p2, kl["rocker2"], key=lambda p: dist(p, r2_model))
    phi = math.atan2(*(r2 - m)[::-1]) - math.atan2(*rod_r2[::-1])
    lj = m + rot(rod_leg, phi)
    lo = pick(p1, kl["rocker1"], lj, float(np.hypot(*leg_rod)), key=lambda p: dist(p, lo_model))
    psi = math.atan2(*(lj - lo)[::-1]) - math.atan2(*leg_rod[::-1])
    foot = lo + rot(leg_foot, psi)
    pts = {"O": o, "P1": p1, "P2": p2, "M": m, "R": r2, "L": lj, "K": lo, "foot": foot}
    return {
        "name": "Klann's linkage (one leg)",
        "description": (
            "One leg of Klann's walking linkage (Joe Klann, US 6,260,862), a six-bar: "
            "crank O-M, ternary connecting rod M-R-L, rocker P2-R, rocker P1-K, ternary leg "
            "K-L-foot. Proportions as reproduced in the open model shift-dynamics/"
            "shift-models (klann_linkage/klann_linkage.json: crank 0.268, fixed pivots "
            "(-0.233, 0.616) and (-0.59, -0.176) from the crank axle, rockers 0.5176 and "
            "0.3206244, rod frame points (-0.59, 0) and (-1.099, 0.116), leg frame point "
            "(-0.8966114, 0)); the foot is the centre of the leg's rounded tip in that "
            "model's leg.obj, (-1.629715, -0.423306) in the leg frame. We did not check "
            "these numbers against the patent's figures. Drawn at that model's initial "
            "crank angle 3.532 rad, the assembly its joint angles give, recomputed "
            "exactly by circle intersections. The crank turns fully."
        ),
        "units": "metres (as in the shift-models file)",
        "points": pts,
        "links": {
            "ground": ["O", "P1", "P2"],
            "crank": ["O", "M"],
            "rod": ["M", "R", "L"],
            "rocker2": ["P2", "R"],
            "rocker1": ["P1", "K"],
            "leg": ["K", "L", "foot"],
        },
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O"},
        "outputs": ["foot"],
    }


PEAUCELLIER = {"crank": 1.0, "arm": 3.0, "side": 1.5, "drawn": -75.0}


def peaucellier():
    r, big, s = PEAUCELLIER["crank"], PEAUCELLIER["arm"], PEAUCELLIER["side"]
    phi = PEAUCELLIER["drawn"] * DEG
    o, q = np.array([0.0, 0.0]), np.array([r, 0.0])
    c = q + r * np.array([math.cos(phi), math.sin(phi)])
    a, b = circles(o, big, c, s)  # A left of O -> C, B right
    p = a + b - c  # the rhombus A-C-B-P
    limit = 2 * math.acos((big - s) / (2 * r)) / DEG  # |OC| = 2 r cos(phi/2) >= big - s
    return {
        "name": "Peaucellier-Lipkin inversor, crank driven",
        "description": (
            f"The Peaucellier-Lipkin straight-line linkage: arms O-A and O-B {big}, "
            f"rhombus A-C-B-P of side {s}, so |OC| |OP| = {big}^2 - {s}^2 = "
            f"{big * big - s * s}. C is driven by the crank Q-C of length {r} pivoted at "
            f"Q = ({r}, 0), so C's circle passes through O and P moves on the exact "
            f"straight line x = {(big * big - s * s) / (2 * r)}. The crank does not turn "
            f"fully: |OC| = 2 r cos(phi/2) >= {big} - {s} limits its angle phi (from +x, "
            f"at Q) to |phi| <= 2 acos({(big - s) / (2 * r)}) = {limit:.4f} deg, dead points "
            f"where A and B meet (a {2 * limit:.4f} deg range). Dimensions are ours; drawn "
            f"at phi = {PEAUCELLIER['drawn']} deg, A on the left of O -> C."
        ),
        "units": "arbitrary length units",
        "points": {"O": o, "Q": q, "C": c, "A": a, "B": b, "P": p},
        "links": {
            "ground": ["O", "Q"],
            "crank": ["Q", "C"],
            "arm1": ["O", "A"],
            "arm2": ["O", "B"],
            "AC": ["A", "C"],
            "CB": ["C", "B"],
            "AP": ["A", "P"],
            "BP": ["B", "P"],
        },
        "ground": "ground",
        "input": {"link": "crank", "pivot": "Q"},
        "outputs": ["P"],
    }


def chebyshev_lambda():
    o2, o4 = np.array([0.0, 0.0]), np.array([2.0, 0.0])
    a = np.array([1.0, 0.0])  # crank angle 0
    b = pick(a, 2.5, o4, 2.5, key=lambda p: -p[1])
    p = a + 2.0 * (b - a)  # on the line A -> B at 5 from A
    sc = {
        "name": "Chebyshev's lambda linkage",
        "description": (
            "Chebyshev's lambda mechanism: ground O2-O4 2, crank O2-A 1, coupler A-B 2.5 "
            "extended along its line to the tracer P at 5 from A (B the midpoint of A-P), "
            "rocker O4-B 2.5 (the classic proportions 2 : 1 : 2.5 : 2.5 : 5). A Grashof "
            "crank-rocker: the crank turns fully; P runs along an approximate straight "
            "line while the crank is on the far side from O4. Drawn at crank angle 0, B "
            "above the ground."
        ),
        **_coupler_fourbar(o2, o4, a, b, p),
    }
    # the straight stretch, measured by the reference: crank angles 90 to 270 deg
    sw = ref.scene_sweep(sc, np.arange(90, 271) * DEG)
    y, x = sw.points["P"][:, 1], sw.points["P"][:, 0]
    sc["description"] += (
        f" Reference sweep: for crank angles 90 to 270 deg P stays between y = {y.min():.6f} "
        f"and {y.max():.6f} while x runs over {np.ptp(x):.6f}."
    )
    return sc
