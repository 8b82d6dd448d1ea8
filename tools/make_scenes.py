"""Writes the built-in scenes' JSON files (python/planarkin/scene/builtin/*.json), a
maintainer's script kept out of the wheel: ``python tools/make_scenes.py``.

Published linkages are assembled from their link lengths by circle intersections; the
six- and eight-bars whose geometry is ours come from seeded random searches near a
starting design, judged by the NumPy scene reference. Every scene is checked (consistent,
mobility 1, its range swept by the reference) and the checks are printed.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
from planarkin import Status
from planarkin.reference import scene as ref
from planarkin.scene._model import KEYS

#: Where the built-in scenes live (package data of planarkin.scene.builtin).
HERE = Path(__file__).resolve().parents[1] / "python" / "planarkin" / "scene" / "builtin"

DEG = math.pi / 180


# --- geometry ------------------------------------------------------------------------


def circles(p, rp, q, rq):
    """Both intersections of the circle (p, rp) with (q, rq): (left, right) of p -> q."""
    p, q = np.asarray(p, float), np.asarray(q, float)
    u = q - p
    d = math.hypot(u[0], u[1])
    a = (rp * rp - rq * rq + d * d) / (2 * d)
    hh = rp * rp - a * a
    if hh < 0:
        raise ValueError(f"circles do not meet: d={d}, rp={rp}, rq={rq}")
    h = math.sqrt(hh)
    m = p + a * u / d
    n = np.array([-u[1], u[0]]) / d
    return m + h * n, m - h * n


def pick(p, rp, q, rq, key):
    """The intersection that minimises key(point)."""
    return min(circles(p, rp, q, rq), key=key)


def rot(v, a):
    c, s = math.cos(a), math.sin(a)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def dist(a, b):
    return math.hypot(a[0] - b[0], a[1] - b[1])


# --- reach: how far the drawn circuit's input turns ------------------------------------


def reach(scene, direction, limit=2 * math.pi, step=1 * DEG, h_min=1e-9):
    """How far the drawn circuit's input turns from the drawn angle in ``direction``
    before a dead point (capped at ``limit``), by the reference's own continuation with
    step halving near the end (to about h_min). Returns (angle turned, [(angle turned,
    reciprocal condition number of the Jacobian)], final state)."""
    sys_ = ref._System(scene)
    t0 = sys_.theta0
    x, st, _ = sys_.newton(np.zeros(sys_.n), t0, 1e-13, 50)
    assert st == Status.CONVERGED, st
    hist = [(t0, x, sys_.sign(x, t0))]
    done, h, trace = 0.0, step, []
    while done < limit - 1e-12:
        h = min(h, limit - done)
        t = done + h
        xn, st, _, hn = ref._march(sys_, hist, t0 + direction * t, 1e-13, 30, h)
        if st != Status.CONVERGED:
            h /= 2
            if h < h_min:
                break
            continue
        _, j = sys_.residual_jacobian(xn, (math.cos(direction * t), math.sin(direction * t)))
        sv = np.linalg.svd(j, compute_uv=False)
        trace.append((t, sv[-1] / sv[0]))
        hist, done, x = hn, t, xn
        h = min(step, 2 * h)
    return done, trace, x


def motion(scene, margin=5 * DEG):
    """(lo, hi, full_turn, worst conditioning): the drawn circuit's input range about the
    drawn angle (radians, relative to it), and the smallest reciprocal condition number
    of the Jacobian met on it more than ``margin`` from its ends (dead points)."""
    hi, tr, xe = reach(scene, +1)
    if hi >= 2 * math.pi - 1e-12:
        closed = np.max(np.abs(np.array([ref.wrap(v) for v in xe]))) < 1e-8
        return 0.0, 2 * math.pi, bool(closed), min(r for _, r in tr)
    lo, tr2, _ = reach(scene, -1)
    inner = [r for t, r in tr if t < hi - margin] + [r for t, r in tr2 if t < lo - margin]
    return -lo, hi, False, min(inner, default=0.0)


def redraw(scene, dtheta):
    """The scene redrawn by the reference at the drawn angle + dtheta (continuation)."""
    th = ref._System(scene).theta0 + np.linspace(0, dtheta, max(2, int(abs(dtheta) / DEG) + 2))
    sw = ref.scene_sweep(scene, th, tol=1e-14)
    assert np.all(sw.status == 0), sw.status
    out = dict(scene)
    out["points"] = {p: [float(v) for v in sw.points[p][-1]] for p in scene["points"]}
    return out


# --- the scenes ------------------------------------------------------------------------


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
    # the straight stretch, measured by the reference: crank angles 90 to 270 deg
    sw = ref.scene_sweep(sc, np.arange(90, 271) * DEG)
    y, x = sw.points["P"][:, 1], sw.points["P"][:, 0]
    sc["description"] += (
        f" Reference sweep: for crank angles 90 to 270 deg P stays between y = {y.min():.6f} "
        f"and {y.max():.6f} while x runs over {np.ptp(x):.6f}."
    )
    return sc


# --- searched geometries ---------------------------------------------------------------


def _points_scene(base, pts, names):
    out = dict(base)
    out["points"] = {k: np.asarray(pts[k], float) for k in names}
    return out


def _separated(pts, links, min_len):
    """No two points closer than min_len, and every link's points spread (not collinear)."""
    xy = np.array(list(pts.values()))
    d = np.sqrt(((xy[:, None] - xy[None]) ** 2).sum(-1))
    if np.min(d + np.eye(len(xy)) * 1e9) < min_len:
        return False
    for ps in links.values():
        if len(ps) == 3:
            p, q, r = (np.asarray(pts[n]) for n in ps)
            area = abs((q - p)[0] * (r - p)[1] - (q - p)[1] * (r - p)[0]) / 2
            if area < 0.15 * max(dist(p, q), dist(q, r), dist(p, r)) ** 2 / 2:
                return False
    return True


