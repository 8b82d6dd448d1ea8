"""Runs every benchmark on this machine and writes BENCHMARKS.md.

    python benches/report.py run      # criterion + pytest-benchmark + tradeoff, then render
    python benches/report.py render   # re-render BENCHMARKS.md from benches/results/

``run`` takes about 4 minutes on 2 cores. It runs, in this order and in one session:
``cargo bench -p planarkin-core --bench sweep --bench scene`` (the core alone, criterion),
``pytest benches/ --benchmark-enable --benchmark-json=...`` (everything from Python,
including the peak-RSS subprocesses), ``benches/paired.py`` (issue 21's ratio targets in
interleaved rounds), and ``planarkin.fourbar.tradeoff.tradeoff()`` with its
defaults. Raw results go to ``benches/results/``; the hand-written analysis in
``benches/analysis.md`` is appended to the generated tables.
"""

from __future__ import annotations

import argparse
import datetime as dt
import glob
import json
import os
import platform
import shlex
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
RESULTS = os.path.join(HERE, "results")
OUT = os.path.join(ROOT, "BENCHMARKS.md")

CARGO_CMD = [
    "cargo",
    "bench",
    "-p",
    "planarkin-core",
    "--bench",
    "sweep",
    "--bench",
    "scene",
    "--",
    "--warm-up-time",
    "1",
    "--measurement-time",
    "3",
]
PYTEST_CMD = [
    sys.executable,
    "-m",
    "pytest",
    "benches/",
    "--benchmark-enable",
    "--benchmark-min-rounds=5",
    "--benchmark-json=benches/results/pytest.json",
    "-p",
    "no:cacheprovider",
    "-q",
]


# --- running ----------------------------------------------------------------------------


def _sh(cmd: list[str], **kw) -> str:
    return subprocess.run(cmd, check=True, text=True, capture_output=True, cwd=ROOT, **kw).stdout


def _try(cmd: list[str]) -> str:
    try:
        return _sh(cmd).strip()
    except (OSError, subprocess.CalledProcessError):
        return "n/a"


def _version(mod: str) -> str:
    try:
        m = __import__(mod)
        return getattr(m, "__version__", "?")
    except ImportError:
        return "not installed"


def machine() -> dict:
    lscpu = _try(["lscpu"])
    model = next(
        (ln.split(":", 1)[1].strip() for ln in lscpu.splitlines() if ln.startswith("Model name")),
        platform.processor(),
    )
    mem = "n/a"
    try:
        with open("/proc/meminfo") as f:
            kb = int(f.readline().split()[1])
        mem = f"{kb / 2**20:.0f} GiB"
    except OSError:
        pass
    import planarkin as pk

    return {
        "cpu": model,
        "cores": os.cpu_count(),
        "memory": mem,
        "os": f"{platform.system()} {platform.release()}",
        "python": platform.python_version(),
        "numpy": _version("numpy"),
        "planarkin": f"{pk.__version__} ({pk.BUILD_PROFILE} build)",
        "rustc": _try(["rustc", "-V"]),
        "pylinkage": _version("pylinkage"),
        "numba": _version("numba"),
        "mpmath": _version("mpmath"),
        "pytest-benchmark": _version("pytest_benchmark"),
        "git": _try(["git", "rev-parse", "--short", "HEAD"])
        + (
            " (uncommitted changes)"
            if _try(["git", "status", "--porcelain", "--", "rust", "python"])
            else ""
        ),
        "date": dt.datetime.now().astimezone().isoformat(timespec="minutes"),
    }


def _loadavg() -> str:
    try:
        return " ".join(f"{x:.2f}" for x in os.getloadavg())
    except OSError:
        return "n/a"


def extension_freshness() -> str:
    """Whether the installed extension is newer than every Rust source: criterion builds
    from the sources, Python loads the extension, and the two must be the same code."""
    import planarkin._core as core

    so = os.path.getmtime(core.__file__)
    srcs = [
        p
        for pat in ("rust/**/*.rs", "rust/**/Cargo.toml", "Cargo.toml", "Cargo.lock")
        for p in glob.glob(os.path.join(ROOT, pat), recursive=True)
        if os.sep + "benches" + os.sep not in p
    ]
    newer = [os.path.relpath(p, ROOT) for p in srcs if os.path.getmtime(p) > so]
    if newer:
        return "STALE: sources newer than the extension: " + ", ".join(sorted(newer))
    return "extension built after the last Rust source change"


