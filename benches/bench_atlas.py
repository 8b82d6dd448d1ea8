"""The atlas of path synthesis (issue 33): building entries (random linkage, coupler curve,
descriptor) per topology, retrieval of the top 100 from the default four-bar atlas by the
exact scan, and the placement of the retrieved candidates onto a target. Correctness is
checked outside the timed calls (tests/atlas). The 10-million-entry build through Dask and
the faiss index's recall are measured by benches/atlas_scale.py (minutes, not a
pytest-benchmark)."""

from __future__ import annotations

import numpy as np
import planarkin as pk
import pytest
from conftest import record
from planarkin import _kernel as k

N = {"four-bar": 100_000, "slider-crank": 100_000, "watt2": 50_000}


@pytest.mark.parametrize("topology", list(N))
def test_atlas_build(benchmark, topology):
    n = N[topology]
    label = f"atlas: {n} {topology} entries built (linkage, 128-point curve, descriptor)"
    record(benchmark, f"atlas_build_{topology}", label, entries=n)
    benchmark.group = "atlas: building"
    p, s, full, cond, d = benchmark.pedantic(
        k.atlas_shard, args=(topology, 0, 0, n), rounds=3, iterations=1
    )
    assert np.isfinite(d).all() and p.shape[0] == n
    benchmark.extra_info["entries_per_second"] = n / benchmark.stats.stats.median


@pytest.fixture(scope="module")
def default_atlas():
    return pk.atlas.default("four-bar")


def _target(atlas, i):
    pts, _, _, _ = k.atlas_curve("four-bar", atlas.params[i], atlas.signs[i].astype(float), 60)
    z = (pts[:, 0] + 1j * pts[:, 1]) * 4 * np.exp(1.3j) + 2
    return np.column_stack([z.real, z.imag])


def test_atlas_query_exact(benchmark, default_atlas):
    i = int(np.flatnonzero(default_atlas.full_turn)[1234])
    t = _target(default_atlas, i)
    record(
        benchmark,
        "atlas_query_exact",
        f"atlas: top 100 of the default four-bar atlas ({len(default_atlas)} entries), exact scan",
    )
    benchmark.group = "atlas: retrieval"
    got = benchmark(default_atlas.query, t, 100, closed=True, method="exact")
    assert got.rows[0] == i


def test_atlas_placement(benchmark, default_atlas):
    from planarkin.synthesis.path.search import place
    from planarkin.synthesis.path.targets import CurveTarget

    i = int(np.flatnonzero(default_atlas.full_turn)[99])
    t = CurveTarget(_target(default_atlas, i), "closed")
    rows = default_atlas.query(t.points, 300, closed=True).rows
    record(benchmark, "atlas_place_300", "atlas: 300 candidates placed onto a closed target")
    benchmark.group = "atlas: retrieval"
    got = benchmark(place, default_atlas, t, rows)
    assert got[0].row == i and got[0].cost < 1e-3
