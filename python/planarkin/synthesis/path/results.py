"""What a path synthesis returns: ranked designs with their true errors and defects, and
the files they are written as (scene files ``planarkin analyze`` and ``planarkin web``
open, and report.json), written whole or not at all."""

from __future__ import annotations

import contextlib
import json
import math
import os
import re
import shutil
import tempfile
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..pool import SigintDeferred
from ..results import versions
from .targets import CurveTarget

if TYPE_CHECKING:  # a design holds a Scene; its class is the scene's own at run time
    from ...scene import Scene

__all__ = ["REPORT_JSON", "Defects", "Design", "PathError", "PathResult", "staged", "versions"]

#: the report's file name; the designs are ``design_1.json``, ``design_2.json``, ...
REPORT_JSON = "report.json"
_DESIGN_FILE = re.compile(r"design_\d+\.json")


@dataclass(frozen=True)
class PathError:
    """Distances from the target's points to the design's coupler curve (the traced arc),
    divided by the target's size: the largest and the root mean square."""

    max: float
    rms: float


@dataclass(frozen=True)
class Defects:
    """True where the design has that defect: ``circuit`` (the target's points lie on more
    than one circuit), ``branch`` (a dead point inside the traced arc), ``order`` (the
    input does not reach the points in the target's order)."""

    circuit: bool
    branch: bool
    order: bool

    @property
    def any(self) -> bool:
        """Any of the three."""
        return self.circuit or self.branch or self.order


@dataclass(frozen=True, eq=False)
class Design:
    """One linkage found for a target. ``scene`` is the linkage as drawn, ``tracer`` the
    name of its point that traces the path; ``error`` and ``defects`` are measured on the
    real linkage (a dense sweep), ``inputs`` (n,) the scene's input value (radians, or a
    displacement for a linear input) that reaches each target point. ``topology`` is the
    template's name ("four-bar", "slider-crank", "watt2", "stephenson3");
    ``min_transmission`` the least transmission angle over the traced arc in degrees;
    ``full_turn`` whether the input turns fully; ``verified`` whether the design passed the
    dense re-verification with no defect; ``source`` where it came from (an atlas entry,
    a start)."""

    scene: Scene
    tracer: str
    error: PathError
    defects: Defects
    inputs: np.ndarray
    topology: str = "four-bar"
    min_transmission: float = math.nan
    full_turn: bool = False
    verified: bool = False
    source: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if self.tracer not in self.scene.points:
            raise ValueError(f"tracer {self.tracer!r} is not a point of the scene")
        t = np.array(self.inputs, dtype=np.float64, copy=True).reshape(-1)
        t.flags.writeable = False
        object.__setattr__(self, "inputs", t)

    def to_dict(self) -> dict[str, Any]:
        """The design's row in report.json (without its file name)."""
        return {
            "tracer": self.tracer,
            "error": {"max": self.error.max, "rms": self.error.rms},
            "defects": {
                "circuit": self.defects.circuit,
                "branch": self.defects.branch,
                "order": self.defects.order,
            },
            "inputs": self.inputs.tolist(),
            "topology": self.topology,
            "min_transmission_deg": self.min_transmission,
            "full_turn": self.full_turn,
            "verified": self.verified,
            "source": dict(self.source),
        }

    def scene_file_dict(self, rank: int) -> dict[str, Any]:
        """The scene as written to ``design_<rank>.json``: the scene itself, its tracer
        among its outputs (so ``planarkin analyze`` follows it) and a description that says
        what it is."""
        d = self.scene.to_dict()
        e = self.error
        words = (
            f"Design {rank} of a path synthesis (planarkin synthesize path): {self.topology}, "
            f"tracer {self.tracer}; error max {e.max:.3g}, rms {e.rms:.3g} of the target's "
            f"size; {'verified, no defect' if self.verified else 'NOT verified'}."
        )
        d["description"] = f"{d['description']} {words}" if d.get("description") else words
        outs = list(d.get("outputs") or [])
        if outs and self.tracer not in outs:
            d["outputs"] = [*outs, self.tracer]
        return d


