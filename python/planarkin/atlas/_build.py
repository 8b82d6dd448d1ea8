"""Building an atlas: its shards are Dask tasks (a LocalCluster by default, any
``distributed`` scheduler by address, or in this process), each entry a function of the
seed and its index alone, so the atlas is the same bit for bit however many workers made
it. A finished shard is kept and not recomputed; Ctrl-C stops cleanly (the manifest stays
incomplete until every shard is written)."""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import platform
import time
from collections.abc import Callable, Generator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .._kernel import atlas_shard
from ._store import (
    MANIFEST,
    Atlas,
    manifest_of,
    open_atlas,
    read_manifest,
    require_pyarrow,
    shard_table,
    topology_checked,
    write_shard,
)

#: entries per shard unless told: about 30 MB of Parquet for a four-bar shard
SHARD_SIZE = 250_000
#: what ``scheduler`` may name besides an address
IN_PROCESS = "synchronous"


@dataclass(frozen=True)
class AtlasFiles:
    """A built atlas on disk: its directory and manifest; :meth:`open` reads it."""

    path: Path
    manifest: dict[str, Any]

    def open(self) -> Atlas:
        """The atlas in memory."""
        return open_atlas(self.path)


def _sha256(path: Path) -> str:
    with open(path, "rb") as f:
        return hashlib.file_digest(f, "sha256").hexdigest()


def make_shard(out: str, topology: str, seed: int, start: int, count: int, file: str) -> dict:
    """Builds and writes one shard (a Dask task), or reads back the one already there."""
    path = Path(out) / file
    if not path.is_file():
        cols = atlas_shard(topology, seed, start, count)
        write_shard(path, shard_table(topology, start, cols))
    rows = require_pyarrow().parquet.ParquetFile(path).metadata.num_rows
    if rows != count:
        raise ValueError(f"atlas: shard {path} has {rows} rows, expected {count}")
    return {"file": file, "start": start, "count": count, "sha256": _sha256(path)}


def _manifest(topology: str, seed: int, size: int, shard_size: int) -> dict[str, Any]:
    n = -(-size // shard_size)
    shards = [
        {
            "file": f"shard-{i:05d}.parquet",
            "start": i * shard_size,
            "count": min(shard_size, size - i * shard_size),
        }
        for i in range(n)
    ]
    return {
        **manifest_of(topology, seed, size),
        "shard_size": shard_size,
        "complete": False,
        "shards": shards,
    }


def client_for(scheduler: str | None, workers: int | None) -> tuple[Any, Any]:
    """A Dask client and the LocalCluster it owns (None: ``scheduler`` is an address)."""
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise ImportError(
            'building an atlas on Dask needs distributed: pip install "planarkin[atlas]" '
            f"(or scheduler={IN_PROCESS!r})"
        ) from None
    if scheduler is None:
        n = workers or min(os.cpu_count() or 1, 8)
        cluster = LocalCluster(
            n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None
        )
        return Client(cluster), cluster
    return Client(scheduler), None


def run_tasks(
    fn: Callable[..., Any],
    calls: list[tuple],
    scheduler: str | None,
    workers: int | None = None,
) -> Generator[tuple[int, Any], None, None]:
    """``fn(*args)`` for each ``args`` of ``calls`` as Dask tasks on ``scheduler`` (see
    :func:`client_for`): yields (index in ``calls``, result) as each finishes. When the
    caller stops taking them (done, broken off, Ctrl-C; close the generator), the tasks
    left are cancelled and a LocalCluster made here is closed."""
    from distributed import as_completed

    client, cluster = client_for(scheduler, workers)
    futures = []
    try:
        futures = [client.submit(fn, *args, pure=False) for args in calls]
        index = {f.key: i for i, f in enumerate(futures)}
        for f in as_completed(futures):
            yield index[f.key], f.result()
    finally:
        for f in futures:
            f.cancel()
        client.close()
        if cluster is not None:
            cluster.close()


def build(
    topology: str,
    size: int,
    out: str | os.PathLike[str],
    *,
    seed: int = 0,
    scheduler: str | None = None,
    workers: int | None = None,
    shard_size: int | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> AtlasFiles:
    """Builds the atlas of ``size`` linkages of ``topology`` drawn from ``seed`` into the
    directory ``out``: shards of ``shard_size`` entries as Dask tasks on ``scheduler``
    (None: a LocalCluster of ``workers`` processes; an address: that cluster;
    ``"synchronous"``: this process, no Dask). Shards already in ``out`` from the same
    options are kept. ``progress(done, total)`` is called as shards finish."""
    topology_checked(topology)
    if int(size) != size or size < 1:
        raise ValueError(f"size must be an integer >= 1, got {size!r}")
    if int(seed) != seed or not 0 <= seed < 2**64:
        raise ValueError(f"seed must be an integer in [0, 2**64), got {seed!r}")
    shard_size = SHARD_SIZE if shard_size is None else shard_size
    if int(shard_size) != shard_size or shard_size < 1:
        raise ValueError(f"shard_size must be an integer >= 1, got {shard_size!r}")
    if workers is not None and (int(workers) != workers or workers < 1):
        raise ValueError(f"workers must be an integer >= 1, got {workers!r}")
    require_pyarrow()
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    manifest = _manifest(topology, int(seed), int(size), int(shard_size))
    if (out / MANIFEST).is_file():
        old = read_manifest(out)
        keys = ("topology", "seed", "size", "shard_size")
        if any(old.get(k) != manifest[k] for k in keys):
            was = ", ".join(f"{k} {old.get(k)}" for k in keys)
            raise ValueError(f"out: {out} holds an atlas of other options ({was})")
    for stale in out.glob("*.parquet.tmp"):
        stale.unlink()
    (out / MANIFEST).write_text(json.dumps(manifest, indent=1))
    t0 = time.perf_counter()
    todo = [
        (str(out), topology, int(seed), s["start"], s["count"], s["file"])
        for s in manifest["shards"]
    ]
    total = len(todo)
    done: dict[str, dict] = {}
    if progress:
        progress(0, total)
    if scheduler == IN_PROCESS:
        for args in todo:
            done[args[-1]] = make_shard(*args)
            if progress:
                progress(len(done), total)
    else:
        with contextlib.closing(run_tasks(make_shard, todo, scheduler, workers)) as shards:
            for _, info in shards:
                done[info["file"]] = info
                if progress:
                    progress(len(done), total)
    manifest["shards"] = [done[s["file"]] for s in manifest["shards"]]
    manifest["complete"] = True
    manifest["build"] = {
        "seconds": round(time.perf_counter() - t0, 3),
        "scheduler": scheduler or f"LocalCluster({workers or 'auto'})",
        "machine": platform.machine(),
        "bytes": sum((out / s["file"]).stat().st_size for s in manifest["shards"]),
    }
    (out / MANIFEST).write_text(json.dumps(manifest, indent=1))
    return AtlasFiles(out, manifest)
