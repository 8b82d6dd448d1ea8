"""The declared output reported (issue 32, item 8): a slider's stroke, a lever's swing,
the quick-return time ratio computed from the sweep, the extremes with the inputs where
they occur and a slider's least transmission angle, against closed forms (slider-crank
inline 2r and offset, Whitworth's and the oscillating cylinder's time ratios, the
four-bar's toggles, the boom's law of cosines); the output's link reported without
outputs="all"; the CSV's and the circuits figure's output."""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import planarkin as pk
import pytest
from _support import run_cli
from planarkin.face.figures import circuits as circuits_fig
from planarkin.scene import report

DEG = math.degrees


def wrapped_deg(rad: float) -> float:
    d = DEG(rad) % 360.0
    return d - 360.0 if d > 180.0 else d


def piston_x(t, r=40.0, rod=160.0, e=0.0):
    """The slider-crank's piston along its line (closed form)."""
    return r * np.cos(t) + np.sqrt(rod**2 - (r * np.sin(t) - e) ** 2)


@pytest.mark.parametrize(("name", "e"), [("slider-crank", 0.0), ("slider-crank-offset", 20.0)])
def test_slider_crank_stroke_time_ratio_and_transmission(name, e):
    r, rod = 40.0, 160.0
    sc = pk.scenes.load(name)
    o = report.output_summary(sc, sc.sweep())
    assert o is not None and o["kind"] == "displacement" and o["unit"] == "mm"
    # stroke: 2r inline, sqrt((l + r)^2 - e^2) - sqrt((l - r)^2 - e^2) offset
    stroke = math.sqrt((rod + r) ** 2 - e**2) - math.sqrt((rod - r) ** 2 - e**2)
    assert o["stroke"] == pytest.approx(stroke, abs=1e-7)
    if e == 0:
        assert stroke == 2 * r
    # the dead centres: crank and rod in line, extended (outer) and folded (inner)
    outer, inner = math.asin(e / (rod + r)), math.pi + math.asin(e / (rod - r))
    x0 = piston_x(math.radians(30.0), r, rod, e)
    assert o["max"]["input"] == pytest.approx(wrapped_deg(outer), abs=1e-4)
    assert o["min"]["input"] == pytest.approx(wrapped_deg(inner), abs=1e-4)
    assert o["max"]["value"] == pytest.approx(math.sqrt((rod + r) ** 2 - e**2) - x0, abs=1e-7)
    # the quick-return ratio of the offset slider-crank: (180 + a) / (180 - a)
    a = math.asin(e / (rod - r)) - math.asin(e / (rod + r))
    assert o["time_ratio"] == pytest.approx((math.pi + a) / (math.pi - a), abs=1e-6)
    # transmission angle (rod against the slot's normal): least at the crank across the line
    assert o["transmission_angle_min_deg"] == pytest.approx(
        90.0 - DEG(math.asin((r + e) / rod)), abs=1e-6
    )
    # at the crank across the line on the offset's far side (either side inline)
    want = 90.0 if e == 0 else -90.0
    assert abs(o["transmission_angle_min_input"]) == pytest.approx(90.0, abs=1e-6)
    assert e == 0 or o["transmission_angle_min_input"] == pytest.approx(want, abs=1e-6)


def test_whitworth_time_ratio_is_the_crank_shaper_closed_form():
    r, c = 60.0, 30.0  # crank, pivot distance (whitworth.json)
    sc = pk.scenes.load("whitworth")
    o = report.output_summary(sc, sc.sweep())
    b = 2 * math.asin(c / r)
    assert o["time_ratio"] == pytest.approx((math.pi + b) / (math.pi - b), abs=1e-6)
    assert o["time_ratio"] == pytest.approx(2.0, abs=1e-6)
    t = o["time_ratio_input_deg"]
    assert max(t["rising"], t["falling"]) == pytest.approx(180.0 + DEG(b), abs=1e-4)
    # the ram: lever arm 50, rod 150, both horizontal at the ends: stroke 2 x 50
    assert o["stroke"] == pytest.approx(100.0, abs=1e-7)
    assert o["transmission_angle_min_deg"] == pytest.approx(90 - DEG(math.asin(50 / 150)), abs=1e-6)


