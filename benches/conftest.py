"""Shared fixtures for the benchmarks (``pytest benches/ --benchmark-enable``).

Every benchmark records ``extra_info["label"]`` (the row name in BENCHMARKS.md) and
``extra_info["impl"]`` (a stable key that ``benches/report_targets.py`` uses for ratios and
targets). Correctness is checked outside the timed call, so a fast wrong answer fails.
"""

from __future__ import annotations

import os
import sys
from functools import cache

import numpy as np
import planarkin as pk
import pytest

sys.path.insert(0, os.path.dirname(__file__))

import peers  # noqa: E402

THETA2 = pk.DEFAULT_THETA2


@cache
def links(m: int) -> np.ndarray:
    """The benchmark batch of M linkages: the seed linkage first, then random
    crank-rockers (every angle assembles, so every implementation solves every point)."""
    if m == 1:
        return np.array([peers.SEED])
    return np.vstack([np.array([peers.SEED]), peers.random_links(m - 1, seed=2024)])


@cache
def closed_truth(m: int) -> tuple[np.ndarray, np.ndarray]:
    """planarkin's closed form of the open mode at THETA2 for ``links(m)``: the yardstick
    the benchmarks check every implementation's angles against."""
    return pk.closed_form_batch(links(m), THETA2)


def max_angle_error(a, b) -> float:
    d = np.abs(np.asarray(a, dtype=float) - np.asarray(b, dtype=float))
    d = np.minimum(d, 2 * np.pi - d)
    return float(np.nanmax(d))


@pytest.fixture
def seed_fb() -> pk.FourBar:
    return pk.FourBar(*peers.SEED)


def record(benchmark, impl: str, label: str, **info) -> None:
    benchmark.extra_info["impl"] = impl
    benchmark.extra_info["label"] = label
    benchmark.extra_info.update(info)
