"""Path verification on the real linkage: exact designs pass with their generating inputs
and the closed-form transmission angle; hand-made defective designs are labelled (an arc
through a rocking four-bar's dead point: branch; points split between a crank-rocker's two
assemblies: circuit; points reached out of order: order); bad input refused by name."""

from __future__ import annotations

import math

import numpy as np
import planarkin as pk
import pytest
from _path_linkages import (
    fourbar_curve,
    fourbar_scene,
    slider_curve,
    slider_scene,
    transmission_sines,
)
from planarkin.synthesis.path.targets import CurveTarget
from planarkin.synthesis.path.verify import verify

CRANK_ROCKER = ((0.0, 0.0), (6.0, 0.0), 2.0, 5.0, 5.0, 1.5, 2.0)
ROCKING = ((0.0, 0.0), (5.0, 0.0), 3.0, 3.0, 4.0, 1.0, 1.5)  # non-Grashof: |theta| <= 120 deg
TURN = np.linspace(0.0, 2 * math.pi, 25)[:-1]


def _closest_angle(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.abs(np.angle(np.exp(1j * (a - b)))).max())


def test_an_exact_crank_rocker_passes_with_its_inputs_and_transmission() -> None:
    _, _, p = fourbar_curve(*CRANK_ROCKER, TURN)
    target = CurveTarget(p, "closed")
    sc = pk.Scene.from_dict(fourbar_scene(*CRANK_ROCKER, 0.3))
    v = verify(sc, "P", target, TURN, dense=256)
    assert v.ok and v.converged and v.full_turn and not v.defects.any
    assert v.error.max < 1e-12 and v.distances.shape == (TURN.size,)
    assert _closest_angle(v.inputs, TURN) < 1e-9
    fine = np.linspace(0, 2 * math.pi, 200001)
    mu = math.degrees(math.asin(transmission_sines(*CRANK_ROCKER[:5], fine).min()))
    assert abs(v.min_transmission - mu) < 1e-6, (v.min_transmission, mu)
    # asked for more than it has: labelled, not hidden
    assert not verify(sc, "P", target, TURN, min_transmission=mu + 1.0).ok


def test_the_error_is_the_distance_to_the_curve_not_to_the_inputs_points() -> None:
    # every target point moved 1e-3 along the curve's normal: the error is 1e-3 / size,
    # whatever inputs are given near the right ones
    theta = np.linspace(0.2, 2.6, 9)
    _, _, p = fourbar_curve(*CRANK_ROCKER, theta)
    h = 1e-6
    tangent = (
        fourbar_curve(*CRANK_ROCKER, theta + h)[2] - fourbar_curve(*CRANK_ROCKER, theta - h)[2]
    ) / (2 * h)
    normal = np.stack([-tangent[:, 1], tangent[:, 0]], -1)
    normal /= np.hypot(normal[:, 0], normal[:, 1])[:, None]
    q = p + 1e-3 * normal
    target = CurveTarget(q, "open")
    sc = pk.Scene.from_dict(fourbar_scene(*CRANK_ROCKER, 0.2))
    v = verify(sc, "P", target, theta + 0.01 * np.sin(np.arange(9)))
    # the arc's ends move with the inputs: compare inside it
    assert np.allclose(v.distances[1:-1] * target.size, 1e-3, rtol=1e-6)


def test_an_arc_through_a_rocking_fourbars_dead_point_is_a_branch_defect() -> None:
    tmax = math.acos(-0.5)  # |A - O4| = r3 + r4 = 7 at the crank's limit
    up = np.linspace(1.2, tmax - 0.02, 6)
    p_up = fourbar_curve(*ROCKING, up)[2]
    p_back = fourbar_curve(*ROCKING, up[::-1], side=-1.0)[2][1:]
    sc = pk.Scene.from_dict(fourbar_scene(*ROCKING, 1.2))
    # the way up only: no defect
    v = verify(sc, "P", CurveTarget(p_up, "open"), up)
    assert v.ok and not v.defects.any and not v.full_turn
    # up to the limit and back on the other branch, the inputs driven on past the limit
    target = CurveTarget(np.vstack([p_up, p_back]), "open")
    inputs = np.concatenate([up, tmax + (tmax - up[::-1][1:])])
    v = verify(sc, "P", target, inputs)
    assert v.defects.branch and not v.ok and not v.converged


