"""Retrieval: the atlas entries whose curves' descriptors are nearest a target's. An exact
scan (one BLAS product) below :data:`APPROXIMATE_FROM` entries; above it an inverted-file
index (faiss IVF-Flat, the ``index`` extra) built once and kept beside the atlas."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from .._kernel import atlas_describe

#: entries from which an approximate index pays (below, the exact scan takes < 20 ms)
APPROXIMATE_FROM = 2_000_000
#: inverted lists probed per query (recall@100 on 10 million four-bars: see BENCHMARKS.md)
NPROBE = 128


@dataclass(frozen=True)
class Candidates:
    """Atlas entries nearest a target, nearest first: ``rows`` index the atlas's columns,
    ``distance`` is the Euclidean distance between descriptors (over the normalisation's
    variants, the nearest)."""

    #: the Atlas they come from
    atlas: Any
    rows: np.ndarray
    distance: np.ndarray

    def __len__(self) -> int:
        return int(self.rows.size)

    @property
    def params(self) -> np.ndarray:
        """The candidates' parameters."""
        return self.atlas.params[self.rows]

    @property
    def signs(self) -> np.ndarray:
        """The candidates' assembly signs."""
        return self.atlas.signs[self.rows]


def descriptor_variants(points: np.ndarray, closed: bool) -> np.ndarray:
    """The target's descriptors a query asks with: the curve and the curve reversed, each
    with the even harmonics' sign as computed and flipped (the one ambiguity the
    normalisation leaves); (V, D) float32."""
    pts = np.ascontiguousarray(points, dtype=np.float64)
    out = []
    for p in (pts, np.ascontiguousarray(pts[::-1])):
        d = atlas_describe(p, bool(closed))
        if d is None:
            raise ValueError("target: its points have no extent (all at one place)")
        even = (np.arange(d.size) // 4 + 1) % 2 == 0
        out += [d, np.where(even, -d, d)]
    return np.unique(np.asarray(out, dtype=np.float32), axis=0)


def _subset(atlas: Any, closed: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The rows a target may use, their descriptors and those's squared norms (kept with
    the atlas): a closed target needs an input that turns fully; an open one may use any."""
    key = f"rows-{closed}"
    if key not in atlas._indexes:
        if closed:
            rows = np.flatnonzero(atlas.full_turn)
            base = np.ascontiguousarray(atlas.descriptor[rows])
        else:
            # every row: the atlas's own (contiguous) descriptors, not a copy of them
            rows = np.arange(len(atlas))
            base = np.ascontiguousarray(atlas.descriptor)
        atlas._indexes[key] = (rows, base, np.einsum("ij,ij->i", base, base))
    return atlas._indexes[key]


def exact_search(
    base: np.ndarray, queries: np.ndarray, k: int, norms: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """The k nearest rows of ``base`` (N, D) to each query (V, D): (distances, rows), both
    (V, k), by one matrix product; ``norms`` (N,) the rows' squared norms if known."""
    k = min(k, base.shape[0])
    if norms is None:
        norms = np.einsum("ij,ij->i", base, base)
    # |x - q|^2 up to the query's own norm, which does not change the order
    d2 = np.ascontiguousarray((base @ (-2.0 * queries.T)).T)
    d2 += norms[None, :]
    part = np.argpartition(d2, k - 1, axis=1)[:, :k]
    dist = np.take_along_axis(d2, part, axis=1).astype(np.float64)
    dist += np.einsum("ij,ij->i", queries, queries)[:, None]
    order = np.argsort(dist, axis=1)
    rows = np.take_along_axis(part, order, axis=1)
    return np.sqrt(np.maximum(np.take_along_axis(dist, order, axis=1), 0.0)), rows


def require_faiss() -> Any:
    """faiss, or a one-line error naming the extra that brings it."""
    try:
        import faiss
    except ImportError:
        raise ImportError(
            'an approximate atlas index needs faiss: pip install "planarkin[index]"'
        ) from None
    return faiss


def ivf_index(atlas: Any, closed: bool, nlist: int | None = None) -> Any:
    """The IVF-Flat index of the atlas's (closed: full-turn) entries, built once per atlas
    (kept in memory, and beside an atlas on disk as index-*.faiss)."""
    faiss = require_faiss()
    key = f"ivf-{'closed' if closed else 'all'}"
    if key in atlas._indexes:
        return atlas._indexes[key]
    base = _subset(atlas, closed)[1]
    n, dim = base.shape
    nlist = nlist or int(np.clip(4 * np.sqrt(n), 16, 16384))
    file = atlas.path / f"index-{key}-{nlist}.faiss" if atlas.path else None
    if file is not None and file.is_file():
        index = faiss.read_index(str(file))
    else:
        index = faiss.IndexIVFFlat(faiss.IndexFlatL2(dim), dim, nlist)
        rng = np.random.default_rng(0)
        train = base[rng.choice(n, size=min(n, 64 * nlist), replace=False)]
        index.train(np.ascontiguousarray(train))
        index.add(np.ascontiguousarray(base))
        if file is not None:
            faiss.write_index(index, str(file))
    atlas._indexes[key] = index
    return index


def query(
    atlas: Any,
    target: Any,
    k: int = 100,
    *,
    closed: bool | None = None,
    method: str = "auto",
    nprobe: int = NPROBE,
) -> Candidates:
    """The ``k`` atlas entries whose descriptors are nearest the target's (a CurveTarget,
    or an (n, 2) array of points with ``closed``). ``method``: "exact" (a BLAS scan),
    "ivf" (faiss IVF-Flat, ``nprobe`` lists) or "auto" (ivf from
    :data:`APPROXIMATE_FROM` entries where faiss is installed)."""
    if int(k) != k or k < 1:
        raise ValueError(f"k must be an integer >= 1, got {k!r}")
    if method not in ("auto", "exact", "ivf"):
        raise ValueError(f"method must be 'auto', 'exact' or 'ivf', got {method!r}")
    points = getattr(target, "points", target)
    if closed is None:
        closed = getattr(target, "kind", "closed") == "closed"
    points = np.asarray(points, dtype=np.float64)
    if points.ndim != 2 or points.shape[1] != 2 or points.shape[0] < 3:
        raise ValueError(f"target must be >= 3 points of shape (n, 2), got {points.shape}")
    q = descriptor_variants(points, closed)
    sub, base, norms = _subset(atlas, closed)
    if sub.size == 0:
        return Candidates(atlas, np.zeros(0, np.int64), np.zeros(0))
    if method == "auto":
        method = "exact"
        if sub.size >= APPROXIMATE_FROM:
            try:
                require_faiss()
                method = "ivf"
            except ImportError:
                pass
    if method == "ivf":
        index = ivf_index(atlas, closed)
        index.nprobe = int(nprobe)
        d2, rows = index.search(q, int(min(k, sub.size)))
        dist = np.sqrt(np.maximum(d2, 0.0))
    else:
        dist, rows = exact_search(base, q, int(k), norms)
    dist, rows = dist.ravel(), rows.ravel()
    ok = rows >= 0
    dist, rows = dist[ok], sub[rows[ok]]
    order = np.argsort(dist, kind="stable")
    rows, first = np.unique(rows[order], return_index=True)
    keep = np.argsort(first)[:k]
    return Candidates(atlas, rows[keep], dist[order][first[keep]])
