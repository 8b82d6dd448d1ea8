"""The scene commands: planarkin analyze SCENE, animate SCENE, circuits SCENE, scenes —
their files checked against the NumPy reference and the four-bar's own classification."""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import planarkin as pk
import pytest
from planarkin.face import cli
from planarkin.reference import scene_sweep


def test_analyze_scene_writes_what_the_reference_computes(tmp_path, capsys):
    out = tmp_path / "o"
    assert cli.main(["analyze", "jansen", "--out", str(out), "--no-figures", "--step", "5"]) == 0
    text = capsys.readouterr().out
    assert "plan step 1" in text and "dyad" in text
    s = json.loads((out / "summary.json").read_text())
    assert s["converged"] == s["angles"] == 73 and s["mobility"] == 1
    assert [st["kind"] for st in s["plan"]] == ["dyad"] * len(s["plan"])
    rows = list(csv.DictReader((out / "results.csv").open()))
    u = pk.scenes.load("jansen").units
    assert u and f"foot_vx [{u}/s]" in rows[0]
    theta = np.radians([float(r["theta [deg]"]) for r in rows])
    assert np.all((-180 < np.degrees(theta)) & (np.degrees(theta) <= 180))
    foot = np.array([[float(r[f"foot_x [{u}]"]), float(r[f"foot_y [{u}]"])] for r in rows])
    ref = scene_sweep(pk.scenes.data("jansen"), theta)
    np.testing.assert_allclose(foot, ref.points["foot"], atol=1e-9)
    # velocities by central differences of the reference
    h = 1e-6
    fd = (scene_sweep(pk.scenes.data("jansen"), theta + h).points["foot"]
          - scene_sweep(pk.scenes.data("jansen"), theta - h).points["foot"]) / (2 * h)  # fmt: skip
    omega = 100 * 2 * math.pi / 60  # the default --rpm
    assert s["input_speed"]["omega_rad_s"] == pytest.approx(omega, rel=1e-15)
    assert s["input_speed"]["rpm"] == pytest.approx(100.0, rel=1e-12)
    assert "omega = 10.4720 rad/s (100 rpm, constant)" in text
    v = np.array([[float(r[f"foot_vx [{u}/s]"]), float(r[f"foot_vy [{u}/s]"])] for r in rows])
    np.testing.assert_allclose(v, fd * omega, atol=1e-5 * np.abs(fd * omega).max())


@pytest.mark.slow  # three figures laid out: 1-2 s on 2 cores (test_animate_scene draws too)
def test_analyze_scene_figures(tmp_path):
    out = tmp_path / "f"
    code = cli.main(["analyze", "stephenson3", "--out", str(out), "--step", "10", "--dpi", "40"])
    assert code == 0
    for name in ("scene_linkage.png", "scene_conditioning.png", "scene_tracers.png"):
        assert (out / name).stat().st_size > 1000


def test_analyze_a_scene_file(tmp_path):
    p = pk.scenes.load("fourbar").save(tmp_path / "mine.toml")
    assert cli.main(["analyze", str(p), "--out", str(tmp_path), "--no-figures"]) == 0
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["converged"] == 361


def test_circuits_command_matches_the_grashof_class(tmp_path, capsys):
    fb = pk.FourBar(6, 2, 5, 5)
    assert fb.grashof().kind == "crank-rocker"
    assert cli.main(["circuits", "fourbar", "--theta", "30", "--out", str(tmp_path)]) == 0
    s = json.loads((tmp_path / "circuits.json").read_text())
    # a crank-rocker: two circuits (open, crossed), the crank turning fully on each
    assert len(s["circuits"]) == 2 and all(c["full_turn"] for c in s["circuits"])
    assert (tmp_path / "circuits.png").stat().st_size > 1000
    assert "circuit 2" in capsys.readouterr().out


def test_circuits_of_a_triple_rocker(tmp_path):
    r = (4.0, 3.0, 1.5, 2.0)
    fb = pk.FourBar(*r)
    t3, _ = fb.closed_form(0.0)
    d = {
        "points": {
            "O2": [0, 0],
            "O4": [4, 0],
            "A": [3, 0],
            "B": [3 + 1.5 * math.cos(t3), 1.5 * math.sin(t3)],
        },  # fmt: skip
        "links": {"g": ["O2", "O4"], "c": ["O2", "A"], "k": ["A", "B"], "r": ["O4", "B"]},
        "ground": "g",
        "input": {"link": "c", "pivot": "O2"},
    }
    p = tmp_path / "tr.json"
    p.write_text(json.dumps(d))
    assert cli.main(["circuits", str(p), "--out", str(tmp_path), "--no-figures", "--json"]) == 0
    s = json.loads((tmp_path / "circuits.json").read_text())
    (c,) = s["circuits"]
    assert not c["full_turn"]
    np.testing.assert_allclose(
        sorted(c["turning_points_deg"]), sorted(np.degrees(fb.limits().toggles)), atol=1e-7
    )


