"""A slot on a turning guide whose line passes through the guide's pivot, driven by a crank
whose length equals the pivot distance (issue 32, found by hand 1): the crank pin passes
through the pivot once a turn. The guide's direction is smooth through the pass -- the pin
goes on behind the pivot -- so a sweep follows it instead of flipping the guide by 180 deg,
and the step's conditioning (the pin's signed distance from the pivot along the slot)
falls to 0 there, changing sign.

Truth: the chord's direction. A crank pin A = r (cos t, sin t) and a pivot on the crank
circle at O4 = r (cos a, sin a): A - O4 = 2 r sin((t - a) / 2) (-sin((t + a) / 2),
cos((t + a) / 2)), so the guide, continued through t = a, points at (t + a) / 2 + 90 deg
(90 + t / 2 for the inverted slider-crank, a = 0) and the pin's distance from the pivot
is 2 r |sin((t - a) / 2)|."""

from __future__ import annotations

import math

import numpy as np
import planarkin as pk
import pytest

R = 100.0


def slotted(a_deg: float, t0_deg: float = 60.0, arm: float = 60.0) -> pk.Scene:
    """Crank O2-A (r = R) with its pin A in a slot of the guide O4-C, O4 on the crank
    circle at angle a; the guide's point C on the slot's line ahead of O4 towards A by
    `arm` (behind it, opposite the pin, for a negative arm). Drawn at crank angle t0."""
    a, t0 = math.radians(a_deg), math.radians(t0_deg)
    o4 = [R * math.cos(a), R * math.sin(a)]
    pa = [R * math.cos(t0), R * math.sin(t0)]
    g = math.atan2(pa[1] - o4[1], pa[0] - o4[0])
    c = [o4[0] + arm * math.cos(g), o4[1] + arm * math.sin(g)]
    return pk.Scene.from_dict(
        {
            "points": {"O2": [0.0, 0.0], "O4": o4, "A": pa, "C": c},
            "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "guide": ["O4", "C"]},
            "ground": "ground",
            "input": {"link": "crank", "pivot": "O2"},
            "output": {"link": "guide", "pivot": "O4"},
            "slots": {"block": {"point": "A", "guide": "guide", "line": ["O4", "C"]}},
        }
    )


def gap_deg(x, y):
    return np.abs((np.asarray(x) - np.asarray(y) + 180.0) % 360.0 - 180.0)


@pytest.mark.parametrize("a_deg", [0.0, 90.0, -135.0])
@pytest.mark.parametrize("arm", [60.0, -40.0])
def test_guide_follows_the_chord_through_the_pivot(a_deg, arm):
    sc = slotted(a_deg, arm=arm)
    assert [s.kind for s in sc.plan().steps] == ["rpr"]
    sw = sc.sweep(outputs="all")  # one turn from the drawn 60 deg: the pin meets O4 once
    t = np.degrees(sw.theta)
    # continued through the pass: the guide turns half as fast as the crank, on the
    # chord's side as drawn (the pin ahead of O4 where sin((t0 - a) / 2) > 0), C ahead of
    # O4 or behind it
    ahead = math.sin(math.radians(60.0 - a_deg) / 2.0) > 0
    want = (t + a_deg) / 2.0 + 90.0 + (0.0 if ahead else 180.0) + (0.0 if arm > 0 else 180.0)
    ok = sw.status == pk.Status.CONVERGED
    np.testing.assert_array_less(gap_deg(np.degrees(sw.angles["guide"][ok]), want[ok]), 1e-9)
    # every row but the pass itself converges; there, SINGULAR (the pin on the pivot)
    passing = gap_deg(t, a_deg) < 1e-6
    assert ok[~passing].all()
    assert (sw.status[passing & ~ok] == pk.Status.SINGULAR).all()


def test_inverted_slider_crank_through_the_pass_is_90_plus_half_theta():
    sc = slotted(0.0)
    t = np.radians([350.0, 355.0, 359.0, 359.9, 360.1, 361.0, 365.0, 370.0])
    sw = sc.sweep(t, outputs="all")
    assert sw.success.all()
    want = 90.0 + np.degrees(t) / 2.0
    np.testing.assert_array_less(gap_deg(np.degrees(sw.angles["guide"]), want), 1e-9)
    # the pin goes on past the pivot: A - O4 against the guide's direction changes sign
    u = np.stack([np.cos(sw.angles["guide"]), np.sin(sw.angles["guide"])], axis=1)
    along = ((sw.points["A"] - sw.points["O4"]) * u).sum(axis=1)
    assert (along[:4] > 0).all() and (along[4:] < 0).all()


