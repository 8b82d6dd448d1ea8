"""A full turn asked for in any order: from the drawn angle, reversed, starting 30 deg
away, shuffled. Each dyad or slider plan runs on the column path whatever the order, so
every order should cost about what the drawn start does (issue 36's yardstick: within
1.3x, and at least 5x pylinkage + numba, which can only step from its drawn pose). Each
reordered turn's rows are bit for bit those of its values swept in increasing order; the
drawn and the shifted turns are checked against the NumPy reference."""

from __future__ import annotations

import numpy as np
import planarkin as pk
import pytest
import scene_peers
from conftest import record

#: scene -> the outputs asked for, those pylinkage's peer rows give (None: every point)
SCENES = {"jansen": ["foot"], "slider-crank": ["B"], "watt2": None}
ORDERS = ("drawn", "reversed", "from 30 deg", "shuffled")


def _theta(sc: pk.Scene, order: str) -> np.ndarray:
    base = sc.input_angle + np.radians(np.arange(361.0))
    if order == "reversed":
        return base[::-1].copy()
    if order == "from 30 deg":
        return base + np.radians(30.0)
    if order == "shuffled":
        return np.random.default_rng(36).permutation(base)
    return base


def _key(name: str, order: str) -> str:
    return f"order_{name}_{order.replace(' ', '_')}"


@pytest.mark.parametrize("name", list(SCENES))
@pytest.mark.parametrize("order", ORDERS)
def test_full_turn_in_any_order(benchmark, name, order):
    benchmark.group = f"scene: {name}, a full turn of 361 angles in any order"
    sc = pk.scenes.load(name)
    outputs = SCENES[name] or list(sc.points)
    theta = _theta(sc, order)
    sw = benchmark(sc.sweep, theta, outputs=outputs)
    assert sw.success.all()
    if order in ("drawn", "from 30 deg"):  # values of their own: the NumPy reference
        ref = pk.reference.scene_sweep(sc.to_dict(), theta)
        size = float(np.ptp(np.array(list(sc.points.values())), axis=0).max())
        for p, xy in sw.points.items():
            np.testing.assert_allclose(xy, ref.points[p], rtol=0, atol=1e-9 * size)
    else:  # the drawn turn's values reordered: bit for bit those swept in increasing order
        rank = np.argsort(theta, kind="stable")
        ordered = sc.sweep(theta[rank], outputs=outputs)
        for p, xy in sw.points.items():
            np.testing.assert_array_equal(xy[rank], ordered.points[p])
    record(benchmark, _key(name, order), f"planarkin {name}, {order}")


@pytest.mark.benchmark(group="scene: watt2, a full turn of 361 angles in any order")
def test_watt2_pylinkage(benchmark):
    pytest.importorskip("numba")
    pylinkage = pytest.importorskip("pylinkage")
    sc = pk.scenes.load("watt2")
    pl = scene_peers.PylinkageScene(sc.to_dict())
    traj = benchmark(pl.run)
    truth = sc.sweep(_theta(sc, "drawn"), outputs=list(sc.points))
    err = max(float(np.abs(traj[:, pl.names.index(p)] - truth.points[p]).max()) for p in pl.names)
    assert err < 1e-9
    record(benchmark, "order_watt2_pylinkage",
           f"pylinkage {pylinkage.__version__} step_fast (numba)", max_error=err)  # fmt: skip
