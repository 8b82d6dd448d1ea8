"""What the figures show: every line against the sweep it was drawn from, computed here
independently in NumPy (labels included, so swapping two legends fails), and no text of
any figure outside the canvas at any resolution."""

from __future__ import annotations

import math

import numpy as np
import planarkin as pk
import pytest
from _support import texts_outside
from planarkin.face import animate, cli
from planarkin.face.cli import analyze_fourbar
from planarkin.face.figures import fourbar as plot
from planarkin.fourbar import analysis
from truth import angdiff, mp_solve, mp_toggles

SEED = (6.0, 2.0, 5.0, 5.0)
THETA2 = np.radians(np.arange(0.0, 360.1, 2.0))


def deg_unwrapped(a):
    """Radians to degrees, unwrapped over the finite entries (NaN stays NaN)."""
    a = np.asarray(a, dtype=float)
    out = np.full(a.shape, np.nan)
    ok = np.isfinite(a)
    out[ok] = np.degrees(np.unwrap(a[ok]))
    return out


def lines_by_label(ax) -> dict:
    """Legend label -> the Line2D it stands for."""
    handles, labels = ax.get_legend_handles_labels()
    return {lab: h for h, lab in zip(handles, labels, strict=True)}


def same(a, b, tol=1e-9):
    np.testing.assert_allclose(np.asarray(a, float), np.asarray(b, float), atol=tol, rtol=0)


@pytest.fixture(scope="module")
def seed_sweep():
    return pk.FourBar(*SEED).sweep(THETA2, omega2=10.0, alpha2=2.0)


def test_position_lines_are_theta3_and_theta4(seed_sweep):
    s = seed_sweep
    fig = plot.position(s)
    top, bottom = fig.axes
    (l3,) = [v for k, v in lines_by_label(top).items() if "θ3" in k]
    (l4,) = [v for k, v in lines_by_label(bottom).items() if "θ4" in k]
    for line, t in ((l3, s.theta3), (l4, s.theta4)):
        same(line.get_xdata(), np.degrees(THETA2))
        same(line.get_ydata(), deg_unwrapped(t))
    assert "θ3" in top.get_ylabel() and "θ4" in bottom.get_ylabel()
    assert "θ2" in bottom.get_xlabel()


def test_combined_positions_legend_matches_each_line(seed_sweep):
    s = seed_sweep
    lines = lines_by_label(plot.positions_combined(s).axes[0])
    same(lines["coupler θ3"].get_ydata(), deg_unwrapped(s.theta3))
    same(lines["rocker θ4"].get_ydata(), deg_unwrapped(s.theta4))


def test_rate_lines_are_the_sweep_rates(seed_sweep):
    s = seed_sweep
    v = lines_by_label(plot.velocity(s).axes[0])
    same(v["coupler ω3"].get_ydata(), s.omega3)
    same(v["rocker ω4"].get_ydata(), s.omega4)
    a = lines_by_label(plot.acceleration(s).axes[0])
    same(a["coupler α3"].get_ydata(), s.alpha3)
    same(a["rocker α4"].get_ydata(), s.alpha4)
    # the velocity is the derivative of the plotted angle (central differences, rad/s)
    h = THETA2[1] - THETA2[0]
    dt4 = np.gradient(np.unwrap(s.theta4), h) * s.omega2
    same(s.omega4[1:-1], dt4[1:-1], tol=2e-3 * np.abs(s.omega4).max())


def test_transmission_lines(seed_sweep):
    s = seed_sweep
    top, bottom = plot.transmission(s).axes
    mu = lines_by_label(top)["transmission angle μ"].get_ydata()
    gap = np.abs(np.angle(np.exp(1j * (s.theta4 - s.theta3))))  # |t4 - t3| in [0, pi]
    same(mu, np.degrees(np.minimum(gap, math.pi - gap)))
    same(lines_by_label(bottom)["sin(θ4 − θ3)"].get_ydata(), np.sin(s.theta4 - s.theta3))


def test_coupler_curve_and_linkage_drawing(seed_sweep):
    s = seed_sweep
    p, delta = 3.0, 0.5
    r1, r2, _, r4 = SEED
    ax_ = r2 * np.cos(THETA2)
    ay_ = r2 * np.sin(THETA2)
    px = ax_ + p * np.cos(s.theta3 + delta)
    py = ay_ + p * np.sin(s.theta3 + delta)
    fig = plot.coupler_curve(s, p, delta)
    curve = fig.axes[0].get_lines()[0]
    same(curve.get_xdata(), px)
    same(curve.get_ydata(), py)
    # the linkage drawing: each pose is O2 - A - B - O4, with B = O4 + r4 (cos t4, sin t4)
    fig = plot.linkage(s, p, delta)
    ax = fig.axes[0]
    same(lines_by_label(ax)["coupler curve"].get_xdata(), px)
    poses = [ln for ln in ax.get_lines() if ln.get_label().startswith("θ2 = ")]
    assert len(poses) == 6
    for ln in poses:
        t2 = math.radians(float(ln.get_label()[5:-1]))
        i = int(np.argmin(np.abs(THETA2 - t2)))
        bx, by = r1 + r4 * np.cos(s.theta4[i]), r4 * np.sin(s.theta4[i])
        same(ln.get_xdata(), [0.0, ax_[i], bx, r1])
        same(ln.get_ydata(), [0.0, ay_[i], by, 0.0])


