"""The atlas: descriptors' invariances, the same atlas bit for bit from any number of
workers, resumed builds, retrieval that finds a curve's own linkage, and the scene of an
entry checked against the scene solver."""

from __future__ import annotations

import json
import math

import numpy as np
import planarkin as pk
import pytest
from planarkin import _kernel as k
from planarkin.atlas._query import descriptor_variants, exact_search
from planarkin.synthesis.path.templates import input_offset, scene_of

pytest.importorskip("pyarrow")


def _curve(topology: str, seed: int, i: int, n: int = 90):
    p, s, full, _, _ = k.atlas_shard(topology, seed, 0, i + 1)
    pts, th, closed, _ = k.atlas_curve(topology, p[i], s[i].astype(float), n)
    return p[i], s[i], pts, th, closed


def _similar(pts: np.ndarray, a: complex, b: complex) -> np.ndarray:
    z = a * (pts[:, 0] + 1j * pts[:, 1]) + b
    return np.column_stack([z.real, z.imag])


def _nearest(d: np.ndarray, variants: np.ndarray) -> float:
    return float(np.min(np.linalg.norm(variants - d[None, :], axis=1)))


@pytest.mark.parametrize("topology", ["four-bar", "slider-crank", "watt2"])
def test_descriptor_ignores_translation_rotation_scale_start_and_direction(topology):
    rng = np.random.default_rng(5)
    p, s, full, _, _ = k.atlas_shard(topology, 11, 0, 40)
    tested = 0
    for i in np.flatnonzero(full)[:8]:
        pts, _, closed, _ = k.atlas_curve(topology, p[i], s[i].astype(float), 240)
        base = k.atlas_describe(pts[:-1], True)
        a = rng.uniform(0.1, 20) * np.exp(1j * rng.uniform(-np.pi, np.pi))
        moved = _similar(
            np.roll(pts[:-1], rng.integers(1, 200), axis=0), a, complex(*rng.normal(0, 50, 2))
        )
        for q in (moved, moved[::-1]):
            variants = descriptor_variants(q, True)
            assert _nearest(base, variants) < 5e-3
        tested += 1
    assert tested >= 3


def test_descriptors_of_different_curves_differ():
    p, s, full, _, d = k.atlas_shard("four-bar", 3, 0, 400)
    rows = np.flatnonzero(full)[:30]
    dist = np.linalg.norm(d[rows, None, :] - d[None, rows, :], axis=2)
    assert np.all(dist[~np.eye(rows.size, dtype=bool)] > 1e-3)


@pytest.mark.parametrize("topology", ["four-bar", "slider-crank", "watt2", "stephenson3"])
def test_an_entry_as_a_scene_traces_the_kernels_curve(topology):
    # the template's scene, solved by the scene solver (numerical continuation), against
    # the atlas kernel's closed form, carried by the same similarity (the Stephenson III
    # has no closed form: its kernel is the scene solver, so for it the independent truth
    # is the next check alone)
    p, s, full, _, _ = k.atlas_shard(topology, 2, 0, 30)
    for i in np.flatnonzero(full)[:3]:
        pts, th, _, _ = k.atlas_curve(topology, p[i], s[i].astype(float), 60)
        a, b = 3.5 * np.exp(2.1j), 10 - 4j
        sc = scene_of(topology, p[i], s[i], a, b, float(th[7]))
        sw = sc.sweep(th + input_offset(a), outputs="all")
        assert np.all(sw.status == 0)
        np.testing.assert_allclose(sw.points["P"], _similar(pts, a, b), atol=1e-11 * 3.5)
        # every link stays rigid: its points keep their drawn distances at every angle
        drawn = sc.points
        for link in sc.to_dict()["links"].values():
            for u, v in zip(link, link[1:] + link[:1], strict=True):
                want = math.dist(drawn[u], drawn[v])
                got = np.hypot(*(sw.points[u] - sw.points[v]).T)
                np.testing.assert_allclose(got, want, atol=1e-9 * 3.5)


def _build(tmp_path, name, **kw):
    return pk.atlas.build("four-bar", 3000, tmp_path / name, shard_size=700, **kw)


def test_the_same_atlas_in_process_and_resumed(tmp_path):
    one = _build(tmp_path, "one", scheduler="synchronous", seed=4)
    assert one.manifest["complete"] and len(one.manifest["shards"]) == 5
    # a stopped build: one shard lost, the manifest not complete
    two = tmp_path / "two"
    _build(tmp_path, "two", scheduler="synchronous", seed=4)
    (two / "shard-00003.parquet").unlink()
    kept = (two / "shard-00001.parquet").stat().st_mtime_ns
    m = json.loads((two / "manifest.json").read_text())
    m["complete"] = False
    (two / "manifest.json").write_text(json.dumps(m))
    with pytest.raises(ValueError, match="incomplete"):
        pk.atlas.open(two)
    again = _build(tmp_path, "two", scheduler="synchronous", seed=4)
    assert (two / "shard-00001.parquet").stat().st_mtime_ns == kept
    assert [s["sha256"] for s in again.manifest["shards"]] == [
        s["sha256"] for s in one.manifest["shards"]
    ]
    a = one.open()
    assert len(a) == 3000 and a.ids.tolist() == list(range(3000))
    # the columns are the kernel's, row for row
    p, s, full, cond, d = k.atlas_shard("four-bar", 4, 0, 3000)
    np.testing.assert_array_equal(a.params, p)
    np.testing.assert_array_equal(a.descriptor, d)
    np.testing.assert_array_equal(a.full_turn, full)
    with pytest.raises(ValueError, match="other options"):
        _build(tmp_path, "two", scheduler="synchronous", seed=5)


