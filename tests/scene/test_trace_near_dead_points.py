"""Traces and circuits from a drawing next to a dead point (issue 32): the first step of the
trace passes the dead point and comes back past the drawn input, and the last step closes
onto the start across it; neither may lose a turning point or the other assembly met
there, so the circuits are those of a drawing far from the dead point.

Truth: closed forms written here -- a non-Grashof four-bar's toggles (the coupler and
rocker in line), an offset slider-crank's dead points (the rod perpendicular to the slot,
sin t = (e - l) / r), the hydraulic boom's stroke ends (the triangle O-C1-E flat)."""

import math

import numpy as np
import planarkin as pk
import pytest

TOL = 1e-9  # DESIGN: turning points refined to about 1e-9 rad (of size for a length)


def fourbar(a, b, c, d, th, side):
    """Four-bar O2-A-B-O4 (crank a, coupler b, rocker c, ground d) drawn at crank angle th,
    B on the given side of the diagonal A-O4."""
    o4, pa = np.array([d, 0.0]), a * np.array([math.cos(th), math.sin(th)])
    r = math.dist(o4, pa)
    u = (o4 - pa) / r
    x = (b * b - c * c + r * r) / (2 * r)
    pb = pa + x * u + side * math.sqrt(b * b - x * x) * np.array([-u[1], u[0]])
    return pk.Scene.from_dict(
        {
            "points": {"O2": [0, 0], "O4": [d, 0], "A": pa.tolist(), "B": pb.tolist()},
            "links": {
                "ground": ["O2", "O4"],
                "crank": ["O2", "A"],
                "coupler": ["A", "B"],
                "rocker": ["O4", "B"],
            },
            "ground": "ground",
            "input": {"link": "crank", "pivot": "O2"},
            "output": {"link": "rocker", "pivot": "O4"},
        }
    )


def slider_crank(r, rod, e, th, side):
    """Offset slider-crank: crank O2-A (r), rod A-B (rod), B in a ground slot at height e."""
    pa = [r * math.cos(th), r * math.sin(th)]
    pb = [pa[0] + side * math.sqrt(rod * rod - (e - pa[1]) ** 2), e]
    return pk.Scene.from_dict(
        {
            "points": {"O2": [0, 0], "X": [1, 0], "A": pa, "B": pb},
            "links": {"ground": ["O2", "X"], "crank": ["O2", "A"], "rod": ["A", "B"]},
            "ground": "ground",
            "input": {"link": "crank", "pivot": "O2"},
            "slots": {"piston": {"point": "B", "guide": "ground", "line": ["O2", "X"]}},
        }
    )


def wrapped(t):
    return (np.asarray(t) + math.pi) % (2 * math.pi) - math.pi


def assert_one_circuit(sc, ends, atol, n=2):
    """One circuit through both assemblies at the drawn input, not a full turn, turning at
    `ends` (sorted); the trace from the drawing closes with the same turning points."""
    tr = sc.trace()
    assert tr.closed
    got = tr.turning_points if sc.input_kind != "angle" else wrapped(tr.turning_points)
    np.testing.assert_allclose(np.sort(got), ends, rtol=0, atol=atol)
    (c,) = sc.circuits()
    assert len(c.assemblies) == n and not c.full_turn
    np.testing.assert_allclose(np.sort(c.turning_points), ends, rtol=0, atol=atol)


# (a, b, c, d) = (2, 3, 2.5, 6): a + d > b + c, so non-Grashof: the crank rocks between the
# toggles, where coupler and rocker lie in line (|A O4| = b + c)
A, B, C, D = 2.0, 3.0, 2.5, 6.0
TOGGLE = math.acos((A * A + D * D - (B + C) ** 2) / (2 * A * D))


@pytest.mark.parametrize("eps", [0.3, 1e-5, 1e-7, 1e-9])
@pytest.mark.parametrize("at", [TOGGLE, -TOGGLE])
@pytest.mark.parametrize("side", [1, -1])
def test_non_grashof_four_bar_near_its_toggle_is_one_circuit_with_both_toggles(eps, at, side):
    th = at - math.copysign(eps, at)  # inside the range
    sc = fourbar(A, B, C, D, th, side)
    assert_one_circuit(sc, [-TOGGLE, TOGGLE], TOL)
    # the circuit holds both closed-form assemblies at the drawn angle
    (c,) = sc.circuits()
    want = [fourbar(A, B, C, D, th, s).points["B"] for s in (1, -1)]
    got = sorted([a["B"] for a in c.assemblies], key=lambda p: -p[1] * side)
    np.testing.assert_allclose(got, want if side > 0 else want[::-1], rtol=0, atol=1e-9)


