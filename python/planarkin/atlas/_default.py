"""The atlas a path synthesis uses when given none: built in this process by the Rust
kernel (no Dask, no pyarrow) the first time, then kept in the user's cache directory as
one NumPy file and loaded from there."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np

from .._kernel import __version__, atlas_shard
from ._store import FORMAT_VERSION, Atlas, manifest_of, topology_checked

#: entries of the default atlas per topology (four-bars: about 6 s to build on 2 cores)
DEFAULT_SIZE = {
    "four-bar": 1_000_000,
    "slider-crank": 300_000,
    "watt2": 500_000,
    # solved by the scene solver (a Newton group): about 9000 entries a second on 2 cores
    "stephenson3": 100_000,
}
#: the default atlases' seed
DEFAULT_SEED = 0
#: entries built per kernel call (for progress and Ctrl-C)
CHUNK = 100_000
#: default atlases already in this process, by (topology, size): a second query does not
#: read the file again (nor recompute what retrieval keeps with an atlas)
_LOADED: dict[tuple[str, int], Atlas] = {}


def cache_dir() -> Path:
    """Where default atlases are kept: $PLANARKIN_CACHE, else $XDG_CACHE_HOME/planarkin,
    else ~/.cache/planarkin."""
    if os.environ.get("PLANARKIN_CACHE"):
        return Path(os.environ["PLANARKIN_CACHE"])
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "planarkin"


def default(topology: str = "four-bar", *, size: int | None = None, progress=None) -> Atlas:
    """The default atlas of ``topology`` (``size`` entries, seed 0), loaded from the cache
    or built there first, and kept in this process for the next call (the cache is keyed
    by its file, so another $PLANARKIN_CACHE gets its own). ``progress(done, total)`` is
    called while it is built."""
    topology_checked(topology)
    size = DEFAULT_SIZE[topology] if size is None else int(size)
    if size < 1:
        raise ValueError(f"size must be >= 1, got {size}")
    manifest = {**manifest_of(topology, DEFAULT_SEED, size), "complete": True, "default": True}
    file = (
        cache_dir()
        / f"atlas-{topology}-{size}-seed{DEFAULT_SEED}-v{FORMAT_VERSION}-{__version__}.npz"
    )
    key = (str(file), size)
    if key in _LOADED:
        return _LOADED[key]
    if file.is_file():
        try:
            with np.load(file) as z:
                cols = {k: z[k] for k in z.files}
            _LOADED[key] = Atlas(manifest=manifest, path=None, **cols)
            return _LOADED[key]
        except (OSError, ValueError, KeyError):
            pass  # a damaged cache file is rebuilt
    parts = []
    for start in range(0, size, CHUNK):
        if progress:
            progress(start, size)
        parts.append(atlas_shard(topology, DEFAULT_SEED, start, min(CHUNK, size - start)))
    if progress:
        progress(size, size)
    cols = {
        name: np.concatenate([p[i] for p in parts])
        for i, name in enumerate(("params", "signs", "full_turn", "conditioning", "descriptor"))
    }
    cols["ids"] = np.arange(size, dtype=np.int64)
    file.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.NamedTemporaryFile(dir=file.parent, suffix=".npz", delete=False) as tmp:
        np.savez(tmp, **cols)
    os.replace(tmp.name, file)
    _LOADED[key] = Atlas(manifest=manifest, path=None, **cols)
    return _LOADED[key]
