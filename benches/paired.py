"""Ratios of two implementations measured in interleaved rounds, for a host whose speed
changes over seconds.

pytest-benchmark times one implementation after the other; on a host that alternates
between a fast and a slow phase (this project's, BENCHMARKS.md), a ratio of two medians
taken a minute apart can compare two phases. Here each round times a batch of calls of
one implementation, then a batch of the other (which goes first alternates), so both see
the same phase; the ratio is the median of the rounds' ratios, with its quartiles.

    python benches/paired.py            # writes benches/results/paired.json
    python benches/paired.py --rounds 9 # a smoke run

Pairs: the seed sweep across angles (``fb.sweep(predictor="closed-form")``) against
pylinkage + numba and against NumPy's vectorized closed form, and Jansen's leg (the foot
requested) against pylinkage + numba: the issue 21 ratio targets whose calls take
microseconds. Each implementation's answer is checked against planarkin's closed form
(or the foot's sweep) before timing, as the pytest benchmarks do.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
from collections.abc import Callable

import numpy as np
import planarkin as pk
from planarkin.reference import closed_form_vectorized

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import peers  # noqa: E402
import scene_peers  # noqa: E402
from conftest import THETA2, max_angle_error  # noqa: E402


def _batch(f: Callable[[], object], k: int) -> float:
    """Seconds per call over ``k`` calls."""
    t0 = time.perf_counter()
    for _ in range(k):
        f()
    return (time.perf_counter() - t0) / k


def paired(ours: Callable[[], object], peer: Callable[[], object], rounds: int) -> dict:
    """Interleaved rounds of about 2 ms per side: per-call times of each side (medians)
    and the median and quartiles of the rounds' ratios peer / ours."""
    for f in (ours, peer):  # warm up (numba compiles on its first call)
        f()
    k_ours = max(1, int(2e-3 / _batch(ours, 20)))
    k_peer = max(1, int(2e-3 / _batch(peer, 5)))
    t_ours, t_peer, ratio = [], [], []
    for r in range(rounds):
        if r % 2:
            b, a = _batch(peer, k_peer), _batch(ours, k_ours)
        else:
            a, b = _batch(ours, k_ours), _batch(peer, k_peer)
        t_ours.append(a)
        t_peer.append(b)
        ratio.append(b / a)
    q = statistics.quantiles(ratio, n=4)
    return {
        "ours_s": statistics.median(t_ours),
        "peer_s": statistics.median(t_peer),
        "ratio_median": statistics.median(ratio),
        "ratio_q1": q[0],
        "ratio_q3": q[2],
        "rounds": rounds,
        "calls_per_round": [k_ours, k_peer],
    }


def pairs() -> dict[str, tuple[str, str, Callable[[], object], Callable[[], object]]]:
    """name -> (ours, peer, their callables), each answer checked first."""
    out: dict[str, tuple[str, str, Callable[[], object], Callable[[], object]]] = {}
    fb = pk.FourBar(*peers.SEED)
    c3, c4 = fb.closed_form(THETA2)
    sw = fb.sweep(predictor="closed-form")
    assert max(max_angle_error(sw.theta3, c3), max_angle_error(sw.theta4, c4)) < 1e-12

    def seed() -> object:
        return fb.sweep(predictor="closed-form")

    t3, t4 = closed_form_vectorized(*peers.SEED, THETA2)
    assert max(max_angle_error(t3, c3), max_angle_error(t4, c4)) < 1e-12
    out["seed_across_vs_numpy"] = (
        "planarkin fb.sweep(predictor='closed-form')",
        "NumPy vectorized closed form",
        seed,
        lambda: closed_form_vectorized(*peers.SEED, THETA2),
    )
    try:
        pl = peers.PylinkageFourBar(*peers.SEED)
    except ImportError:
        return out
    p3, p4 = pl.angles(pl.run())
    assert max(max_angle_error(p3, c3), max_angle_error(p4, c4)) < 1e-10
    out["seed_across_vs_pylinkage"] = (
        "planarkin fb.sweep(predictor='closed-form')",
        "pylinkage + numba (step_fast)",
        seed,
        pl.run,
    )
    sc = pk.scenes.load("jansen")
    foot = sc.sweep(outputs=["foot"]).points["foot"]
    pj = scene_peers.PylinkageScene(sc.to_dict())
    assert float(np.abs(pj.run()[:, pj.names.index("foot")] - foot).max()) < 1e-10 * sc._size()
    out["jansen_vs_pylinkage"] = (
        "planarkin sc.sweep(outputs=['foot'])",
        "pylinkage + numba (step_fast)",
        lambda: sc.sweep(outputs=["foot"]),
        pj.run,
    )
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rounds", type=int, default=201, help="interleaved rounds per pair")
    ap.add_argument("--out", default=os.path.join(HERE, "results", "paired.json"))
    args = ap.parse_args(argv)
    res = {}
    for name, (ours, peer, f, g) in pairs().items():
        r = paired(f, g, args.rounds)
        res[name] = {"ours": ours, "peer": peer, **r}
        q = f"quartiles {r['ratio_q1']:.2f}-{r['ratio_q3']:.2f}"
        us = f"{r['ours_s'] * 1e6:.1f} us vs {r['peer_s'] * 1e6:.1f} us"
        print(f"{name}: {r['ratio_median']:.2f} ({q}), {us}")
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w") as fh:
        json.dump(res, fh, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
