"""Batches of M linkages x 361 crank angles (M = 1, 100, 10 000): planarkin's batch
Newton on one thread and on all threads, its closed-form batch, a vectorized NumPy
Newton-Raphson over the batch (same criterion, same predictor) and the vectorized NumPy
closed form, one group per M."""

from __future__ import annotations

import os

import numpy as np
import peers
import planarkin as pk
import pytest
from conftest import THETA2, closed_truth, links, max_angle_error, record
from planarkin.reference import closed_form_vectorized

SIZES = [1, 100, 10_000]
CORES = os.cpu_count() or 1


def _group(m: int) -> str:
    return f"batch: M={m} x 361 angles"


def _check(m, t3, t4, tol):
    c3, c4 = closed_truth(m)
    err = max(max_angle_error(t3, c3), max_angle_error(t4, c4))
    assert err < tol, err
    return err


@pytest.mark.parametrize("m", SIZES)
@pytest.mark.parametrize("threads", [1, None], ids=["1thread", "allthreads"])
def test_planarkin_sweep_batch(benchmark, m, threads):
    benchmark.group = _group(m)
    arr = links(m)
    b = benchmark(pk.sweep_batch, arr, THETA2, threads=threads)
    assert b.success.all()
    name = "1 thread" if threads == 1 else f"all threads ({CORES})"
    record(
        benchmark,
        f"pk_batch_{'t1' if threads == 1 else 'tall'}",
        f"planarkin sweep_batch, {name}",
        m=m,
        threads=threads or CORES,
        nit_mean=float(b.nit.mean()),
        max_error=_check(m, b.theta3, b.theta4, 1e-8),
    )


@pytest.mark.parametrize("m", SIZES)
def test_planarkin_sweep_batch_across_angles(benchmark, m):
    benchmark.group = _group(m)
    arr = links(m)
    b = benchmark(pk.sweep_batch, arr, THETA2, predictor="closed-form", threads=1)
    assert b.success.all()
    record(
        benchmark,
        "pk_batch_across_t1",
        "planarkin sweep_batch(predictor='closed-form'), 1 thread",
        m=m,
        threads=1,
        nit_mean=float(b.nit.mean()),
        max_error=_check(m, b.theta3, b.theta4, 1e-8),
    )


@pytest.mark.parametrize("m", SIZES)
@pytest.mark.parametrize(
    "threads, into",
    [(1, False), (None, False), (1, True)],
    ids=["1thread", "allthreads", "1thread-out"],
)
def test_planarkin_closed_form_batch(benchmark, m, threads, into):
    """``into``: written into arrays the caller keeps (``out=``), no new memory to clear."""
    benchmark.group = _group(m)
    arr = links(m)
    out = (np.empty((m, THETA2.size)), np.empty((m, THETA2.size))) if into else None
    t3, t4 = benchmark(pk.closed_form_batch, arr, THETA2, threads=threads, out=out)
    name = "1 thread" if threads == 1 else f"all threads ({CORES})"
    key = f"pk_cf_batch_{'t1' if threads == 1 else 'tall'}{'_out' if into else ''}"
    record(
        benchmark,
        key,
        f"planarkin closed_form_batch{'(out=...)' if into else ''}, {name}",
        m=m,
        threads=threads or CORES,
        max_error=_check(m, t3, t4, 1e-15),
    )


def _scalar(f, *args, **kw):
    with pk.use_simd(False):
        return f(*args, **kw)


def test_planarkin_batches_scalar_path(benchmark):
    """The bit-exact scalar path (SIMD kernels off), 1 thread, M = 10 000: the SIMD speed-up."""
    m = 10_000
    benchmark.group = _group(m)
    arr = links(m)
    b = benchmark(_scalar, pk.sweep_batch, arr, THETA2, threads=1)
    assert b.success.all()
    record(
        benchmark,
        "pk_batch_t1_scalar",
        "planarkin sweep_batch, 1 thread, pk.use_simd(False)",
        m=m,
        threads=1,
        nit_mean=float(b.nit.mean()),
        max_error=_check(m, b.theta3, b.theta4, 1e-8),
    )


def test_planarkin_closed_form_batch_scalar_path(benchmark):
    m = 10_000
    benchmark.group = _group(m)
    arr = links(m)
    t3, t4 = benchmark(_scalar, pk.closed_form_batch, arr, THETA2, threads=1)
    record(
        benchmark,
        "pk_cf_batch_t1_scalar",
        "planarkin closed_form_batch, 1 thread, pk.use_simd(False)",
        m=m,
        threads=1,
        max_error=_check(m, t3, t4, 1e-14),
    )


@pytest.mark.parametrize("m", SIZES)
def test_numpy_newton_batch(benchmark, m):
    benchmark.group = _group(m)
    arr = links(m)
    t3, t4, nit = benchmark(peers.numpy_newton_batch, arr, THETA2)
    record(
        benchmark,
        "np_newton_batch",
        "NumPy vectorized Newton-Raphson (quadratic predictor)",
        m=m,
        nit_mean=float(nit.mean()),
        max_error=_check(m, t3, t4, 1e-8),
    )


@pytest.mark.parametrize("m", SIZES)
def test_numpy_closed_form_batch(benchmark, m):
    benchmark.group = _group(m)
    arr = links(m)
    r = [arr[:, k : k + 1] for k in range(4)]  # (M, 1) columns broadcast against (N,)
    t3, t4 = benchmark(closed_form_vectorized, *r, THETA2)
    record(
        benchmark,
        "np_closed_form",
        "NumPy vectorized closed form",
        m=m,
        max_error=_check(m, t3, t4, 1e-14),
    )


def test_numpy_newton_tangent_matches():
    """The tangent variant of the NumPy Newton is correct too (it is slower than the
    quadratic one benchmarked above: more iterations, more array passes)."""
    arr = links(100)
    t3, t4, nit = peers.numpy_newton_batch(arr, THETA2, predictor="tangent")
    assert _check(100, t3, t4, 1e-8) < 1e-8 and 1.0 < nit.mean() < 1.6
