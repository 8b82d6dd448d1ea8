"""A group's sweep stops at a dead point found to within max_step / 2**16 of it
(DESIGN.md, "Scenes"), by a search aimed where the group's conditioning extrapolates to
zero: checked against the tracer's turning points, which it finds on its own
(pseudo-arclength continuation passes through the fold; the turning point is where the
conditioning changes sign along its step), and with the search's Newton work bounded."""

import math

import numpy as np
import planarkin as pk
import pytest

#: the sweep's default largest step
MAX_STEP = math.radians(3.0)


@pytest.mark.parametrize("name", ["double-butterfly-1", "double-butterfly-2"])
def test_a_sweep_stops_at_the_tracers_turning_point(name):
    sc = pk.scenes.load(name)
    sw = sc.sweep()
    lim = np.unique(sw.limit[np.isfinite(sw.limit)])
    assert len(lim) >= 1
    tps = sc.trace().turning_points
    for v in lim:
        gap = np.min(np.abs(np.angle(np.exp(1j * (tps - v)))))
        # the last solved input before the dead point: within the search's floor of it
        assert gap <= MAX_STEP * 2.0**-16, (v, gap)


@pytest.mark.parametrize("name", ["double-butterfly-1", "double-butterfly-2"])
def test_finding_a_dead_point_takes_a_handful_of_newton_steps(name):
    # halving the failing step 16 times took about 400 Newton steps per dead point (twice
    # the whole sweep's other work); the aimed search takes a few dozen
    sc = pk.scenes.load(name)
    sw = sc.sweep()
    solved = int(sw.success.sum())
    assert (sw.status == pk.Status.LIMIT).any() and solved > 100
    assert sw.nit.sum() < 2 * solved, (int(sw.nit.sum()), solved)
