"""Forces beside the kinematics they need: Jansen's leg with its loads (the jansen-loaded
built-in: a foot ground reaction, link masses, gravity) over 361 crank angles. Rows: the
kinematic sweep with velocities and accelerations (every point, ``rate`` given), the
inverse dynamics and the statics on that sweep (every pin reaction and the input torque,
by the core's kernel: the Newton-Euler equations block by block per row, virtual work
and the energy check), the same by the NumPy reference (a batched dense solve), and
sweep plus dynamics together, as a user runs them. The issue's target: forces within 3x
the kinematic sweep. Correctness (virtual work against Newton-Euler) is checked outside
the timed calls."""

from __future__ import annotations

import math

import numpy as np
import planarkin as pk
import pytest
from conftest import record

FORCES = "forces: Jansen's leg with loads, 361 angles, every reaction"
DEG = math.pi / 180
RATE = 2 * math.pi  # one turn a second


@pytest.fixture(scope="module")
def jansen():
    sc = pk.scenes.load("jansen-loaded")
    theta = sc.input_angle + np.arange(361) * DEG
    sw = sc.sweep(theta, outputs="all", rate=RATE)
    r = sc.dynamics(sw)
    assert r.success.all() and r.check < 1e-10
    return sc, theta, sw


@pytest.mark.benchmark(group=FORCES)
def test_forces_kinematic_sweep(benchmark, jansen):
    sc, theta, _ = jansen
    sw = benchmark(sc.sweep, theta, outputs="all", rate=RATE)
    assert sw.success.all() and sw.acceleration_array is not None
    record(benchmark, "forces_sweep", "planarkin sc.sweep(theta, outputs='all', rate=w)")


@pytest.mark.benchmark(group=FORCES)
def test_forces_dynamics(benchmark, jansen):
    sc, _, sw = jansen
    r = benchmark(sc.dynamics, sw)
    assert r.check < 1e-10
    record(benchmark, "forces_dynamics", "planarkin sc.dynamics(sw) (on the sweep)")


@pytest.mark.benchmark(group=FORCES)
def test_forces_statics(benchmark, jansen):
    sc, _, sw = jansen
    r = benchmark(sc.statics, sw)
    assert r.check < 1e-10
    record(benchmark, "forces_statics", "planarkin sc.statics(sw) (on the sweep)")


@pytest.mark.benchmark(group=FORCES)
def test_forces_dynamics_numpy_reference(benchmark, jansen):
    sc, _, sw = jansen
    r = benchmark(sc.dynamics, sw, engine="numpy")
    assert r.check < 1e-10
    record(benchmark, "forces_dynamics_numpy", "NumPy reference sc.dynamics(sw, engine='numpy')")


def _both(sc, theta):
    return sc.dynamics(sc.sweep(theta, outputs="all", rate=RATE))


@pytest.mark.benchmark(group=FORCES)
def test_forces_sweep_and_dynamics(benchmark, jansen):
    sc, theta, _ = jansen
    r = benchmark(_both, sc, theta)
    assert r.check < 1e-10
    record(benchmark, "forces_both", "planarkin sweep + dynamics")