def run_criterion(quick: bool = False) -> dict:
    subprocess.run(CARGO_CMD + (["--quick"] if quick else []), check=True, cwd=ROOT)
    meta = json.loads(_sh(["cargo", "metadata", "--format-version", "1", "--no-deps"]))
    base = os.path.join(meta["target_directory"], "criterion")
    out = {}
    for bj in glob.glob(os.path.join(base, "**", "new", "benchmark.json"), recursive=True):
        with open(bj) as f:
            b = json.load(f)
        with open(os.path.join(os.path.dirname(bj), "estimates.json")) as f:
            e = json.load(f)
        tp = (b.get("throughput") or {}).get("Elements")
        out[b["full_id"]] = {"median_ns": e["median"]["point_estimate"], "elements": tp}
    return out


def compact_pytest_json() -> None:
    """Drops the raw per-round samples (tens of MB) from the pytest-benchmark JSON; the
    statistics stay."""
    path = os.path.join(RESULTS, "pytest.json")
    with open(path) as f:
        data = json.load(f)
    for b in data["benchmarks"]:
        b["stats"].pop("data", None)
    with open(path, "w") as f:
        json.dump(data, f, indent=1)


#: The web page's measurement (needs selenium, chromium, chromedriver).
WEB_CMD = ["python", "benches/web_frame.py"]
PAIRED_CMD = ["python", "benches/paired.py"]


def run_all(quick: bool = False) -> None:
    """``quick``: a smoke run (criterion --quick, one round each, a 10 000-row memory
    batch, a small tradeoff) to debug the pipeline; its numbers are not for publishing."""
    os.makedirs(RESULTS, exist_ok=True)
    info = machine()
    info["load_before"] = _loadavg()
    info["extension"] = extension_freshness()
    if info["extension"].startswith("STALE"):
        print(f"warning: {info['extension']} (rebuild with maturin develop -r)", file=sys.stderr)
    if quick:
        info["quick"] = "yes: smoke run, not for publishing"
    print("== criterion:", " ".join(CARGO_CMD), flush=True)
    crit = run_criterion(quick)
    with open(os.path.join(RESULTS, "criterion.json"), "w") as f:
        json.dump(crit, f, indent=1, sort_keys=True)
    print("== pytest-benchmark:", " ".join(PYTEST_CMD[2:]), flush=True)
    # nothing benchmarked uses BLAS; keep OpenBLAS's idle threads off the two cores
    cmd, env = PYTEST_CMD, {**os.environ, "OPENBLAS_NUM_THREADS": "1"}
    if quick:
        cmd = [*PYTEST_CMD, "--benchmark-min-rounds=1", "--benchmark-max-time=0.05"]
        env["PLANARKIN_BENCH_MEMORY_M"] = "10000"
    subprocess.run(cmd, check=True, cwd=ROOT, env=env)
    compact_pytest_json()
    print("== paired ratios:", " ".join(PAIRED_CMD), flush=True)
    subprocess.run([sys.executable, *PAIRED_CMD[1:], *(["--rounds", "9"] if quick else [])],
                   check=True, cwd=ROOT, env=env)  # fmt: skip
    print("== tradeoff", flush=True)
    from planarkin.face.figures.tradeoff import save
    from planarkin.fourbar.tradeoff import tradeoff

    res = tradeoff(n_random=15, truth_links=4, repeat=1) if quick else tradeoff()
    save(res, os.path.join(RESULTS, "tradeoff.png"))
    with open(os.path.join(RESULTS, "tradeoff.json"), "w") as f:
        json.dump(res.to_dict(), f, indent=1)
    print("== web page:", " ".join(WEB_CMD), flush=True)
    try:
        subprocess.run([sys.executable, *WEB_CMD[1:]], check=True, cwd=ROOT)
    except (subprocess.CalledProcessError, OSError) as e:
        # it needs selenium, chromium and chromedriver: keep the last web.json without them
        print(f"warning: web page not measured ({e}); keeping the last web.json", file=sys.stderr)
    info["load_after"] = _loadavg()
    with open(os.path.join(RESULTS, "machine.json"), "w") as f:
        json.dump(info, f, indent=1)
    render()


# --- rendering --------------------------------------------------------------------------


def _load(name: str):
    with open(os.path.join(RESULTS, name)) as f:
        return json.load(f)


