"""The built-in scenes whose geometry comes from a seeded random search near a drawn
starting design, judged by the NumPy scene reference: the Stephenson-III six-bar and the
two double butterflies (eight-bars)."""

from __future__ import annotations

import numpy as np
from planarkin.reference import scene as ref

from .geometry import DEG, dist, motion, redraw


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


def double_butterfly_scene(kind):
    """The double butterfly of inversion ``kind`` (1 or 2): searched, redrawn in the middle
    of its range where its input does not turn fully, and described."""
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
    return sc
