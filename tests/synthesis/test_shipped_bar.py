"""The shipped Ackermann design (what the default ``planarkin synthesize ackermann`` writes)
against the bar the command documents on each of its three criteria: the true error from
the Ackermann condition in closed form, every joint in the box over the whole motion on
poses checked rigid, and the least conditioning with one sign over the motion."""

from __future__ import annotations

import json
import math
from itertools import combinations
from pathlib import Path

import numpy as np
import planarkin as pk
import pytest
from _support import out_rotation
from planarkin.synthesis import ackermann as ak
from planarkin.synthesis.ackermann_report import BUDGET_DEG
from truth import ackermann

SHIPPED = Path(__file__).resolve().parents[2] / "examples" / "ackermann"
#: the command's defaults (its --help): the conditioning margin the search holds
DET_MARGIN = 0.1
#: SLSQP's feasibility: every constraint holds to 1e-6 of its scale
FEAS = 1e-6


def _range(n: int) -> np.ndarray:
    hi = math.radians(61.0)
    lo = -math.atan(1 / (1 / math.tan(hi) + 0.6))  # the outer wheel at full inner lock
    return np.linspace(lo, hi, n)


@pytest.mark.skipif(not (SHIPPED / "report.json").exists(), reason="no shipped design")
def test_shipped_design_is_the_default_commands():
    rep = json.loads((SHIPPED / "report.json").read_text())
    o = rep["options"]
    # the bar below is the default command's: its budget, margin and box
    assert (o["budget"], o["det_margin"], o["select"]) == (BUDGET_DEG, DET_MARGIN, "robust")
    assert o["envelope"] and rep["box"] == ak.BOX == 0.35


@pytest.mark.skipif(not (SHIPPED / "design.json").exists(), reason="no shipped design")
def test_shipped_design_meets_the_documented_bar_on_all_three_criteria():
    sc = pk.Scene.load(SHIPPED / "design.json")
    rep = json.loads((SHIPPED / "report.json").read_text())
    dl = _range(1001)
    # 1. true error: the Ackermann condition in closed form, within --budget
    err = float(np.degrees(np.max(np.abs(out_rotation(sc, dl) - ackermann(dl)))))
    assert err <= BUDGET_DEG
    assert err == pytest.approx(rep["true_max_error_deg_1001"], rel=1e-6, abs=1e-9)
    # 2. the box over the motion: every joint of every pose, the poses checked to be the
    # drawn linkage (each link's joint distances as drawn)
    sw = sc.sweep(sc.input_angle + dl, outputs="all")
    assert np.all(sw.status == 0)
    names = list(sc.points)
    for link in sc.links.values():
        for a, b in combinations(link, 2):
            i, j = names.index(a), names.index(b)
            drawn = math.dist(sc.points[a], sc.points[b])
            d = np.hypot(*(sw.coords[:, i] - sw.coords[:, j]).T)
            np.testing.assert_allclose(d, drawn, rtol=0, atol=1e-9)
    reach = np.max(np.abs(sw.coords), axis=(0, 1))
    assert np.all(reach <= ak.BOX + FEAS)
    assert reach == pytest.approx([rep["motion_max_abs_x"], rep["motion_max_abs_y"]], abs=1e-9)
    # 3. conditioning: one sign over the motion and at least the margin (the solver's
    # signed conditioning of each pose)
    assert np.all(sw.det > 0) or np.all(sw.det < 0)
    assert float(np.min(np.abs(sw.det))) >= DET_MARGIN * (1 - FEAS)
