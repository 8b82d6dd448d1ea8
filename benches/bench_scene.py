"""Scenes side by side: Jansen's leg (foot requested) by planarkin, a vectorized NumPy chain of
circle intersections and pylinkage (numba); groups that no dyad reaches (Stephenson III,
the double butterflies) with iterations per point; a plan that needs one dyad against the
whole six-bar; every assembly, a traced circuit and all circuits of a double butterfly; and
loading a 16 000-point file against json.loads of its text. Correctness is checked outside
the timed calls."""

from __future__ import annotations

import json
import math

import numpy as np
import planarkin as pk
import pytest
import scene_peers
from conftest import record

DEG = math.pi / 180


def _theta(sc: pk.Scene) -> np.ndarray:
    return sc.input_angle + np.arange(361) * DEG


def _size(sc: pk.Scene) -> float:
    return float(np.ptp(np.array(list(sc.points.values())), axis=0).max())


# --- Jansen's leg, the foot requested --------------------------------------------------

JANSEN = "scene: Jansen's leg, 361 angles, foot requested"


@pytest.fixture(scope="module")
def jansen():
    sc = pk.scenes.load("jansen")
    truth = sc.sweep(outputs=["foot"]).points["foot"]
    return sc, truth


@pytest.mark.benchmark(group=JANSEN)
def test_jansen_planarkin(benchmark, jansen):
    sc, truth = jansen
    sw = benchmark(sc.sweep, outputs=["foot"])
    assert sw.success.all()
    record(benchmark, "scene_jansen_pk", "planarkin sc.sweep(outputs=['foot'])",
           max_error=float(np.abs(sw.points["foot"] - truth).max()))  # fmt: skip


@pytest.mark.benchmark(group=JANSEN)
def test_jansen_planarkin_all_points(benchmark, jansen):
    sc, truth = jansen
    sw = benchmark(sc.sweep, outputs="all")
    record(benchmark, "scene_jansen_pk_all", "planarkin sc.sweep(outputs='all') (every point)",
           max_error=float(np.abs(sw.points["foot"] - truth).max()))  # fmt: skip


@pytest.mark.benchmark(group=JANSEN)
def test_jansen_numpy_chain(benchmark, jansen):
    sc, truth = jansen
    chain = scene_peers.NumpyChain(sc.to_dict())
    t = _theta(sc)
    out = benchmark(chain.run, t)
    err = float(np.abs(out["foot"] - truth).max())
    assert err < 1e-10 * _size(sc)
    record(benchmark, "scene_jansen_numpy", "NumPy vectorized circle-intersection chain",
           max_error=err)  # fmt: skip


@pytest.mark.benchmark(group=JANSEN)
def test_jansen_pylinkage(benchmark, jansen):
    pytest.importorskip("numba")
    pylinkage = pytest.importorskip("pylinkage")
    sc, truth = jansen
    pl = scene_peers.PylinkageScene(sc.to_dict())
    traj = benchmark(pl.run)
    err = float(np.abs(traj[:, pl.names.index("foot")] - truth).max())
    assert err < 1e-10 * _size(sc)
    record(benchmark, "scene_jansen_pylinkage",
           f"pylinkage {pylinkage.__version__} step_fast (numba)", max_error=err)  # fmt: skip


# --- groups: no dyad reaches them ------------------------------------------------------

GROUPS = "scene: groups solved by Newton, 361 angles (tol 1e-9, 1 deg steps)"


@pytest.mark.benchmark(group=GROUPS)
@pytest.mark.parametrize("name", ["stephenson3", "double-butterfly-1", "double-butterfly-2"])
def test_group_sweep(benchmark, name):
    sc = pk.scenes.load(name)
    sw = benchmark(sc.sweep, outputs="all")
    ok = sw.success
    ref = pk.reference.scene_sweep(sc.to_dict(), sw.theta)
    both = ok & (ref.status == 0)
    err = max(float(np.abs(sw.points[p][both] - ref.points[p][both]).max()) for p in sc.points)
    assert err < 1e-9 * _size(sc)
    record(benchmark, f"scene_group_{name}",
           f"planarkin {name}: {int(ok.sum())} solved, {int((~ok).sum())} LIMIT",
           nit_mean=float(sw.nit[ok].mean()), solved=int(ok.sum()), max_error=err,
           note="pylinkage: cannot solve (no dyad reaches the group)")  # fmt: skip


NEAR = "scene: double butterflies, 361 angles within 20 deg of the drawn pose (all converge)"


@pytest.mark.benchmark(group=NEAR)
@pytest.mark.parametrize("name", ["double-butterfly-1", "double-butterfly-2"])
def test_group_sweep_converged(benchmark, name):
    # every angle converges: the group's Newton work alone, no dead point to bracket
    sc = pk.scenes.load(name)
    theta = sc.input_angle + np.radians(np.linspace(-20.0, 20.0, 361))
    sw = benchmark(sc.sweep, theta, outputs="all")
    assert sw.success.all()
    ref = pk.reference.scene_sweep(sc.to_dict(), theta)
    assert (ref.status == 0).all()
    err = max(float(np.abs(sw.points[p] - ref.points[p]).max()) for p in sc.points)
    assert err < 1e-9 * _size(sc)
    record(benchmark, f"scene_group_near_{name}",
           f"planarkin {name}: 361 angles within 20 deg, all solved",
           nit_mean=float(sw.nit.mean()), max_error=err)  # fmt: skip


# --- the plan: only what the outputs need ----------------------------------------------

PLAN = "scene: Watt-II six-bar, one dyad requested vs the whole plan"


