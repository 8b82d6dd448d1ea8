"""The switch between the SIMD kernels (the default where the CPU has AVX2 and FMA) and
the scalar path, which is bit-identical to ``planarkin.reference``.

The SIMD kernels evaluate sin/cos/atan2 by polynomials (within 2 ulp of glibc) 4 values
at a time; their statuses are the scalar path's, their angles agree with it and with the
NumPy reference to 1e-12 rad (measured: below 1e-13 rad, most points within a few ulp;
see benches/analysis.md). ``PLANARKIN_SIMD=0`` in the environment starts with the scalar
path.

>>> import planarkin as pk
>>> with pk.use_simd(False):
...     s = pk.FourBar(6, 2, 5, 5).sweep()  # bit-identical to pk.reference.sweep
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

from . import _kernel


def set_simd(enabled: bool) -> bool:
    """Uses the SIMD kernels (where the CPU has them) or the bit-exact scalar path, for the
    whole process; returns the previous setting."""
    return _kernel.set_simd(bool(enabled))


def simd_enabled() -> bool:
    """Whether the SIMD kernels are in use."""
    return _kernel.simd_enabled()


def simd_available() -> bool:
    """Whether this CPU has what the SIMD kernels need (AVX2 and FMA)."""
    return _kernel.simd_available()


@contextmanager
def use_simd(enabled: bool) -> Iterator[None]:
    """Within the block, SIMD kernels on or off; the previous setting afterwards. The
    setting is process-wide: do not switch it while other threads compute."""
    was = set_simd(enabled)
    try:
        yield
    finally:
        set_simd(was)
