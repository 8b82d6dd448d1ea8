"""Figures and animations of a scene driven by a linear input (issue 32, item 2): the
built-in hydraulic boom's axes in millimetres (never wrapped, never an angle), its rates
against the law-of-cosines closed form, the poses in stroke order spanning the stroke,
frames labelled with the displacement, the cylinder drawn as barrel and rod overlapping;
--speed for a linear input, --rpm refused there; a slot on a moving lever drawn on it, a
line's direction point not drawn as a pivot; SVG text kept as text."""

from __future__ import annotations

import csv
import json
import math
import re
import xml.etree.ElementTree as ET

import numpy as np
import planarkin as pk
import pytest
from _support import run_cli
from matplotlib.patches import Polygon
from matplotlib.path import Path as MplPath
from planarkin.face import animate
from planarkin.face.figures import scene as scene_fig

# the boom (hydraulic-boom.json): pivot O, barrel pivot C1, the rod's pin E on the boom
# 800 mm from O, the tip T 2000 mm from O; C1, C2 and E in line (the cylinder's axis)
C1 = np.array([600.0, -400.0])  # O is the origin
E0 = np.array([692.820323027551, 399.99999999999994])
A_, B_ = float(np.hypot(*C1)), 800.0  # |O C1|, |O E|
L0 = float(np.hypot(*(E0 - C1)))  # the cylinder's pin-to-pin length as drawn
S_LO, S_HI = (B_ - A_) - L0, (A_ + B_) - L0  # its stroke: the triangle O-C1-E flat


def stroke(sc: pk.Scene) -> tuple[float, float]:
    """The boom's stroke: the law-of-cosines one, within the cylinder's travel limits when
    the scene has them (a sweep stops at either)."""
    lim = (sc.to_dict().get("limits") or {}).get("cylinder")
    if not isinstance(lim, (list, tuple)):
        return S_LO, S_HI
    return max(S_LO, float(lim[0])), min(S_HI, float(lim[1]))


def tip_speed(s: np.ndarray, v: float) -> np.ndarray:
    """|dT/dt| of the boom's tip when the cylinder extends at v: |OT| dgamma/dL v, with
    gamma the angle at O of the triangle O-C1-E (law of cosines) and L = L0 + s."""
    length = L0 + np.asarray(s, dtype=np.float64)
    cos_g = (A_**2 + B_**2 - length**2) / (2 * A_ * B_)
    return 2000.0 * length / (A_ * B_ * np.sqrt(1 - cos_g**2)) * v


@pytest.fixture(scope="module")
def boom():
    sc = pk.scenes.load("hydraulic-boom")
    return sc, sc.sweep(rate=25.0)


def test_the_stroke_is_the_law_of_cosines_one(boom):
    sc, sw = boom
    lo, hi = stroke(sc)
    assert sw.theta.min() == pytest.approx(lo, abs=1e-3)
    assert sw.theta.max() == pytest.approx(hi, abs=1e-3)


def test_rate_panels_are_in_millimetres_and_not_blank(boom):
    sc, sw = boom
    fig = scene_fig.tracers(sc, sw)
    assert fig is not None and len(fig.axes) == 3
    for ax in fig.axes:
        assert "deg" not in ax.get_xlabel() and "θ" not in ax.get_xlabel()
    xlabel = fig.axes[-1].get_xlabel()
    assert "[mm]" in xlabel and "displacement" in xlabel
    title = fig.axes[1].get_title()
    assert "25 mm/s" in title and "rad/s" not in title and "ω" not in title
    (speed,) = [ln for ln in fig.axes[1].get_lines() if ln.get_label() == "speed of T"]
    x, y = (np.asarray(a, dtype=float) for a in speed.get_data())
    # one curve over the stroke in millimetres: not wrapped into (-180, 180]
    lo, hi = stroke(sc)
    assert np.all(np.diff(x) > 0) and x.min() == pytest.approx(lo, abs=1e-3)
    inner = np.isfinite(y) & (x > lo + 20) & (x < hi - 20)
    assert inner.sum() > 300 * (hi - lo) / (S_HI - S_LO)
    np.testing.assert_allclose(y[inner], tip_speed(x[inner], 25.0), rtol=1e-6)
    # the panel shows the bulk of the curve, not just the rows at the stroke's ends
    lo, hi = fig.axes[1].get_ylim()
    assert hi < 20 * np.median(y[inner])


