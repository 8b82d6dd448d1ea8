"""Runs every benchmark on this machine and writes BENCHMARKS.md.

    python benches/report.py run      # criterion + pytest-benchmark + tradeoff, then render
    python benches/report.py render   # re-render BENCHMARKS.md from benches/results/

``run`` takes about 4 minutes on 2 cores. It runs, in this order and in one session:
``cargo bench -p planarkin-core --bench sweep --bench scene`` (the core alone, criterion),
``pytest benches/ --benchmark-enable --benchmark-json=...`` (everything from Python,
including the peak-RSS subprocesses), ``benches/paired.py`` (the ratio targets in
interleaved rounds), and ``planarkin.fourbar.tradeoff.tradeoff()`` with its
defaults. Raw results go to ``benches/results/``; the hand-written analysis in
``benches/analysis.md`` is appended to the generated tables.

Running is ``report_run.py``, rendering ``report_render.py``, and the targets, as data,
``report_targets.py``.
"""

from __future__ import annotations

import argparse
import sys

from report_render import render
from report_run import run_all


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    p.add_argument("what", choices=("run", "render"))
    p.add_argument("--quick", action="store_true", help="smoke run to debug the pipeline")
    a = p.parse_args(argv)
    if a.what == "run":
        run_all(a.quick)
    render()
    return 0


if __name__ == "__main__":
    sys.exit(main())