def test_points_split_between_the_two_assemblies_are_a_circuit_defect() -> None:
    theta = np.linspace(0.0, 3.0, 10)
    open_, crossed = (fourbar_curve(*CRANK_ROCKER, theta, side=s)[2] for s in (1.0, -1.0))
    for side, pts in ((1.0, open_), (-1.0, crossed)):
        sc = pk.Scene.from_dict(fourbar_scene(*CRANK_ROCKER, 0.0, side=side))
        v = verify(sc, "P", CurveTarget(pts, "open"), theta)
        assert v.ok and not v.defects.any, side
    split = np.vstack([open_[:5], crossed[5:]])
    sc = pk.Scene.from_dict(fourbar_scene(*CRANK_ROCKER, 0.0))
    v = verify(sc, "P", CurveTarget(split, "open"), theta)
    assert v.defects.circuit and not v.ok


def test_points_reached_out_of_order_are_an_order_defect() -> None:
    sc = pk.Scene.from_dict(fourbar_scene(*CRANK_ROCKER, 0.0))
    for kind, theta in (("closed", TURN), ("open", np.linspace(0.0, 3.0, 10))):
        _, _, p = fourbar_curve(*CRANK_ROCKER, theta)
        swap = np.arange(theta.size)
        swap[[3, 4]] = swap[[4, 3]]
        v = verify(sc, "P", CurveTarget(p[swap], kind), theta[swap])
        assert v.defects.order and not v.ok, kind
        assert v.error.max < 1e-12  # on the curve: only the order is wrong
        # the same points the other way round are in order (the input turning back)
        v = verify(sc, "P", CurveTarget(p[::-1], kind), theta[::-1])
        assert not v.defects.any and v.ok, kind


def test_an_exact_offset_slider_crank_passes_with_its_transmission() -> None:
    geo = ((0.5, 0.2), 0.3, 0.4, 1.0, 3.5, 1.2, 0.8)
    a, b, p = slider_curve(*geo, TURN)
    sc = pk.Scene.from_dict(slider_scene(*geo, 0.0))
    v = verify(sc, "P", CurveTarget(p, "closed"), TURN, dense=256)
    assert v.ok and v.full_turn and v.error.max < 1e-12
    # the rod's angle to the slide: its transmission sine is the cosine of that angle
    fine = np.linspace(0, 2 * math.pi, 200001)
    a, b, _ = slider_curve(*geo, fine)
    u = np.array([math.cos(geo[1]), math.sin(geo[1])])
    c = np.abs((b - a) @ u) / geo[4]
    assert abs(v.min_transmission - math.degrees(math.asin(c.min()))) < 1e-6


def test_bad_input_is_refused_naming_the_parameter() -> None:
    _, _, p = fourbar_curve(*CRANK_ROCKER, TURN)
    target = CurveTarget(p, "closed")
    sc = pk.Scene.from_dict(fourbar_scene(*CRANK_ROCKER, 0.0))
    for args, kw, name in (
        ((sc, "Q", target, TURN), {}, "tracer"),
        ((sc, "P", target, TURN[:3]), {}, "inputs"),
        ((sc, "P", p, TURN), {}, "target"),
        ((sc, "P", target, TURN), {"dense": 1}, "dense"),
        ((sc, "P", target, TURN), {"min_transmission": -5}, "min_transmission"),
        ((sc, "P", target, TURN), {"floor": 2.0}, "floor"),
        (("fourbar", "P", target, TURN), {}, "scene"),
    ):
        with pytest.raises(ValueError, match=f"^{name}") as e:
            verify(*args, **kw)
        assert "\n" not in str(e.value)
