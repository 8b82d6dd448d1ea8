"""The pool the starts run on: a process pool whose workers ignore Ctrl-C (it reaches only
the parent) and run BLAS on one thread (the pool already has a process per core), stopped
at once when asked (queued work cancelled, workers terminated), and Ctrl-C held back while
work is submitted."""

from __future__ import annotations

import ctypes
import importlib
import os
import signal
import threading
from collections.abc import Sequence
from concurrent.futures import Executor, Future, ProcessPoolExecutor
from typing import Any

#: the thread-count setters of the OpenBLAS builds NumPy and SciPy bundle (and a system one)
_BLAS_SETTERS = (
    "openblas_set_num_threads",
    "openblas_set_num_threads64_",
    "scipy_openblas_set_num_threads",
    "scipy_openblas_set_num_threads64_",
)


def one_blas_thread() -> int:
    """Runs every OpenBLAS loaded in this process (NumPy's and SciPy's, each bundles its
    own) on one thread; returns how many libraries were told. A worker of a pool with a
    process per core gains nothing from BLAS threads on SLSQP's small matrices, and
    OpenBLAS threads wait for work spinning: two workers with two spinning threads each
    on two cores ran the default Ackermann search 3 to 4 times slower on a loaded
    machine. Linux only (the loaded libraries are read from /proc/self/maps); elsewhere
    nothing is changed."""
    # NumPy's OpenBLAS and SciPy's (SLSQP's) loaded first, so that both are told
    for name in ("numpy", "scipy.linalg"):
        importlib.import_module(name)

    try:
        with open("/proc/self/maps", encoding="utf-8", errors="replace") as f:
            paths = {ln.split()[-1] for ln in f if "openblas" in ln.lower() and "/" in ln}
    except OSError:
        return 0
    told = 0
    for path in sorted(paths):
        try:
            lib = ctypes.CDLL(path)  # already loaded: the same handle
        except OSError:
            continue
        for name in _BLAS_SETTERS:
            setter = getattr(lib, name, None)
            if setter is not None:
                setter(1)
                told += 1
                break
    return told


def _worker_init() -> None:
    # Ctrl-C goes to the whole process group, and only the parent should act on it (it
    # stops the workers); a worker would print a traceback and go on
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    one_blas_thread()


def process_pool(workers: int | None = None) -> ProcessPoolExecutor:
    """A process pool for :func:`synthesize`: ``workers`` processes (default up to 2)
    that ignore Ctrl-C, so that it reaches only the parent, which stops them
    (:func:`stop_pool`), and run BLAS on one thread each (:func:`one_blas_thread`)."""
    return ProcessPoolExecutor(
        max_workers=workers or min(2, os.cpu_count() or 1), initializer=_worker_init
    )


def stop_pool(ex: Executor) -> None:
    """Stops a pool at once: queued starts are cancelled and, for a process pool, the
    worker processes terminated (``shutdown(cancel_futures=True)`` alone waits for the
    running starts, minutes of SLSQP)."""
    terminate = getattr(ex, "terminate_workers", None)  # Python >= 3.14
    if terminate is not None:
        terminate()
        return
    # before 3.14 a process pool's workers have no public handle
    processes = list((getattr(ex, "_processes", None) or {}).values())
    ex.shutdown(wait=False, cancel_futures=True)
    for p in processes:
        if p.is_alive():
            p.terminate()
    for p in processes:
        p.join(timeout=5)


class SigintDeferred:
    """Ctrl-C held back (raised on exit) while starts are submitted: worker processes are
    forked then, and one forked before its initializer ignores Ctrl-C would print a
    traceback; the pool's own bookkeeping is never cut half way. Only in the main thread
    (the only one Python delivers signals to)."""

    def __enter__(self) -> None:
        self.hits: list[int] = []
        self.old: Any = None
        self.own = threading.current_thread() is threading.main_thread()
        if self.own:
            self.old = signal.signal(signal.SIGINT, lambda sig, frame: self.hits.append(sig))

    def __exit__(self, kind: object, *exc: object) -> None:
        if self.own:
            signal.signal(signal.SIGINT, self.old if self.old is not None else signal.SIG_DFL)
            if self.hits and kind is None:
                raise KeyboardInterrupt


def abandon(futs: Sequence[Future] | dict[Future, int], own: Executor | None) -> None:
    """Cancels what has not run of ``futs`` and stops ``own`` (an own pool) at once."""
    for f in futs:
        f.cancel()
    if own is not None:
        stop_pool(own)