def test_animate_scene(tmp_path):
    code = cli.main(["animate", "klann", "--out", str(tmp_path), "--frames", "4", "--dpi", "30"])
    assert code == 0
    assert (tmp_path / "linkage.gif").stat().st_size > 1000
    assert "<html" in (tmp_path / "linkage.html").read_text()


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["analyze", "nosuch"], "SCENE must be a .json/.toml file or a built-in name"),
        (["analyze", "missing.json"], "does not exist"),
        (["circuits", "fourbar", "--theta", "nan"], "--theta must be finite"),
        (["analyze", "jansen", "--step", "0"], "--step must be in (0, 360]"),
    ],
)
def test_scene_command_errors_are_one_line(argv, message, capsys, tmp_path):
    assert cli.main([*argv, "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1


def test_scenes_lists_the_built_ins(capsys):
    assert cli.main(["scenes"]) == 0
    out = capsys.readouterr().out
    for name in pk.scenes.names():
        assert name in out


def _boom_stroke_ends() -> tuple[float, float]:
    # the law of cosines' triangle O-C1-E flattens when |C1 E| = |O C1| + |O E| or
    # |O E| - |O C1|: the extension is that length minus the drawn |C1 E|
    p = {n: np.asarray(v) for n, v in pk.scenes.data("hydraulic-boom")["points"].items()}
    oc, oe = np.linalg.norm(p["C1"] - p["O"]), np.linalg.norm(p["E"] - p["O"])
    ce = np.linalg.norm(p["E"] - p["C1"])
    return float(abs(oe - oc) - ce), float(oc + oe - ce)


def _free_boom(tmp_path):
    """The built-in boom without its cylinder's limits (the linkage's whole motion)."""
    d = {k: v for k, v in pk.scenes.data("hydraulic-boom").items() if k != "limits"}
    path = tmp_path / "free-boom.json"
    path.write_text(json.dumps(d))
    return path


def test_circuits_of_a_linear_input_are_in_its_length_unit(tmp_path, capsys):
    boom = _free_boom(tmp_path)
    assert cli.main(["circuits", str(boom), "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    lo, hi = _boom_stroke_ends()
    assert "at input = 0 mm" in out and "deg" not in out.split("\n")[2]
    assert f"turning points (mm): {hi:.6g}, {lo:.6g}" in out
    s = json.loads((tmp_path / "circuits.json").read_text())
    (c,) = pk.Scene.load(boom).circuits(0.0)
    assert s["input_kind"] == "displacement" and s["units"] == "mm"
    (row,) = s["circuits"]
    np.testing.assert_allclose(row["turning_points"], c.turning_points, rtol=0, atol=0)
    np.testing.assert_allclose(sorted(row["turning_points"]), [lo, hi], rtol=0, atol=1e-6)
    # the input moves between the stroke's ends (the turning points are its extremes)
    np.testing.assert_allclose(row["input_range"], [lo, hi], rtol=0, atol=1e-6)


def test_circuits_say_where_the_scenes_limits_stop_the_motion(tmp_path, capsys):
    assert cli.main(["circuits", "hydraulic-boom", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert out.count("stopped by the scene's limits at -200, 300 mm") == 2
    s = json.loads((tmp_path / "circuits.json").read_text())
    for r in s["circuits"]:
        np.testing.assert_allclose(r["limits"], [-200.0, 300.0], rtol=1e-12)


def test_circuits_of_a_linear_input_out_of_its_stroke_names_the_reachable_range(tmp_path, capsys):
    argv = ["circuits", "hydraulic-boom", "--theta", "1000", "--out", str(tmp_path)]
    assert cli.main(argv) == 0
    out = capsys.readouterr().out
    assert "no assembly at input = 1000 mm" in out
    s = json.loads((tmp_path / "circuits.json").read_text())
    lo, hi = _boom_stroke_ends()
    # the 801-value grid over four sizes each way brackets the stroke to a grid step
    (near,) = [r for r in s["reachable"] if r[0] <= 0.0 <= r[1]]
    step = 8 * 2000.0 / 800
    assert lo <= near[0] < lo + step and hi - step < near[1] <= hi


def test_analyze_scene_with_the_closed_form_predictor(tmp_path, capsys):
    """``--predictor closed-form`` with a scene: every angle on its own, on the drawn sides.
    Jansen's leg (dyads only) gives the positions the NumPy reference follows; a scene
    with a group, or a four-bar continuation predictor, is a one-line error naming it."""
    out = tmp_path / "cf"
    argv = ["analyze", "jansen", "--out", str(out), "--no-figures", "--step", "5"]
    assert cli.main([*argv, "--predictor", "closed-form"]) == 0
    rows = list(csv.DictReader((out / "results.csv").open()))
    u = pk.scenes.load("jansen").units
    theta = np.radians([float(r["theta [deg]"]) for r in rows])
    foot = np.array([[float(r[f"foot_x [{u}]"]), float(r[f"foot_y [{u}]"])] for r in rows])
    ref = scene_sweep(pk.scenes.data("jansen"), theta)
    np.testing.assert_allclose(foot, ref.points["foot"], atol=1e-9)
    capsys.readouterr()
    bad = ["analyze", "stephenson3", "--out", str(tmp_path / "g"), "--no-figures"]
    assert cli.main([*bad, "--predictor", "closed-form"]) == 2
    assert "predictor must be 'continuation' for a plan with a group" in capsys.readouterr().err
    assert cli.main([*argv, "--predictor", "quadratic"]) == 2
    assert "--predictor does not apply to a scene" in capsys.readouterr().err