def _t(seconds: float) -> str:
    """A duration with a unit that keeps three significant digits."""
    for unit, scale in (("s", 1.0), ("ms", 1e-3), ("µs", 1e-6), ("ns", 1e-9)):
        if seconds >= scale or unit == "ns":
            return f"{seconds / scale:.3g} {unit}"
    return str(seconds)


def _ratio(x: float) -> str:
    return f"{x:.2f}x" if x < 10 else f"{x:.0f}x" if x < 1000 else f"{x:.2g}x"


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


def _info_cell(ei: dict) -> str:
    parts = []
    if "nit_mean" in ei:
        parts.append(f"{ei['nit_mean']:.2f} it/pt")
    if "max_error" in ei:
        parts.append(f"err {ei['max_error']:.1e}")
    if "note" in ei:
        parts.append(ei["note"])
    return ", ".join(parts)


def _group_table(rows: list[dict], base: dict | None, points: int | None) -> list[str]:
    head = "| implementation | median | per point | vs planarkin | notes |"
    if base is None:
        head = "| implementation | median | per point | notes |"
    lines = [head, "|---|---:|---:|" + ("---:|" if base else "") + "---|"]
    for b in sorted(rows, key=lambda b: b["stats"]["median"]):
        ei = b.get("extra_info", {})
        med = b["stats"]["median"]
        pts = ei.get("points") or points or (ei.get("m", 1) * 361)
        name = ei.get("label", b["name"])
        if b is base:
            name = f"**{name}**"
        per = "-" if points == 0 else f"{med / pts * 1e9:.0f} ns"  # whole calls, not points
        cells = [name, _t(med), per]
        if base:
            cells.append(_ratio(med / base["stats"]["median"]))
        cells.append(_info_cell(ei))
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def _verdict(ok: bool | None) -> str:
    return "n/a" if ok is None else ("**met**" if ok else "**missed**")


def _faster(target: str, ours: float | None, peer: float | None, at_least: float):
    """A (target, measured, ratio, verdict) row: ours at least ``at_least`` times faster."""
    if not (ours and peer):
        return []
    return [(target, f"{_t(ours)} vs {_t(peer)}", f"{peer / ours:.2f}x faster",
             _verdict(peer / ours >= at_least))]  # fmt: skip


def scene_targets(bench: Bench) -> list[tuple[str, str, str, str]]:
    """(target, measured, ratio, verdict) for the scenes issue's targets."""
    pk, pl, npc = (bench.median(k) for k in ("scene_jansen_pk", "scene_jansen_pylinkage",
                                             "scene_jansen_numpy"))  # fmt: skip
    out = _faster("Jansen's leg (foot, 361 angles) >= 3x faster than pylinkage + numba",
                  pk, pl, 3)  # fmt: skip
    out += _faster("Jansen's leg: pylinkage + numba / planarkin >= 8 (issue 21)", pk, pl, 8)
    out += _faster("Jansen's leg faster than a vectorized NumPy circle-intersection chain",
                   pk, npc, 1)  # fmt: skip
    for name in ("double-butterfly-1", "double-butterfly-2"):
        row = bench.get(f"scene_group_{name}")
        if row:
            nit = row["extra_info"]["nit_mean"]
            out.append(
                (
                    f"{name}: Newton iterations per solved angle < 1.5 (tol 1e-9, 1 deg)",
                    f"{nit:.2f} it/pt over {row['extra_info']['solved']} angles",
                    "-",
                    _verdict(nit < 1.5),
                )
            )
            med = bench.median(f"scene_group_{name}")
            out.append(
                (
                    f"{name} sweep, 361 angles (both dead points found): <= 0.3 ms (issue 21)",
                    _t(med),
                    "-",
                    _verdict(med is not None and med <= 0.3e-3),
                )
            )
    sk, sl, sn = (bench.median(k) for k in ("slider_pk", "slider_pylinkage", "slider_numpy"))
    out += _faster("slider-crank (piston, 361 angles) >= 3x faster than pylinkage + numba "
                   "(RRPDyad)", sk, sl, 3)  # fmt: skip
    out += _faster("slider-crank faster than the NumPy closed form written as a user would",
                   sk, sn, 1)  # fmt: skip
    row = bench.get("scene_assemblies")
    if row and "paths" in row["extra_info"]:
        paths, finite = row["extra_info"]["paths"], row["extra_info"]["finite"]
        med = bench.median("scene_assemblies")
        out.append(
            (
                "double butterfly assemblies: >= 60% of homotopy paths finite, <= 8 ms (issue 21)",
                f"{finite} of {paths} paths finite, {_t(med)}",
                f"{finite / paths:.0%}",
                _verdict(finite / paths >= 0.6 and med is not None and med <= 8e-3),
            )
        )
    ex, fd = bench.median("scene_gradient_exact"), bench.median("scene_gradient_fd")
    if ex and fd:
        out.append(
            (
                "exact gradients (16 coordinates x 1001 angles) vs forward differences",
                f"{_t(ex)} vs {_t(fd)}",
                f"{fd / ex:.1f}x faster",
                "-",
            )
        )
    for what, key in (
        ("synthesis: the residuals' derivatives at one steering design, exact vs fd", "rows"),
        ("synthesis: one SLSQP start (60 iterations), exact vs fd", "start"),
    ):
        ex, fd = bench.median(f"synth_{key}_exact"), bench.median(f"synth_{key}_fd")
        if ex and fd:
            out.append((what, f"{_t(ex)} vs {_t(fd)}", f"{fd / ex:.1f}x faster", "-"))
    ex, fd = bench.median("synth_cli_exact"), bench.median("synth_cli_fd")
    if ex and fd:
        out.append(
            (
                "planarkin synthesize ackermann --starts 2: exact >= 8x faster than fd (issue 19)",
                f"{_t(ex)} vs {_t(fd)}",
                f"{fd / ex:.1f}x faster",
                _verdict(fd / ex >= 8),
            )
        )
    one, full = bench.median("scene_plan_first_dyad"), bench.median("scene_plan_all")
    if one and full:
        out.append(
            (
                "Watt II: one requested dyad measurably cheaper than the whole plan",
                f"{_t(one)} vs {_t(full)}",
                f"{one / full:.2f}",
                _verdict(one < 0.8 * full),
            )
        )
    return out