def test_conditioning_is_the_pins_signed_distance_from_the_pivot():
    sc = slotted(0.0)
    t = np.radians([300.0, 340.0, 359.0, 359.99, 360.01, 361.0, 380.0])
    sw = sc.sweep(t, outputs="all")
    (cond,) = sw.step_det.T
    dist = 2.0 * R * np.sin(t / 2.0)  # signed: + before the pass, - after
    # proportional to the closed form (the solving frame's scale is a power of two)
    ratio = cond / dist
    np.testing.assert_allclose(ratio, ratio[0], rtol=1e-9)
    assert 0 < abs(cond[3]) < 1e-3 * abs(cond[0])


def test_exactly_on_the_pivot_is_singular_not_not_assemblable():
    # drawn so that the crank meets O4 = (R, 0) at exactly 0 rad (A = (R, 0) bit for bit)
    sc = slotted(0.0, t0_deg=-60.0)
    sw = sc.sweep([sc.input_angle, -1e-3, 0.0, 1e-3], outputs="all")
    assert sw.status[2] == pk.Status.SINGULAR
    assert sw.success[[0, 1, 3]].all()
    # drawn at -60 deg, the pin behind O4 along the guide (sin(-30 deg) < 0)
    want = 270.0 + np.degrees(sw.theta[[1, 3]]) / 2.0
    np.testing.assert_array_less(gap_deg(np.degrees(sw.angles["guide"][[1, 3]]), want), 1e-9)
    # the pose at the pass is a continuum (the guide at any angle), not listed
    assert len(sc.assemblies(0.0)) == 0 and sc.assemblies(0.0).continua == 1


def test_circuit_through_the_pass_is_one_full_turn_without_turning_points():
    # a crank turn takes the guide half round, onto the other assembly: one circuit, both
    # assemblies, closing after two turns of the crank; the pass is no dead point
    (c,) = slotted(0.0).circuits()
    assert len(c.assemblies) == 2 and c.full_turn and len(c.turning_points) == 0
    assert c.net_turn == pytest.approx(4 * math.pi, abs=1e-9)


def test_crank_and_slotted_lever_at_the_whitworth_boundary_drives_its_ram_through():
    # the built-in Whitworth with its crank shortened to the pivot distance (r = c = 30):
    # the lever (its arm O4-C opposite the slot, |O4 C| = 50) turns on through the pass and
    # the ram D (rod C-D = 150 on the line y = c) follows: x_D = x_C - sqrt(rod^2 - (y_C -
    # c)^2), the lever's slot at (t + 90) / 2 + 90 deg, plus 180 as drawn at 30 deg (the
    # pin behind O4: sin((30 - 90) / 2) < 0)
    c, big_r, rod, t0 = 30.0, 50.0, 150.0, math.radians(30.0)
    d = pk.scenes.data("whitworth")
    pa = [c * math.cos(t0), c * math.sin(t0)]
    g = math.atan2(pa[1] - c, pa[0])
    pc = [-big_r * math.cos(g), c - big_r * math.sin(g)]
    pd = [pc[0] - math.sqrt(rod**2 - (pc[1] - c) ** 2), c]
    d["points"].update({"A": pa, "C": pc, "D": pd})
    sc = pk.Scene.from_dict(d)
    sw = sc.sweep(outputs="all")
    slot = np.radians((np.degrees(sw.theta) + 90.0) / 2.0 + 90.0 + 180.0)
    cx, cy = big_r * np.cos(slot + np.pi), c + big_r * np.sin(slot + np.pi)
    ram = cx - np.sqrt(rod**2 - (cy - c) ** 2)
    passing = gap_deg(np.degrees(sw.theta), 90.0) < 1e-6
    assert sw.success[~passing].all()
    assert np.abs(sw.points["D"][~passing, 0] - ram[~passing]).max() < 1e-12 * rod
