"""A group's sweep predicts each angle from its last three solutions and their tangents
(a quintic), so that at an ordinary angle the start is already within the Newton
tolerance and one evaluation converges; the rates then come from the Jacobian at the
solution, not at the start (DESIGN.md, "Scenes"). Checked against independent truths:
fourth-order central differences of the positions, and the count of Newton steps."""

import numpy as np
import planarkin as pk
import pytest

GROUP_SCENES = ["double-butterfly-1", "double-butterfly-2", "stephenson3", "watt2"]


@pytest.mark.parametrize("name", GROUP_SCENES)
def test_group_velocities_are_the_derivatives_of_the_positions(name):
    # where the start converged at once its Jacobian is a whole correction (about the
    # tolerance) from the solution: rates from it were off by ~3e-9 on the double butterfly
    sc = pk.scenes.load(name)
    sw = sc.sweep(sc.input_angle + np.radians(np.arange(361.0)), omega=1.0)
    # away from the dead points (where the differences' truncation grows)
    ok = sw.success & (np.abs(sw.det) > 0.5 * np.abs(sw.det[sw.success]).max())
    theta = sw.theta[ok][::7]
    h = 3e-4
    at = sc.sweep(theta, omega=1.0)
    p = {k: sc.sweep(theta + k * h).points for k in (-2, -1, 1, 2)}
    for n in at.points:
        # (8 (p1 - p-1) - (p2 - p-2)) / 12h: truncation h^4 |p^(5)| / 30, rounding ~1e-12
        fd = (8 * (p[1][n] - p[-1][n]) - (p[2][n] - p[-2][n])) / (12 * h)
        scale = max(1.0, float(np.abs(fd).max()))
        np.testing.assert_allclose(at.velocities[n], fd, atol=5e-11 * scale, rtol=0, err_msg=n)


@pytest.mark.parametrize("name", ["stephenson3", "watt2"])
def test_an_ordinary_sweep_converges_at_its_first_evaluation(name):
    # away from dead points the quintic's start is within the tolerance (its error is
    # about h^6 |phi^(6)| / 20 at one-degree steps): no Newton step is needed at all but
    # at the first angles, before three solutions are known
    sc = pk.scenes.load(name)
    sw = sc.sweep(sc.input_angle + np.radians(np.arange(361.0)))
    assert sw.success.all()
    assert sw.nit.sum() <= 10, int(sw.nit.sum())
