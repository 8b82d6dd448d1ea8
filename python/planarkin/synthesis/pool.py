"""The pool the starts run on: a process pool whose workers ignore Ctrl-C (it reaches only
the parent) and run BLAS on one thread (the pool already has a process per core), stopped
at once when asked (queued work cancelled, workers terminated), and Ctrl-C held back while
work is submitted."""

from __future__ import annotations

import contextlib
import ctypes
import importlib
import os
import signal
import threading
from collections.abc import Iterator, Sequence
from concurrent.futures import Executor, Future, ProcessPoolExecutor
from typing import Any


def openblas() -> list[tuple[Any, Any]]:
    """The (get, set) thread-count functions of every OpenBLAS loaded in this process
    (NumPy's and SciPy's each bundle their own; a system one too), found once they are
    loaded. Linux only (the loaded libraries are read from /proc/self/maps); elsewhere
    none."""
    global _OPENBLAS
    if _OPENBLAS is not None:  # found before (none found is an answer too)
        return _OPENBLAS
    # NumPy's OpenBLAS and SciPy's (SLSQP's) loaded first, so that both are found
    for name in ("numpy", "scipy.linalg"):
        importlib.import_module(name)
    try:
        with open("/proc/self/maps", encoding="utf-8", errors="replace") as f:
            paths = {ln.split()[-1] for ln in f if "openblas" in ln.lower() and "/" in ln}
    except OSError:
        _OPENBLAS = []
        return _OPENBLAS
    found = []
    for path in sorted(paths):
        try:
            lib = ctypes.CDLL(path)  # already loaded: the same handle
        except OSError:
            continue
        for prefix, suffix in _NAMES:
            get = getattr(lib, f"{prefix}_get_num_threads{suffix}", None)
            put = getattr(lib, f"{prefix}_set_num_threads{suffix}", None)
            if get is not None and put is not None:
                found.append((get, put))
                break
    _OPENBLAS = found
    return found


#: the name prefixes and suffixes of OpenBLAS's thread-count functions in the builds NumPy
#: and SciPy bundle and in a system one
_NAMES = (("scipy_openblas", "64_"), ("scipy_openblas", ""), ("openblas", "64_"), ("openblas", ""))
_OPENBLAS: list[tuple[Any, Any]] | None = None


def one_blas_thread() -> int:
    """Runs every OpenBLAS loaded in this process (NumPy's and SciPy's, each bundles its
    own) on one thread; returns how many libraries were told. A worker of a pool with a
    process per core gains nothing from BLAS threads on SLSQP's small matrices, and
    OpenBLAS threads wait for work spinning: two workers with two spinning threads each
    on two cores ran the default Ackermann search 3 to 4 times slower on a loaded
    machine. Linux only; elsewhere nothing is changed."""
    libs = openblas()
    for _, put in libs:
        put(1)
    return len(libs)


@contextlib.contextmanager
def blas_held_to_one_thread() -> Iterator[None]:
    """:func:`one_blas_thread` for the duration of a block, the thread counts restored
    after: for SLSQP in this process (a path refinement), whose subproblems are a few
    dozen rows (measured: 7 ms an SLSQP step against 0.3 ms single-threaded, on 2 shared
    cores)."""
    held = [(put, int(get())) for get, put in openblas()]
    for put, _ in held:
        put(1)
    try:
        yield
    finally:
        for put, n in held:
            put(n)


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
    # the queued starts cancelled here and now: shutdown(cancel_futures=True) leaves that to
    # the pool's manager thread, which may not have run when this returns
    for item in list((getattr(ex, "_pending_work_items", None) or {}).values()):
        item.future.cancel()
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
