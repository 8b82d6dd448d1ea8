"""Where the benchmark report reads and writes, and the commands ``report.py run`` runs
(``report_run.py`` runs them, ``report_render.py`` lists them in BENCHMARKS.md)."""

from __future__ import annotations

import os
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
#: The web page's measurement (needs selenium, chromium, chromedriver).
WEB_CMD = ["python", "benches/web_frame.py"]
PAIRED_CMD = ["python", "benches/paired.py"]
