"""The performance targets as data: one row per target (what is measured, the yardstick it
is compared with, how, the target value and its unit, the words of the row), read against
the raw results into the (target, measured, ratio, verdict) rows of BENCHMARKS.md.

A measure key is a pytest-benchmark ``impl`` (its median, seconds), ``impl@m=M`` (the row
of that batch size; ``@m=None``: the row without one), or ``kind:what`` for a quantity
read otherwise (:data:`MEASURES`)."""

from __future__ import annotations

import operator
import os
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, NamedTuple


def fmt_time(seconds: float) -> str:
    """A duration with a unit that keeps three significant digits."""
    for unit, scale in (("s", 1.0), ("ms", 1e-3), ("µs", 1e-6), ("ns", 1e-9)):
        if seconds >= scale or unit == "ns":
            return f"{seconds / scale:.3g} {unit}"
    return str(seconds)


def verdict(ok: bool | None) -> str:
    return "n/a" if ok is None else ("**met**" if ok else "**missed**")


class Bench:
    """Lookups into the pytest-benchmark JSON by (impl, extra_info filters)."""

    def __init__(self, data: dict):
        self.rows = data["benchmarks"]
        self.groups: dict[str, list[dict]] = {}
        for b in self.rows:
            self.groups.setdefault(b["group"], []).append(b)

    def get(self, impl: str, **filt) -> dict | None:
        for b in self.rows:
            ei = b.get("extra_info", {})
            if ei.get("impl") == impl and all(ei.get(k) == v for k, v in filt.items()):
                return b
        return None

    def median(self, impl: str, **filt) -> float | None:
        b = self.get(impl, **filt)
        return b["stats"]["median"] if b else None


class Reading(NamedTuple):
    """A measure's value (in the unit its target compares), the words the "measured"
    cell shows, and what else the row's words may name."""

    value: float
    shown: str
    info: dict[str, Any] = {}


class Results(NamedTuple):
    """The raw results a target is read from."""

    bench: Bench
    crit: dict
    trade: dict


def _row(res: Results, key: str) -> tuple[dict | None, float | None]:
    impl, _, filt = key.partition("@")
    kw: dict[str, Any] = {}
    if filt:
        name, _, v = filt.partition("=")
        kw[name] = None if v == "None" else int(v)
    return res.bench.get(impl, **kw), res.bench.median(impl, **kw)


def _median(res: Results, key: str) -> Reading | None:
    _, med = _row(res, key)
    return Reading(med, fmt_time(med)) if med else None


def _nit(res: Results, key: str) -> Reading | None:
    """Newton iterations per point of a benchmark row (and, when it says, over how many
    solved angles)."""
    row, _ = _row(res, key)
    if not row:
        return None
    ei = row["extra_info"]
    nit = ei["nit_mean"]
    over = f" it/pt over {ei['solved']} angles" if "solved" in ei else ""
    return Reading(nit, f"{nit:.2f}{over}")


def _tradeoff_nit(res: Results, method: str) -> Reading | None:
    """Iterations per point of a tradeoff row (tol 1e-9) over its linkages."""
    row = next(
        (r for r in res.trade.get("rows", []) if r["method"] == method and r["tol"] == 1e-9),
        None,
    )
    return Reading(row["nit_mean"], f"{row['nit_mean']:.2f}") if row else None


def _ns_per_point(res: Results, key: str) -> Reading | None:
    row, med = _row(res, key)
    if not med:
        return None
    ns = med / (row["extra_info"]["m"] * 361) * 1e9
    return Reading(ns, f"{ns:.1f} ns per point")


def _finite_paths(res: Results, key: str) -> Reading | None:
    """The share of homotopy paths that end finite."""
    row, _ = _row(res, key)
    if not (row and "paths" in row["extra_info"]):
        return None
    paths, finite = row["extra_info"]["paths"], row["extra_info"]["finite"]
    return Reading(finite / paths, f"{finite} of {paths} paths finite")


def _overhead(res: Results, key: str) -> Reading | None:
    """The Python side's share of a sweep: 1 - criterion's Rust time / the Python call."""
    py, crit = key.split("|")
    med = res.bench.median(py)
    rust = res.crit.get(crit, {}).get("median_ns")
    if not (med and rust):
        return None
    return Reading(1 - rust * 1e-9 / med, f"{fmt_time(med)} Python vs {fmt_time(rust * 1e-9)} Rust")


