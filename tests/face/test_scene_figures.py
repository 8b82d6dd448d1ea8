"""The scene figures as a user sees them (issue 20, items 4-9): drawn as an engineer draws
a linkage (checked on the artists), angles in (-180, 180], no blank figure, no text over
text or off the canvas, every figure in png, svg and pdf, names in any script."""

from __future__ import annotations

import json
import math
import warnings
import xml.etree.ElementTree as ET

import numpy as np
import planarkin as pk
import pytest
from _support import text_faults
from matplotlib.figure import Figure
from matplotlib.patches import Polygon, Rectangle
from planarkin.face import animate, cli, draw
from planarkin.face.degrees import on_wrapped_axis, wrap_deg
from planarkin.face.figures import circuits as circuits_fig
from planarkin.face.figures import scene as scene_fig


def segments_cross(p, q, r, s) -> bool:
    """Whether the open segments p-q and r-s cross (an independent orientation test)."""

    def orient(a, b, c):
        return np.sign((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))

    return orient(p, q, r) * orient(p, q, s) < 0 and orient(r, s, p) * orient(r, s, q) < 0


def simple(poly: np.ndarray) -> bool:
    """No two non-adjacent edges of the closed polygon cross."""
    n = len(poly)
    edges = [(poly[i], poly[(i + 1) % n]) for i in range(n)]
    return not any(
        segments_cross(*edges[i], *edges[j])
        for i in range(n)
        for j in range(i + 2, n)
        if not (i == 0 and j == n - 1)
    )


# a Stephenson-II-like plate listed in crossing order: the old drawing filled a bow-tie
PLATE = {
    "points": {
        "O": [0.0, 0.0],
        "Q": [6.0, 0.0],
        "A": [1.0, 1.0],
        "B": [4.0, 4.0],
        "C": [4.0, 1.0],
        "D": [1.0, 4.0],
        "P": [2.5, 6.0],
    },
    "links": {
        "ground": ["O", "Q"],
        "crank": ["O", "A"],
        "plate": ["A", "B", "C", "D"],
        "rocker": ["Q", "C"],
        "tail": ["D", "P"],
    },
    "ground": "ground",
    "input": {"link": "crank", "pivot": "O"},
}


def test_a_plate_of_four_points_is_its_outline_never_a_bow_tie():
    st = draw.Structure.from_dict(PLATE)
    fig = Figure()
    ax = fig.subplots()
    xy = {k: np.array(v) for k, v in PLATE["points"].items()}
    draw.pose(ax, st, xy)
    plates = [p for p in ax.patches if isinstance(p, Polygon)]
    assert len(plates) == 1
    poly = plates[0].get_xy()[:-1]  # matplotlib closes the path by repeating the first
    assert len(poly) == 4 and simple(poly)
    listed = np.array([xy[p] for p in PLATE["links"]["plate"]])
    assert not simple(listed)  # the listed order would cross itself
    # every point of the plate on or inside the outline (counter-clockwise: all turns left)
    for k in range(4):
        a, b = poly[k], poly[(k + 1) % 4]
        for v in listed:
            assert (b[0] - a[0]) * (v[1] - a[1]) - (b[1] - a[1]) * (v[0] - a[0]) >= -1e-12


def test_hull_of_points_in_line_is_its_two_ends():
    pts = np.array([[0.0, 0.0], [2.0, 2.0], [1.0, 1.0]])
    assert sorted(draw.hull(pts)) == [0, 1]


def test_ground_is_hatched_at_every_pivot_and_joints_are_circles():
    sc = pk.scenes.load("jansen")
    st = draw.Structure.of(sc)
    fig = Figure()
    ax = fig.subplots()
    draw.pose(ax, st, sc.points)
    draw.ground(ax, st, sc.points, 1.0)
    hatched = [p for p in ax.patches if isinstance(p, Rectangle) and p.get_hatch()]
    ground = [sc.points[p] for p in sc.links[sc.ground]]
    assert len(hatched) == len(ground)
    for (gx, gy), r in zip(ground, hatched, strict=True):
        x, y = r.get_xy()
        assert x < gx < x + r.get_width() and y < gy  # under its pivot
    circles = np.vstack([
        np.column_stack([ln.get_xdata(), ln.get_ydata()])
        for ln in ax.get_lines()
        if ln.get_marker() == "o"
    ])  # fmt: skip
    for j in sc.joints:
        assert np.min(np.hypot(*(circles - sc.points[j]).T)) < 1e-12, j


