"""The path synthesis pipeline: retrieve atlas entries whose curves look like the target,
place each onto it (similarity, start, direction, input per point), refine the best by
SLSQP on the real linkage with exact gradients and the defect constraints, re-verify each
on a dense sweep, and rank by true error (defect-free designs first)."""

from __future__ import annotations

import contextlib
import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ... import atlas as atlases
from ..._kernel import atlas_match
from ...scene import Scene
from .refine import refine
from .results import Defects, Design, PathError, PathResult
from .targets import CurveTarget, load_target
from .templates import TRACER, NotAssembled, input_offset, scene_of
from .verify import verify

#: the topologies a path synthesis can return ("auto" tries each)
TOPOLOGIES = ("four-bar", "slider-crank", "watt2", "stephenson3")
#: descriptor neighbours placed onto the target
RETRIEVE = 300
#: atlas entries placed onto an open or partial target besides the neighbours (the
#: descriptors of a whole curve do not see a part of it)
SCAN = 20_000
#: an error (over the target's size) no refinement improves on: rounding
EXACT = 1e-12
#: longest refinement of one candidate (seconds): a four-bar's takes about 0.1 s, and a
#: six-bar start that needs longer seldom ends better than the next start
CANDIDATE_SECONDS = 2.5
#: (starts per direction, target resampling) of the placement a refinement starts from
FINE = (64, 64)
#: the same for a quick first pass over the scanned entries, about 25 times cheaper
COARSE = (12, 16)
#: scanned entries kept from the quick pass for the fine one
KEEP = 300


@dataclass(frozen=True)
class Placed:
    """An atlas entry placed onto the target: ``a`` z + ``b`` carries its frame onto the
    target's, ``theta`` (n,) the entry's input angle at each target point, ``cost`` the
    residual of the fit over the target's spread."""

    topology: str
    row: int
    entry: int
    params: np.ndarray
    signs: np.ndarray
    cost: float
    a: complex
    b: complex
    theta: np.ndarray
    reversed: bool
    fraction: float

    def scene(self, index: int = 1) -> Any:
        """The entry as a scene in the target's frame, drawn at the first point."""
        return scene_of(
            self.topology,
            self.params,
            self.signs,
            self.a,
            self.b,
            float(self.theta[0]),
            name=f"path design {index} ({self.topology})",
            description=f"from atlas entry {self.entry} of the {self.topology} atlas, "
            "placed onto the target and refined",
        )

    @property
    def inputs(self) -> np.ndarray:
        """The scene's input value at each target point."""
        return self.theta + input_offset(self.a)


def _match(
    atlas: atlases.Atlas, target: CurveTarget, rows: np.ndarray, search: tuple[int, int]
) -> tuple[np.ndarray, ...]:
    """The kernel's placement of the atlas rows: (cost, a, b, fraction, reversed, theta),
    a row each; cost NaN where none fits."""
    return atlas_match(
        atlas.topology,
        np.ascontiguousarray(atlas.params[rows]),
        np.ascontiguousarray(atlas.signs[rows], dtype=np.float64),
        np.ascontiguousarray(target.points, dtype=np.float64),
        target.kind == "closed",
        *search,
    )


def place(
    atlas: atlases.Atlas, target: CurveTarget, rows: np.ndarray, search: tuple[int, int] = FINE
) -> list[Placed]:
    """The atlas rows placed onto the target, best fit first (those with no fit left out);
    ``search``: starts per direction and the target's resampling (:data:`FINE`)."""
    if rows.size == 0:
        return []
    cost, a, b, frac, rev, theta = _match(atlas, target, rows, search)
    order = [i for i in np.argsort(cost, kind="stable") if math.isfinite(cost[i])]
    return [
        Placed(
            topology=atlas.topology,
            row=int(rows[i]),
            entry=int(atlas.ids[rows[i]]),
            params=atlas.params[rows[i]],
            signs=atlas.signs[rows[i]],
            cost=float(cost[i]),
            a=complex(*a[i]),
            b=complex(*b[i]),
            theta=theta[i],
            reversed=bool(rev[i]),
            fraction=float(frac[i]),
        )
        for i in order
    ]


def retrieve(atlas: atlases.Atlas, target: CurveTarget, k: int = RETRIEVE) -> list[Placed]:
    """The atlas entries placed onto the target, best first: the descriptor neighbours of a
    closed target; for an open one, those of the curve traced there and back, and for an
    open or partial one the first :data:`SCAN` entries, each placed on its best arc (a
    quick pass, then the best :data:`KEEP` finely)."""
    if target.kind == "closed":
        rows = atlases.query(atlas, target.points, k, closed=True).rows
    else:
        rows = np.arange(min(SCAN, len(atlas)))
        if target.kind == "open":
            # an open target may be a rocking input's whole arc: its descriptor finds those
            near = atlases.query(atlas, target.points, k, closed=False).rows
            rows = np.unique(np.concatenate([near, rows]))
        # the quick pass ranks the many by their cost alone; only the best are placed finely
        cost = _match(atlas, target, rows, COARSE)[0]
        best = np.argsort(np.where(np.isfinite(cost), cost, np.inf), kind="stable")[:KEEP]
        rows = rows[best[np.isfinite(cost[best])]]
    return place(atlas, target, rows)