def _memory(res: Results, key: str) -> Reading | None:
    """Peak RSS beyond the output arrays (MiB) of a memory benchmark row."""
    row, _ = _row(res, key)
    if not row:
        return None
    ei = row["extra_info"]
    return Reading(
        ei["overhead_bytes"] / 2**20,
        f"{ei['delta_bytes'] / 2**20:.0f} MiB for {ei['output_bytes'] / 2**20:.0f} MiB of output",
        {"m": ei["m"], "n": ei["n"]},
    )


#: ``kind:what`` measure keys: how each kind is read.
MEASURES: dict[str, Callable[[Results, str], Reading | None]] = {
    "nit": _nit,
    "tradeoff-nit": _tradeoff_nit,
    "ns-per-point": _ns_per_point,
    "finite-paths": _finite_paths,
    "overhead": _overhead,
    "memory": _memory,
}

#: How a target compares: "speedup" = yardstick / measure, "ratio" = measure / yardstick,
#: "value" = the measure itself.
COMPARISONS = ("speedup", "ratio", "value")
_OPS = {">=": operator.ge, "<=": operator.le, "<": operator.lt}


def read(res: Results, key: str) -> Reading | None:
    kind, _, what = key.partition(":")
    return MEASURES[kind](res, what) if what else _median(res, key)


@dataclass(frozen=True)
class Target:
    """One target: ``text`` is the row's words, where ``{target}`` is the comparison with
    its value and unit (">= 3x"), ``{limit}`` the value and unit alone."""

    text: str
    measure: str
    yardstick: str | None
    comparison: str
    #: ">=", "<=", "<"; None: reported, no verdict
    op: str | None
    value: float | None
    unit: str = ""
    #: the value in the measure's own unit: ``value * scale`` (0.3 ms: 0.3, 1e-3)
    scale: float = 1.0
    #: the ratio cell, a format of the compared quantity (None: "-")
    ratio: str | None = "{:.2f}x faster"
    #: the "measured" cell when the yardstick is missing (None: no row)
    missing: str | None = None
    #: points per call: the measure's time per point is added to the "measured" cell
    points: int | None = None
    info: dict[str, Any] = field(default_factory=dict)

    def words(self, reading: Reading) -> str:
        limit = "" if self.value is None else f"{self.value:g}{self.unit}"
        return self.text.format(
            target=f"{self.op} {limit}", limit=limit, **self.info, **reading.info
        )

    def row(self, res: Results) -> tuple[str, str, str, str] | None:
        """(target, measured, ratio, verdict), or None when it was not measured."""
        ours = read(res, self.measure)
        if ours is None:
            return None
        shown, q = ours.shown, ours.value
        if self.yardstick is not None:
            peer = read(res, self.yardstick)
            if peer is None:
                return (
                    None if self.missing is None else (self.words(ours), self.missing, "-", "n/a")
                )
            shown = f"{ours.shown} vs {peer.shown}"
            q = peer.value / ours.value if self.comparison == "speedup" else ours.value / peer.value
        if self.points:
            shown += f" ({ours.value / self.points * 1e9:.1f} ns per point)"
        ok = None
        if self.op is not None and self.value is not None:
            ok = _OPS[self.op](q, self.value * self.scale)
        return (
            self.words(ours),
            shown,
            "-" if self.ratio is None else self.ratio.format(q),
            "-" if self.op is None else verdict(ok),
        )


_M = "@m=10000"  # the batch size of the batch targets
_X = "{:.2f}x"

