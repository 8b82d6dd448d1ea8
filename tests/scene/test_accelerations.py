"""Scene accelerations at constant input speed: the four-bar's own closed-form analysis
(FourBar's alpha3 and alpha4) on both solving paths, and second central differences of
positions for dyad and group scenes."""

import numpy as np
import planarkin as pk
import pytest


@pytest.mark.parametrize(
    "links",
    [
        (6.0, 2.0, 5.0, 5.0),  # crank-rocker: the column path
        (3.0, 4.0, 2.0, 2.5),  # triple rocker (dead points): followed by continuation
    ],
)
def test_four_bar_scene_accelerations_match_the_four_bar(links):
    fb = pk.FourBar(*links)
    sc = fb.to_scene()
    w = 10.0
    sw = sc.sweep(omega=w, outputs="all")
    ref = fb.sweep(sw.theta, omega2=w, alpha2=0.0)
    ok = sw.success & ref.success
    assert ok.sum() > 100
    scale = np.abs(ref.alpha3[ok]).max()
    np.testing.assert_allclose(
        sw.angular_accelerations["coupler"][ok], ref.alpha3[ok], atol=1e-10 * scale
    )
    np.testing.assert_allclose(
        sw.angular_accelerations["rocker"][ok], ref.alpha4[ok], atol=1e-10 * scale
    )
    np.testing.assert_array_equal(sw.angular_accelerations["crank"][ok], 0.0)
    assert np.isnan(sw.accelerations["B"][~sw.success]).all()


@pytest.mark.parametrize("name", ["jansen", "stephenson3", "watt2"])
def test_accelerations_are_second_derivatives_of_positions(name):
    sc = pk.scenes.load(name)
    w = 3.0
    theta = sc.sweep().theta[::7]
    h = 1e-4
    at = sc.sweep(theta, omega=w, outputs="all")
    up, down = sc.sweep(theta + h, outputs="all"), sc.sweep(theta - h, outputs="all")
    for n, a in at.accelerations.items():
        fd = (up.points[n] - 2 * at.points[n] + down.points[n]) / h**2 * w**2
        size = max(np.abs(fd).max(), 1.0)
        np.testing.assert_allclose(a, fd, atol=1e-5 * size, err_msg=n)
    for n, alpha in at.angular_accelerations.items():
        fd = np.angle(np.exp(1j * (up.angles[n] - at.angles[n]))) - np.angle(
            np.exp(1j * (at.angles[n] - down.angles[n]))
        )
        np.testing.assert_allclose(
            alpha, fd / h**2 * w**2, atol=1e-5 * max(np.abs(alpha).max(), 1.0)
        )
