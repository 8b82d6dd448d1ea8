"""The torque objective of synthesis (``minimise_effort``) on its template, an arm under
gravity lifted by a zero-free-length spring from a ground anchor S: by hand, the spring's
moment about the pivot is k r S.y cos(t) - k r S.x sin(t) and the weight's -m g l cos(t),
so the input torque vanishes at every angle exactly when S = (0, m g l / (k r))."""

from __future__ import annotations

import numpy as np
import pytest
from planarkin.synthesis import balanced_arm, minimise_effort

THETA = np.linspace(-1.2, 1.2, 13)
M, G, L, R, K = 3.0, 9.81, 0.6, 0.45, 150.0
BALANCED = (0.0, M * G * L / (K * R))


@pytest.mark.parametrize("measure", ["rms", "peak"])
def test_the_spring_anchor_that_balances_the_arm_is_found(measure):
    sc = balanced_arm(mass=M, gravity=G, center=L, attach=R, k=K, anchor=(0.25, 0.45))
    d = minimise_effort(sc, ["S"], THETA, measure=measure)
    assert d.success, d.message
    assert d.free == ("S.x", "S.y")
    np.testing.assert_allclose(d.x, BALANCED, atol=1e-7)
    np.testing.assert_allclose(d.scene.points["S"], BALANCED, atol=1e-7)
    # the torque as drawn, by hand: m g l cos t - k r (S.y cos t - S.x sin t)
    t0 = M * G * L * np.cos(THETA) - K * R * (0.45 * np.cos(THETA) - 0.25 * np.sin(THETA))
    start = np.sqrt(np.mean(t0**2)) if measure == "rms" else np.abs(t0).max()
    assert d.start == pytest.approx(start, rel=1e-12)
    assert d.value < 1e-9 * d.start
    r = d.scene.statics(d.scene.sweep(THETA, outputs="all", rate=1.0))
    assert np.abs(r.input).max() < 1e-9 * d.start


def test_the_objective_and_its_bad_input():
    sc = balanced_arm()
    with pytest.raises(ValueError, match="measure"):
        minimise_effort(sc, ["S"], THETA, measure="mean")
    with pytest.raises(ValueError, match="span"):
        minimise_effort(sc, ["S"], THETA, span=-1.0)