#: Every target, in the order BENCHMARKS.md lists them: the scenes' first, then the
#: four-bar's.
TARGETS = (
    Target("Jansen's leg (foot, 361 angles) {target} faster than pylinkage + numba",
           "scene_jansen_pk", "scene_jansen_pylinkage", "speedup", ">=", 3, "x"),
    Target("Jansen's leg: pylinkage + numba / planarkin {target}",
           "scene_jansen_pk", "scene_jansen_pylinkage", "speedup", ">=", 8),
    Target("Jansen's leg faster than a vectorized NumPy circle-intersection chain",
           "scene_jansen_pk", "scene_jansen_numpy", "speedup", ">=", 1),
    *(
        t
        for name in ("double-butterfly-1", "double-butterfly-2")
        for t in (
            Target(f"{name}: Newton iterations per solved angle {{target}} (tol 1e-9, 1 deg)",
                   f"nit:scene_group_{name}", None, "value", "<", 1.5, ratio=None),
            Target(f"{name} sweep, 361 angles (both dead points found): {{target}}",
                   f"scene_group_{name}", None, "value", "<=", 0.3, " ms", 1e-3, ratio=None),
            Target(f"{name}, 361 angles within 20 deg (all converge): {{target}}",
                   f"scene_group_near_{name}", None, "value", "<=", 0.15, " ms", 1e-3,
                   ratio=None),
        )
    ),
    Target("Jansen's leg with loads: every reaction and the input torque (dynamics, 361 "
           "angles) within {target} its kinematic sweep (velocities and accelerations)",
           "forces_dynamics", "forces_sweep", "ratio", "<=", 3, "x", ratio="{:.1f}x"),
    *(
        t
        for name, peer in (
            ("jansen", "scene_jansen_pylinkage"),
            ("slider-crank", "slider_pylinkage"),
            ("watt2", "order_watt2_pylinkage"),
        )
        for t in (
            Target(f"{name}, a full turn from 30 deg away: within {{target}} of the drawn start",
                   f"order_{name}_from_30_deg", f"order_{name}_drawn", "ratio", "<=", 1.3, "x",
                   ratio="{:.2f}x"),
            Target(f"{name}, a full turn shuffled: within {{target}} of the drawn start",
                   f"order_{name}_shuffled", f"order_{name}_drawn", "ratio", "<=", 1.3, "x",
                   ratio="{:.2f}x"),
            Target(f"{name} from 30 deg away: {{target}} faster than pylinkage + numba",
                   f"order_{name}_from_30_deg", peer, "speedup", ">=", 5, "x"),
        )
    ),
    Target("slider-crank (piston, 361 angles) {target} faster than pylinkage + numba (RRPDyad)",
           "slider_pk", "slider_pylinkage", "speedup", ">=", 3, "x"),
    Target("slider-crank faster than the NumPy closed form written as a user would",
           "slider_pk", "slider_numpy", "speedup", ">=", 1),
    Target("double butterfly assemblies: {target} of homotopy paths finite",
           "finite-paths:scene_assemblies", None, "value", ">=", 60, "%", 0.01, ratio="{:.0%}"),
    Target("double butterfly assemblies: {target}",
           "scene_assemblies", None, "value", "<=", 8, " ms", 1e-3, ratio=None),
    Target("loading a 16 000-point link: {target} json.loads",
           "scene_load_16000", "scene_load_json", "ratio", "<=", 3, "x", ratio="{:.2f}x"),
    Target("exact gradients (16 coordinates x 1001 angles) vs forward differences",
           "scene_gradient_exact", "scene_gradient_fd", "speedup", None, None,
           ratio="{:.1f}x faster"),
    Target("synthesis: the residuals' derivatives at one steering design, exact vs fd",
           "synth_rows_exact", "synth_rows_fd", "speedup", None, None, ratio="{:.1f}x faster"),
    Target("synthesis: one SLSQP start (60 iterations), exact vs fd",
           "synth_start_exact", "synth_start_fd", "speedup", None, None, ratio="{:.1f}x faster"),
    Target("planarkin synthesize ackermann --starts 2: exact {target} faster than fd",
           "synth_cli_exact", "synth_cli_fd", "speedup", ">=", 8, "x", ratio="{:.1f}x faster"),
    Target("planarkin synthesize ackermann, the default run (12 starts, 2 workers): {target}",
           "synth_cli_default", None, "value", "<=", 15, " s", ratio=None),
    Target("atlas: 100 000 four-bars built (curve, descriptor) in {target}: 100 000 a second",
           "atlas_build_four-bar", None, "value", "<=", 1, " s", ratio=None),
    Target("path synthesis, a four-bar for a closed 24-point curve, end to end: {target}",
           "path_fourbar", None, "value", "<=", 5, " s", ratio=None),
    Target("path synthesis, a four-bar for a partial 12-point target, end to end: {target}",
           "path_fourbar_partial", None, "value", "<=", 5, " s", ratio=None),
    Target("path synthesis, a Watt II six-bar for a closed 30-point curve: {target}",
           "path_watt2", None, "value", "<=", 30, " s", ratio=None),
    Target("Watt II: one requested dyad measurably cheaper than the whole plan",
           "scene_plan_first_dyad", "scene_plan_all", "ratio", "<", 0.8, ratio="{:.2f}"),
    Target("seed sweep from Python vs NumPy vectorized closed form (ratio {target})",
           "pk_sweep_quadratic", "np_closed_form@m=None", "ratio", "<=", 1.0, ratio="{:.2f}"),
    Target("seed sweep, across-angles option / NumPy closed form {target}",
           "pk_sweep_closed-form", "np_closed_form@m=None", "ratio", "<=", 0.5, ratio="{:.2f}"),
    Target("pylinkage + numba / seed sweep (across-angles option) {target}",
           "pk_sweep_closed-form", "pylinkage", "speedup", ">=", 4),
    Target("seed sweep {target} faster than pylinkage + numba",
           "pk_sweep_quadratic", "pylinkage", "speedup", ">=", 3, "x",
           missing="pylinkage not installed"),
    Target("Python-side overhead {target} of the seed sweep (vs criterion: the same sweep, "
           "allocating its outputs, in Rust)",
           "overhead:pk_sweep_quadratic|seed_sweep_361/quadratic_alloc", None, "value", "<", 25,
           "%", 0.01, ratio="{:.0%}"),
    Target("mean iterations per point, tol 1e-9, tangent predictor {target} (seed sweep)",
           "nit:pk_sweep_tangent", None, "value", "<=", 1.6, ratio=None),
    Target("(same, over the seed + random crank-rockers of the tradeoff run)",
           "tradeoff-nit:tangent", None, "value", "<=", 1.6, ratio=None),
    Target("batch 10000 x 361, Newton on 1 thread: throughput >= NumPy closed form",
           f"pk_batch_t1{_M}", f"np_closed_form{_M}", "speedup", ">=", 1, ratio=_X),
    Target("Newton batch 10000 x 361 across angles (predictor='closed-form'), 1 thread: "
           "{target} NumPy closed form",
           f"pk_batch_across_t1{_M}", f"np_closed_form{_M}", "speedup", ">=", 1.5, "x",
           ratio=_X, points=10_000 * 361),
    Target("closed-form batch 10000 x 361, 1 thread: {target}",
           f"ns-per-point:pk_cf_batch_t1{_M}", None, "value", "<=", 10, " ns per point",
           ratio=None),
    Target("(same, written into arrays the caller keeps: `out=`, no new memory to clear)",
           f"ns-per-point:pk_cf_batch_t1_out{_M}", None, "value", "<=", 10, " ns per point",
           ratio=None),
    Target("closed-form batch 10000 x 361 {target} NumPy closed form (1 thread)",
           f"pk_cf_batch_t1{_M}", f"np_closed_form{_M}", "speedup", ">=", 3, "x", ratio=_X),
    Target("(same, closed-form batch on all {cores} threads)",
           f"pk_cf_batch_tall{_M}", f"np_closed_form{_M}", "speedup", ">=", 3, "x", ratio=_X,
           info={"cores": os.cpu_count()}),
    Target("batch 10000 x 361 Newton: all threads {target} one thread",
           f"pk_batch_tall{_M}", f"pk_batch_t1{_M}", "speedup", ">=", 1.8, "x", ratio=_X),
    Target("peak RSS of a {m} x {n} sweep_batch <= outputs + small constant ({limit})",
           "memory:mem_sweep", None, "value", "<=", 32, " MiB", ratio="+{:.1f} MiB"),
)  # fmt: skip


