"""The parse door of TOML scene files, and of JSON ones the core's reader leaves to Python
(``load_scene_json``: text that is not plain JSON): text to plain data, every way it can
go wrong a one-line ValueError naming the file and the entry (a key given twice, nesting
deeper than a scene has, a number beyond the float range, text that is not JSON or TOML)."""

from __future__ import annotations

import json
import tomllib
from collections.abc import Iterator, Mapping
from typing import Any

import numpy as np

from .._kernel import SCENE_MAX_DEPTH

__all__ = ["MAX_DEPTH", "check_depth", "parse"]

#: Deepest nesting a scene may have (the core's, where the data's own check is made); a
#: file is refused by it here, naming the file, before its keys are read.
MAX_DEPTH = SCENE_MAX_DEPTH
#: Longest integer literal read as an integer: a longer one is beyond every double
#: (10^309 > DBL_MAX), so it is read as infinity and refused, by name, as non-finite.
_MAX_DIGITS = 309


def _int(text: str) -> int | float:
    if len(text.lstrip("+-")) > _MAX_DIGITS:
        return float("-inf") if text.startswith("-") else float("inf")
    return int(text)


class _Twice(dict):
    """A JSON object in which the key ``twice`` was given more than once."""

    twice: str


def _object(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    out = dict(pairs)
    if len(out) == len(pairs):
        return out
    seen: set[str] = set()
    twice = next(k for k, _ in pairs if k in seen or seen.add(k))  # type: ignore[func-returns-value]
    marked = _Twice(out)
    marked.twice = twice
    return marked


def _json_depth_bound(text: str) -> int:
    """An upper bound on a JSON text's nesting: its deepest run of brackets (those inside
    strings counted too), in one vectorized pass."""
    b = np.frombuffer(text.encode("utf-8"), dtype=np.uint8)
    step = (b == ord("[")).astype(np.int32) + (b == ord("{"))
    step -= (b == ord("]")).astype(np.int32) + (b == ord("}"))
    return int(np.cumsum(step).max(initial=0))


def _walk(data: Any) -> Iterator[tuple[str, Any, int]]:
    """(dotted entry, value, depth) of everything in ``data``, parents first, without
    recursion (so any depth is safe)."""
    todo: list[tuple[str, Any, int]] = [("", data, 1)]
    while todo:
        name, v, depth = todo.pop()
        yield name, v, depth
        if isinstance(v, Mapping):
            kids = [(f"{name}.{k}" if name else str(k), x) for k, x in v.items()]
        elif isinstance(v, (list, tuple)):
            kids = [(f"{name}[{i}]", x) for i, x in enumerate(v)]
        else:
            continue
        todo.extend((n, x, depth + 1) for n, x in reversed(kids))


def check_depth(data: Any, where: str = "scene") -> None:
    """ValueError when ``data`` nests lists and mappings deeper than :data:`MAX_DEPTH`,
    naming the entry where it does."""
    for name, v, depth in _walk(data):
        if depth > MAX_DEPTH and isinstance(v, (Mapping, list, tuple)):
            raise ValueError(
                f"{where}: {name} nests deeper than {MAX_DEPTH} levels (a scene has at most 4)"
            )


def parse(text: str, suffix: str, where: str) -> Any:
    """The data of a scene file's ``text`` (``suffix`` ".json" or ".toml"); ``where``
    (the file) begins every error message."""
    try:
        twice: list[bool] = []

        def hook(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
            out = _object(pairs)
            if isinstance(out, _Twice):
                twice.append(True)
            return out

        if suffix == ".json":
            data = json.loads(text, object_pairs_hook=hook, parse_int=_int)
        else:
            data = tomllib.loads(text)
    except RecursionError:
        raise ValueError(
            f"{where}: nested too deeply to read (a scene nests at most 4 levels)"
        ) from None
    except ValueError as e:  # JSONDecodeError and TOMLDecodeError are ValueErrors
        kind = "JSON" if suffix == ".json" else "TOML"
        raise ValueError(f"{where}: not valid {kind}: {e}") from None
    # the walks name the entry; they run only where a cheap test says they will find one
    if suffix != ".json" or _json_depth_bound(text) > MAX_DEPTH:
        check_depth(data, where)
    if twice:
        for name, v, _ in _walk(data):
            if isinstance(v, _Twice):
                entry = f"{name}.{v.twice}" if name else v.twice
                raise ValueError(
                    f"{where}: {entry} is given twice (JSON would silently keep the last one)"
                )
    return data
