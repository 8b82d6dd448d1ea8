"""The two SLSQP phases of one start and the workers' BLAS threads: the least squares hand
over to the minimax polish when they stall, the polish (in scaled steps) lowers the true
error it starts from, and a worker runs OpenBLAS on one thread."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
from planarkin.synthesis import ackermann
from planarkin.synthesis.screening import sample_starts
from planarkin.synthesis.start import STALL_ITER, run_start
from planarkin.synthesis.verify import true_error


@pytest.fixture(scope="module")
def steering():
    p = ackermann.problem()
    ((_, x0),) = sample_starts(
        p, 600, 1, np.random.default_rng(2), ackermann.mirror_sampler(p.space)
    )
    return p, x0


def _true_max(p, x) -> float:
    # the real linkage swept here through 1001 angles, against Ackermann's closed form
    phi = np.linspace(p.target.dense_in[0], p.target.dense_in[-1], 1001)
    e, info = true_error(p.scene(x), phi, ackermann.right_steer(phi))
    assert info["converged"] and info["det_sign_changes"] == 0
    return float(np.max(np.abs(e)))


@pytest.mark.slow  # two least-squares runs of the steering problem: about 2 s on 2 cores
def test_least_squares_hand_over_when_they_stall(steering):
    p, x0 = steering
    full = run_start(p, x0, maxiter=150, minimax=False, stall_iter=None)
    early = run_start(p, x0, maxiter=150, minimax=False)
    assert full.nit == 150 or full.success
    (ph,) = early.phases
    if ph.get("stalled"):
        assert STALL_ITER < early.nit < full.nit and "stalled" in early.message
    else:  # ran to SLSQP's own end: the same run as without the test
        assert early.nit == full.nit and np.array_equal(early.x, full.x)


@pytest.mark.slow  # a least-squares run and its polish: about 2 s on 2 cores
def test_minimax_polish_lowers_the_true_error(steering):
    p, x0 = steering
    ls = run_start(p, x0, minimax=False)
    both = run_start(p, x0)
    assert both.phases[0] == ls.phases[0]  # the same least squares
    assert both.phases[-1]["phase"] == "minimax" and both.phases[-1]["kept"]
    assert both.feasible and ls.feasible
    assert _true_max(p, both.x) < _true_max(p, ls.x)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc/self/maps")
def test_a_worker_runs_openblas_on_one_thread():
    # in a fresh process (the test process keeps its threads); each library asked itself
    code = """
import ctypes
from planarkin.synthesis.pool import one_blas_thread
assert one_blas_thread() >= 1
libs = {l.split()[-1] for l in open('/proc/self/maps') if 'openblas' in l.lower() and '/' in l}
got = []
for path in libs:
    lib = ctypes.CDLL(path)
    for name in ('openblas_get_num_threads', 'openblas_get_num_threads64_',
                 'scipy_openblas_get_num_threads', 'scipy_openblas_get_num_threads64_'):
        f = getattr(lib, name, None)
        if f is not None:
            got.append(f())
            break
print(got)
assert got and all(n == 1 for n in got), got
"""
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