@pytest.mark.slow
def test_the_same_atlas_bit_for_bit_from_one_two_workers_and_a_cluster(tmp_path):
    distributed = pytest.importorskip("distributed")
    ref = _build(tmp_path, "sync", scheduler="synchronous")
    two = _build(tmp_path, "two", workers=2)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, dashboard_address=None) as c:
        far = _build(tmp_path, "far", scheduler=c.scheduler_address)
    shas = [[s["sha256"] for s in f.manifest["shards"]] for f in (ref, two, far)]
    assert shas[0] == shas[1] == shas[2]
    for f in ("two", "far"):
        for s in ref.manifest["shards"]:
            assert (tmp_path / f / s["file"]).read_bytes() == (
                tmp_path / "sync" / s["file"]
            ).read_bytes()


def test_bad_options_name_themselves(tmp_path):
    with pytest.raises(ValueError, match="topology"):
        pk.atlas.build("five-bar", 10, tmp_path / "x")
    with pytest.raises(ValueError, match="size"):
        pk.atlas.build("four-bar", 0, tmp_path / "x")
    with pytest.raises(ValueError, match="shard_size"):
        pk.atlas.build("four-bar", 10, tmp_path / "x", shard_size=0)
    with pytest.raises(FileNotFoundError, match="manifest"):
        pk.atlas.open(tmp_path)
    a = pk.atlas.default("four-bar", size=500)
    with pytest.raises(ValueError, match="k must"):
        a.query(np.eye(3, 2), k=0)
    with pytest.raises(ValueError, match="target"):
        a.query(np.zeros((2, 2)))


def test_default_atlas_is_built_once_and_loaded(tmp_path, monkeypatch):
    monkeypatch.setenv("PLANARKIN_CACHE", str(tmp_path))
    a = pk.atlas.default("four-bar", size=2500)
    files = list(tmp_path.glob("atlas-four-bar-2500-*.npz"))
    assert len(files) == 1
    b = pk.atlas.default("four-bar", size=2500)
    np.testing.assert_array_equal(a.descriptor, b.descriptor)
    p, *_ = k.atlas_shard("four-bar", 0, 0, 2500)
    np.testing.assert_array_equal(b.params, p)


def test_retrieval_finds_the_linkage_a_curve_came_from():
    a = pk.atlas.default("four-bar", size=20000)
    rng = np.random.default_rng(8)
    for i in rng.choice(np.flatnonzero(a.full_turn), 5, replace=False):
        pts, _, _, _ = k.atlas_curve("four-bar", a.params[i], a.signs[i].astype(float), 47)
        moved = _similar(np.roll(pts, 11, axis=0), 0.3 * np.exp(0.4j), 7 + 2j)
        got = a.query(moved, k=10, closed=True)
        assert got.rows[0] == i
        # a closed target only gets inputs that turn fully
        assert a.full_turn[got.rows].all()


def test_exact_search_against_brute_force():
    rng = np.random.default_rng(1)
    base = rng.normal(size=(500, 32)).astype(np.float32)
    q = rng.normal(size=(3, 32)).astype(np.float32)
    dist, rows = exact_search(base, q, 7)
    full = np.linalg.norm(base[None, :, :].astype(np.float64) - q[:, None, :], axis=2)
    np.testing.assert_array_equal(rows, np.argsort(full, axis=1)[:, :7])
    np.testing.assert_allclose(dist, np.sort(full, axis=1)[:, :7], rtol=1e-5)


def test_ivf_index_recall_against_the_exact_scan():
    pytest.importorskip("faiss")
    a = pk.atlas.default("four-bar", size=200_000)
    rng = np.random.default_rng(2)
    recalls = []
    for i in rng.choice(np.flatnonzero(a.full_turn), 10, replace=False):
        pts, _, _, _ = k.atlas_curve("four-bar", a.params[i], a.signs[i].astype(float), 64)
        ex = a.query(pts, 100, closed=True, method="exact")
        ap = a.query(pts, 100, closed=True, method="ivf")
        recalls.append(np.intersect1d(ex.rows, ap.rows).size / 100)
    assert np.mean(recalls) >= 0.9, recalls
    assert math.isfinite(np.mean(recalls))


def test_curve_matching_names_the_length_that_is_wrong():
    """The kernel's placement of ready-made curves checks each argument's length on its own:
    a wrong ``closed`` is named, not reported as points of the right length."""
    from planarkin import _core

    points, theta, target = np.zeros((6, 2)), np.zeros((2, 3)), np.eye(4, 2)
    with pytest.raises(ValueError, match=r"closed has length 3, expected 2"):
        _core.atlas_match_curves(points, theta, [True] * 3, target, True, 4, 8)
    with pytest.raises(ValueError, match=r"points has length 6, expected 9"):
        _core.atlas_match_curves(points, np.zeros((3, 3)), [True] * 3, target, True, 4, 8)