@dataclass
class _Clock:
    limit: float | None
    start: float = field(default_factory=time.perf_counter)

    def over(self) -> bool:
        return self.limit is not None and time.perf_counter() - self.start > self.limit

    def left(self) -> float | None:
        return (
            None
            if self.limit is None
            else max(0.1, self.limit - (time.perf_counter() - self.start))
        )


def refine_one(
    cand: Placed, target: CurveTarget, constraints: dict, time_limit: float | None
) -> dict | None:
    """One candidate refined and verified, as plain data (a Dask task's result): the
    scene's dict, error, defects, inputs, transmission, full turn and the verdict; None
    where the candidate does not assemble at its start."""
    try:
        sc = cand.scene()
    except NotAssembled:
        return None
    r = refine(sc, TRACER, target, cand.inputs, time_limit=time_limit, **constraints)
    mt = constraints["min_transmission"]
    v = verify(r.scene, TRACER, target, r.inputs, min_transmission=mt)
    return {
        "scene": r.scene.to_dict(),
        "error": (v.error.max, v.error.rms),
        "defects": (v.defects.circuit, v.defects.branch, v.defects.order),
        "inputs": np.asarray(v.inputs),
        "min_transmission": float(v.min_transmission),
        "full_turn": bool(v.full_turn),
        "verified": bool(v.ok),
    }


def _distributed(
    todo: list[Placed],
    target: CurveTarget,
    constraints: dict,
    clock: _Clock,
    scheduler: str,
    keep: Callable[[int, dict | None], None],
    say: Callable[[str, int, int], None],
) -> str:
    """The candidates refined as Dask tasks on ``scheduler`` (an address, or "local": a
    LocalCluster on this machine); returns why it stopped."""
    calls = [(c, target, constraints, clock.left()) for c in todo]
    where = None if scheduler == "local" else scheduler
    got: dict[int, dict | None] = {}
    stopped = "done"
    with contextlib.closing(atlases.run_tasks(refine_one, calls, where)) as tasks:
        for n, (i, result) in enumerate(tasks, 1):
            got[i] = result
            say("refinement", n, len(todo))
            if clock.over():
                stopped = "time limit"
                break
    # in the candidates' order, as in this process: the same designs kept
    for i in sorted(got):
        keep(i, got[i])
    return stopped


def _same(d: Design, others: list[Design], tol: float) -> bool:
    # two starts that refine to one linkage give one design
    pts = np.array(list(d.scene.points.values()))
    for o in others:
        if o.topology != d.topology:
            continue
        q = np.array(list(o.scene.points.values()))
        if q.shape == pts.shape and np.abs(q - pts).max() < tol:
            return True
    return False


