"""Fixtures shared by every test folder. The independent truth they check against is in
truth.py, and helpers the folders share are in _support.py (both importable from any
folder: ``pythonpath = ["tests"]`` in pyproject.toml)."""

from __future__ import annotations

import numpy as np
import pytest


@pytest.fixture
def scalar_path():
    """The bit-exact scalar path (SIMD kernels off) for the duration of a test: what the
    bit-for-bit parity tests with ``planarkin.reference`` compare."""
    import planarkin as pk

    with pk.use_simd(False):
        yield


@pytest.fixture
def rng():
    return np.random.default_rng(20240601)
