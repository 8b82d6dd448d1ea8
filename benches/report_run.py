"""Running the benchmarks: criterion (the core alone), pytest-benchmark (everything from
Python, the peak-RSS subprocesses included), the interleaved ratio rounds, the tradeoff
and the web page, each writing its raw results into ``benches/results/`` with the
machine's description (``machine.json``). Rendering them is ``report_render.py``'s."""

from __future__ import annotations

import datetime as dt
import glob
import json
import os
import platform
import subprocess
import sys

from report_common import CARGO_CMD, PAIRED_CMD, PYTEST_CMD, RESULTS, ROOT, WEB_CMD


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
