"""The ``planarkin`` command, run in a temporary folder: the files ``analyze`` and
``animate`` promise, their contents against the API and independent formulas, and how
bad options and awkward linkages are reported."""

from __future__ import annotations

import csv
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import planarkin as pk
import pytest
from _support import run_cli as run
from planarkin.face import cli
from planarkin.face.cli import _common
from planarkin.face.cli import tradeoff as tradeoff_cli

PIL_Image = pytest.importorskip("PIL.Image")

SEED = (6.0, 2.0, 5.0, 5.0)
OMEGA2 = 100 * 2 * math.pi / 60
P, DELTA = 3.0, math.radians(30.0)
FIGURES = [
    "figure_a_position_analysis.png",
    "figure_combined_positions.png",
    "figure_b_convergence.png",
    "figure_c_velocity.png",
    "figure_d_acceleration.png",
    "figure_e_transmission_angle.png",
    "figure_f_coupler_curve.png",
    "figure_g_linkage.png",
]
COLUMNS = [
    "theta2 [deg]", "theta3 [deg]", "theta4 [deg]", "status [code]", "status_name", "nit [-]",
    "residual [-]", "closed_form_deviation [deg]", "omega3 [rad/s]", "omega4 [rad/s]",
    "alpha3 [rad/s^2]", "alpha4 [rad/s^2]", "transmission_angle [deg]", "branch_indicator [-]",
    "coupler_x [length]", "coupler_y [length]",
]  # fmt: skip