def test_oscillating_cylinder_swing_and_time_ratio():
    r, d = 40.0, 100.0  # inverted-slider-crank.json
    sc = pk.scenes.load("inverted-slider-crank")
    o = report.output_summary(sc, sc.sweep())
    b = 2 * math.asin(r / d)
    assert o["kind"] == "angle" and o["swing_deg"] == pytest.approx(DEG(b), abs=1e-6)
    assert o["time_ratio"] == pytest.approx((math.pi + b) / (math.pi - b), abs=1e-6)
    # the extremes where the cylinder is tangent to the crank circle: cos t = r / d
    assert abs(o["max"]["input"]) == pytest.approx(DEG(math.acos(r / d)), abs=1e-4)
    assert o["transmission_angle_min_deg"] is None  # an angle output has no slider


def test_fourbar_rocker_swing_and_time_ratio_from_its_toggles():
    sc = pk.scenes.load("fourbar")  # (6, 2, 5, 5)
    o = report.output_summary(sc, sc.sweep())
    # rocker at the toggles: |O2 B| = 7 (extended) and 3 (folded)
    at_o4 = [math.acos((36 + 25 - rho**2) / 60) for rho in (7.0, 3.0)]
    assert o["swing_deg"] == pytest.approx(DEG(at_o4[0] - at_o4[1]), abs=1e-6)
    extended = math.acos((36 + 49 - 25) / 84)
    folded = math.pi + math.acos((36 + 9 - 25) / 36)
    q = (folded - extended) / (math.tau - (folded - extended))
    assert o["time_ratio"] == pytest.approx(max(q, 1 / q), abs=1e-6)


def test_boom_swing_is_the_law_of_cosines_and_its_angle_is_reported():
    sc = pk.scenes.load("hydraulic-boom")
    sw = sc.sweep()  # outputs: ["T"] as the scene asks; the boom's angle comes too
    assert sc.outputs == ("T",) and "boom" in sw.angles
    c1, e0 = np.array([600.0, -400.0]), np.array([692.820323027551, 399.99999999999994])
    a, b, l0 = math.hypot(*c1), 800.0, math.hypot(*(e0 - c1))

    def boom_angle(s):
        # the angle at O from O->C1 to O->E, law of cosines, plus O->C1's direction
        g = np.arccos((a**2 + b**2 - (l0 + s) ** 2) / (2 * a * b))
        return math.atan2(c1[1], c1[0]) + g

    ok = sw.success & (sw.theta > sw.theta.min() + 5) & (sw.theta < sw.theta.max() - 5)
    np.testing.assert_allclose(sw.angles["boom"][ok], boom_angle(sw.theta[ok]), atol=1e-9)
    o = report.output_summary(sc, sw)
    s = sw.theta[sw.success]
    assert o["swing_deg"] == pytest.approx(DEG(boom_angle(s.max()) - boom_angle(s.min())), abs=1e-6)
    assert o["min"]["input"] == pytest.approx(s.min()) and o["max"]["input"] == pytest.approx(
        s.max()
    )


def test_fourbar_rocker_angle_without_outputs_all():
    sc = pk.scenes.load("fourbar")
    sw = sc.sweep([0.5], outputs=["P"])
    assert "rocker" in sw.angles
    # B by the circle intersection, open mode: the rocker's angle from O4
    a, o4 = np.array([2 * math.cos(0.5), 2 * math.sin(0.5)]), np.array([6.0, 0.0])
    d = o4 - a
    dist = math.hypot(*d)
    bpt = a + d / 2 + math.sqrt(25 - (dist / 2) ** 2) * np.array([-d[1], d[0]]) / dist
    want = math.atan2(bpt[1] - o4[1], bpt[0] - o4[0])
    assert sw.angles["rocker"][0] == pytest.approx(want, abs=1e-12)