def _plain(x: object) -> object:
    """NaN/inf -> None, arrays -> lists, NumPy scalars -> Python, recursively (strict
    JSON)."""
    if isinstance(x, np.ndarray):
        x = x.tolist()
    if isinstance(x, dict):
        return {str(k): _plain(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_plain(v) for v in x]
    if isinstance(x, np.generic):
        x = x.item()
    if isinstance(x, Path):
        return str(x)
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


def _json(data: object) -> str:
    # default=str: an option given as an object (an Atlas) is written as its text
    return json.dumps(_plain(data), indent=2, allow_nan=False, default=str) + "\n"


@dataclass(frozen=True, eq=False)
class PathResult:
    """A path synthesis: ``designs`` best first, the ``target``, the ``options`` it ran
    with, ``timings`` (stage -> seconds), the ``seed``, why it ``stopped`` ("done",
    "time limit", "interrupted"), and the ``atlas`` it drew from (its manifest)."""

    designs: list[Design]
    target: CurveTarget
    options: dict[str, Any] = field(default_factory=dict)
    timings: dict[str, float] = field(default_factory=dict)
    seed: int = 0
    stopped: str = "done"
    atlas: dict[str, Any] = field(default_factory=dict)

    @property
    def best(self) -> Design | None:
        """The first design, or None when there is none."""
        return self.designs[0] if self.designs else None

    @property
    def verified(self) -> list[Design]:
        """The designs that passed the dense re-verification with no defect, best first."""
        return [d for d in self.designs if d.verified]

    def report(self, *, command: str | None = None) -> dict[str, Any]:
        """report.json as plain data: ``designs`` (each: ``file``, ``tracer``, ``error``
        {max, rms}, ``defects`` {circuit, branch, order}, ``inputs``, ``topology``,
        ``min_transmission_deg``, ``full_turn``, ``verified``, ``source``), then
        ``target``, ``options``, ``seed``, ``versions``, ``timings``, ``stopped``,
        ``atlas`` and (given) the ``command`` that reproduces the run."""
        rows = [{"file": f"design_{k}.json", **d.to_dict()} for k, d in enumerate(self.designs, 1)]
        rep: dict[str, Any] = {
            "designs": rows,
            "target": self.target.to_dict(),
            "options": dict(self.options),
            "seed": self.seed,
            "versions": versions(),
            "timings": dict(self.timings),
            "stopped": self.stopped,
            "atlas": dict(self.atlas),
        }
        if command is not None:
            rep["command"] = command
        return rep

    def write_into(self, folder: str | Path, *, command: str | None = None) -> list[Path]:
        """Writes ``design_1.json``, ... and report.json straight into ``folder`` (which
        exists); :meth:`write` is the one that leaves nothing half-written."""
        folder = Path(folder)
        paths = []
        for k, d in enumerate(self.designs, 1):
            # through the Scene class: the file is the scene format, checked as it is read
            sc = type(d.scene).from_dict(d.scene_file_dict(k))
            paths.append(sc.save(folder / f"design_{k}.json"))
        p = folder / REPORT_JSON
        p.write_text(_json(self.report(command=command)), encoding="utf-8")
        return [*paths, p]

    def write(self, out_dir: str | Path, *, command: str | None = None) -> list[Path]:
        """Writes the designs (``design_1.json``, ``design_2.json``, ...: scene files,
        best first) and report.json into ``out_dir`` (created if needed), all or none:
        they are written beside it first and moved in at the end, so a Ctrl-C or an error
        leaves ``out_dir`` as it was. Design files of an earlier run there are removed.
        Returns the paths written."""
        with staged(out_dir) as tmp:
            names = [p.name for p in self.write_into(tmp, command=command)]
        return [Path(out_dir) / n for n in names]


@contextlib.contextmanager
def staged(out_dir: str | Path) -> Iterator[Path]:
    """A fresh folder beside ``out_dir`` to write into. When the block ends normally its
    files are moved into ``out_dir`` (report.json last; Ctrl-C held back while they
    move) and stale ``design_N.json`` files of an earlier run are removed; when it raises
    (Ctrl-C included) the folder is removed and ``out_dir`` is left as it was."""
    out = Path(out_dir)
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{out.name}.", suffix=".partial", dir=out.parent))
    try:
        yield tmp
        with SigintDeferred():  # the files move in whole
            _publish(tmp, out)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def _publish(tmp: Path, out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    names = sorted(p.name for p in tmp.iterdir())
    for old in out.iterdir():
        if _DESIGN_FILE.fullmatch(old.name) and old.name not in names:
            old.unlink()
    for n in sorted(names, key=lambda n: n == REPORT_JSON):  # the report, which lists the
        os.replace(tmp / n, out / n)  # rest, last
