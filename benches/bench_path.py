"""Path synthesis end to end (issue 33): a four-bar query (retrieval from the default atlas,
refinement of the top candidates, verification) and a six-bar one, on curves of linkages
that are not in the atlases, by their closed forms. The default atlases are built before
the timed calls (their build is benches/bench_atlas.py's). Each result is checked outside
the timed call: the best design is verified and within 1e-6 of the target's size."""

from __future__ import annotations

import json
import os
import sys

import numpy as np
import planarkin as pk
from conftest import record
from planarkin.synthesis.path import CurveTarget

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests"))  # _support
sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests", "synthesis", "path"))
from _path_linkages import fourbar_curve  # noqa: E402

ROOT = os.path.join(os.path.dirname(__file__), "..")
#: a Grashof crank-rocker not in the atlas: O2, O4, crank, coupler, rocker, P (u, v)
CRANK_ROCKER = ((1.0, 2.0), (5.0, 1.5), 1.1, 3.7, 3.2, 1.5, 1.2)


def _fourbar_target() -> CurveTarget:
    th = 0.3 + np.linspace(0, 2 * np.pi, 24, endpoint=False)
    return CurveTarget(
        fourbar_curve((1.0, 2.0), (5.0, 1.5), 1.1, 3.7, 3.2, 1.5, 1.2, th)[2], "closed"
    )


def _watt2_target() -> CurveTarget:
    with open(os.path.join(ROOT, "python/planarkin/scene/builtin/watt2.json")) as f:
        d = json.load(f)
    d["points"]["P"] = [10.0, 4.0]
    d["links"]["coupler2"].append("P")
    sc = pk.Scene(d)
    th = sc.input_angle + np.linspace(0, 2 * np.pi, 30, endpoint=False)
    return CurveTarget(sc.sweep(th, outputs=["P"]).points["P"], "closed")


def test_path_fourbar(benchmark):
    pk.atlas.default("four-bar")
    t = _fourbar_target()
    record(
        benchmark,
        "path_fourbar",
        "path: a four-bar for a closed 24-point curve (retrieval, 15 refined, verified; default "
        "atlas loaded)",
    )
    benchmark.group = "path synthesis"
    res = benchmark.pedantic(pk.synthesis.path, args=(t,), rounds=3, iterations=1)
    assert res.designs[0].verified and res.designs[0].error.max <= 1e-6


def test_path_fourbar_open(benchmark):
    pk.atlas.default("four-bar")
    th = np.linspace(0.3, 2.8, 12)
    t = CurveTarget(
        fourbar_curve((1.0, 2.0), (5.0, 1.5), 1.1, 3.7, 3.2, 1.5, 1.2, th)[2], "partial"
    )
    record(benchmark, "path_fourbar_partial", "path: a four-bar for a partial 12-point target")
    benchmark.group = "path synthesis"
    res = benchmark.pedantic(pk.synthesis.path, args=(t,), rounds=3, iterations=1)
    assert res.designs[0].verified and res.designs[0].error.max <= 1e-3


def test_path_watt2(benchmark):
    pk.atlas.default("watt2")
    t = _watt2_target()
    record(benchmark, "path_watt2", "path: a Watt II six-bar for a closed 30-point curve")
    benchmark.group = "path synthesis"
    res = benchmark.pedantic(
        pk.synthesis.path, args=(t,), kwargs={"topology": "watt2"}, rounds=1, iterations=1
    )
    assert res.designs[0].verified and res.designs[0].error.max <= 1e-3
