"""An atlas on disk and in memory: a manifest (topology, seed, size, shards, versions) and
its shards as Parquet files (one row per linkage: id, parameters, assembly signs, full
turn, conditioning, descriptor), read into NumPy columns."""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .._kernel import (
    ATLAS_DESCRIPTOR,
    ATLAS_HARMONICS,
    ATLAS_SAMPLES,
    ATLAS_TOPOLOGIES,
    __version__,
)
from ._query import query

#: the manifest's file name inside an atlas directory
MANIFEST = "manifest.json"
#: the layout this code writes and reads, and how entries are drawn (raised when either
#: changes: a cached default atlas of another version is rebuilt)
FORMAT_VERSION = 1
#: topology name -> (parameter count, sign count)
TOPOLOGIES: dict[str, tuple[int, int]] = {n: (p, s) for n, p, s in ATLAS_TOPOLOGIES}
#: the parameters' names per topology (the normalised frames of the Rust kernel)
PARAMS: dict[str, tuple[str, ...]] = {
    "four-bar": ("r2", "r3", "r4", "u", "v"),
    "slider-crank": ("r3", "e", "u", "v"),
    "watt2": ("r2", "r3", "r4", "r4c", "beta", "x6", "y6", "r5", "r6", "u", "v"),
    "stephenson3": tuple(f"{p}{c}" for p in ("j6", "j1", "j2", "j4", "j5", "P") for c in "xy"),
}


def topology_checked(topology: str) -> str:
    """``topology`` if the atlas knows it, else a ValueError naming the known ones."""
    if topology not in TOPOLOGIES:
        raise ValueError(f"topology: unknown {topology!r}; known: {', '.join(TOPOLOGIES)}")
    return topology


def require_pyarrow() -> Any:
    """pyarrow, or a one-line error naming the extra that brings it."""
    try:
        import pyarrow
        import pyarrow.parquet  # noqa: F401
    except ImportError:
        raise ImportError('atlas files need pyarrow: pip install "planarkin[atlas]"') from None
    return pyarrow


def manifest_of(topology: str, seed: int, size: int) -> dict[str, Any]:
    """What every atlas's manifest says of it: format, topology, seed, size, parameters,
    signs, descriptor and the planarkin that made it."""
    return {
        "format": "planarkin-atlas",
        "version": FORMAT_VERSION,
        "topology": topology,
        "seed": seed,
        "size": size,
        "params": list(PARAMS[topology]),
        "signs": TOPOLOGIES[topology][1],
        "descriptor": descriptor_info(),
        "planarkin": __version__,
    }


def descriptor_info() -> dict[str, Any]:
    """What the descriptor is (recorded in every manifest)."""
    return {
        "kind": "complex Fourier, arc-length resampled, first-harmonic normalised",
        "harmonics": ATLAS_HARMONICS,
        "length": ATLAS_DESCRIPTOR,
        "curve_samples": ATLAS_SAMPLES,
    }


@dataclass
class Atlas:
    """The linkages of one topology with their curves' descriptors, as columns:
    ``params`` (N, P), ``signs`` (N, S) of +1/-1, ``full_turn`` (N,), ``conditioning``
    (N,) (the smallest transmission sine over the curve), ``descriptor`` (N, D) float32,
    ``ids`` (N,) the entries' indices in the atlas (entry i is a function of the seed and i
    alone). ``manifest`` says how it was made; ``path`` where it lives (None in memory)."""

    manifest: dict[str, Any]
    params: np.ndarray
    signs: np.ndarray
    full_turn: np.ndarray
    conditioning: np.ndarray
    descriptor: np.ndarray
    ids: np.ndarray
    path: Path | None = None
    _indexes: dict[str, Any] = field(default_factory=dict, repr=False)

    @property
    def topology(self) -> str:
        """The linkages' topology."""
        return str(self.manifest["topology"])

    def __len__(self) -> int:
        return int(self.ids.size)

    def __repr__(self) -> str:
        where = f" at {self.path}" if self.path else ""
        return (
            f"Atlas({self.topology}, {len(self)} entries, seed {self.manifest['seed']}, "
            f"{int(self.full_turn.sum())} full turns{where})"
        )

    def query(self, target: Any, k: int = 100, **options: Any) -> Any:
        """The k entries nearest the target (see :func:`planarkin.atlas.query`)."""
        return query(self, target, k, **options)