def test_slots_draw_a_rail_and_a_block_aligned_with_the_line():
    """A slider-crank written by hand with the slot of DESIGN.md's 'Prismatic joints':
    the block is centred on the pin, its sides along the line; the rail runs along it."""
    d = {
        "points": {"O2": [0.0, 0.0], "A": [1.0, 1.0], "B": [4.0, 1.0], "X": [1.0, 1.0]},
        "links": {"ground": ["O2", "X"], "crank": ["O2", "A"], "rod": ["A", "B"]},
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O2"},
        "slots": {"piston": {"point": "B", "guide": "ground", "line": ["O2", "X"]}},
        "prismatic": {"cyl": {"link": "rod", "guide": "ground", "line": ["O2", "X"]}},
    }
    st = draw.Structure.from_dict(d)
    assert st.slots == {"piston": ("B", "ground", ("O2", "X"))}
    fig = Figure()
    ax = fig.subplots()
    xy = {k: np.array(v) for k, v in d["points"].items()}
    draw.pose(ax, st, xy)
    u = np.array([1.0, 1.0]) / math.sqrt(2)
    (block,) = [p for p in ax.patches if isinstance(p, Polygon) and len(p.get_xy()) == 5]
    corners = block.get_xy()[:-1]
    np.testing.assert_allclose(corners.mean(axis=0), xy["B"], atol=1e-12)
    sides = np.diff(np.vstack([corners, corners[:1]]), axis=0)
    for s in sides:  # each side along the line or across it
        c = abs(np.dot(s, u)) / np.hypot(*s)
        assert min(c, 1 - c) < 1e-12
    along = [ln for ln in ax.get_lines() if len(ln.get_xdata()) == 2 and ln.get_marker() != "o"]
    rails = [
        ln
        for ln in along
        if abs(abs(np.dot(np.diff(np.column_stack(ln.get_data()), axis=0)[0], u))
               - np.hypot(*np.diff(np.column_stack(ln.get_data()), axis=0)[0])) < 1e-9
    ]  # fmt: skip
    assert len(rails) >= 2  # the two sides of the slot
    # the prismatic sleeve: an open rectangle (4 corners, one side left open)
    sleeves = [ln for ln in ax.get_lines() if len(ln.get_xdata()) == 4]
    assert len(sleeves) == 1


def test_linkage_figure_single_pose_named_beside_labelled_poses():
    sc = pk.scenes.load("jansen")
    sw = sc.sweep(outputs="all")
    fig = scene_fig.linkage(sc, sw)
    one, many = fig.axes[:2]
    named = {t.get_text() for t in one.texts}
    assert named == set(sc.points)
    labels = [t.get_text() for t in many.get_legend().get_texts() if t.get_text().startswith("θ")]
    assert len(labels) == 4
    shown = [float(s[4:-1]) for s in labels]
    assert all(-180 < v <= 180 for v in shown)
    idx = scene_fig._poses(sw, 4)
    np.testing.assert_allclose(shown, wrap_deg(sw.theta[idx]), atol=0.05)
    assert "θ = 0.0°" in one.get_title()


def test_wrapped_angles():
    np.testing.assert_allclose(
        wrap_deg(np.radians([397.8, 388.88, 180, -180, 540, 0, -0.5])),
        [37.8, 28.88, 180, 180, 180, 0, -0.5],
        atol=1e-9,
    )


def test_a_full_turn_is_one_curve_on_the_wrapped_axis():
    """Stephenson III is drawn at 37.8 deg: its sweep runs 37.8..397.8 deg. On the axis it
    is one curve over (-180, 180], every value in its place."""
    sc = pk.scenes.load("stephenson3")
    sw = sc.sweep(outputs=["j4"])
    x, y = on_wrapped_axis(sw.theta, sw.points["j4"][:, 0])
    assert np.isfinite(x).all() and np.isfinite(y).all()  # no break
    assert x.min() > -180 and x.max() <= 180 and np.all(np.diff(x) >= 0)
    for k in range(0, len(x), 40):  # each value sits at its own angle
        i = int(np.argmin(np.abs(wrap_deg(sw.theta) - x[k])))
        assert y[k] == pytest.approx(sw.points["j4"][i, 0], abs=1e-12)