def paired_targets(paired: dict) -> list[tuple[str, str, str, str]]:
    """(target, measured, ratio, verdict) for issue 21's ratio targets, from interleaved
    rounds (benches/paired.py): both sides timed in the same phase of the host."""
    out = []
    rows = [
        ("seed_across_vs_numpy", "seed sweep, across-angles option / NumPy closed form <= 0.5",
         lambda r: 1.0 / r <= 0.5, True),
        ("seed_across_vs_pylinkage",
         "pylinkage + numba / seed sweep (across-angles option) >= 4", lambda r: r >= 4.0, False),
        ("jansen_vs_pylinkage", "Jansen's leg: pylinkage + numba / planarkin >= 8",
         lambda r: r >= 8.0, False),
    ]  # fmt: skip
    for key, name, ok, inverse in rows:
        p = paired.get(key)
        if not p:
            continue
        med, q1, q3 = p["ratio_median"], p["ratio_q1"], p["ratio_q3"]
        if inverse:  # ours / peer
            med, q1, q3 = 1.0 / med, 1.0 / q3, 1.0 / q1
            ratio = f"{med:.2f} (quartiles {q1:.2f}-{q3:.2f})"
        else:
            ratio = f"{med:.2f}x faster (quartiles {q1:.2f}-{q3:.2f})"
        out.append(
            (
                f"{name} (issue 21; {p['rounds']} interleaved rounds)",
                f"{_t(p['ours_s'])} vs {_t(p['peer_s'])}",
                ratio,
                _verdict(ok(p["ratio_median"])),
            )
        )
    return out


