"""The centred slider-crank over 361 crank angles, piston position, side by side:
planarkin's scene sweep (the circle-line closed form at every angle at once, certified
free of dead points, else continuation), pylinkage 1.3 with numba on the same mechanism
(Crank + RRPDyad, its circle-line dyad, ``step_fast``), and the closed form written in
NumPy the way a user would. Each is checked against the closed form outside the timed
call. A fourth row times the binding alone (the compiled plan's sweep, no Python layer):
with criterion's ``slider_crank_361/piston`` (the core alone, ``benches/scene.rs``) it
splits planarkin's time into core, binding and Python layer."""

from __future__ import annotations

import math

import numpy as np
import planarkin as pk
import pytest
from conftest import record

SLIDER = "scene: centred slider-crank, 361 angles, piston position"
DEG = math.pi / 180


@pytest.fixture(scope="module")
def slider():
    sc = pk.scenes.load("slider-crank")
    a, b = np.asarray(sc.points["A"]), np.asarray(sc.points["B"])
    r, rod = float(np.hypot(*a)), float(np.hypot(*(b - a)))
    theta = sc.input_angle + np.arange(361) * DEG
    return sc, r, rod, theta


def numpy_piston(theta: np.ndarray, r: float, rod: float) -> np.ndarray:
    """The user's closed form: x = r cos t + sqrt(l^2 - (r sin t)^2)."""
    s, c = np.sin(theta), np.cos(theta)
    return r * c + np.sqrt(rod * rod - (r * s) ** 2)


@pytest.mark.benchmark(group=SLIDER)
def test_slider_planarkin(benchmark, slider):
    sc, r, rod, theta = slider
    sw = benchmark(sc.sweep, theta, outputs=["B"])
    assert sw.success.all()
    err = float(np.abs(sw.points["B"][:, 0] - numpy_piston(theta, r, rod)).max())
    assert err < 1e-12 * rod
    record(benchmark, "slider_pk", "planarkin sc.sweep(theta, outputs=['B'])", max_error=err)


@pytest.mark.benchmark(group=SLIDER)
def test_slider_binding(benchmark, slider):
    sc, r, rod, theta = slider
    _, core = sc._compiled(["B"])
    args = (theta, 1e-9, 100, math.radians(3.0), None, "continuation")
    out = benchmark(core.sweep, *args)
    err = float(np.abs(out[0][:, 3, 0] - numpy_piston(theta, r, rod)).max())
    assert err < 1e-12 * rod
    record(benchmark, "slider_binding", "planarkin binding alone (compiled plan's sweep)",
           max_error=err)  # fmt: skip


@pytest.mark.benchmark(group=SLIDER)
def test_slider_numpy_closed_form(benchmark, slider):
    sc, r, rod, theta = slider
    x = benchmark(numpy_piston, theta, r, rod)
    assert np.isfinite(x).all()
    record(benchmark, "slider_numpy", "NumPy closed form r cos t + sqrt(l^2 - (r sin t)^2)")


class PylinkageSlider:
    """The slider-crank in pylinkage 1.3: Ground O2 and the slide line's two ground points,
    a Crank at O2 and an RRPDyad for the piston, stepped 1 degree per step by numba's
    ``step_fast``, started one step before the drawn angle."""

    def __init__(self, sc: pk.Scene, n: int = 361) -> None:
        from pylinkage.actuators import Crank
        from pylinkage.components import Ground
        from pylinkage.dyads import RRPDyad
        from pylinkage.simulation import Linkage

        p = {k: np.asarray(v, dtype=float) for k, v in sc.points.items()}
        self.p, self.n, self.step = p, n, DEG
        o2, x = Ground(*p["O2"], name="O2"), Ground(*p["X"], name="X")
        r = float(np.hypot(*(p["A"] - p["O2"])))
        self.crank = Crank(anchor=o2, radius=r, angular_velocity=self.step, name="A")
        rod = float(np.hypot(*(p["B"] - p["A"])))
        piston = RRPDyad(self.crank.output, o2, x, distance=rod, x=float(p["B"][0]),
                         y=float(p["B"][1]), name="B")  # fmt: skip
        self.linkage = Linkage([o2, x, self.crank, piston], name="slider-crank")
        self.linkage.compile()
        self.run()  # numba compiles (or loads its cache) on the first call

    def run(self) -> np.ndarray:
        c, s = math.cos(-self.step), math.sin(-self.step)
        a = self.p["A"]
        turned = (c * a[0] - s * a[1], s * a[0] + c * a[1])
        self.linkage.set_coords(
            [tuple(self.p["O2"]), tuple(self.p["X"]), turned, tuple(self.p["B"])]
        )
        return self.linkage.step_fast(iterations=self.n)


@pytest.mark.benchmark(group=SLIDER)
def test_slider_pylinkage(benchmark, slider):
    pytest.importorskip("numba")
    pylinkage = pytest.importorskip("pylinkage")
    sc, r, rod, theta = slider
    pl = PylinkageSlider(sc)
    traj = benchmark(pl.run)
    err = float(np.abs(traj[:, 3, 0] - numpy_piston(theta, r, rod)).max())
    assert err < 1e-9 * rod, err
    record(benchmark, "slider_pylinkage", f"pylinkage {pylinkage.__version__} step_fast (numba)",
           max_error=err)  # fmt: skip
