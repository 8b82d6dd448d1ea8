"""The ends of a circuit's input range (issue 32, item 5): where the input reverses they
are the refined turning points, in ``Circuit.range``, ``circuits.json``, the printed table
and the figure's turning-point dots -- never the traced sample nearest a dead point.

Truth: a non-Grashof four-bar's toggles in closed form (coupler and rocker in line); for
Jansen's linkage, whose turning points have no closed form here, the trace's own turning
points (refined by bisection on the conditioning's sign, about 1e-9 rad)."""

from __future__ import annotations

import json
import math

import numpy as np
import planarkin as pk
from planarkin.face import cli
from planarkin.face.figures import circuits as circuits_fig

# (2, 3, 2.5, 6): a + d > b + c, non-Grashof: the crank rocks between the toggles, where
# |A O4| = b + c
A, B, C, D = 2.0, 3.0, 2.5, 6.0
TOGGLE = math.acos((A * A + D * D - (B + C) ** 2) / (2 * A * D))
TOL_DEG = math.degrees(1e-9) * 10


def fourbar_dict(th: float = math.radians(30.0)) -> dict:
    o4, pa = np.array([D, 0.0]), A * np.array([math.cos(th), math.sin(th)])
    r = math.dist(o4, pa)
    u = (o4 - pa) / r
    x = (B * B - C * C + r * r) / (2 * r)
    pb = pa + x * u + math.sqrt(B * B - x * x) * np.array([-u[1], u[0]])
    return {
        "name": "non-Grashof four-bar",
        "points": {"O2": [0, 0], "O4": [D, 0], "A": pa.tolist(), "B": pb.tolist()},
        "links": {"g": ["O2", "O4"], "c": ["O2", "A"], "k": ["A", "B"], "r": ["O4", "B"]},
        "ground": "g",
        "input": {"link": "c", "pivot": "O2"},
        "output": {"link": "r", "pivot": "O4"},
    }


def test_four_bar_circuit_range_is_its_closed_form_toggles():
    (c,) = pk.Scene.from_dict(fourbar_dict()).circuits()
    np.testing.assert_allclose(c.range, (-TOGGLE, TOGGLE), rtol=0, atol=1e-9)


def test_circuits_json_and_table_give_the_toggles_as_range_ends(tmp_path, capsys):
    p = tmp_path / "ng.json"
    p.write_text(json.dumps(fourbar_dict()))
    assert cli.main(["circuits", str(p), "--out", str(tmp_path), "--no-figures"]) == 0
    out = capsys.readouterr().out
    (row,) = json.loads((tmp_path / "circuits.json").read_text())["circuits"]
    t = math.degrees(TOGGLE)
    np.testing.assert_allclose(row["input_range_deg"], [-t, t], rtol=0, atol=TOL_DEG)
    np.testing.assert_allclose(sorted(row["turning_points_deg"]), [-t, t], rtol=0, atol=TOL_DEG)
    assert f"input rocks between {-t:.4f} and {t:.4f} deg" in out


def test_circuits_figure_marks_the_toggles_themselves():
    sc = pk.Scene.from_dict(fourbar_dict())
    found = sc.circuits()
    fig = circuits_fig.circuits(sc, found, sc.input_angle)
    dots = [ln for ln in fig.axes[0].lines if ln.get_marker() == "o"]
    (xs,) = [np.asarray(ln.get_xdata(), dtype=float) for ln in dots]
    t = math.degrees(TOGGLE)
    np.testing.assert_allclose(np.sort(xs), [-t, t], rtol=0, atol=TOL_DEG)


def test_jansen_range_ends_are_its_turning_points(tmp_path):
    sc = pk.scenes.load("jansen")
    assert cli.main(["circuits", "jansen", "--out", str(tmp_path), "--no-figures"]) == 0
    rows = json.loads((tmp_path / "circuits.json").read_text())["circuits"]
    found = sc.circuits()
    rocking = [(r, c) for r, c in zip(rows, found, strict=True) if not r["full_turn"]]
    assert rocking
    for r, c in rocking:
        # each end of the range, in the turn shown, is one of the trace's turning points
        tps = np.degrees(c.trace.turning_points)
        for end in r["input_range_deg"]:
            gap = np.abs((tps - end + 180.0) % 360.0 - 180.0).min()
            assert gap < TOL_DEG, (end, tps)