def targets(bench: Bench, crit: dict, trade: dict) -> list[tuple[str, str, str, str]]:
    """(target, measured, ratio, verdict) for each target in the issue."""
    out = scene_targets(bench)

    def add(name, measured, ratio, ok):
        out.append((name, measured, ratio, _verdict(ok)))

    pk_sweep = bench.median("pk_sweep_quadratic")
    seed_np = bench.median("np_closed_form", m=None)  # the seed group's row has no "m"
    if pk_sweep and seed_np:
        r = pk_sweep / seed_np
        add(
            "seed sweep from Python vs NumPy vectorized closed form (ratio <= 1.0)",
            f"{_t(pk_sweep)} vs {_t(seed_np)}",
            f"{r:.2f}",
            r <= 1.0,
        )
    across = bench.median("pk_sweep_closed-form")
    if across and seed_np:
        r = across / seed_np
        add(
            "seed sweep, across-angles option / NumPy closed form <= 0.5 (issue 21)",
            f"{_t(across)} vs {_t(seed_np)}",
            f"{r:.2f}",
            r <= 0.5,
        )
    pl = bench.median("pylinkage")
    if across and pl:
        r = pl / across
        add(
            "pylinkage + numba / seed sweep (across-angles option) >= 4 (issue 21)",
            f"{_t(across)} vs {_t(pl)}",
            f"{r:.2f}x faster",
            r >= 4.0,
        )
    if pk_sweep and pl:
        r = pl / pk_sweep
        add(
            "seed sweep >= 3x faster than pylinkage + numba",
            f"{_t(pk_sweep)} vs {_t(pl)}",
            f"{r:.2f}x faster",
            r >= 3.0,
        )
    elif pk_sweep:
        add("seed sweep >= 3x faster than pylinkage + numba", "pylinkage not installed", "-", None)
    rust = crit.get("seed_sweep_361/quadratic_alloc", {}).get("median_ns")
    if pk_sweep and rust:
        frac = 1 - rust * 1e-9 / pk_sweep
        add(
            "Python-side overhead < 25% of the seed sweep (vs criterion: the same sweep, "
            "allocating its outputs, in Rust)",
            f"{_t(pk_sweep)} Python vs {_t(rust * 1e-9)} Rust",
            f"{frac:.0%}",
            frac < 0.25,
        )
    b = bench.get("pk_sweep_tangent")
    if b:
        nit = b["extra_info"]["nit_mean"]
        add(
            "mean iterations per point, tol 1e-9, tangent predictor <= 1.6 (seed sweep)",
            f"{nit:.2f}",
            "-",
            nit <= 1.6,
        )
    tr_row = next(
        (r for r in trade.get("rows", []) if r["method"] == "tangent" and r["tol"] == 1e-9), None
    )
    if tr_row:
        add(
            "(same, over the seed + random crank-rockers of the tradeoff run)",
            f"{tr_row['nit_mean']:.2f}",
            "-",
            tr_row["nit_mean"] <= 1.6,
        )
    m = 10_000
    t1 = bench.median("pk_batch_t1", m=m)
    npcf = bench.median("np_closed_form", m=m)
    if t1 and npcf:
        r = npcf / t1
        add(
            f"batch {m} x 361, Newton on 1 thread: throughput >= NumPy closed form",
            f"{_t(t1)} vs {_t(npcf)}",
            f"{r:.2f}x",
            r >= 1.0,
        )
    across = bench.median("pk_batch_across_t1", m=m)
    if across and npcf:
        r = npcf / across
        add(
            f"Newton batch {m} x 361 across angles (predictor='closed-form'), 1 thread: "
            ">= 1.5x NumPy closed form (issue 21)",
            f"{_t(across)} vs {_t(npcf)} ({across / (m * 361) * 1e9:.1f} ns per point)",
            f"{r:.2f}x",
            r >= 1.5,
        )
    cf1 = bench.median("pk_cf_batch_t1", m=m)
    cfa = bench.median("pk_cf_batch_tall", m=m)
    if cf1:
        ns = cf1 / (m * 361) * 1e9
        add(
            f"closed-form batch {m} x 361, 1 thread: <= 10 ns per point (issue 21)",
            f"{ns:.1f} ns per point",
            "-",
            ns <= 10.0,
        )
    cfo = bench.median("pk_cf_batch_t1_out", m=m)
    if cfo:
        ns = cfo / (m * 361) * 1e9
        add(
            "(same, written into arrays the caller keeps: `out=`, no new memory to clear)",
            f"{ns:.1f} ns per point",
            "-",
            ns <= 10.0,
        )
    if cf1 and npcf:
        r = npcf / cf1
        add(
            f"closed-form batch {m} x 361 >= 3x NumPy closed form (1 thread)",
            f"{_t(cf1)} vs {_t(npcf)}",
            f"{r:.2f}x",
            r >= 3.0,
        )
    if cfa and npcf:
        r = npcf / cfa
        add(
            f"(same, closed-form batch on all {os.cpu_count()} threads)",
            f"{_t(cfa)} vs {_t(npcf)}",
            f"{r:.2f}x",
            r >= 3.0,
        )
    ta = bench.median("pk_batch_tall", m=m)
    if t1 and ta:
        r = t1 / ta
        add(
            f"batch {m} x 361 Newton: all threads >= 1.8x one thread",
            f"{_t(ta)} vs {_t(t1)}",
            f"{r:.2f}x",
            r >= 1.8,
        )
    mem = bench.get("mem_sweep")
    if mem:
        ei = mem["extra_info"]
        over = ei["overhead_bytes"]
        add(
            f"peak RSS of a {ei['m']} x {ei['n']} sweep_batch <= outputs + small constant (32 MiB)",
            f"{ei['delta_bytes'] / 2**20:.0f} MiB for "
            f"{ei['output_bytes'] / 2**20:.0f} MiB of output",
            f"+{over / 2**20:.1f} MiB",
            over <= 32 * 2**20,
        )
    return out


