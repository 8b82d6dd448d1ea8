"""The atlas at scale: builds a large atlas through Dask (a LocalCluster on this machine),
reports its build time, entries per second, size on disk and this process's peak memory,
then the retrieval of the top 100 (exact scan against faiss IVF-Flat): recall@100 and
query time, median of many queries. Writes a JSON report.

    python benches/atlas_scale.py --size 10000000 --out /tmp/atlas10m \
        --report benches/results/atlas_scale.json
"""

from __future__ import annotations

import argparse
import json
import platform
import resource
import statistics
import time
from pathlib import Path

import numpy as np
import planarkin as pk
from planarkin import _kernel as k


def _du(path: Path) -> int:
    return sum(f.stat().st_size for f in path.iterdir() if f.is_file())


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--topology", default="four-bar")
    ap.add_argument("--size", type=int, default=10_000_000)
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--queries", type=int, default=50)
    ap.add_argument("--no-query", action="store_true", help="build and measure it, no queries")
    ap.add_argument("--report", type=Path)
    a = ap.parse_args()
    t0 = time.perf_counter()
    files = pk.atlas.build(a.topology, a.size, a.out, workers=a.workers)
    build_s = time.perf_counter() - t0
    fresh = files.manifest["build"]["seconds"]
    if a.no_query:
        report = {
            "command": f"python benches/atlas_scale.py --topology {a.topology} --size {a.size} "
            f"--out {a.out} --no-query",
            "topology": a.topology,
            "size": a.size,
            "workers": a.workers,
            "build_seconds_fresh": fresh,
            "entries_per_second": round(a.size / fresh, 0),
            "disk_bytes": _du(a.out),
            "peak_rss_bytes_this_process": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
            * 1024,
        }
        print(json.dumps(report, indent=1))
        if a.report:
            a.report.write_text(json.dumps(report, indent=1) + "\n")
        return
    t0 = time.perf_counter()
    atlas = files.open()
    load_s = time.perf_counter() - t0
    rng = np.random.default_rng(0)
    rows = rng.choice(np.flatnonzero(atlas.full_turn), a.queries, replace=False)
    targets = []
    for i in rows:
        pts, _, _, _ = k.atlas_curve(a.topology, atlas.params[i], atlas.signs[i].astype(float), 64)
        # a noisy copy of the curve, turned and scaled: not the entry's own descriptor
        z = (pts[:, 0] + 1j * pts[:, 1]) * 2.5 * np.exp(0.9j) + 3
        z += rng.normal(0, 2e-3 * np.ptp(z.real), z.size) * (1 + 1j)
        targets.append(np.column_stack([z.real, z.imag]))
    t0 = time.perf_counter()
    pk.atlas.query(atlas, targets[0], 100, closed=True, method="ivf")
    index_s = time.perf_counter() - t0
    out = {}
    for method in ("exact", "ivf"):
        times, found = [], []
        for t in targets:
            s = time.perf_counter()
            found.append(pk.atlas.query(atlas, t, 100, closed=True, method=method).rows)
            times.append(time.perf_counter() - s)
        out[method] = (statistics.median(times), found)
    pairs = zip(out["exact"][1], out["ivf"][1], strict=True)
    recall = [np.intersect1d(e, f).size / 100 for e, f in pairs]
    # how much farther the approximate 100th neighbour is than the exact one: where the
    # recall is low the neighbours are nearly equidistant (a dense cluster of curves)
    ratio = []
    for t in targets[:20]:
        e = pk.atlas.query(atlas, t, 100, closed=True, method="exact").distance[-1]
        v = pk.atlas.query(atlas, t, 100, closed=True, method="ivf").distance[-1]
        ratio.append(v / e)
    report = {
        "command": f"python benches/atlas_scale.py --size {a.size} --out {a.out}",
        "machine": f"{platform.machine()}, 2 cores (shared)",
        "topology": a.topology,
        "size": a.size,
        "full_turn_entries": int(atlas.full_turn.sum()),
        "workers": a.workers,
        "build_seconds_this_run": round(build_s, 2),
        "build_seconds_fresh": fresh,
        "entries_per_second": round(a.size / fresh, 0),
        "disk_bytes": _du(a.out),
        "open_seconds": round(load_s, 2),
        "peak_rss_bytes_this_process": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024,
        "ivf_index_build_seconds": round(index_s, 2),
        "query_top100_median_ms": {m: round(v[0] * 1e3, 2) for m, v in out.items()},
        "recall_at_100_ivf_vs_exact": {
            "mean": float(np.mean(recall)),
            "min": float(np.min(recall)),
        },
        "distance_100th_ivf_over_exact": {"median": float(np.median(ratio)), "max": max(ratio)},
        "nprobe": pk.atlas.NPROBE,
    }
    text = json.dumps(report, indent=1)
    print(text)
    if a.report:
        a.report.write_text(text + "\n")


if __name__ == "__main__":
    main()
