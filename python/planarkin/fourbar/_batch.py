"""Many four-bars at once: sweeps and closed forms of an (M, 4) array of linkages, in
parallel in the kernel with the GIL released, returned as (M, N) arrays."""

from __future__ import annotations

import numpy as np

from .. import _kernel
from .._args import as_angles, as_i64, as_str, as_theta2_1d, sweep_inputs
from ._model import _KERNEL_GEOMETRY
from ._results import BatchSweep


def _threads(threads: object) -> int | None:
    return None if threads is None else as_i64("threads", threads)


def _links(links: object) -> np.ndarray:
    arr = as_angles("links", links)
    if arr.ndim != 2 or arr.shape[1] != 4:
        raise ValueError(f"links must have shape (M, 4), got {arr.shape}")
    return arr


def sweep_batch(
    links: object,
    theta2: object = None,
    *,
    mode: str = "open",
    tol: float = 1e-9,
    max_iter: int = 100,
    predictor: str = "quadratic",
    method: str = "newton",
    threads: int | None = None,
) -> BatchSweep:
    """Sweeps M linkages (an (M, 4) array of r1, r2, r3, r4) over N crank angles, in
    parallel over linkages with the GIL released. Returns (M, N) arrays. ``threads=None``
    uses all cores; ``method="closed-form"`` as in :meth:`FourBar.sweep`."""
    arr = _links(links)
    a = sweep_inputs(theta2, mode, tol, max_iter, predictor, method)
    th = _threads(threads)
    out = _kernel.sweep_batch(arr, a.theta2, a.mode, a.tol, a.max_iter, a.predictor, a.method, th)
    return BatchSweep(arr, a.mode, a.theta2, *out, a.method, geometry=_KERNEL_GEOMETRY)


def closed_form_batch(
    links: object,
    theta2: object = None,
    mode: str = "open",
    *,
    threads: int | None = None,
    out: tuple[np.ndarray, np.ndarray] | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Closed-form (theta3, theta4) for M linkages at N crank angles: (M, N) arrays, NaN
    where a linkage cannot assemble.

    ``out=(theta3, theta4)``: two writable, C-contiguous float64 arrays of shape (M, N)
    that share no memory, written in place and returned (a loop over many batches then
    writes into memory it already has, rather than new arrays the system must first
    clear)."""
    arr = _links(links)
    t2 = as_theta2_1d(theta2)
    mode = as_str("mode", mode)
    if out is not None:
        _check_out(out)
    return _kernel.closed_form_batch(arr, t2, mode, _threads(threads), out)


def _check_out(out: object) -> None:
    """A ValueError naming ``out`` unless it is two float64 arrays that share no memory (the
    kernel checks their shape, order and writability, and that they share none with the
    inputs)."""
    if not (isinstance(out, tuple) and len(out) == 2):
        got = type(out).__name__
        raise ValueError(f"out must be a tuple of two arrays (theta3, theta4), got {got}")
    for i, a in enumerate(out):
        if not isinstance(a, np.ndarray) or a.dtype != np.float64:
            got = a.dtype if isinstance(a, np.ndarray) else type(a).__name__
            raise ValueError(f"out[{i}] must be a float64 array, got {got}")
    if np.may_share_memory(out[0], out[1]):
        raise ValueError("out[0] and out[1] must not share memory")
