"""Fixtures shared by every test folder. The independent truth they check against is in
truth.py, and helpers the folders share are in _support.py (both importable from any
folder: ``pythonpath = ["tests"]`` in pyproject.toml)."""

from __future__ import annotations

import os
import signal

import numpy as np
import pytest

# A runner started as a background job of a shell without job control (`cmd &`) has
# SIGINT ignored, and every process it starts inherits that: the Ctrl-C tests' children
# would never see their SIGINT. A handler, unlike "ignored", is reset to the default in
# a child at exec, so the children start as they would from a terminal.
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)


@pytest.fixture(autouse=True, scope="session")
def _private_cache(tmp_path_factory):
    """Default atlases (path synthesis) go to a cache of the session's own, never the
    user's: built once per session, by whichever test needs one first."""
    old = os.environ.get("PLANARKIN_CACHE")
    os.environ["PLANARKIN_CACHE"] = str(tmp_path_factory.mktemp("planarkin-cache"))
    yield
    if old is None:
        os.environ.pop("PLANARKIN_CACHE", None)
    else:
        os.environ["PLANARKIN_CACHE"] = old


def pytest_configure(config: pytest.Config) -> None:
    # the inner loop (`pytest -m "not slow"`) runs each property test on a quarter of its
    # examples (_support.examples reads this); any other run, plain `pytest` included, on
    # all of them. Set either way, so that a value left in the shell cannot weaken a full run
    inner = "not slow" in (config.getoption("markexpr") or "")
    os.environ["PLANARKIN_TESTS_INNER_LOOP"] = "1" if inner else "0"


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
