"""Peak RSS of a 100 000 x 361 batch, each measured once in a fresh subprocess
(``benches/memory.py``); the numbers land in ``extra_info`` for the report. The timing
of this group is the subprocess's whole run, not a benchmark of its own."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest
from conftest import record

HERE = os.path.dirname(__file__)
M = int(os.environ.get("PLANARKIN_BENCH_MEMORY_M", "100000"))


def _measure(kind: str) -> dict:
    out = subprocess.run(
        [sys.executable, os.path.join(HERE, "memory.py"), kind, str(M), "361"],
        check=True,
        capture_output=True,
        text=True,
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


@pytest.mark.benchmark(group=f"memory: peak RSS, {M} x 361 batch (one run each)")
@pytest.mark.parametrize("kind", ["sweep", "closed_form", "numpy_closed_form"])
def test_peak_rss(benchmark, kind):
    info = benchmark.pedantic(_measure, args=(kind,), rounds=1, iterations=1)
    assert (
        info["output_bytes"]
        == {"sweep": 29, "closed_form": 16, "numpy_closed_form": 16}[kind] * M * 361
    )
    label = {
        "sweep": "planarkin sweep_batch (all threads)",
        "closed_form": "planarkin closed_form_batch (all threads)",
        "numpy_closed_form": "NumPy vectorized closed form",
    }[kind]
    record(benchmark, f"mem_{kind}", label, **info)