def read_csv(path: Path) -> tuple[list[str], dict[str, np.ndarray]]:
    with path.open(newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    cols = {}
    for k, name in enumerate(header):
        vals = [r[k] for r in body]
        cols[name] = np.array(vals) if name == "status_name" else np.array(vals, dtype=float)
    return header, cols


# `planarkin analyze` with no options draws eight figures at 300 dpi: 2-3 s on 2 cores,
# so the tests that read its files are left out of the inner loop
SEED_RUN = pytest.mark.slow


@pytest.fixture(scope="module")
def seed_run(tmp_path_factory):
    """``planarkin analyze`` with no options, in an empty folder (figures go to ./figures)."""
    folder = tmp_path_factory.mktemp("analyze")
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(folder)
        code, out, err = run("analyze")
    return code, out, err, folder / "figures"


@pytest.fixture(scope="module")
def seed_api():
    fb = pk.FourBar(*SEED)
    return fb, fb.sweep(omega2=OMEGA2, alpha2=0.0)


# --- analyze: the seeds' linkage ---------------------------------------------------------


@SEED_RUN
def test_analyze_writes_every_promised_file(seed_run):
    code, out, err, folder = seed_run
    assert code == 0, err
    assert err == ""
    assert sorted(p.name for p in folder.iterdir()) == sorted(
        FIGURES + ["results.csv", "summary.json"]
    )


@SEED_RUN
def test_figures_are_300_dpi_and_not_blank(seed_run):
    folder = seed_run[3]
    for name in FIGURES:
        with PIL_Image.open(folder / name) as im:
            assert im.format == "PNG"
            assert im.info["dpi"] == pytest.approx((300, 300), abs=0.01), name
            assert min(im.size) >= 1000, name  # a print-size figure
            gray = np.asarray(im.convert("L"), dtype=float)
        assert gray.std() > 10, f"{name} looks blank"
        assert (gray < 128).mean() > 0.005, f"{name} has almost no ink"


@SEED_RUN
def test_summary_table_is_printed(seed_run):
    out = seed_run[1]
    for expect in (
        "r1 = 6 (ground), r2 = 2 (crank), r3 = 5 (coupler), r4 = 5 (rocker); open mode",
        "GCRR crank-rocker",
        "361 / 361",
        "total 360, mean 0.997",  # the quadratic predictor: about one Newton step a point
        "max residual",
        "max |sweep - closed form|",
        "rocker swing (theta4)",
        "transmission angle",
        "none: the crank turns fully round",
        "order of convergence 2.0",
        "wall time",
    ):
        assert expect in out, expect
    assert out.isascii()  # any console encoding can print it


@SEED_RUN
def test_csv_rows_and_values_agree_with_the_api(seed_run, seed_api):
    fb, sw = seed_api
    header, c = read_csv(seed_run[3] / "results.csv")
    assert header == COLUMNS
    assert all(len(v) == 361 for v in c.values())
    # the same numbers as the API, to the last bit (written with repr)
    np.testing.assert_array_equal(c["theta2 [deg]"], np.degrees(pk.DEFAULT_THETA2))
    np.testing.assert_array_equal(c["theta3 [deg]"], np.degrees(sw.theta3))
    np.testing.assert_array_equal(c["theta4 [deg]"], np.degrees(sw.theta4))
    np.testing.assert_array_equal(c["status [code]"], sw.status)
    assert set(c["status_name"]) == {"CONVERGED"}
    np.testing.assert_array_equal(c["nit [-]"], sw.nit)
    np.testing.assert_array_equal(c["residual [-]"], sw.residual)
    for name in ("omega3", "omega4", "alpha3", "alpha4"):
        unit = "rad/s" if name.startswith("omega") else "rad/s^2"
        np.testing.assert_array_equal(c[f"{name} [{unit}]"], getattr(sw, name))

    # and against independent formulas
    t2, t3, t4 = (np.radians(c[f"theta{k} [deg]"]) for k in (2, 3, 4))
    r1, r2, r3, r4 = SEED
    np.testing.assert_allclose(r2 * np.cos(t2) + r3 * np.cos(t3) - r4 * np.cos(t4), r1, atol=1e-9)
    np.testing.assert_allclose(r2 * np.sin(t2) + r3 * np.sin(t3) - r4 * np.sin(t4), 0, atol=1e-9)
    assert np.all(c["branch_indicator [-]"] > 0)  # open mode throughout
    np.testing.assert_allclose(c["branch_indicator [-]"], np.sin(t4 - t3), atol=1e-12)
    np.testing.assert_allclose(
        c["transmission_angle [deg]"], np.degrees(np.arcsin(np.abs(np.sin(t4 - t3)))), atol=1e-9
    )
    np.testing.assert_allclose(
        c["coupler_x [length]"], r2 * np.cos(t2) + P * np.cos(t3 + DELTA), atol=1e-12
    )
    np.testing.assert_allclose(
        c["coupler_y [length]"], r2 * np.sin(t2) + P * np.sin(t3 + DELTA), atol=1e-12
    )
    # velocity by finite differences of the positions (central, 1 deg apart)
    h = np.radians(1.0)
    w4 = (np.unwrap(t4)[2:] - np.unwrap(t4)[:-2]) / (2 * h) * OMEGA2
    np.testing.assert_allclose(c["omega4 [rad/s]"][1:-1], w4, rtol=2e-3, atol=2e-3)
    assert np.all(c["closed_form_deviation [deg]"] < 1e-8)


@SEED_RUN
def test_json_summary_agrees_with_the_api(seed_run, seed_api):
    fb, sw = seed_api
    s = json.loads((seed_run[3] / "summary.json").read_text())
    assert s["linkage"] == {"r1": 6.0, "r2": 2.0, "r3": 5.0, "r4": 5.0, "mode": "open"}
    g = fb.grashof()
    assert s["grashof"]["barker"] == g.barker == "GCRR"
    assert s["grashof"]["kind"] == "crank-rocker"
    summ = sw.summary()
    assert s["sweep"] == {
        "points": 361,
        "converged": 361,
        "success_rate": 1.0,
        "nit_total": summ.nit_total,
        "nit_mean": summ.nit_mean,
        "residual_max": summ.residual_max,
        "statuses": {"CONVERGED": 361},
    }
    o = s["options"]
    assert (o["step_deg"], o["tol"], o["rpm"], o["predictor"]) == (1.0, 1e-9, 100.0, "quadratic")
    assert o["omega2_rad_s"] == pytest.approx(OMEGA2)
    assert s["closed_form_max_deviation_deg"] < 1e-8

    lim = fb.limits("open")
    r = s["rocker_deg"]
    assert r["min"] == pytest.approx(math.degrees(lim.rocker_min))
    assert r["swing"] == pytest.approx(math.degrees(lim.rocker_swing))
    # the sampled extremes lie within a 1 deg crank step of the exact ones
    t4 = np.degrees(sw.theta4)
    assert s["theta4_deg"]["min"] == pytest.approx(t4.min()) and t4.min() >= r["min"] - 1e-9
    assert s["theta4_deg"]["max"] == pytest.approx(t4.max()) and t4.max() <= r["max"] + 1e-9
    assert r["max"] - t4.max() < 0.01 and t4.min() - r["min"] < 0.01
    mu = np.degrees(pk.FourBar.transmission_angle(sw.theta3, sw.theta4))
    assert s["transmission_angle_deg"]["min"] == pytest.approx(mu.min())
    assert s["transmission_angle_deg"]["max"] == pytest.approx(mu.max())
    assert s["peak_abs"]["omega4_rad_s"] == pytest.approx(np.abs(sw.omega4).max())
    assert s["limits"]["full_rotation"] is True and s["limits"]["toggles_deg"] == []
    assert s["unreachable_spans_deg"] == [] and s["unsolved_deg"] == {}

    n = s["newton"]
    sol = fb.solve(math.radians(45), guess=(math.radians(80), math.radians(100)), history=True)
    assert (n["theta2_deg"], n["guess_deg"], n["status"]) == (45.0, [80.0, 100.0], "CONVERGED")
    assert n["nit"] == sol.nit and n["history"] == sol.history.tolist()
    assert 1.8 < n["order"] < 2.2  # Newton's quadratic convergence
    assert s["wall_time_s"]["sweep"] > 0
    assert set(s["files"]) == set(FIGURES) | {"results.csv", "summary.json"}


# --- analyze: options --------------------------------------------------------------------


def test_json_flag_no_figures_and_step(tmp_path):
    code, out, err = run(
        "analyze", "--json", "--no-figures", "--step", "7", "--rpm", "60",
        "--coupler", "1", "0", "--out", str(tmp_path),
    )  # fmt: skip
    assert code == 0, err
    s = json.loads(out)  # stdout is the JSON summary, nothing else
    assert s == json.loads((tmp_path / "summary.json").read_text())
    assert sorted(p.name for p in tmp_path.iterdir()) == ["results.csv", "summary.json"]
    assert s["sweep"]["points"] == 52  # 0, 7, ..., 357 deg
    assert s["options"]["omega2_rad_s"] == pytest.approx(2 * math.pi)
    _, c = read_csv(tmp_path / "results.csv")
    assert c["theta2 [deg]"][-1] == pytest.approx(357)
    # coupler point on the coupler line at 1 from A
    t2, t3 = np.radians(c["theta2 [deg]"]), np.radians(c["theta3 [deg]"])
    np.testing.assert_allclose(c["coupler_x [length]"], 2 * np.cos(t2) + np.cos(t3), atol=1e-12)


def test_crossed_mode(tmp_path):
    code, out, err = run(
        "analyze", "--mode", "crossed", "--json", "--no-figures", "--step", "10",
        "--predictor", "previous", "--tol", "1e-12", "--out", str(tmp_path),
    )  # fmt: skip
    assert code == 0, err
    s = json.loads(out)
    assert s["linkage"]["mode"] == "crossed" and s["sweep"]["converged"] == 37
    assert s["newton"]["status"] == "CONVERGED"  # the mirrored cold guess stays on crossed
    _, c = read_csv(tmp_path / "results.csv")
    assert np.all(c["branch_indicator [-]"] < 0)
    cf3, cf4 = pk.FourBar(*SEED).closed_form(np.radians(c["theta2 [deg]"]), "crossed")
    np.testing.assert_allclose(np.radians(c["theta3 [deg]"]), cf3, atol=1e-11)


def test_crank_angles():
    np.testing.assert_array_equal(_common.crank_angles(1), pk.DEFAULT_THETA2)
    assert len(_common.crank_angles(0.5)) == 721
    np.testing.assert_allclose(np.degrees(_common.crank_angles(360)), [0, 360])
    np.testing.assert_allclose(np.degrees(_common.crank_angles(7))[[0, -1]], [0, 357])


# --- linkages that cannot turn fully, and dead points ------------------------------------


@pytest.mark.slow  # eight figures drawn: 1-2 s on 2 cores, the layout whatever the dpi
def test_non_grashof_linkage_reports_unreachable_spans(tmp_path):
    links = (5.0, 3.0, 4.0, 2.5)  # S + L = 7.5 > P + Q = 7: triple rocker
    code, out, err = run(
        "analyze", "--links", *map(str, links), "--step", "5", "--dpi", "40", "--out", str(tmp_path)
    )
    assert code == 0, err
    assert "non-grashof, RRR1 triple-rocker" in out
    assert "not assemblable" in out and "crank toggles at theta2" in out
    assert all((tmp_path / f).stat().st_size > 0 for f in FIGURES)

    # the crank stops where coupler and rocker line up: |O4 A| = r3 + r4
    r1, r2, r3, r4 = links
    stop = math.degrees(math.acos((r1**2 + r2**2 - (r3 + r4) ** 2) / (2 * r1 * r2)))
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["grashof"]["condition"] == "non-grashof"
    assert s["unreachable_spans_deg"] == [[pytest.approx(stop), pytest.approx(360 - stop)]]
    assert s["limits"]["toggles_deg"] == [pytest.approx(stop), pytest.approx(360 - stop)]
    _, c = read_csv(tmp_path / "results.csv")
    out_of_reach = (c["theta2 [deg]"] > stop) & (c["theta2 [deg]"] < 360 - stop)
    np.testing.assert_array_equal(c["status [code]"] == pk.Status.NOT_ASSEMBLABLE, out_of_reach)
    assert np.all(np.isnan(c["theta3 [deg]"][out_of_reach]))
    assert s["sweep"]["statuses"]["NOT_ASSEMBLABLE"] == out_of_reach.sum()


def test_change_point_linkage_reports_dead_points(tmp_path):
    code, out, err = run("analyze", "--links", "6", "2", "6", "2", "--no-figures",
                         "--out", str(tmp_path))  # fmt: skip
    assert code == 0, err
    assert "change-point" in out and "singular points" in out
    assert "dead points" in out and "theta2 = 0, 180 deg" in out
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["unsolved_deg"] == {"SINGULAR": [0.0, 180.0, 360.0]}


# --- bad options -------------------------------------------------------------------------

BAD = [
    ("analyze", "--links", "6", "2", "5"),
    ("analyze", "--links", "6", "-2", "5", "5"),
    ("analyze", "--links", "6", "2", "5", "inf"),
    ("analyze", "--mode", "sideways"),
    ("analyze", "--step", "0"),
    ("analyze", "--step", "361"),
    ("analyze", "--step", "one"),
    ("analyze", "--tol", "-1"),
    ("analyze", "--max-iter", "0"),
    ("analyze", "--rpm", "nan"),
    ("analyze", "--dpi", "0"),
    ("analyze", "--predictor", "psychic"),
    ("analyze", "--frobnicate"),
    ("animate", "--frames", "0"),
    ("animate", "--fps", "-1"),
    ("analyse",),
    (),
]


@pytest.mark.parametrize("argv", BAD, ids=" ".join)
def test_bad_option_is_one_line_and_exit_code_2(argv, tmp_path):
    out_dir = tmp_path / "out"
    code, out, err = run(
        *argv, *(["--out", str(out_dir)] if argv[:1] in (("analyze",), ("animate",)) else [])
    )
    assert code == 2
    assert out == ""
    assert err.startswith("planarkin: error: ") and err.count("\n") == 1, err
    assert not out_dir.exists()  # nothing written


@pytest.mark.slow  # two fresh processes (a real exit, no 2.6 TiB in the test's process)
def test_cli_step_too_small_is_a_one_line_error(tmp_path):
    """`analyze` and `animate` with `--step 1e-9` (360000000001 crank angles, 2.6 TiB of
    outputs): a one-line error naming --step and the count, exit code 2, no traceback."""
    for cmd in ("analyze", "animate"):
        out = subprocess.run(
            [sys.executable, "-m", "planarkin", cmd, "--step", "1e-9", "--out", str(tmp_path)],
            capture_output=True,
            text=True,
            timeout=120,
        )
        assert out.returncode == 2
        lines = out.stderr.strip().splitlines()
        assert len(lines) == 1, out.stderr
        assert lines[0].startswith("planarkin: error: --step")
        assert "360000000001 crank angles" in lines[0]
        assert "Traceback" not in out.stderr


def test_python_dash_m_runs_the_same_command():
    p = subprocess.run(
        [sys.executable, "-m", "planarkin", "analyze", "--links", "1", "2", "3", "0"],
        capture_output=True, text=True, timeout=60,
    )  # fmt: skip
    assert p.returncode == 2
    assert p.stdout == ""
    assert p.stderr.strip().startswith("planarkin: error: r4 must be")
    assert p.stderr.count("\n") == 1


def test_subcommands_and_tradeoff_registration():
    parser = cli.build_parser()
    (sub,) = [a for a in parser._actions if a.dest == "command"]
    commands = {
        "analyze",
        "animate",
        "circuits",
        "export",
        "forces",
        "scenes",
        "synthesize",
        "atlas",
        "tradeoff",
    }
    commands.add("web")
    assert set(sub.choices) == commands
    assert sub.choices["tradeoff"].get_default("func") is tradeoff_cli.run
    help_text = sub.choices["analyze"].format_help()
    for opt in ("--links", "--mode", "--step", "--tol", "--rpm", "--coupler", "--out",
                "--no-figures", "--json", "--predictor"):  # fmt: skip
        assert opt in help_text


# --- animate -----------------------------------------------------------------------------


def test_animate_writes_gif_and_self_contained_html(tmp_path):
    code, out, err = run("animate", "--frames", "6", "--step", "10", "--dpi", "40",
                         "--out", str(tmp_path))  # fmt: skip
    assert code == 0, err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["linkage.gif", "linkage.html"]
    with PIL_Image.open(tmp_path / "linkage.gif") as im:
        assert im.format == "GIF" and im.n_frames == 6
        frames = []
        for k in range(im.n_frames):
            im.seek(k)
            frames.append(np.asarray(im.convert("L"), dtype=float))
    assert all(f.std() > 10 for f in frames)
    assert any(np.abs(frames[0] - f).max() > 0 for f in frames[1:])  # it moves

    html = (tmp_path / "linkage.html").read_text(encoding="utf-8")
    assert html.startswith("<!DOCTYPE html>") and html.rstrip().endswith("</html>")
    assert "http://" not in html and "https://" not in html and "//cdn" not in html
    assert "<link" not in html and 'class="fa' not in html  # no web font for the icons
    assert html.count("data:image/png;base64,") == 6  # frames embedded
    assert "play_animation()" in html and "<script" in html


def test_linkage_that_never_assembles(tmp_path):
    code, out, err = run("analyze", "--links", "10", "1", "1", "1", "--json", "--no-figures",
                         "--out", str(tmp_path))  # fmt: skip
    assert code == 0, err
    s = json.loads(out)
    assert s["sweep"]["converged"] == 0 and s["sweep"]["residual_max"] is None
    assert s["unreachable_spans_deg"] == [[0.0, 360.0]]
    assert s["newton"]["status"] == "NOT_ASSEMBLABLE"
    code, out, _ = run("analyze", "--links", "10", "1", "1", "1", "--no-figures",
                       "--out", str(tmp_path))  # fmt: skip
    assert "cannot be assembled at any crank angle" in out


# --- wall time ------------------------------------------------------------------------------


def test_sweep_time_is_a_warm_median(monkeypatch):
    """The sweep's wall time is the median of warm calls, the first call (cold caches, many
    times a warm one) untimed. A fake clock makes each call's duration known: the first
    call costs 1000, the others 3, 1, 2, 5, 4 units, so the answer is 3 over 5 runs."""
    costs = iter([1000.0, 3.0, 1.0, 2.0, 5.0, 4.0])
    clock = [0.0]
    monkeypatch.setattr(_common.time, "perf_counter", lambda: clock[0])

    def call():
        clock[0] += next(costs)

    med, n = _common.warm_median(call, runs=5, budget_s=1e9)
    assert (med, n) == (3.0, 5)  # median of 3, 1, 2, 5, 4; the 1000 is not timed


def test_table_reports_the_warm_median(tmp_path):
    code, out, _ = run("analyze", "--no-figures", "--out", str(tmp_path))
    assert code == 0
    s = json.loads((tmp_path / "summary.json").read_text())
    w = s["wall_time_s"]
    assert w["sweep_runs"] >= 3
    (line,) = [x for x in out.splitlines() if x.strip().startswith("wall time")]
    assert f"median of {w['sweep_runs']} warm runs" in line