class Paired(NamedTuple):
    """A ratio target measured in interleaved rounds (``benches/paired.py``): ``key`` in
    paired.json, its words, and whether the ratio is read as ours / peer (``ratio``) or
    peer / ours (``speedup``, as paired.json holds it)."""

    key: str
    text: str
    comparison: str
    op: str
    value: float


PAIRED = (
    Paired("seed_across_vs_numpy", "seed sweep, across-angles option / NumPy closed form",
           "ratio", "<=", 0.5),
    Paired("seed_across_vs_pylinkage", "pylinkage + numba / seed sweep (across-angles option)",
           "speedup", ">=", 4),
    Paired("jansen_vs_pylinkage", "Jansen's leg: pylinkage + numba / planarkin",
           "speedup", ">=", 8),
)  # fmt: skip


def targets(res: Results) -> list[tuple[str, str, str, str]]:
    """(target, measured, ratio, verdict) of every target that was measured."""
    return [r for t in TARGETS if (r := t.row(res)) is not None]


def paired_targets(paired: dict) -> list[tuple[str, str, str, str]]:
    """(target, measured, ratio, verdict) of the ratio targets from interleaved rounds:
    both sides timed in the same phase of the host."""
    out = []
    for t in PAIRED:
        p = paired.get(t.key)
        if not p:
            continue
        med, q1, q3 = p["ratio_median"], p["ratio_q1"], p["ratio_q3"]
        if t.comparison == "ratio":  # ours / peer
            med, q1, q3 = 1.0 / med, 1.0 / q3, 1.0 / q1
            ratio = f"{med:.2f} (quartiles {q1:.2f}-{q3:.2f})"
        else:
            ratio = f"{med:.2f}x faster (quartiles {q1:.2f}-{q3:.2f})"
        out.append(
            (
                f"{t.text} {t.op} {t.value:g} ({p['rounds']} interleaved rounds)",
                f"{fmt_time(p['ours_s'])} vs {fmt_time(p['peer_s'])}",
                ratio,
                verdict(_OPS[t.op](med, t.value)),
            )
        )
    return out