def render() -> None:
    info = _load("machine.json")
    bench = Bench(_load("pytest.json"))
    crit = _load("criterion.json")
    trade = _load("tradeoff.json") if os.path.exists(os.path.join(RESULTS, "tradeoff.json")) else {}
    L: list[str] = []
    L += [
        "# planarkin benchmarks",
        "",
        "Generated by `python benches/report.py run` (do not edit by hand; the analysis "
        "at the end comes from `benches/analysis.md`). All numbers below come from one run "
        "on one machine; ratios compare medians from that run.",
        "",
    ]

    L += ["## Targets", "", "| target | measured | ratio | verdict |", "|---|---|---|---|"]
    for t in targets(bench, crit, trade):
        L.append("| " + " | ".join(t) + " |")
    if os.path.exists(os.path.join(RESULTS, "paired.json")):
        L += [
            "",
            "The same ratio targets measured in interleaved rounds (`benches/paired.py`): each "
            "round times about 2 ms of calls of one side, then of the other, so both see the "
            "same phase of a host whose speed changes over seconds; the ratio is the median of "
            "the rounds' ratios (times: medians per call).",
            "",
            "| target | measured | ratio | verdict |",
            "|---|---|---|---|",
        ]
        for t in paired_targets(_load("paired.json")):
            L.append("| " + " | ".join(t) + " |")

    L += ["", "## Machine and command", ""]
    for k in (
        "quick",
        "cpu",
        "cores",
        "memory",
        "os",
        "python",
        "numpy",
        "planarkin",
        "rustc",
        "pylinkage",
        "numba",
        "mpmath",
        "pytest-benchmark",
        "git",
        "extension",
        "date",
        "load_before",
        "load_after",
    ):
        if k in info:
            L.append(f"- {k.replace('_', ' ')}: {info[k]}")
    L += [
        "",
        "Commands (run by `python benches/report.py run`, in this order):",
        "",
        "```",
        " ".join(shlex.quote(c) for c in CARGO_CMD),
        " ".join(shlex.quote(c) for c in ["python", *PYTEST_CMD[1:]]),
        " ".join(PAIRED_CMD),
        "python -c 'from planarkin.fourbar.tradeoff import tradeoff; tradeoff()'"
        "  # = planarkin tradeoff",
        "# environment: OPENBLAS_NUM_THREADS=1 for pytest (no benchmark uses BLAS)",
        "```",
        "",
        "Times are medians. *per point* divides by the crank angles solved (M x N). "
        "*vs planarkin* is median / median of the bold row (above 1: slower than planarkin). "
        "*it/pt* is the mean number of Newton steps per point; *err* the largest angle "
        "difference (rad) from planarkin's closed form, checked outside the timed call.",
        "",
    ]

    order = [
        ("seed sweep", "pk_sweep_quadratic", None),
        ("seed sweep: Python layers", "layers_api", None),
        ("batch: M=1 ", "pk_batch_t1", None),
        ("batch: M=100 ", "pk_batch_t1", None),
        ("batch: M=10000 ", "pk_batch_t1", None),
        ("growth with N", None, None),
        ("growth with M", None, None),
        ("overhead", "ovh_solve", 1),
        ("scene: Jansen", "scene_jansen_pk", 361),
        ("scene: centred slider-crank", "slider_pk", 361),
        ("scene: groups", None, 361),
        ("scene: Watt", "scene_plan_all", 361),
        ("scene: double butterfly", None, 0),
    ]
    done = set()
    for prefix, base_impl, points in order:
        for g, rows in bench.groups.items():
            if not g.startswith(prefix) or g in done:
                continue
            done.add(g)
            base = next((b for b in rows if b["extra_info"].get("impl") == base_impl), None)
            L += [f"## {g}", ""]
            L += _group_table(rows, base, points)
            if prefix == "seed sweep: Python layers":
                L += _layers_note(bench, crit)
            if prefix == "scene: centred slider-crank":
                L += _slider_note(bench, crit)
            if prefix.startswith("growth"):
                L += _growth_note(rows)
            L.append("")

    L += [
        "## Rust core alone (criterion)",
        "",
        "| benchmark | median | per element |",
        "|---|---:|---:|",
    ]
    for k in sorted(crit):
        v = crit[k]
        per = f"{v['median_ns'] / v['elements']:.0f} ns" if v.get("elements") else ""
        L.append(f"| {k} | {_t(v['median_ns'] * 1e-9)} | {per} |")
    L.append("")

    mem = [b for b in bench.rows if b["extra_info"].get("impl", "").startswith("mem_")]
    if mem:
        L += [
            f"## Peak memory of one {mem[0]['extra_info']['m']} x 361 batch",
            "",
            "Each call measured in a fresh process (`benches/memory.py`): the peak RSS "
            "(Linux VmHWM) after the call minus the RSS after importing, building the inputs "
            "and a small warm-up call (where the peak mark is reset), compared with the bytes "
            "of the arrays the call returns. (`getrusage` maxrss is not used on Linux: a "
            "child inherits its parent's maxrss across fork and exec, so under pytest it "
            "starts at the size of the pytest process.)",
            "",
            "| call | time | peak RSS increase | output arrays | beyond the output |",
            "|---|---:|---:|---:|---:|",
        ]
        for b in mem:
            e = b["extra_info"]
            L.append(
                f"| {e['label']} | {e['seconds']:.2f} s | {e['delta_bytes'] / 2**20:.0f} MiB | "
                f"{e['output_bytes'] / 2**20:.0f} MiB | {e['overhead_bytes'] / 2**20:+.1f} MiB |"
            )
        L.append("")

    if trade:
        L += [
            "## Speed/accuracy trade (`planarkin tradeoff`)",
            "",
            trade["summary"] + ".",
            "",
            _tradeoff_md(trade),
            "",
            "*Pareto*: `all` = no row is both faster and more accurate; `N` = the same among "
            "the Newton rows only.",
            "",
            "![speed vs accuracy](benches/results/tradeoff.png)",
            "",
        ]

    if os.path.exists(os.path.join(RESULTS, "web.json")):
        L += _web_md(_load("web.json"))

    for name in ("analysis.md", "analysis_scenes.md"):
        analysis = os.path.join(HERE, name)
        if os.path.exists(analysis):
            with open(analysis, encoding="utf-8") as f:
                L += [f.read().rstrip(), ""]
    with open(OUT, "w", encoding="utf-8") as f:
        f.write("\n".join(L))
    print(f"wrote {OUT}")