# offset slider-crank r = 1, l = 1.2, e = 0.5: the rod reaches the slot while
# |e - r sin t| <= l, so the crank rocks between sin t = (e - l) / r = -0.7 (both roots)
R, L, E = 1.0, 1.2, 0.5
DEAD = math.asin((E - L) / R)
DEADS = [-math.pi - DEAD, DEAD]


@pytest.mark.parametrize("eps", [1e-5, 1e-7, 1e-9])
@pytest.mark.parametrize("inside", [(DEAD, 1), (-math.pi - DEAD, -1)])
@pytest.mark.parametrize("side", [1, -1])
def test_rocking_slider_crank_near_its_dead_point_is_one_circuit(eps, inside, side):
    th = inside[0] + inside[1] * eps  # inside the crank's range
    assert_one_circuit(slider_crank(R, L, E, th, side), DEADS, TOL)


def boom_stroke(points):
    """The boom's stroke ends from a drawing (input 0 there): |C1 E| extends from its drawn
    length to |O C1| + |O E| (E beyond O) or shrinks to ||O E| - |O C1|| (E towards C1)."""
    p = {n: np.asarray(v) for n, v in points.items()}
    oc, oe, ce = (math.dist(p[a], p[b]) for a, b in (("C1", "O"), ("E", "O"), ("E", "C1")))
    return [abs(oe - oc) - ce, oc + oe - ce]


@pytest.mark.parametrize("end", [0, 1])
@pytest.mark.parametrize("gap", [1e-2, 1e-5, 1e-7])
def test_hydraulic_boom_redrawn_next_to_a_stroke_end_keeps_both_ends(end, gap):
    boom = pk.scenes.load("hydraulic-boom")
    s = boom_stroke(boom.points)[end] + (gap if end == 0 else -gap)
    # the linkage itself: its cylinder's limits (measured from the drawn pose) left out
    d = {k: v for k, v in pk.scenes.data("hydraulic-boom").items() if k != "limits"}
    size = float(max(np.ptp(np.array(list(boom.points.values())), axis=0)))
    for asm in boom.assemblies(s):
        sc = pk.Scene.from_dict({**d, "points": {n: list(xy) for n, xy in asm.items()}})
        ends = boom_stroke(sc.points)
        assert abs(ends[end]) < 2 * gap  # redrawn where asked
        assert_one_circuit(sc, ends, TOL * size)


def test_slider_group_drawn_next_to_a_fold_is_one_circuit_with_both_folds():
    # a slot inside a Newton group (test_slider_groups.slot_triad): the folds have no closed
    # form here; the NumPy reference (one Newton system of every link, no plan) brackets
    # each: it converges 2e-9 inside and fails 2e-9 outside
    from planarkin.reference import scene_sweep
    from test_slider_groups import slot_triad

    d = slot_triad()
    far = pk.Scene.from_dict(d)
    assert [s.kind for s in far.plan().steps] == ["group"]
    (c,) = far.circuits()
    tps = np.sort(c.turning_points)
    assert len(tps) == 2
    for tp in tps:
        inward = math.copysign(1.0, far.input_angle - tp)
        ref = scene_sweep(d, [tp + inward * 2e-9, tp - inward * 2e-9])
        assert ref.status[0] == pk.Status.CONVERGED and ref.status[1] != pk.Status.CONVERGED
    for tp in tps:
        inward = math.copysign(1.0, far.input_angle - tp)
        for eps in (1e-5, 1e-7):
            found = far.assemblies(tp + inward * eps)
            assert len(found) == 2  # the two branches meeting at the fold
            for a in found:
                near = pk.Scene.from_dict({**d, "points": {n: list(xy) for n, xy in a.items()}})
                assert len(near.assemblies()) == 2
                assert_one_circuit(near, tps, 1e-9)
