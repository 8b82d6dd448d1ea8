"""The built-in scenes (``pk.scenes``): classic linkages as scene data files
(``<name>.json``) shipped inside the scene package. ``names()`` lists them, ``path(name)``
finds one, ``data(name)`` parses it and ``load(name)`` builds its ``Scene``. The files are
written by ``tools/make_scenes.py`` (which also says where each geometry comes from).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from .._model import Scene

__all__ = ["data", "load", "names", "path"]

_HERE = Path(__file__).resolve().parent


def names() -> list[str]:
    """The built-in scenes' names, sorted."""
    return sorted(p.stem for p in _HERE.glob("*.json"))


def path(name: str) -> Path:
    """The data file of the built-in scene ``name``; ValueError for an unknown name."""
    known = names()
    if not isinstance(name, str) or name not in known:
        raise ValueError(f"unknown built-in scene {name!r}; known: {', '.join(known)}")
    return _HERE / f"{name}.json"


def data(name: str) -> dict[str, Any]:
    """The built-in scene ``name`` as a dict in the scene format (a fresh copy)."""
    with path(name).open(encoding="utf-8") as f:
        return json.load(f)


def load(name: str) -> Scene:
    """The built-in scene ``name`` as a :class:`planarkin.Scene`."""
    return Scene.from_dict(data(name))