def _web_md(web: dict) -> list[str]:
    """The web page (issue 18): frame times, frame rate and size, measured in headless
    Chromium by ``benches/web_frame.py`` (its own run: see the command below)."""

    def ms(k: str) -> str:
        return f"{web[k]['median_ms'] * 1000:.0f} µs (best {web[k]['min_ms'] * 1000:.0f} µs)"

    samples = sorted(web["fps_jansen"]["samples"] + web["fps_fourbar"]["samples"])
    fps, low = samples[len(samples) // 2], samples[0]
    return [
        "## Web page: the core compiled to WebAssembly, in headless Chromium",
        "",
        f"Measured by `{' '.join(WEB_CMD)}` in Chromium {web['browser']} (headless, this "
        "machine), on the page's own calls: a JSON request in, the reply and its numbers "
        "out, through the module's C interface. Times per call: the median (and the best) "
        "of 9 blocks of calls, each block timed as a whole.",
        "",
        "| what | target | measured | verdict |",
        "|---|---|---|---|",
        f"| one frame of Jansen's leg: the pose and the full tracer path (361 inputs) | "
        f"<= 1 ms | {ms('jansen_frame')} | {_verdict(web['jansen_frame']['median_ms'] <= 1)} |",
        f"| (its parts: the pose alone; the 361-input path alone) | - | "
        f"{ms('jansen_pose')}; {ms('jansen_path')} | - |",
        f"| one four-bar frame: pose, coupler path (361), class, limits | - | "
        f"{ms('fourbar_frame')} | - |",
        f"| frame rate while auto-rotating (requestAnimationFrame count per second, five "
        f"1-s samples each of Jansen and the four-bar: median, lowest) | 60 fps | "
        f"{fps:.1f} fps (lowest {low:.1f}) | {_verdict(fps >= 59)} |",
        f"| planarkin.wasm, gzip -9 (raw {web['wasm_bytes'] / 1000:.0f} kB) | < 500 kB | "
        f"{web['wasm_gzip_bytes'] / 1000:.0f} kB | {_verdict(web['wasm_gzip_bytes'] < 500_000)} |",
        "",
        "requestAnimationFrame fires at 60 Hz in headless Chromium here, so 60 fps is the "
        "ceiling; a frame's solve takes a few percent of its 16.7 ms. Load average "
        f"{' '.join(web['load_before'])} before and {' '.join(web['load_after'])} after "
        "(the machine was shared while this ran).",
        "",
    ]


def _layers_note(bench: Bench, crit: dict) -> list[str]:
    api = bench.median("layers_api")
    binding = bench.median("layers_binding")
    one = bench.median("layers_binding_1pt")
    rust = crit.get("seed_sweep_361/quadratic_alloc", {}).get("median_ns")
    rust0 = crit.get("seed_sweep_361/quadratic", {}).get("median_ns")
    if not (api and binding and rust):
        return []
    r = rust * 1e-9
    return [
        "",
        f"Rust alone (criterion, same sweep, allocating its outputs): {_t(r)}"
        + (f" ({_t(rust0 * 1e-9)} into preallocated buffers)" if rust0 else "")
        + f". Binding cost {_t(binding - r)} ({(binding - r) / api:.0%} of the API call), "
        f"Python API layer {_t(api - binding)} ({(api - binding) / api:.0%}); a 1-angle "
        f"binding call costs {_t(one)}.",
    ]


def _slider_note(bench: Bench, crit: dict) -> list[str]:
    """The slider-crank's planarkin time split into the core alone (criterion), the
    binding and the Python layer."""
    api, binding = bench.median("slider_pk"), bench.median("slider_binding")
    rust = crit.get("slider_crank_361/piston", {}).get("median_ns")
    if not (api and binding and rust):
        return []
    r = rust * 1e-9
    if not r < binding < api:
        # each median from its own stretch of the run: on a host whose speed changes,
        # a later layer can time faster than the one inside it
        return [
            "",
            f"Rust core alone (criterion `slider_crank_361/piston`, into preallocated "
            f"buffers): {_t(r)}; binding alone {_t(binding)}, the whole call {_t(api)}: not "
            "split in this run (the rows fell in different phases of the host).",
        ]
    return [
        "",
        f"Rust core alone (criterion `slider_crank_361/piston`, into preallocated buffers): "
        f"{_t(r)}; binding {_t(binding - r)} (its arrays and call); Python layer "
        f"{_t(api - binding)} (arguments, the result object).",
    ]


def _growth_note(rows: list[dict]) -> list[str]:
    per = sorted(
        (b["extra_info"]["points"], b["stats"]["median"] / b["extra_info"]["points"]) for b in rows
    )
    if len(per) < 2:
        return []
    lo, hi = min(p for _, p in per), max(p for _, p in per)
    return [
        "",
        f"Time per point from {per[0][0]} to {per[-1][0]} points: "
        + ", ".join(f"{p * 1e9:.0f} ns" for _, p in per)
        + f" (max/min {hi / lo:.2f}: linear growth when close to 1).",
    ]


def _tradeoff_md(trade: dict) -> str:
    head = (
        "| method | tol | iter/pt | iter/pt (seed) | ns/pt | max error (rad) | seed max error "
        "| median error | failed | Pareto |"
    )
    lines = [head, "|---|---:|---:|---:|---:|---:|---:|---:|---:|:---:|"]
    for r in trade["rows"]:
        par = "/".join(x for x, on in (("all", r["pareto"]), ("N", r["pareto_newton"])) if on)
        tol = "-" if r["tol"] is None else f"{r['tol']:.0e}"
        lines.append(
            f"| {r['label']} | {tol} | {r['nit_mean']:.2f} | {r['nit_seed']:.2f} | "
            f"{r['ns_per_point']:.0f} | {r['err_max']:.1e} | {r['err_seed']:.1e} | "
            f"{r['err_median']:.1e} | {r['failed']} | {par} |"
        )
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    p.add_argument("what", choices=("run", "render"))
    p.add_argument("--quick", action="store_true", help="smoke run to debug the pipeline")
    a = p.parse_args(argv)
    if a.what == "run":
        run_all(a.quick)
    else:
        render()
    return 0


if __name__ == "__main__":
    sys.exit(main())