@pytest.mark.benchmark(group=PLAN)
@pytest.mark.parametrize("what", ["first dyad", "all"])
def test_plan_pruning(benchmark, what):
    # without its declared output, which every plan reports (the rocker: the second dyad)
    d = pk.scenes.data("watt2")
    d.pop("output")
    sc = pk.Scene.from_dict(d)
    full = sc.plan("all")
    outputs = [full[0].points[0]] if what == "first dyad" else "all"
    sw = benchmark(sc.sweep, outputs=outputs)
    assert sw.success.all()
    record(benchmark, f"scene_plan_{what.replace(' ', '_')}",
           f"planarkin watt2, outputs={outputs!r}: {len(sc.plan(outputs))} step(s)")  # fmt: skip


# --- every assembly, tracing, circuits ---------------------------------------------------

CIRCUITS = "scene: double butterfly (type II): assemblies, a traced circuit, all circuits"


@pytest.mark.benchmark(group=CIRCUITS)
def test_assemblies(benchmark):
    sc = pk.scenes.load("double-butterfly-2")
    a = benchmark(sc.assemblies)
    assert a.complex_counts == [[18]]
    (paths,) = a.paths[0]
    record(benchmark, "scene_assemblies", f"sc.assemblies(): {len(a)} real of 18 complex "
           f"(2 homotopy runs, {paths} paths: the isotropic start system)",
           paths=paths, finite=18 * 2)  # fmt: skip


@pytest.mark.benchmark(group=CIRCUITS)
def test_trace(benchmark):
    sc = pk.scenes.load("double-butterfly-2")
    tr = benchmark(sc.trace)
    assert tr.closed
    record(benchmark, "scene_trace", f"sc.trace(): one full circuit, {len(tr)} points, "
           f"{len(tr.turning_points)} turning points")  # fmt: skip


@pytest.mark.benchmark(group=CIRCUITS)
def test_circuits(benchmark):
    sc = pk.scenes.load("double-butterfly-2")
    cs = benchmark(sc.circuits)
    record(benchmark, "scene_circuits", f"sc.circuits(): {len(cs)} circuit(s), "
           f"{sum(len(c.assemblies) for c in cs)} assemblies")  # fmt: skip


# --- exact gradients by the drawn coordinates (synthesis) -----------------------------------

GRADIENT = "scene: d(points)/d(drawn coordinates), double butterfly, 16 coordinates, 1001 angles"


def _gradient_case():
    sc = pk.scenes.load("double-butterfly-1")
    d = sc.to_dict()
    ground = set(d["links"][d["ground"]])
    free = [p for p in d["points"] if p not in ground][:8]
    theta = sc.input_angle + np.radians(np.linspace(-20.0, 20.0, 1001))
    return sc, d, free, theta


@pytest.mark.benchmark(group=GRADIENT)
def test_gradient_exact(benchmark):
    sc, _, free, theta = _gradient_case()
    g = benchmark(sc.gradient, free, theta)
    record(benchmark, "scene_gradient_exact", "sc.gradient(free, theta): implicit "
           f"differentiation, its sweep included ({len(g.free)} coordinates)")  # fmt: skip


@pytest.mark.benchmark(group=GRADIENT)
def test_gradient_forward_differences(benchmark):
    sc, d, free, theta = _gradient_case()
    labels = [f"{p}.{a}" for p in free for a in "xy"]

    def fd():
        base = sc.sweep(theta, outputs="all")
        out = []
        for label in labels:
            p, a = label.split(".")
            pts = {n: list(v) for n, v in d["points"].items()}
            pts[p]["xy".index(a)] += 1e-7
            out.append(pk.Scene({**d, "points": pts}).sweep(theta, outputs="all"))
        return base, out

    benchmark(fd)
    record(benchmark, "scene_gradient_fd", f"forward differences: 1 + {len(labels)} sweeps "
           "of redrawn scenes")  # fmt: skip


# --- loading a file: the core's reader and checks against json.loads --------------------------

LOAD = "scene: loading a 16 000-point link from a JSON file (700 kB)"


@pytest.fixture(scope="module")
def big_file(tmp_path_factory):
    """One link carrying 16 000 points besides its pivot and first point, each offset from
    the last (none coincide), written as json.dumps writes it."""
    n = 16_000
    points = {"O": [0.0, 0.0], "X": [1.0, 0.0], "A": [0.3, 0.4]}
    points |= {f"p{i}": [0.31 + 1e-3 * i, 0.4 + 5e-4 * i] for i in range(n)}
    data = {
        "points": points,
        "links": {"ground": ["O", "X"], "crank": ["O", "A", *(f"p{i}" for i in range(n))]},
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O"},
    }
    path = tmp_path_factory.mktemp("load") / "link16000.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    return path, data


@pytest.mark.benchmark(group=LOAD)
def test_load_planarkin(benchmark, big_file):
    path, data = big_file
    sc = benchmark(pk.Scene.load, path)
    assert sc.points == {k: tuple(v) for k, v in data["points"].items()}
    record(benchmark, "scene_load_16000", "planarkin pk.Scene.load(path): read, checked, "
           "the plan proven (the file read from disk)")  # fmt: skip


@pytest.mark.benchmark(group=LOAD)
def test_load_json_loads(benchmark, big_file):
    path, data = big_file
    text = path.read_text(encoding="utf-8")
    assert benchmark(json.loads, text) == data
    record(benchmark, "scene_load_json", "json.loads(text) of the same file (the text "
           "already read)")  # fmt: skip