def test_peaucellier_single_range_is_one_piece():
    """Its solved range -82..82 deg, swept from 0 round to 360, is one piece on the axis."""
    sc = pk.scenes.load("peaucellier")
    sw = sc.sweep(sc.input_angle + np.radians(np.arange(0.0, 361.0) - 75.0 + 75.0))
    fig = scene_fig.conditioning(sc, sw)
    (whole,) = [ln for ln in fig.axes[0].get_lines() if ln.get_label().startswith("whole")]
    y = np.asarray(whole.get_ydata(), dtype=float)
    ok = np.isfinite(y).astype(int)
    assert np.count_nonzero(np.diff(ok) == 1) + ok[0] == 1  # one run of finite values


def test_analyze_scene_tables_wrap_angles(tmp_path):
    out = tmp_path / "s3"
    cli.main(["analyze", "stephenson3", "--out", str(out), "--no-figures", "-q"])
    s = json.loads((out / "summary.json").read_text())
    assert -180 < s["drawn_input_deg"] <= 180
    for v in s["dead_points_deg"] + [e["deg"] for e in s["motion_stops_deg"]]:
        assert -180 < v <= 180


def four_bar_without_tracers() -> dict:
    d = pk.scenes.data("fourbar")
    d["links"]["coupler"] = ["A", "B"]
    del d["points"]["P"]
    d.pop("outputs", None)
    d["name"] = "no tracers"
    return d


def test_no_blank_tracer_figure(tmp_path, capsys):
    p = tmp_path / "plain.json"
    p.write_text(json.dumps(four_bar_without_tracers()))
    out = tmp_path / "o"
    assert cli.main(["analyze", str(p), "--out", str(out), "--dpi", "30", "--step", "10"]) == 0
    assert not list(out.glob("scene_tracers.*"))
    assert (out / "scene_linkage.png").exists()
    assert "no tracer figure" in capsys.readouterr().out


def scene_figures(name: str) -> dict[str, Figure]:
    sc = pk.scenes.load(name)
    sw = sc.sweep(omega=1.0)
    whole = sc.sweep(outputs="all")
    figs = {
        "linkage": scene_fig.linkage(sc, whole),
        "conditioning": scene_fig.conditioning(sc, sw),
    }
    if not (sc.slots or sc.prismatic):  # circuits of slider scenes are not traced yet
        figs["circuits"] = circuits_fig.circuits(sc, sc.circuits(), sc.input_angle)
    t = scene_fig.tracers(sc, sw)
    if t is not None:
        figs["tracers"] = t
    return figs


# a scene's figures take about 2 s to lay out and draw on 2 cores: every built-in scene
# is left out of the inner loop (-m "not slow"); test_axis_labels_fit_their_axes stays in it
@pytest.mark.slow
@pytest.mark.parametrize("name", pk.scenes.names())
def test_no_text_over_text_nor_off_the_canvas(name):
    for what, fig in scene_figures(name).items():
        outside, overlapping = text_faults(fig, 100)
        assert outside == [], what
        assert overlapping == [], what


@pytest.mark.slow  # every figure of four commands rendered: about 3 s on 2 cores per format
@pytest.mark.parametrize("fmt", ["svg", "pdf"])
def test_every_scene_figure_in_vector_formats(tmp_path, fmt):
    out = tmp_path / fmt
    argv = ["--out", str(out), "--format", fmt, "-q"]
    assert cli.main(["analyze", "jansen", "--step", "10", *argv]) == 0
    assert cli.main(["circuits", "fourbar", *argv]) == 0
    files = sorted(out.glob(f"*.{fmt}"))
    assert [f.stem for f in files] == [
        "circuits", "scene_conditioning", "scene_linkage", "scene_tracers",
    ]  # fmt: skip
    # the four-bar's eight figures and the trade-off plot too
    assert cli.main(["analyze", "--step", "10", *argv]) == 0
    plot = tmp_path / "pareto.png"
    tradeoff = ["tradeoff", "--tols", "1e-6", "--methods", "closed-form", "--random", "1",
                "--truth-links", "1", "--points", "13", "--repeat", "1", "-q"]  # fmt: skip
    assert cli.main([*tradeoff, "--plot", str(plot), "--format", fmt]) == 0
    files = sorted(out.glob(f"*.{fmt}")) + [plot.with_suffix(f".{fmt}")]
    assert len(files) == 4 + 8 + 1
    for f in files:
        if fmt == "svg":
            assert ET.parse(f).getroot().tag.endswith("svg")
        else:
            assert f.read_bytes().startswith(b"%PDF")