def search(base_scene, base_pts, fixed, sigma, n, seed, min_len, want_full=False):
    """Seeded random search: perturb the free points of base_pts by N(0, sigma) (the
    first trial is base_pts itself); rank candidates by a full turn of the input, then by
    the input range of the drawn circuit in 10 deg bins up to 150 deg, then by the worst
    conditioning met more than 5 deg inside the range. Returns (scene, lo, hi, full,
    rcond, trial)."""
    rng = np.random.default_rng(seed)
    names = list(base_pts)
    best, best_key = None, None
    for trial in range(n):
        pts = {
            k: np.asarray(v, float) + (0 if k in fixed else rng.normal(0, sigma, 2))
            for k, v in base_pts.items()
        }
        if trial == 0:
            pts = {k: np.asarray(v, float) for k, v in base_pts.items()}
        if not _separated(pts, base_scene["links"], min_len):
            continue
        sc = _points_scene(base_scene, pts, names)
        try:
            lo, hi, full, w = motion(sc)
        except (AssertionError, ValueError):
            continue
        rng_deg = (hi - lo) / DEG
        key = (full, min(rng_deg, 150.0) // 10, w)
        if best_key is None or key > best_key:
            best, best_key = (sc, lo, hi, full, w, trial), key
    return best


STEPHENSON_BASE = {
    "j3": (0.0, 0.0),
    "j7": (5.0, 0.0),
    "j6": (5.8, 0.6),
    "j1": (1.0, 3.0),
    "j2": (2.5, 2.0),
    "j4": (3.5, 4.0),
    "j5": (4.8, 3.0),
}


def stephenson3_base():
    return {
        "name": "Stephenson-III six-bar",
        "points": {},
        "links": {
            "ground": ["j3", "j7"],
            "crank": ["j7", "j6"],
            "T1": ["j1", "j2", "j3"],
            "T2": ["j4", "j5", "j6"],
            "B1": ["j1", "j4"],
            "B2": ["j2", "j5"],
        },
        "ground": "ground",
        "input": {"link": "crank", "pivot": "j7"},
    }


def stephenson3():
    base = stephenson3_base()
    sc, lo, hi, full, w, trial = search(
        base, STEPHENSON_BASE, fixed=("j3", "j7"), sigma=0.5, n=60, seed=3, min_len=0.6
    )
    print(
        f"  stephenson3: trial {trial}, range {(hi - lo) / DEG:.3f} deg, full {full}, "
        f"min rcond {w:.3e}"
    )
    sc["description"] = (
        "A Stephenson-III six-bar (Stephenson chain: ternaries T1 {j1, j2, j3} and "
        "T2 {j4, j5, j6}, binaries B1 {j1, j4}, B2 {j2, j5}, the ground bar B3 {j3, j7} "
        "and the input crank B4 {j7, j6}). With this input there is no dyad: T1, B1, T2 "
        "and B2 form one rigid group solved together. Geometry: the best of 60 seeded "
        "random perturbations (numpy default_rng(3), sigma 0.5 on every moving point) of "
        "a hand-drawn starting design (_make.py, STEPHENSON_BASE), ranked first by a "
        "full turn of the crank (checked by the NumPy reference), then by the worst "
        f"reciprocal condition number of the Jacobian over the turn ({w:.2e}). "
        + (
            "The crank turns fully."
            if full
            else f"The input moves through {(hi - lo) / DEG:.2f} deg between two dead points."
        )
    )
    sc["units"] = "arbitrary length units"
    sc["output"] = {"link": "T1", "pivot": "j3"}  # the ground-pivoted ternary
    sc["outputs"] = ["j4", "j5"]
    return sc, lo, hi, full


DB_BASE = {
    "A": (0.0, 0.0),
    "K": (4.0, 0.0),
    "B": (0.3, 1.6),
    "I": (3.7, 1.6),
    "C": (1.2, 0.6),
    "H": (2.8, 0.6),
    "E": (0.8, 2.2),
    "F": (3.2, 2.2),
    "D": (1.2, 3.2),
    "G": (2.8, 3.2),
}

N_DB = 100  # candidates per double-butterfly search

DB_LINKS_1 = {
    "ground": ["A", "K"],
    "input": ["A", "B", "C"],
    "T3": ["B", "D", "E"],
    "bar4": ["E", "H"],
    "output": ["K", "H", "I"],
    "bar6": ["D", "G"],
    "T7": ["F", "G", "I"],
    "bar8": ["C", "F"],
}

DB_LINKS_2 = {
    "ground": ["B", "D", "E"],
    "input": ["B", "A", "C"],
    "bar1": ["A", "K"],
    "bar4": ["E", "H"],
    "T5": ["H", "I", "K"],
    "bar6": ["D", "G"],
    "T7": ["F", "G", "I"],
    "bar8": ["C", "F"],
}


def double_butterfly(kind):
    if kind == 1:
        base = {
            "name": "double butterfly, type I (ground a binary bar)",
            "points": {},
            "links": DB_LINKS_1,
            "ground": "ground",
            "input": {"link": "input", "pivot": "A"},
            "output": {"link": "output", "pivot": "K"},
        }
        fixed, seed = ("A", "K"), 11
    else:
        base = {
            "name": "double butterfly, type II (ground a ternary)",
            "points": {},
            "links": DB_LINKS_2,
            "ground": "ground",
            "input": {"link": "input", "pivot": "B"},
        }
        fixed, seed = ("B",), 22
    sc, lo, hi, full, w, trial = search(
        base, DB_BASE, fixed=fixed, sigma=0.35, n=N_DB, seed=seed, min_len=0.4
    )
    print(
        f"  double-butterfly-{kind}: trial {trial}, range {(hi - lo) / DEG:.3f} deg, "
        f"full {full}, min rcond {w:.3e}"
    )
    return base, sc, lo, hi, full, w, trial, seed


# --- checks and output -----------------------------------------------------------------


# --- slider scenes (prismatic joints) ----------------------------------------------------


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
            "extension. Dimensions chosen here. Drawn with the boom at 30 deg."
        ),
        "units": "mm",
        "points": {
            "O": o,
            "C1": c1,
            "E": e,
            "T": tip,
            "C2": c1 + 300.0 * ax,
            "R": e - 400.0 * ax,
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


def check_slider(name, scene):
    """Prints and asserts: the kernel loads it (mobility 1, regular as drawn) and sweeps its
    default range; the NumPy reference has no sliders, so the tests hold the closed forms."""
    import planarkin as pk

    points = {k: [float(v[0]), float(v[1])] for k, v in scene["points"].items()}
    sc = pk.Scene.from_dict({**scene, "points": points})
    sw = sc.sweep()
    # a linear input's default range ends at its dead points: SINGULAR there if met exactly
    ends_ok = all(st in (Status.CONVERGED, Status.SINGULAR) for st in sw.status[[0, -1]])
    ok = bool(sw.success[1:-1].all()) and ends_ok
    rng = f"{sw.theta[0]:+.4f} to {sw.theta[-1]:+.4f} {'rad' if sw.input == 'angle' else 'mm'}"
    print(
        f"{name:24s} mobility {sc.mobility}  plan {[s.kind for s in sc.plan('all')]}  {rng}  "
        f"sweep converged {ok}"
    )
    assert sc.mobility == 1 and ok, name


def check(name, scene, lo=None, hi=None):
    """Prints and asserts: consistent, mobility 1, the range swept by the reference."""
    err = ref.scene_assemble_check(scene)
    mob = ref.scene_mobility(scene)
    if lo is None:
        lo, hi, full, w = motion(scene)
    else:
        full = hi - lo >= 2 * math.pi
        w = float("nan")
    t0 = ref._System(scene).theta0
    if full:
        th = t0 + np.arange(361) * DEG
    else:  # inside the range, 0.5 deg clear of its ends
        th = t0 + np.linspace(lo + 0.5 * DEG, hi - 0.5 * DEG, 361)
    sw = ref.scene_sweep(scene, th)
    ok = bool(np.all(sw.status == Status.CONVERGED))
    print(
        f"{name:20s} assemble {err:.1e}  mobility {mob}  drawn {t0 / DEG:9.4f} deg  "
        f"range [{lo / DEG:+9.4f}, {hi / DEG:+9.4f}] deg from drawn "
        f"({'full turn' if full else f'{(hi - lo) / DEG:.4f} deg'})  sweep converged {ok} "
        f"max nit {sw.nit.max()}  min rcond {w:.2e}"
    )
    assert err < 1e-12 and mob == 1 and ok, name
    return lo, hi, full


def write(name, scene):
    order = KEYS  # the scene format's keys, in the order the files list them
    out = {k: scene[k] for k in order if k in scene}
    out["points"] = {k: [float(v[0]), float(v[1])] for k, v in scene["points"].items()}
    rows = []
    for key, value in out.items():
        if key in ("points", "links"):  # one entry a line
            inner = ",\n".join(f"    {json.dumps(k)}: {json.dumps(v)}" for k, v in value.items())
            rows.append(f"  {json.dumps(key)}: {{\n{inner}\n  }}")
        else:
            rows.append(f"  {json.dumps(key)}: {json.dumps(value)}")
    text = "{\n" + ",\n".join(rows) + "\n}\n"
    assert json.loads(text) == out
    (HERE / f"{name}.json").write_text(text)


def main(only=()):
    """Writes every built-in scene, or only those named (``python tools/make_scenes.py
    whitworth scotch-yoke``; ``sliders`` names the slider scenes)."""
    if only:
        names = set(SLIDERS) if "sliders" in only else set(only)
        for name in sorted(names):
            if name not in SLIDERS:
                raise SystemExit(f"only the slider scenes can be made alone: {', '.join(SLIDERS)}")
            sc = SLIDERS[name]()
            check_slider(name, sc)
            write(name, sc)
        return
    made = {
        "fourbar": fourbar(),
        "watt2": watt2(),
        "jansen": jansen(),
        "klann": klann(),
        "peaucellier": peaucellier(),
        "chebyshev-lambda": chebyshev_lambda(),
    }
    made["stephenson3"], *_ = stephenson3()
    for kind in (1, 2):
        base, sc, lo, hi, full, w, trial, seed = double_butterfly(kind)
        if not full:  # redraw in the middle of the range: a typical pose, far from both
            mid = 0.5 * (lo + hi)  # dead points (sweeps go forward, then back from it)
            sc = redraw(sc, mid)
            lo, hi = lo - mid, hi - mid
        ground = "a binary bar" if kind == 1 else "the ternary B-D-E"
        inp = (
            "the adjacent ternary A-B-C, pivoted at A; output the ternary K-H-I pivoted at K"
            if kind == 1
            else "its butterfly partner, the ternary B-A-C hinged to it at B and pivoted "
            "there; output the bar D-G pivoted at D"
        )
        t0 = ref._System(sc).theta0
        sc["description"] = (
            f"The eight-bar double butterfly (4 ternaries, 4 binaries, 10 joints, no "
            f"four-bar sub-loop), inversion {'I' if kind == 1 else 'II'}: ground {ground}, "
            f"input {inp}. With ground and input fixed the other six links form one rigid "
            "group with no dyad. Joint letters and link numbers (bar1, T3, ...) as in "
            "DESIGN.md's type I: ternaries A-B-C (2), B-D-E (3), H-I-K (5), F-G-I (7); "
            "binaries A-K (1), E-H (4), D-G (6), C-F (8). "
            "Geometry: the best of "
            f"{N_DB} seeded random perturbations (numpy default_rng({seed}), sigma 0.35) of a "
            "mirror-symmetric starting design (_make.py, DB_BASE), ranked by the input "
            "range of the drawn circuit as swept by the NumPy reference (10 deg bins up to 150 "
            "deg), then by the worst reciprocal condition number of the Jacobian more than 5 "
            f"deg inside the range ({w:.2e}). "
            + (
                "The input turns fully."
                if full
                else f"The input moves through {(hi - lo) / DEG:.2f} deg between two dead "
                f"points, input angle {(t0 + lo) / DEG:.2f} to {(t0 + hi) / DEG:.2f} deg "
                "(unwrapped); drawn in the middle of that range. A sweep from the drawn "
                "angle reaches the upper dead point going forward (angles past it are "
                "LIMIT) and the lower one going back from the drawn pose."
            )
        )
        sc["units"] = "arbitrary length units"
        if kind == 1:
            sc["outputs"] = ["H", "I"]  # the output ternary's moving joints
        else:  # a ground-pivoted bar as the output, as in the seed's type II
            sc["output"] = {"link": "bar6", "pivot": "D"}
            sc["outputs"] = ["G"]
        made[f"double-butterfly-{kind}"] = sc
    print()
    for name, sc in sorted(made.items()):
        check(name, sc)
        write(name, sc)
    for name, make in SLIDERS.items():
        sc = make()
        check_slider(name, sc)
        write(name, sc)
        made[name] = sc
    print(f"wrote {len(made)} scenes to {HERE}")


if __name__ == "__main__":
    import sys

    main(tuple(sys.argv[1:]))
