"""Control and honesty of the multistart (issue 19, items 4 and 6): runs collected by start
index whatever order the workers finish in, ties to the lower index, a failed start gets
its status, a time limit stops a start at its next iteration, Ctrl-C keeps the finished
runs, a pool is stopped at once; "converged" only where scipy succeeded and the
constraints were checked to hold; the seed's generated error on the linkage's own roots."""

from __future__ import annotations

import math
import os
import threading
import time
from concurrent.futures import Executor, Future, ThreadPoolExecutor
from pathlib import Path

import numpy as np
import planarkin as pk
import pytest
from _support import out_rotation
from planarkin.synthesis import (
    STEERING_LEVER,
    TYPE_I,
    DesignSpace,
    FunctionTarget,
    Problem,
    SeedPlan,
    SynthesisInterrupted,
    ackermann,
    driver,
    run_start,
    synthesize,
    verify,
)
from truth import ackermann as ackermann_truth

# --- a small problem: recover the type I double butterfly's own output ------------------


def _small() -> tuple[Problem, list[np.ndarray]]:
    d = pk.scenes.load("double-butterfly-1").to_dict()
    d["output"] = {"link": "output", "pivot": "K"}
    sc = pk.Scene.from_dict(d)
    phi = np.linspace(0.05, 0.8, 9)
    dense = np.linspace(0.05, 0.8, 21)
    space = DesignSpace(TYPE_I, sc.points, ("C", "D", "F", "H", "I"), -20.0, 20.0)
    x = space.x_of(sc.points)
    rng = np.random.default_rng(9)
    xs = [x + rng.normal(0, 2e-3, x.size) for _ in range(2)]
    target = FunctionTarget(phi, out_rotation(sc, phi), dense, out_rotation(sc, dense))
    return Problem(space, target, det_margin=1e-3), xs


class ReverseExecutor(Executor):
    """Runs ``n`` submitted calls on n threads and lets them finish in the reverse order
    of submission: call k's future completes only after call k + 1's has (``finished``
    records the order)."""

    def __init__(self, n: int) -> None:
        self.n = n
        self.pool = ThreadPoolExecutor(n)
        self.done = [threading.Event() for _ in range(n)]
        self.finished: list[int] = []
        self.k = 0

    def submit(self, fn, /, *args, **kwargs):  # type: ignore[override]
        k = self.k
        self.k += 1

        def call():
            try:
                return fn(*args, **kwargs)
            finally:
                if k + 1 < self.n:
                    self.done[k + 1].wait()

        def finished(_):
            self.finished.append(k)
            self.done[k].set()

        f = self.pool.submit(call)
        f.add_done_callback(finished)
        return f

    def shutdown(self, wait=True, *, cancel_futures=False):  # type: ignore[override]
        self.pool.shutdown(wait=wait, cancel_futures=cancel_futures)


@pytest.mark.slow  # eight starts to 15 iterations: about 5 s on 2 cores
def test_results_do_not_depend_on_the_order_workers_finish():
    p, (a, b) = _small()
    x0 = [a, b, a]  # starts 0 and 2 tie exactly
    with ThreadPoolExecutor(1) as ex:
        inorder = synthesize(p, starts=3, samples=0, x0=x0, executor=ex, maxiter=15)
    rev = ReverseExecutor(3)
    backwards = synthesize(p, starts=3, samples=0, x0=x0, executor=rev, maxiter=15)
    rev.shutdown()
    assert rev.finished == [2, 1, 0]  # they did finish backwards
    assert [r.index for r in backwards.runs] == [0, 1, 2]
    for r, q in zip(inorder.runs, backwards.runs, strict=True):
        np.testing.assert_array_equal(r.x, q.x)
        assert (r.status, r.message, r.max_error) == (q.status, q.message, q.max_error)
    np.testing.assert_array_equal(backwards.runs[0].x, backwards.runs[2].x)
    assert backwards.best is not None and inorder.best is not None
    assert backwards.best.index == inorder.best.index
    # of two equal runs the lower index wins, though the higher one finished first
    rev = ReverseExecutor(2)
    tie = synthesize(p, starts=2, samples=0, x0=[a, a], executor=rev, maxiter=15)
    rev.shutdown()
    assert rev.finished == [1, 0]
    assert tie.runs[0].max_error == tie.runs[1].max_error
    assert tie.best is tie.runs[0]


