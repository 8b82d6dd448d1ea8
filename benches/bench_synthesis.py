"""Synthesis with exact gradients against forward differences (issue 19), side by side in
one run: the derivatives of one steering design's residuals (the rows SLSQP sees), one
SLSQP start of the steering problem (least squares, 60 iterations), and the whole
``planarkin synthesize ackermann --starts 2`` command; and the default command (12 starts,
figures and tolerance study included) against its time target. Both ends are checked outside the
timed calls (tests/synthesis/test_synthesis_gradient.py compares the rows)."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import record
from planarkin.face.cli import main
from planarkin.synthesis import ackermann
from planarkin.synthesis.exact import exact_rows, extrema, fd_rows, picks, subgrid
from planarkin.synthesis.screening import sample_starts
from planarkin.synthesis.start import FD_STEP, run_start

ROWS = "synthesis: the residuals' derivatives at one steering design (16 coordinates)"
START = "synthesis: one SLSQP start of the steering problem (least squares, 60 iterations)"
CLI = "synthesis: planarkin synthesize ackermann --starts 2 (whole command)"
DEFAULT = "synthesis: planarkin synthesize ackermann, the default run (12 starts, whole command)"


@pytest.fixture(scope="module")
def steering():
    p = ackermann.problem()
    ((_, x0),) = sample_starts(
        p, 600, 1, np.random.default_rng(2), ackermann.mirror_sampler(p.space)
    )
    return p, x0


def _at(p, x):
    ev = p.evaluate(x, p.grid())
    res = p.residuals_of(x, ev)
    return ev, res, picks(res, subgrid(res.branch.size, 41), extrema(np.abs(res.dense), 64))


@pytest.mark.benchmark(group=ROWS)
def test_rows_exact(benchmark, steering):
    p, x = steering
    ev, res, pk_ = _at(p, x)
    benchmark(exact_rows, p, x, ev, res, pk_)
    record(benchmark, "synth_rows_exact", "exact rows (implicit differentiation)")


@pytest.mark.benchmark(group=ROWS)
def test_rows_fd(benchmark, steering):
    p, x = steering
    ev, res, pk_ = _at(p, x)
    step = FD_STEP * float(np.max(p.upper - p.lower))
    benchmark(fd_rows, p, x, res, pk_, p.grid(), step)
    record(benchmark, "synth_rows_fd", "forward differences (16 sweeps)")


@pytest.mark.parametrize("gradient", ["exact", "fd"])
@pytest.mark.benchmark(group=START)
def test_one_start(benchmark, steering, gradient):
    p, x0 = steering
    # the stall test off: both run the same 60 iterations
    r = benchmark.pedantic(
        run_start, args=(p, x0),
        kwargs={"maxiter": 60, "minimax": False, "gradient": gradient, "stall_iter": None},
        rounds=2, iterations=1,
    )  # fmt: skip
    assert r.nit == 60 or r.success
    record(benchmark, f"synth_start_{gradient}", f"run_start, gradient={gradient!r}")


@pytest.mark.parametrize("gradient", ["exact", "fd"])
@pytest.mark.benchmark(group=CLI)
def test_cli_two_starts(benchmark, tmp_path, gradient):
    args = ["synthesize", "ackermann", "--starts", "2", "--out", str(tmp_path), "--quiet",
            "--no-figures", "--no-tolerance", "--gradient", gradient]  # fmt: skip
    code = benchmark.pedantic(main, args=(args,), rounds=1, iterations=1)
    assert code == 0
    record(benchmark, f"synth_cli_{gradient}", f"--starts 2 --gradient {gradient}")


@pytest.mark.benchmark(group=DEFAULT)
def test_cli_default(benchmark, tmp_path):
    args = ["synthesize", "ackermann", "--out", str(tmp_path), "--quiet"]
    code = benchmark.pedantic(main, args=(args,), rounds=1, iterations=1)
    assert code == 0
    record(benchmark, "synth_cli_default", "planarkin synthesize ackermann (defaults)")