def path(
    target: Any,
    *,
    kind: str | None = None,
    topology: str = "four-bar",
    designs: int = 5,
    min_transmission: float | None = None,
    atlas: Any = None,
    refine_count: int | None = None,
    box: Any = None,
    max_link_ratio: float | None = None,
    full_turn: bool | None = None,
    time_limit: float | None = None,
    scheduler: str | None = None,
    seed: int = 0,
    progress: Callable[[str, int, int], None] | None = None,
) -> PathResult:
    """Linkages whose tracer point follows ``target`` (a CurveTarget, an (n, 2) array, or
    a CSV, JSON or SVG file; ``kind`` "closed", "open" or "partial"), best first: up to
    ``designs`` of them, each refined and verified (see the module). ``topology``: one of
    :data:`TOPOLOGIES` or "auto" (each). ``atlas``: an Atlas or an atlas directory (default:
    the topology's default atlas, built into the user cache on first use).
    ``min_transmission`` (degrees), ``box`` ((xmin, xmax), (ymin, ymax)) for the fixed
    pivots, ``max_link_ratio`` and ``full_turn`` constrain the refinement;
    ``refine_count`` candidates are refined (default 3 x designs, at least 8);
    ``time_limit`` (seconds) stops refining and returns what is verified so far;
    ``scheduler`` refines the candidates as Dask tasks (an address, or "local" for a
    LocalCluster here; None: in this process); Ctrl-C returns the designs so far with
    ``stopped`` "interrupted".
    ``progress(stage, done, total)`` is told each stage's advance. ``seed`` is recorded
    in the result: nothing here draws at random (an atlas carries its own seed)."""
    clock = _Clock(time_limit)
    tgt = target if isinstance(target, CurveTarget) else load_target(target, kind=kind)
    if kind is not None and tgt.kind != kind:
        tgt = CurveTarget(tgt.points, kind, tgt.inputs)
    if topology != "auto" and topology not in TOPOLOGIES:
        raise ValueError(
            f"topology must be one of {', '.join(TOPOLOGIES)} or 'auto', got {topology!r}"
        )
    if int(designs) != designs or designs < 1:
        raise ValueError(f"designs must be an integer >= 1, got {designs!r}")
    if time_limit is not None and not (time_limit > 0):
        raise ValueError(f"time_limit must be > 0 seconds, got {time_limit!r}")
    if min_transmission is not None and not (0 <= min_transmission < 90):
        raise ValueError(f"min_transmission must be in [0, 90) degrees, got {min_transmission!r}")
    n_refine = refine_count if refine_count is not None else max(8, 3 * designs)
    if int(n_refine) != n_refine or n_refine < 1:
        raise ValueError(f"refine_count must be an integer >= 1, got {refine_count!r}")
    say = progress or (lambda stage, done, total: None)
    timings: dict[str, float] = {}
    tops = TOPOLOGIES if topology == "auto" else (topology,)
    if atlas is not None and topology == "auto":
        raise ValueError("atlas: give a topology with an atlas (auto uses the default atlases)")
    placed: list[Placed] = []
    manifests = []
    for top in tops:
        t0 = time.perf_counter()
        if atlas is None:
            at = atlases.default(top, progress=lambda d, t, top=top: say(f"atlas {top}", d, t))
        elif isinstance(atlas, atlases.Atlas):
            at = atlas
        else:
            at = atlases.open_atlas(atlas)
        if at.topology != top:
            raise ValueError(f"atlas: holds {at.topology} linkages, not {top}")
        manifests.append(at.manifest)
        timings[f"atlas {top}"] = time.perf_counter() - t0
        t0 = time.perf_counter()
        say("retrieval", 0, 1)
        placed += retrieve(at, tgt)
        timings["retrieval"] = timings.get("retrieval", 0.0) + time.perf_counter() - t0
    placed.sort(key=lambda p: p.cost)
    say("retrieval", 1, 1)
    found: list[Design] = []
    stopped = "done"
    t0 = time.perf_counter()
    tol = 1e-6 * tgt.size
    todo = placed[:n_refine]
    constraints = {
        "min_transmission": min_transmission,
        "box": box,
        "max_link_ratio": max_link_ratio,
        "full_turn": bool(full_turn) if full_turn is not None else tgt.kind != "open",
    }
    seeds = {m["topology"]: int(m["seed"]) for m in manifests}

    def keep(i: int, got: dict | None) -> None:
        # the i-th candidate's refined design, unless it is one already kept
        if got is None:
            return
        cand = todo[i]
        d = Design(
            scene=Scene(got["scene"]),
            tracer=TRACER,
            error=PathError(*got["error"]),
            defects=Defects(*got["defects"]),
            inputs=got["inputs"],
            topology=cand.topology,
            min_transmission=got["min_transmission"],
            full_turn=got["full_turn"],
            verified=got["verified"],
            source={
                "rank": i + 1,
                "atlas_entry": cand.entry,
                "atlas_seed": seeds[cand.topology],
                "placement_cost": cand.cost,
                "reversed": cand.reversed,
                "arc_fraction": cand.fraction,
            },
        )
        if not _same(d, found, tol):
            found.append(d)

    try:
        if scheduler is None:
            for i, cand in enumerate(todo):
                if clock.over():
                    stopped = "time limit"
                    break
                say("refinement", i, len(todo))
                keep(i, refine_one(cand, tgt, constraints, clock.left()))
                if sum(d.verified and d.error.max <= EXACT for d in found) >= designs:
                    break  # as many exact designs as asked: no later start can do better
        else:
            stopped = _distributed(todo, tgt, constraints, clock, scheduler, keep, say)
    except KeyboardInterrupt:
        stopped = "interrupted"
    say("refinement", len(todo), len(todo))
    timings["refinement"] = time.perf_counter() - t0
    # verified first, then by error to 3 digits (cognates trace one curve), then in the
    # order retrieval placed them
    found.sort(
        key=lambda d: (not d.verified, float(f"{max(d.error.max, 1e-12):.3g}"), d.source["rank"])
    )
    timings["total"] = time.perf_counter() - clock.start
    return PathResult(
        designs=found[:designs],
        target=tgt,
        options={
            "kind": tgt.kind,
            "topology": topology,
            "designs": designs,
            "min_transmission": min_transmission,
            "refine_count": n_refine,
            "box": box,
            "max_link_ratio": max_link_ratio,
            "full_turn": full_turn,
            "time_limit": time_limit,
            "timing": tgt.inputs is not None,
            "scheduler": scheduler,
        },
        timings=timings,
        seed=seed,
        stopped=stopped,
        atlas=manifests[0] if len(manifests) == 1 else {"atlases": manifests},
    )
