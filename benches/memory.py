"""Peak memory of one big batch, measured in a fresh process.

    python benches/memory.py [sweep|closed_form|numpy_closed_form] [M] [N]

Prints one JSON object: the peak RSS (getrusage ru_maxrss) after importing planarkin and
building the inputs (baseline), the peak after the call, the bytes of the arrays the call
returns, and the difference: the memory the call needed beyond its own output.
"""

from __future__ import annotations

import json
import os
import resource
import sys
import time

import numpy as np
import planarkin as pk
from planarkin.reference import closed_form_vectorized
from planarkin.tradeoff import random_crank_rockers


def maxrss() -> int:
    """Peak resident set size of this process so far, in bytes (Linux reports KiB)."""
    r = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return r if sys.platform == "darwin" else r * 1024


def main(kind: str = "sweep", m: int = 100_000, n: int = 361) -> dict:
    links = random_crank_rockers(m, seed=5)
    theta2 = np.linspace(0.0, 2 * np.pi, n)
    # warm up on a tiny batch: thread pool, lazy imports, first-call allocations
    pk.sweep_batch(links[:4], theta2)
    pk.closed_form_batch(links[:4], theta2)
    closed_form_vectorized(*(links[:4, k : k + 1] for k in range(4)), theta2)
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