def test_conditioning_is_against_the_displacement(boom):
    sc, sw = boom
    fig = scene_fig.conditioning(sc, sw)
    (ax,) = fig.axes
    assert "[mm]" in ax.get_xlabel() and "deg" not in ax.get_xlabel()
    whole = next(ln for ln in ax.get_lines() if ln.get_label() == "whole solve (product)")
    x = np.asarray(whole.get_xdata(), dtype=float)
    np.testing.assert_array_equal(x, np.sort(sw.theta))


def _inside(poly: np.ndarray, pt: np.ndarray) -> bool:
    return bool(MplPath(poly).contains_point(pt, radius=1e-9))


def test_linkage_poses_span_the_stroke_in_order_and_the_cylinder_is_drawn(boom):
    sc, _ = boom
    whole = sc.sweep(outputs="all")
    fig = scene_fig.linkage(sc, whole)
    one, many = fig.axes[:2]
    labels = [t.get_text() for t in many.get_legend().get_texts() if t.get_text().startswith("s")]
    assert len(labels) == 4 and all(lab.endswith(" mm") for lab in labels)
    s = [float(re.match(r"s = (\S+) mm", lab).group(1)) for lab in labels]
    assert s == sorted(s)
    # from one end of the stroke to the other (the ends' own rows may be left unsolved)
    lo, hi = stroke(sc)
    step = (hi - lo) / 360
    assert abs(s[0] - lo) <= 2.5 * step and abs(s[-1] - hi) <= 2.5 * step
    # the cylinder in each drawing: barrel a patch on the axis C1-E, the rod's piston in it
    barrels = [p for p in one.patches if p.get_gid() == "barrel:cylinder"]
    rods = [ln for ln in one.get_lines() if ln.get_gid() == "rod:cylinder"]
    assert len(barrels) == 1 and len(rods) == 1
    tube = barrels[0].get_xy()[:-1]
    (ex, px), (ey, py) = rods[0].get_data()
    np.testing.assert_allclose([ex, ey], E0, atol=1e-9)  # the rod ends at its pin E
    piston = np.array([px, py])
    assert _inside(tube, piston)  # barrel and rod overlap, as a real cylinder's do
    axis = (E0 - C1) / L0
    centre = tube.mean(axis=0)
    off = axis[0] * (centre - C1)[1] - axis[1] * (centre - C1)[0]
    assert abs(off) < 1e-6 * L0  # the tube on the cylinder's axis
    assert len([p for p in many.patches if p.get_gid() == "barrel:cylinder"]) == 4
    # the barrel's and the rod's own helper points are no tracers (no path drawn)
    assert scene_fig.tracer_names(sc, whole) == ["T"]


def test_animation_frames_say_the_displacement(boom):
    sc, _ = boom
    sw = sc.sweep(outputs="all")
    anim = animate.scene(sc, sw, frames=5, dpi=30)
    theta, points, _, back = animate.motion(sc, sw)
    # out across the stroke and back, as a cylinder goes: never a jump end to end
    top = int(np.argmax(theta))
    assert back and np.all(np.diff(theta[: top + 1]) > 0) and np.all(np.diff(theta[top:]) < 0)
    assert np.abs(np.diff(theta)).max() <= 1.01 * np.ptp(sw.theta) / (len(sw) - 1)
    frames = animate.scene_frames(points, 5)
    ax = anim._fig.axes[0]
    for i in frames:
        anim._func(i)
        (label,) = [t for t in ax.texts if t.get_text().startswith("s =")]
        m = re.match(r"s = +(\S+) mm", label.get_text())
        assert m is not None, label.get_text()
        assert float(m.group(1)) == pytest.approx(theta[i], rel=1e-3, abs=1e-3)
        assert [p for p in ax.patches if p.get_gid() == "barrel:cylinder"]
    anim._draw_was_started = True  # drawn by hand, frame by frame: no warning