@pytest.mark.slow  # two commands' figures with fallback fonts: 1-2 s on 2 cores
def test_cjk_and_emoji_names_draw_without_boxes_or_warnings(tmp_path):
    d = pk.scenes.data("fourbar")
    d["name"] = "脚 🦵 leg"
    d["points"]["足"] = d["points"].pop("P")
    d["links"]["coupler"] = ["A", "B", "足"]
    d["outputs"] = ["足"]
    p = tmp_path / "cjk.json"
    p.write_text(json.dumps(d, ensure_ascii=False), encoding="utf-8")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        argv = ["--out", str(tmp_path / "o"), "--dpi", "30", "-q"]
        assert cli.main(["analyze", str(p), "--step", "10", *argv]) == 0
        assert cli.main(["circuits", str(p), *argv]) == 0
    glyphs = [str(w.message) for w in caught if "Glyph" in str(w.message)]
    assert glyphs == []


def test_animation_of_a_limited_motion_rocks_between_dead_points():
    """Peaucellier's crank cannot turn fully: the animation follows its circuit through
    both dead points (no jump from 81 to 278 deg), reaching past the sweep's last solved
    angles on both sides."""
    sc = pk.scenes.load("peaucellier")
    sw = sc.sweep()
    theta, points, status, rocks = animate.motion(sc, sw)
    assert rocks and (status == pk.Status.CONVERGED).all()
    frames = animate.scene_frames(points, 72)
    t = np.unwrap(theta[frames])
    assert np.max(np.abs(np.diff(t))) < math.radians(15)
    solved = wrap_deg(sw.theta[sw.success])
    assert np.degrees(theta).max() >= solved.max() and np.degrees(theta).min() <= solved.min()
    xy = np.stack([points[n] for n in points], axis=1)[frames]
    size = np.ptp(xy.reshape(-1, 2), axis=0).max()
    assert np.hypot(*np.diff(xy, axis=0).transpose(2, 0, 1)).max() < 0.2 * size


def test_axis_labels_fit_their_axes():
    """Jansen's long unit name made the y labels of the stacked tracer axes longer than
    their axes and run into each other ("gosition"): each is wrapped to its axes."""
    sc = pk.scenes.load("jansen")
    assert len(sc.units or "") > 30
    fig = scene_fig.tracers(sc, sc.sweep(omega=1.0))
    assert fig is not None
    fig.draw_without_rendering()
    for ax in fig.axes:
        box = ax.get_window_extent()
        label = ax.yaxis.label
        if label.get_text():
            assert label.get_window_extent().height <= box.height
            assert "\n" in label.get_text()


def test_tracer_figure_draws_accelerations_when_the_sweep_has_them():
    """The core fills accelerations (issue 20, item 11); the figure draws |a| of each
    tracer from them, here arrays made up for the test and read back from the line."""
    import dataclasses

    sc = pk.scenes.load("fourbar")
    sw = sc.sweep(omega=1.0)
    acc = np.random.default_rng(0).normal(size=sw.coords.shape)
    sw = dataclasses.replace(sw, acceleration_array=acc)
    fig = scene_fig.tracers(sc, sw)
    assert fig is not None and len(fig.axes) == 3
    (line,) = fig.axes[2].get_lines()
    assert "acceleration of P" == line.get_label()
    j = sw.point_names.index("P")
    x, y = on_wrapped_axis(sw.theta, np.hypot(acc[:, j, 0], acc[:, j, 1]))
    np.testing.assert_array_equal(line.get_ydata(), y)
    assert fig.axes[2].get_ylabel().endswith("/s^2]")