def test_analyze_reports_the_output_in_its_table_json_and_csv(tmp_path):
    code, out, err = run_cli("analyze", "slider-crank-offset", "--no-figures", "-q",
                             "--out", str(tmp_path))  # fmt: skip
    assert code == 0, err
    assert "output 'piston' stroke" in out and "quick-return time ratio" in out
    assert "transmission angle" in out
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["output"]["stroke"] == pytest.approx(
        math.sqrt(200**2 - 400) - math.sqrt(120**2 - 400), abs=1e-7
    )
    with (tmp_path / "results.csv").open() as f:
        rows = list(csv.DictReader(f))
    t = np.radians([float(r["theta [deg]"]) for r in rows])
    got = np.array([float(r["output_piston [mm]"]) for r in rows])
    x0 = piston_x(math.radians(30.0), e=20.0)
    np.testing.assert_allclose(got, piston_x(t, e=20.0) - x0, atol=1e-9)
    mu = np.array([float(r["transmission_angle [deg]"]) for r in rows])
    phi = np.arcsin((40 * np.sin(t) - 20) / 160)  # the rod's angle to the line
    np.testing.assert_allclose(mu, 90 - np.degrees(np.abs(phi)), atol=1e-9)


def test_circuits_figure_plots_the_declared_output():
    sc = pk.scenes.load("slider-crank-offset")
    found = sc.circuits()
    fig = circuits_fig.circuits(sc, found, sc.input_angle)
    ax = fig.axes[0]
    assert "piston" in ax.get_ylabel() and "[mm]" in ax.get_ylabel()
    (own,) = [ln for ln in ax.get_lines() if ln.get_linewidth() == 1.8]  # circuit 1's
    x, y = (np.asarray(v, dtype=float) for v in own.get_data())
    ok = np.isfinite(x) & np.isfinite(y)
    assert ok.sum() > 100
    # the drawn circuit: x_B - x_B(30 deg)
    want = piston_x(np.radians(x[ok]), e=20.0) - piston_x(math.radians(30.0), e=20.0)
    # or the other circuit's: the rod on the crank pin's far side, B = A_x - sqrt(...)
    other = want - 2 * np.sqrt(160**2 - (40 * np.sin(np.radians(x[ok])) - 20) ** 2)
    assert np.allclose(y[ok], want, atol=1e-6) or np.allclose(y[ok], other, atol=1e-6)


def test_a_rocking_crank_reports_the_swing_across_its_reach():
    """A non-Grashof four-bar (6, 4, 3, 4) drawn at theta2 = 0: its crank rocks between
    +-86.4 deg, so its default sweep (0..360 deg) is solved at both ends and out of reach
    in the middle. The rocker's swing is the closed form's over the solved inputs, the two
    solved spans joined through 0 (not across the unreachable middle)."""
    sc = pk.FourBar(6, 4, 3, 4).to_scene(theta2=0.0)
    sw = sc.sweep()
    ok = sw.success
    assert ok[0] and ok[-1] and not ok.all()
    lim = math.acos(3 / 48)  # |O4 A| = r3 + r4 = 7: the dead points
    t_solved = np.angle(np.exp(1j * sw.theta[ok]))
    assert np.abs(t_solved).max() <= lim
    lo, hi = t_solved.min(), t_solved.max()

    def rocker(t):
        a = np.stack([4 * np.cos(t), 4 * np.sin(t)], axis=-1)
        d = np.array([6.0, 0.0]) - a
        dist = np.hypot(d[..., 0], d[..., 1])
        x = (dist**2 + 9 - 16) / (2 * dist)  # along A -> O4 from A, |AB| = 3
        h = np.sqrt(9 - x**2)
        nrm = np.stack([-d[..., 1], d[..., 0]], axis=-1) / dist[..., None]
        b = a + d * (x / dist)[..., None] + h[..., None] * nrm  # the drawn side (B above)
        return np.unwrap(np.arctan2(b[..., 1], b[..., 0] - 6.0))

    y = np.degrees(rocker(np.linspace(lo, hi, 200_001)))
    o = report.output_summary(sc, sw)
    assert o["swing_deg"] == pytest.approx(y.max() - y.min(), abs=1e-6)
    assert o["time_ratio"] is None  # the crank does not turn