class FailingExecutor(Executor):
    """Runs calls at once; the start with index ``bad`` raises."""

    def __init__(self, bad: int) -> None:
        self.bad = bad

    def submit(self, fn, /, *args, **kwargs):  # type: ignore[override]
        f: Future = Future()
        if kwargs.get("index") == self.bad:
            f.set_exception(RuntimeError("worker lost\nits way"))
        else:
            f.set_result(fn(*args, **kwargs))
        return f


def test_a_failed_start_gets_its_status_and_the_others_are_solved():
    p, (a, b) = _small()
    res = synthesize(p, starts=2, samples=0, x0=[a, b], executor=FailingExecutor(0), maxiter=15)
    assert [r.index for r in res.runs] == [0, 1]
    bad, good = res.runs
    assert bad.status == -1 and not bad.feasible and not bad.converged
    assert bad.message == "start failed: RuntimeError: worker lost its way"
    assert good.status != -1 and res.best is good


@pytest.mark.slow  # a start run to 300 iterations: about 1 s on 2 cores
def test_converged_means_scipy_success_and_verified_feasibility():
    p, (a, _) = _small()
    r = run_start(p, a, maxiter=1, minimax=False)
    # scipy stops at its iteration limit: not converged, whatever the constraints say
    assert (r.status, r.message, r.success) == (9, "Iteration limit reached", False)
    assert r.phases == [{"phase": "least-squares", "status": 9, "success": False,
                         "message": "Iteration limit reached", "nit": 1}]  # fmt: skip
    assert not r.converged
    # feasibility is checked here, not taken from scipy: every constraint and bound
    res = p.residuals(r.x)
    mine = all(bool(np.all(v >= -1e-6)) for v in (res.branch, res.extra, res.lengths))
    assert r.feasible == mine
    full = run_start(p, a, maxiter=300, minimax=False)
    assert full.converged == (full.success and full.feasible)
    assert full.success == (full.status == 0)


def test_time_limit_stops_a_start_at_its_next_iteration():
    p, (a, _) = _small()
    r = run_start(p, a, maxiter=300, deadline=time.time())
    assert r.status == 99 and r.stopped == driver.TIME_LIMIT and r.nit == 1
    assert "StopIteration" in r.message and "time limit" in r.message
    assert not r.success and not r.converged
    assert [ph["phase"] for ph in r.phases] == ["least-squares"]  # no polish after it


def test_time_limit_before_any_start_returns_no_runs():
    p, _ = _small()
    res = synthesize(p, starts=2, samples=50, time_limit=1e-9)
    assert res.runs == [] and res.best is None and res.stopped == driver.TIME_LIMIT
    assert res.screened == 0 and res.sampled == 50
    for bad in (0.0, -1.0, math.nan, math.inf):
        with pytest.raises(ValueError, match="time_limit"):
            synthesize(p, starts=1, time_limit=bad)
    with pytest.raises(ValueError, match="workers"):
        synthesize(p, starts=1, workers=0)


@pytest.mark.slow  # a thread pool's start to 15 iterations, then the interrupt: 1-2 s
def test_ctrl_c_keeps_the_runs_that_finished():
    p, (a, b) = _small()

    def ctrl_c(run):
        raise KeyboardInterrupt

    with ThreadPoolExecutor(1) as ex, pytest.raises(SynthesisInterrupted) as e:
        synthesize(p, starts=2, samples=0, x0=[a, b], executor=ex, maxiter=15, progress=ctrl_c)
    assert isinstance(e.value, KeyboardInterrupt)
    res = e.value.result
    assert res.stopped == driver.INTERRUPTED and res.starts == 2
    assert [r.index for r in res.runs] == [0] and res.best is res.runs[0]


def _sleep(s: float) -> float:
    time.sleep(s)
    return s


def test_stop_pool_terminates_running_workers_and_cancels_queued_starts():
    pool = driver.process_pool(1)
    running = pool.submit(_sleep, 600.0)
    queued = [pool.submit(_sleep, 600.0) for _ in range(3)]
    while not running.running():  # bounded by pytest-timeout
        time.sleep(0.01)
    pids = [p.pid for p in pool._processes.values()]
    assert pids
    driver.stop_pool(pool)
    for pid in pids:
        with pytest.raises(ProcessLookupError):
            os.kill(pid, 0)  # gone (joined: not even a zombie)
    assert queued[-1].cancelled()