def shard_table(topology: str, start: int, cols: tuple[np.ndarray, ...]) -> Any:
    """One shard's columns as a pyarrow Table."""
    pa = require_pyarrow()
    params, signs, full, cond, desc = cols
    n = params.shape[0]
    arrays = {"id": pa.array(np.arange(start, start + n, dtype=np.uint64))}
    for j, name in enumerate(PARAMS[topology]):
        arrays[name] = pa.array(params[:, j])
    for j in range(signs.shape[1]):
        arrays[f"sign{j + 1}"] = pa.array(signs[:, j])
    arrays["full_turn"] = pa.array(full)
    arrays["conditioning"] = pa.array(cond)
    flat = pa.array(np.ascontiguousarray(desc).reshape(-1))
    arrays["descriptor"] = pa.FixedSizeListArray.from_arrays(flat, desc.shape[1])
    return pa.table(arrays)


def write_shard(path: Path, table: Any) -> None:
    """Writes a shard atomically (a half-written file never has the shard's name)."""
    pq = require_pyarrow().parquet
    tmp = path.with_suffix(".parquet.tmp")
    try:
        pq.write_table(table, tmp, compression="zstd")
        os.replace(tmp, path)
    except BaseException:  # Ctrl-C too: no half-written file is left behind
        tmp.unlink(missing_ok=True)
        raise


def read_manifest(path: Path) -> dict[str, Any]:
    """The manifest of the atlas directory ``path``, checked."""
    f = Path(path) / MANIFEST
    if not f.is_file():
        raise FileNotFoundError(f"atlas: no {MANIFEST} in {path} (is it an atlas directory?)")
    m = json.loads(f.read_text())
    if m.get("format") != "planarkin-atlas" or m.get("version") != FORMAT_VERSION:
        raise ValueError(f"atlas: {f} is not a planarkin atlas of format version {FORMAT_VERSION}")
    return m


def open_atlas(path: str | os.PathLike[str]) -> Atlas:
    """Reads a complete atlas directory into memory."""
    path = Path(path)
    m = read_manifest(path)
    if not m.get("complete"):
        raise ValueError(
            f"atlas: {path} is incomplete (a build was stopped): run `planarkin atlas build` "
            "with the same options again to finish it"
        )
    pq = require_pyarrow().parquet
    tables = [pq.read_table(path / s["file"]) for s in m["shards"]]
    return from_tables(m, tables, path)


def from_tables(manifest: dict[str, Any], tables: list[Any], path: Path | None) -> Atlas:
    """An Atlas from its shards' tables."""
    topology = manifest["topology"]
    p, s = TOPOLOGIES[topology]

    def col(name: str) -> np.ndarray:
        return np.concatenate([t.column(name).to_numpy() for t in tables])

    desc = np.concatenate(
        [
            t.column("descriptor").combine_chunks().values.to_numpy().reshape(-1, ATLAS_DESCRIPTOR)
            for t in tables
        ]
    )
    return Atlas(
        manifest=manifest,
        params=np.column_stack([col(n) for n in PARAMS[topology]]).astype(np.float64),
        signs=np.column_stack([col(f"sign{j + 1}") for j in range(s)]).astype(np.int8),
        full_turn=col("full_turn").astype(bool),
        conditioning=col("conditioning"),
        descriptor=np.ascontiguousarray(desc, dtype=np.float32),
        ids=col("id").astype(np.int64),
        path=path,
    )