def test_convergence_line_is_the_history():
    fb = pk.FourBar(*SEED)
    sol = fb.solve(math.radians(45), guess=(math.radians(80), math.radians(100)), history=True)
    ax = plot.convergence(sol, tol=1e-9).axes[0]
    line = ax.get_lines()[0]
    same(line.get_xdata(), np.arange(sol.nit + 1))
    h = np.asarray(sol.history)
    same(line.get_ydata()[h > 0], h[h > 0], tol=0)


# --- no text outside the canvas -------------------------------------------------------------


def cli_figures(links, mode="open", newton_at=45.0):
    args = cli.build_parser().parse_args(
        ["analyze", "--links", *map(str, links), "--mode", mode, "--newton-at", str(newton_at)]
    )
    fb, theta2 = analyze_fourbar.setup(args)
    sweep = fb.sweep(theta2, mode=mode, omega2=args.rpm * math.tau / 60, alpha2=0.0)
    res = analyze_fourbar.analyze(fb, sweep, args)
    return res, analyze_fourbar.figures(res, args)


# drawing a case's eight figures takes about 2 s (the layout, at any dpi): every case is
# left out of the inner loop (-m "not slow"); the figures' layout engine is checked there
CASES = [
    (SEED, "open", 45.0),
    (SEED, "crossed", 45.0),
    ((4.0, 3.0, 1.5, 2.0), "open", 45.0),  # the crank cannot turn fully
    ((6.0, 2.0, 6.0, 2.0), "open", 0.0),  # change points; demo at one
    ((123.456, 2.5, 119.75, 7.125), "crossed", 200.0),  # long numbers in every title
]


@pytest.mark.slow
@pytest.mark.parametrize("links, mode, newton_at", CASES, ids=str)
@pytest.mark.parametrize("dpi", [100, 300])
def test_no_text_leaves_the_canvas(links, mode, newton_at, dpi):
    """No text of any figure of 'analyze' leaves the canvas at 100 or 300 dpi (matplotlib's
    own text extents after a draw), for long numbers in every title, a crank that cannot
    turn fully, and change points with the Newton demo at a dead point."""
    _, figures = cli_figures(links, mode, newton_at)
    for name, draw in figures.items():
        assert texts_outside(draw(), dpi) == [], name


def test_convergence_title_fits_when_the_demo_ends_on_the_other_mode():
    fb = pk.FourBar(*SEED)
    guess = (math.radians(80), math.radians(100))
    sol = fb.solve(math.radians(45), mode="crossed", guess=guess, history=True)
    assert sol.status == pk.Status.BRANCH_JUMP  # the longest convergence title
    fig = plot.convergence(sol, guess=guess, tol=1e-9)
    for dpi in (100, 300):
        assert texts_outside(fig, dpi) == []


def test_figures_use_constrained_layout():
    _, figures = cli_figures(SEED)
    for name, draw in figures.items():
        assert draw().get_layout_engine().__class__.__name__ == "ConstrainedLayoutEngine", name


# --- animating a crank that cannot turn fully ----------------------------------------------


def test_a_crank_that_cannot_turn_fully_rocks_between_its_toggles():
    """(4, 3, 1.5, 2): the crank stops at +-57.9 deg. The animation rocks between the
    toggles, on the open mode one way and, having passed the toggle, on the crossed mode
    back, every frame a whole linkage moving continuously (never the crank alone in its
    unreachable span). Checked against the mpmath toggle angles and mpmath positions."""
    r = (4.0, 3.0, 1.5, 2.0)
    fb = pk.FourBar(*r)
    sweep = fb.sweep()
    path = analysis.rocking(fb, fb.limits(), sweep)
    assert [s.mode for s in path] == ["open", "crossed"]
    (tog,) = (float(t) for t in mp_toggles(r))
    t2 = np.concatenate([s.theta2 for s in path])
    t4 = np.concatenate([s.theta4 for s in path])
    assert np.all(np.abs(t2) < tog) and np.abs(t2).max() > tog - 1e-5  # up to the toggles
    assert t2[0] < 0 < t2[len(path[0])]  # one way, then back
    assert (np.concatenate([s.status for s in path]) == pk.Status.CONVERGED).all()
    for k in range(0, len(t2), 37):
        mode = path[0].mode if k < len(path[0]) else path[1].mode
        assert angdiff(t4[k], mp_solve(r, t2[k], mode).theta4) < 1e-9
    # B moves continuously, through both toggles and round the loop
    bx, by = r[0] + r[3] * np.cos(t4), r[3] * np.sin(t4)
    steps = np.hypot(np.diff(np.append(bx, bx[0])), np.diff(np.append(by, by[0])))
    assert steps.max() < 0.1 * r[3]
    # every frame drawn shows the whole linkage
    anim = animate.fourbar(path, 1.0, 0.3, frames=72)
    frames = animate.fourbar_frames(path, 72)
    assert len(frames) == 72
    ax = anim._fig.axes[0]
    for i in frames:
        anim._func(int(i))
        drawn = [ln for ln in ax.get_lines() if ln.get_color() == "tab:blue"]
        assert all(len(ln.get_xdata()) == 3 for ln in drawn), i
    anim._draw_was_started = True  # drawn by hand: no "deleted without rendering" warning


def test_a_crank_that_turns_fully_plays_its_sweep():
    fb = pk.FourBar(*SEED)
    sweep = fb.sweep()
    assert analysis.rocking(fb, fb.limits(), sweep) == [sweep]
