"""Atlases of normalised coupler curves, for path synthesis: random linkages of a topology
(four-bar, slider-crank, Watt II), each with its curve's descriptor (invariant to
translation, rotation, scale, start point and direction), built by the Rust kernel as
Dask tasks into Parquet shards with a manifest, reproducible bit for bit from a seed; and
retrieval of the entries nearest a target (an exact scan, or a faiss index for large
atlases).

>>> import planarkin as pk
>>> a = pk.atlas.default("four-bar", size=2000)
>>> a.topology, len(a)
('four-bar', 2000)
"""

from ._build import IN_PROCESS, SHARD_SIZE, AtlasFiles, build, client_for, run_tasks
from ._default import DEFAULT_SIZE, cache_dir, default
from ._query import APPROXIMATE_FROM, NPROBE, Candidates, descriptor_variants, query
from ._store import PARAMS, TOPOLOGIES, Atlas, open_atlas

#: ``pk.atlas.open(dir)``: an atlas directory read into memory
open = open_atlas  # noqa: A001

__all__ = [
    "APPROXIMATE_FROM",
    "DEFAULT_SIZE",
    "IN_PROCESS",
    "NPROBE",
    "PARAMS",
    "SHARD_SIZE",
    "TOPOLOGIES",
    "Atlas",
    "AtlasFiles",
    "Candidates",
    "build",
    "client_for",
    "cache_dir",
    "default",
    "descriptor_variants",
    "open",
    "open_atlas",
    "query",
    "run_tasks",
]
