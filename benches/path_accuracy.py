"""Path synthesis accuracy (issue 33): the best defect-free design's error on targets made
from known linkages (exact coupler curves: the error should reach rounding) and on test
problems of the literature, with the time each query took on this machine. Writes
benches/results/path_accuracy.json, which BENCHMARKS.md shows.

    python benches/path_accuracy.py
"""

from __future__ import annotations

import json
import os
import sys
import time

import numpy as np
import planarkin as pk
from planarkin.synthesis.path import CurveTarget, load_target

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests"))  # _support
sys.path.insert(0, os.path.join(HERE, "..", "tests", "synthesis", "path"))
from _path_linkages import fourbar_curve, slider_curve  # noqa: E402

CRANK_ROCKER = ((1.0, 2.0), (5.0, 1.5), 1.1, 3.7, 3.2, 1.5, 1.2)
#: Wampler, Morgan and Sommese's nine precision points (J. Mech. Des. 114, 1992), as the
#: HomotopyContinuation.jl example gives them: exact four-bars through all nine exist
NINE_POINTS = [
    (0.8961867, -0.09802917), (1.2156535, -1.18749100), (1.5151435, -0.85449808),
    (1.6754775, -0.48768058), (1.7138690, -0.30099232), (1.7215236, 0.03269953),
    (1.6642029, 0.33241088), (1.4984171, 0.74435576), (1.3011834, 0.92153806),
]  # fmt: skip
KIDNEY = "M 0 0 C 20 -25, 60 -25, 80 0 C 95 20, 70 45, 40 30 C 10 45, -15 20, 0 0 Z"


def _scene_curve(name: str, link: str, at: tuple[float, float], n: int) -> np.ndarray:
    d = pk.scenes.load(name).to_dict()
    d["points"]["P"] = list(at)
    d["links"][link].append("P")
    sc = pk.Scene(d)
    th = sc.input_angle + np.linspace(0, 2 * np.pi, n, endpoint=False)
    return sc.sweep(th, outputs=["P"]).points["P"]


def cases() -> list[tuple[str, str, CurveTarget, str, float | None]]:
    """(name, origin, target, topology, the published or exact error)."""
    th = 0.3 + np.linspace(0, 2 * np.pi, 24, endpoint=False)
    closed = fourbar_curve(*CRANK_ROCKER, th)[2]
    sl = slider_curve((3.0, -1.0), 0.4, 0.6, 1.0, 3.5, 0.8, 0.9, 0.2 + np.linspace(0, 6.2, 20))
    return [
        ("four-bar, closed, 24 points", "exact coupler curve", CurveTarget(closed, "closed"),
         "four-bar", 0.0),
        ("four-bar, partial, 12 points", "exact coupler curve",
         CurveTarget(fourbar_curve(*CRANK_ROCKER, np.linspace(0.3, 2.8, 12))[2], "partial"),
         "four-bar", 0.0),
        ("four-bar, open, 8 points", "exact coupler curve",
         CurveTarget(fourbar_curve(*CRANK_ROCKER, np.linspace(1.0, 2.2, 8))[2], "open"),
         "four-bar", 0.0),
        ("slider-crank, closed, 20 points", "exact coupler curve",
         CurveTarget(sl[2], "closed"), "slider-crank", 0.0),
        ("Watt II, closed, 30 points", "exact coupler curve (built-in watt2 + a point)",
         CurveTarget(_scene_curve("watt2", "coupler2", (10.0, 4.0), 30), "closed"), "watt2", 0.0),
        ("Stephenson III, closed, 30 points", "exact coupler curve (built-in + a point)",
         CurveTarget(_scene_curve("stephenson3", "T2", (4.0, 5.5), 30), "closed"),
         "stephenson3", 0.0),
        ("nine precision points, open", "Wampler, Morgan, Sommese 1992 (exact four-bars exist; "
         "their defects are not published with them)", CurveTarget(np.array(NINE_POINTS), "open"),
         "four-bar", None),
        ("kidney, SVG cubics, closed", "a drawn shape (no four-bar traces it exactly)",
         load_target(KIDNEY, svg_samples=48), "four-bar", None),
    ]  # fmt: skip


def main() -> None:
    rows = []
    for name, origin, target, topology, reference in cases():
        pk.atlas.default(topology)  # built or loaded before the clock starts
        t0 = time.perf_counter()
        res = pk.synthesis.path(target, topology=topology, designs=3)
        seconds = time.perf_counter() - t0
        best = next((d for d in res.designs if d.verified), None)
        rows.append({
            "target": name,
            "origin": origin,
            "topology": topology,
            "points": len(target.points),
            "kind": target.kind,
            "reference_error": reference,
            "best_verified_error_max": None if best is None else best.error.max,
            "best_verified_error_rms": None if best is None else best.error.rms,
            "min_transmission_deg": None if best is None else best.min_transmission,
            "verified_designs": sum(d.verified for d in res.designs),
            "seconds": round(seconds, 2),
        })  # fmt: skip
        print(rows[-1])
    out = {"command": "python benches/path_accuracy.py", "rows": rows}
    with open(os.path.join(HERE, "results", "path_accuracy.json"), "w") as f:
        json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
