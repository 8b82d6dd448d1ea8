"""Fixtures shared by every test folder. The independent truth they check against is in
truth.py, and helpers the folders share are in _support.py (both importable from any
folder: ``pythonpath = ["tests"]`` in pyproject.toml)."""

from __future__ import annotations

import signal

import numpy as np
import pytest

# A runner started as a background job of a shell without job control (`cmd &`) has
# SIGINT ignored, and every process it starts inherits that: the Ctrl-C tests' children
# would never see their SIGINT. A handler, unlike "ignored", is reset to the default in
# a child at exec, so the children start as they would from a terminal.
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)


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
