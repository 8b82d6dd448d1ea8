"""Growth with the number of crank angles N and of linkages M (it should be linear: the
time per point constant), and the per-call overhead of a one-point solve."""

from __future__ import annotations

import math

import numpy as np
import peers
import planarkin as pk
import pytest
from conftest import links, record
from planarkin.reference import closed_form_vectorized

STEP = 2 * math.pi / 360


@pytest.mark.parametrize("n", [361, 3_610, 36_100, 361_000])
def test_growth_n(benchmark, seed_fb, n):
    """One linkage, N angles 1 degree apart (N/360 turns): the same work per point."""
    benchmark.group = "growth with N: seed linkage, N angles 1 deg apart"
    t2 = np.arange(n) * STEP
    s = benchmark(seed_fb.sweep, t2)
    assert s.summary().converged == n
    record(
        benchmark, "growth_n", f"fb.sweep(), N = {n}", n=n, points=n, nit_mean=float(s.nit.mean())
    )


@pytest.mark.parametrize("m", [10, 100, 1_000, 10_000])
def test_growth_m(benchmark, m):
    benchmark.group = "growth with M: M linkages x 361 angles, 1 thread"
    b = benchmark(pk.sweep_batch, links(m), threads=1)
    assert b.success.all()
    record(
        benchmark,
        "growth_m",
        f"sweep_batch(threads=1), M = {m}",
        m=m,
        points=m * 361,
        nit_mean=float(b.nit.mean()),
    )


OVERHEAD = "overhead: one crank angle"


@pytest.mark.benchmark(group=OVERHEAD)
def test_overhead_solve(benchmark, seed_fb):
    s = benchmark(seed_fb.solve, 0.3)
    assert s.success
    record(benchmark, "ovh_solve", "fb.solve(0.3) (public API)")


@pytest.mark.benchmark(group=OVERHEAD)
def test_overhead_binding_solve(benchmark, seed_fb):
    benchmark(seed_fb._core.solve, 0.3, "open", None, 1e-9, 100, False)
    record(benchmark, "ovh_binding_solve", "fb._core.solve(...) (binding alone)")


@pytest.mark.benchmark(group=OVERHEAD)
def test_overhead_sweep_one(benchmark, seed_fb):
    t2 = np.array([0.3])
    benchmark(seed_fb.sweep, t2)
    record(benchmark, "ovh_sweep_1", "fb.sweep([0.3]) (1-point sweep)")


@pytest.mark.benchmark(group=OVERHEAD)
def test_overhead_closed_form(benchmark, seed_fb):
    benchmark(seed_fb.closed_form, 0.3)
    record(benchmark, "ovh_closed_form", "fb.closed_form(0.3)")


@pytest.mark.benchmark(group=OVERHEAD)
def test_overhead_reference_solve(benchmark, seed_fb):
    benchmark(pk.reference.solve, seed_fb, 0.3)
    record(benchmark, "ovh_reference_solve", "pk.reference.solve(fb, 0.3)")


@pytest.mark.benchmark(group=OVERHEAD)
def test_overhead_math_newton(benchmark):
    guess = tuple(float(x) for x in closed_form_vectorized(*peers.SEED, 0.3))
    benchmark(peers.math_newton, *peers.SEED, 0.3, guess)
    record(benchmark, "ovh_math", "plain-Python math Newton, 1 angle from the closed form")


@pytest.mark.benchmark(group=OVERHEAD)
def test_overhead_batch_one(benchmark):
    arr = links(1)
    t2 = np.array([0.3])
    benchmark(pk.sweep_batch, arr, t2, threads=1)
    record(benchmark, "ovh_batch_1", "sweep_batch(1 linkage, 1 angle, threads=1)")
