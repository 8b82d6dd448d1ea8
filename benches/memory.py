"""Peak memory of one big batch, measured in a fresh process.

    python benches/memory.py [sweep|closed_form|numpy_closed_form] [M] [N]

Prints one JSON object: the peak RSS after importing planarkin, building the inputs and
a small warm-up call (baseline; on Linux the kernel's peak mark VmHWM is reset to the
current RSS there), the peak after the call, the bytes of the arrays the call returns,
and the difference: the memory the call needed beyond its own output.
"""

from __future__ import annotations

import json
import os
import resource
import sys
import time

import numpy as np
import planarkin as pk
from planarkin.fourbar.tradeoff import random_crank_rockers
from planarkin.reference import closed_form_vectorized


def _status(field: str) -> int | None:
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith(field + ":"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return None


def reset_peak() -> bool:
    """Resets the kernel's peak-RSS mark (VmHWM) to the current RSS (Linux >= 4.0)."""
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
        return True
    except OSError:
        return False


def maxrss() -> int:
    """Peak resident set size so far, in bytes. On Linux VmHWM, which reset_peak() can
    lower: getrusage's ru_maxrss also counts the parent's RSS at fork, inherited across
    exec, so under pytest it starts at the size of the pytest process."""
    hwm = _status("VmHWM")
    if hwm is not None:
        return hwm
    r = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return r if sys.platform == "darwin" else r * 1024


def main(kind: str = "sweep", m: int = 100_000, n: int = 361) -> dict:
    links = random_crank_rockers(m, seed=5)
    theta2 = np.linspace(0.0, 2 * np.pi, n)
    # warm up on a tiny batch: thread pool, lazy imports, first-call allocations
    pk.sweep_batch(links[:4], theta2)
    pk.closed_form_batch(links[:4], theta2)
    closed_form_vectorized(*(links[:4, k : k + 1] for k in range(4)), theta2)
    reset_peak()
    base = maxrss()
    t0 = time.perf_counter()
    if kind == "sweep":
        b = pk.sweep_batch(links, theta2)
        out = (b.theta3, b.theta4, b.status, b.nit, b.residual)
    elif kind == "closed_form":
        out = pk.closed_form_batch(links, theta2)
    elif kind == "numpy_closed_form":
        out = closed_form_vectorized(*(links[:, k : k + 1] for k in range(4)), theta2)
    else:
        raise SystemExit(f"unknown kind {kind!r}")
    secs = time.perf_counter() - t0
    peak = maxrss()
    out_bytes = sum(a.nbytes for a in out)
    return {
        "kind": kind,
        "m": m,
        "n": n,
        "threads": os.cpu_count(),
        "baseline_bytes": base,
        "peak_bytes": peak,
        "delta_bytes": peak - base,
        "output_bytes": out_bytes,
        "overhead_bytes": peak - base - out_bytes,
        "seconds": secs,
    }


if __name__ == "__main__":
    args = sys.argv[1:]
    kind = args[0] if args else "sweep"
    m = int(args[1]) if len(args) > 1 else 100_000
    n = int(args[2]) if len(args) > 2 else 361
    print(json.dumps(main(kind, m, n)))
