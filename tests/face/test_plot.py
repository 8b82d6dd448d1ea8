"""The four-bar figures (planarkin.face.figures.fourbar): from result objects, headless,
without pyplot; the helpers (unwrapping, unreachable spans, order of convergence) against
independent truths."""

from __future__ import annotations

import io
import math
import subprocess
import sys

import numpy as np
import planarkin as pk
import pytest
from matplotlib.animation import FuncAnimation
from matplotlib.figure import Figure
from planarkin.face import animate
from planarkin.face.degrees import unwrap_deg
from planarkin.face.figures import fourbar as plot
from planarkin.fourbar.analysis import convergence_order, unreachable_spans

SEED = (6.0, 2.0, 5.0, 5.0)
TRIPLE_ROCKER = (5.0, 3.0, 4.0, 2.5)  # non-Grashof: the crank stops at +-105.96 deg
THETA2 = np.radians(np.arange(0.0, 360.1, 5.0))


def _sweep(links, **kw):
    return pk.FourBar(*links).sweep(THETA2, **kw)


def _legend(fig: Figure) -> set[str]:
    return {t.get_text() for ax in fig.axes if ax.get_legend() for t in ax.get_legend().get_texts()}


@pytest.mark.slow  # a fresh process importing matplotlib and drawing: about 1 s on 2 cores
def test_drawing_and_saving_never_import_pyplot():
    # pyplot would pick (and on a desktop, start) a GUI backend and keep every figure alive
    code = (
        "import io, sys, planarkin as pk, planarkin.face.figures.fourbar as p; "
        "p.position(pk.FourBar(6, 2, 5, 5).sweep()).savefig(io.BytesIO(), format='png'); "
        "print('matplotlib.pyplot' in sys.modules)"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    assert r.stdout.split() == ["False"]


def test_every_figure_function_returns_a_figure():
    fb = pk.FourBar(*SEED)
    sw = fb.sweep(THETA2, omega2=10.0, alpha2=1.0)
    sol = fb.solve(math.radians(45), guess=(math.radians(80), math.radians(100)), history=True)
    figs = [
        plot.position(sw),
        plot.positions_combined(sw),
        plot.velocity(sw),
        plot.acceleration(sw),
        plot.transmission(sw),
        plot.coupler_curve(sw, 3.0, 0.5),
        plot.linkage(sw, 3.0, 0.5),
        plot.convergence(sol, guess=(1.4, 1.7), tol=1e-9),
    ]
    for fig in figs:
        assert isinstance(fig, Figure) and fig.axes
    assert len(figs[0].axes) == 2  # theta3 and theta4 in separate panels
    assert len(figs[1].axes) == 1  # both on one axes
    assert "not assemblable" not in _legend(figs[0])  # nothing to shade


def test_position_plots_unwrapped_degrees():
    # a double crank: theta3 and theta4 turn fully, so wrapped angles would jump by 360
    sw = _sweep((2.0, 6.0, 5.0, 5.0))
    fig = plot.position(sw)
    for ax, t in zip(fig.axes, (sw.theta3, sw.theta4), strict=True):
        x, y = ax.get_lines()[0].get_data()
        np.testing.assert_allclose(x, np.degrees(THETA2))
        assert np.max(np.abs(np.diff(y))) < 30  # continuous
        assert abs(y[-1] - y[0]) == pytest.approx(360)  # one full turn
        np.testing.assert_allclose(np.radians(y) % math.tau, np.asarray(t) % math.tau, atol=1e-12)


@pytest.mark.slow  # six figures laid out: about 1 s on 2 cores
def test_non_grashof_spans_are_shaded_and_dead_points_marked():
    sw = _sweep(TRIPLE_ROCKER, omega2=1.0, alpha2=0.0)
    lim = pk.FourBar(*TRIPLE_ROCKER).limits()
    for fig in (
        plot.position(sw, limits=lim),
        plot.positions_combined(sw, limits=lim),
        plot.velocity(sw, limits=lim),
        plot.acceleration(sw, limits=lim),
        plot.transmission(sw, limits=lim),
    ):
        assert {"not assemblable", "dead point"} <= _legend(fig)
    # the curves have a gap, not a line drawn across the span
    y = plot.position(sw).axes[0].get_lines()[0].get_ydata()
    assert np.isnan(y).sum() == np.count_nonzero(sw.status == pk.Status.NOT_ASSEMBLABLE) > 0
    assert "unreachable" in plot.coupler_curve(sw, 3.0, 0.5).axes[0].get_title()
    plot.linkage(sw, 3.0, 0.5)  # draws only assembled poses


def test_singular_points_are_marked():
    sw = _sweep((6.0, 2.0, 6.0, 2.0))  # parallelogram: dead points at 0 and 180 deg
    assert np.count_nonzero(sw.status == pk.Status.SINGULAR) == 3
    assert "dead point" in _legend(plot.position(sw))


def test_unreachable_spans_against_the_toggle_angle():
    r1, r2, r3, r4 = TRIPLE_ROCKER
    stop = math.acos((r1**2 + r2**2 - (r3 + r4) ** 2) / (2 * r1 * r2))  # |O4 A| = r3 + r4
    sw = _sweep(TRIPLE_ROCKER)
    # exact edges with the limits, within half a step without
    (span,) = unreachable_spans(sw, pk.FourBar(*TRIPLE_ROCKER).limits())
    assert span == pytest.approx((stop, math.tau - stop), abs=1e-12)
    (span,) = unreachable_spans(sw)
    assert span == pytest.approx((stop, math.tau - stop), abs=math.radians(2.5))
    assert unreachable_spans(_sweep(SEED)) == []


def test_unreachable_spans_at_the_ends_of_the_sweep():
    sw = _sweep((4.0, 3.0, 2.0, 3.5))  # reachable only in two bands away from theta2 = 0
    spans = unreachable_spans(sw)
    assert len(spans) == 3
    assert spans[0][0] == 0.0 and spans[-1][1] == pytest.approx(math.tau)


def test_unwrap_deg_keeps_nan_and_removes_jumps():
    t = np.linspace(0, 4 * math.pi, 50)
    wrapped = np.angle(np.exp(1j * t))
    np.testing.assert_allclose(unwrap_deg(wrapped), np.degrees(t), atol=1e-9)
    wrapped[[3, 20]] = np.nan
    u = unwrap_deg(wrapped)
    assert np.isnan(u[[3, 20]]).all()
    np.testing.assert_allclose(np.delete(u, [3, 20]), np.delete(np.degrees(t), [3, 20]), atol=1e-9)


@pytest.mark.parametrize(
    ("history", "order"),
    [
        ([10.0 ** -(2**k) for k in range(5)], 2.0),
        ([10.0 ** -(3**k) for k in range(4)], 3.0),
        ([0.5**k for k in range(8)], 1.0),
        ([1e-1, 1e-2, 1e-4, 1e-8, 1e-16, 1e-16, 0.0], 2.0),  # stagnation at the end ignored
    ],
)
def test_convergence_order(history, order):
    assert convergence_order(history) == pytest.approx(order)


def test_convergence_order_without_a_usable_triple():
    assert math.isnan(convergence_order([]))
    assert math.isnan(convergence_order([1.0, 0.1]))
    assert math.isnan(convergence_order([1.0, 2.0, 3.0]))


def test_convergence_figure_shows_the_order():
    fb = pk.FourBar(*SEED)
    sol = fb.solve(math.radians(45), guess=(math.radians(80), math.radians(100)), history=True)
    fig = plot.convergence(sol)
    (line,) = fig.axes[0].get_lines()
    np.testing.assert_array_equal(line.get_ydata(), sol.history)
    assert fig.axes[0].get_yscale() == "log"
    (label,) = _legend(fig)
    assert f"p ≈ {convergence_order(sol.history):.2f}" in label


def test_missing_data_is_a_value_error():
    fb = pk.FourBar(*SEED)
    with pytest.raises(ValueError, match="omega2"):
        plot.velocity(fb.sweep(THETA2))
    with pytest.raises(ValueError, match="alpha2"):
        plot.acceleration(fb.sweep(THETA2, omega2=1.0))
    with pytest.raises(ValueError, match="history"):
        plot.convergence(fb.solve(0.3))
    with pytest.raises(ValueError, match="frames"):
        animate.fourbar(fb.sweep(THETA2), 1.0, 0.0, frames=0)


def test_animation_frames_do_not_repeat_the_closing_pose():
    sw = pk.FourBar(*SEED).sweep()  # 0..360 deg: the last pose is the first
    idx = animate.fourbar_frames(sw, 72)
    assert len(idx) == 72 and idx[0] == 0 and 360 not in idx
    np.testing.assert_array_equal(np.diff(idx), 5)
    assert len(animate.fourbar_frames(sw, 1000)) == 360


def test_animation_html_is_self_contained():
    sw = _sweep(TRIPLE_ROCKER)
    anim = animate.fourbar(sw, 3.0, 0.5, frames=3, dpi=30)
    assert isinstance(anim, FuncAnimation)
    page = animate.html_page(anim, fps=5, title="a <b> title")
    assert "http" not in page and "<link" not in page
    assert page.count("data:image/png;base64,") == 3
    assert "<title>a &lt;b&gt; title</title>" in page


@pytest.mark.slow  # six figures laid out and saved: 1-2 s on 2 cores
def test_a_linkage_that_never_assembles_still_draws():
    fb = pk.FourBar(10.0, 1.0, 1.0, 1.0)
    sw = fb.sweep(THETA2, omega2=1.0, alpha2=0.0)
    assert not sw.success.any()
    for fig in (
        plot.position(sw),
        plot.velocity(sw),
        plot.transmission(sw),
        plot.coupler_curve(sw, 1.0, 0.0),
        plot.linkage(sw, 1.0, 0.0),
        plot.convergence(fb.solve(0.5, history=True)),
    ):
        fig.savefig(io.BytesIO(), format="png", dpi=20)
    assert "not assemblable" in _legend(plot.position(sw))