# --- the generated error of a design whose linkage passes loop 3's turning point -------------

#: A design of `planarkin synthesize ackermann --starts 2` (seed 2): true error 1e-6 deg;
#: its linkage passes loop 3's turning point near 15 deg of steer.
PASSES_LOOP3_TURN = {
    "KL": (-0.3, 0.0),
    "KR": (0.3, 0.0),
    "O": (-0.06395003464355481, 0.334815071601382),
    "P": (-0.2629410359222825, 0.18673605357693676),
    "Q": (0.2161087435222155, 0.17487650461983997),
    "H": (-0.07307800743630152, 0.003113498960167622),
    "U": (0.024497908734376208, 0.03541074495237174),
    "V": (-0.20896763563790124, 0.14445371505159738),
    "R": (-0.03573176645757025, -0.012068465629848098),
    "S": (-0.09886239933545865, 0.017437509407813554),
}


def test_generated_error_follows_the_linkage_past_a_turning_point():
    p = ackermann.problem()
    x = p.space.x_of(PASSES_LOOP3_TURN)
    t = p.target
    v = verify(p, x)
    sc = pk.Scene.from_dict(STEERING_LEVER.scene_dict(PASSES_LOOP3_TURN))
    e_true = out_rotation(sc, t.phi_in) - ackermann_truth(t.phi_in)
    assert math.degrees(np.max(np.abs(e_true))) < 1e-5
    # with the drawn signs held fixed the closed form jumps to loop 3's other root...
    assert v["generated_root_changes"] > 0 and v["generated_fixed_signs_max_error_deg"] > 10
    first = math.radians(v["generated_root_changes_deg"][0])
    i = int(np.searchsorted(t.phi_in, first))
    # ...because loop 3's radicand touches zero between the last design point on the
    # drawn root and the first off it (the split mechanism's own turning point)
    plan = SeedPlan(STEERING_LEVER, PASSES_LOOP3_TURN)
    fine = np.linspace(t.phi_in[i - 1], t.phi_in[i], 2001)
    rad = plan.generated(fine, ackermann_truth(fine)).radicand[:, 2]
    assert rad.min() < 1e-4 < min(rad[0], rad[-1])
    # on the linkage's own roots it obeys e_g = (1 - k) e_A with the swept e_A
    g, signs = plan.follow(t.phi_in, t.phi_out, _dyad_points(sc, t.phi_in), t.phi_out + e_true)
    np.testing.assert_allclose(g.theta - t.phi_out, (1 - g.k) * e_true, rtol=1e-3, atol=1e-13)
    assert v["generated_max_error_deg"] == pytest.approx(
        math.degrees(np.max(np.abs(g.theta - t.phi_out))), rel=1e-9
    )
    assert v["generated_max_error_deg"] < 1e-3
    assert np.all(signs[:i] == plan.drawn_signs) and np.any(signs[i:] != plan.drawn_signs)
    # and the command says so instead of printing the other root's error as this design's
    from planarkin.face.cli.synthesize import _generated_words

    words = _generated_words(v)
    assert "own roots" in words and f"{v['generated_fixed_signs_max_error_deg']:.3g}" in words


def _dyad_points(sc: pk.Scene, phi: np.ndarray) -> dict[str, np.ndarray]:
    sw = sc.sweep(sc.input_angle + phi, outputs=["H", "R"], tol=1e-12)
    return {"H": sw.points["H"], "R": sw.points["R"]}


#: an earlier shipped steering design (boxed as drawn only), whose loops stay on their roots
ON_ITS_ROOTS = Path(__file__).resolve().parent / "steering_on_its_roots.json"


def test_generated_error_of_a_design_that_stays_on_its_roots_is_the_fixed_signs_one():
    p = ackermann.problem()
    v = verify(p, p.space.x_of(pk.Scene.load(ON_ITS_ROOTS).points))
    assert v["generated_root_changes"] == 0 and v["generated_root_changes_deg"] == []
    assert v["generated_max_error_deg"] == v["generated_fixed_signs_max_error_deg"]