def test_analyze_takes_speed_for_a_linear_input_and_refuses_rpm(tmp_path):
    code, out, err = run_cli("analyze", "hydraulic-boom", "--rpm", "30", "--out", str(tmp_path))
    assert code == 2 and out == "" and err.count("\n") == 1
    assert "--rpm" in err and "--speed" in err
    code, out, err = run_cli("analyze", "fourbar", "--speed", "3", "--no-figures",
                             "--out", str(tmp_path))  # fmt: skip
    assert code == 2 and err.count("\n") == 1 and "--speed" in err and "--rpm" in err
    code, out, err = run_cli("analyze", "hydraulic-boom", "--speed", "25", "--no-figures",
                             "-q", "--out", str(tmp_path))  # fmt: skip
    assert code == 0, err
    assert "25 mm/s" in out
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["input_speed"]["speed_value"] == 25.0 and s["input_speed"]["rpm"] is None
    with (tmp_path / "results.csv").open() as f:
        rows = list(csv.DictReader(f))
    x = np.array([float(r["s [mm]"]) for r in rows])
    v = np.array([math.hypot(float(r["T_vx [mm/s]"]), float(r["T_vy [mm/s]"])) for r in rows])
    lo, hi = stroke(pk.scenes.load("hydraulic-boom"))
    inner = (x > lo + 20) & (x < hi - 20)
    np.testing.assert_allclose(v[inner], tip_speed(x[inner], 25.0), rtol=1e-6)


def test_whitworth_slot_is_drawn_on_its_lever_and_its_direction_point_is_no_pivot():
    from matplotlib.figure import Figure
    from planarkin.face import draw

    sc = pk.scenes.load("whitworth")
    st = draw.Structure.of(sc)
    assert st.helpers == {"X"} and "A" in st.joints and "X" not in st.tracers()
    fig = Figure()
    ax = fig.subplots()
    xy = {k: np.asarray(v) for k, v in sc.points.items()}
    draw.pose(ax, st, xy)
    draw.ground(ax, st, xy, 3.0)
    (slot,) = [p for p in ax.patches if p.get_gid() == "slot:lever"]
    ring = slot.get_xy()[:-1]
    # the slot covers the lever's own points and the pin: one piece with the lever
    for p in ("O4", "C", "A"):
        assert _inside(ring, xy[p]), p
    # support triangles stand under O2 and O4 only; X is a small cross
    tops = {tuple(np.round(p.get_xy()[0], 9)) for p in ax.patches
            if isinstance(p, Polygon) and len(p.get_xy()) == 4 and p.get_gid() is None}  # fmt: skip
    assert (0.0, 0.0) in tops and (0.0, 30.0) in tops and (-1.0, 30.0) not in tops
    (cross,) = [ln for ln in ax.get_lines() if ln.get_gid() == "helper"]
    np.testing.assert_array_equal(np.column_stack(cross.get_data())[0], xy["X"])


def test_svg_figures_keep_text_as_text(tmp_path):
    code, _, err = run_cli("circuits", "fourbar", "--format", "svg", "-q", "--out", str(tmp_path))
    assert code == 0, err
    root = ET.parse(tmp_path / "circuits.svg").getroot()
    texts = ["".join(t.itertext()) for t in root.iter() if t.tag.endswith("}text")]
    assert any("circuit 1" in t for t in texts), texts[:5]
