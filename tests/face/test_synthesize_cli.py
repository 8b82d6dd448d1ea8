"""``planarkin synthesize``: a quick Ackermann run writes its design, report and figures,
and the true error it reports is the design's own, swept by the scene solver and measured
against the Ackermann condition (truth.ackermann); a bad option is refused."""

from __future__ import annotations

import json
import math

import numpy as np
import planarkin as pk
import pytest
from _support import out_rotation
from truth import ackermann


@pytest.mark.slow  # 4 s: a real, if short, synthesis
def test_cli_synthesize_ackermann_quick(tmp_path):
    from planarkin.face.cli import main

    out = tmp_path / "ack"
    argv = ["synthesize", "ackermann", "--out", str(out), "--starts", "2", "--samples", "300",
            "--maxiter", "30", "--no-tolerance", "--select", "accurate"]  # fmt: skip
    assert main(argv) == 0
    rep = json.loads((out / "report.json").read_text())
    sc = pk.Scene.load(out / "design.json")
    assert rep["starts"] == 2 and rep["det_sign_changes"] == 0
    for name in ("error.png", "conditioning.png", "linkage.png"):
        assert (out / name).stat().st_size > 1000
    # the reported true error is the scene's, against the Ackermann condition (truth.py)
    lo, hi = -math.atan(1 / (1 / math.tan(math.radians(61.0)) + 0.6)), math.radians(61.0)
    dl = np.linspace(lo, hi, 1001)
    err = np.degrees(np.max(np.abs(out_rotation(sc, dl) - ackermann(dl))))
    assert err == pytest.approx(rep["true_max_error_deg_1001"], rel=1e-6, abs=1e-9)


def test_cli_synthesize_bad_input(capsys):
    from planarkin.face.cli import main

    assert main(["synthesize", "ackermann", "--starts", "0"]) == 2
    assert "--starts" in capsys.readouterr().err
