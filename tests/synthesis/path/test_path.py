"""The whole path synthesis (retrieval from the default atlas, placement, refinement,
verification) on targets made from known linkages by their closed forms: it recovers a
curve through them within 1e-6 of the target's size, labels every design, ranks them, and
each returned design traces the target when its scene is swept on its own."""

from __future__ import annotations

import math

import numpy as np
import planarkin as pk
import pytest
from _path_linkages import fourbar_curve, slider_curve
from planarkin.synthesis.path import CurveTarget

pytest.importorskip("scipy")

#: a Grashof crank-rocker that is not in the atlas (ground not horizontal, not unit)
CRANK_ROCKER = ((1.0, 2.0), (5.0, 1.5), 1.1, 3.7, 3.2, 1.5, 1.2)


def _closed_fourbar(n: int = 24, start: float = 0.3) -> np.ndarray:
    th = start + np.linspace(0, 2 * np.pi, n, endpoint=False)
    return fourbar_curve(*CRANK_ROCKER, th)[2]


def _traced(d, target: CurveTarget) -> np.ndarray:
    """Each target point's distance to the design's tracer at the input the design gives
    it, the scene swept on its own (over the target's size)."""
    sw = d.scene.sweep(np.asarray(d.inputs), outputs=[d.tracer])
    assert np.all(sw.status == 0)
    return np.hypot(*(sw.points[d.tracer] - target.points).T) / target.size


@pytest.mark.slow
def test_a_closed_four_bar_curve_is_recovered_defect_free():
    target = CurveTarget(_closed_fourbar(), "closed")
    res = pk.synthesis.path(target, designs=3)
    best = res.designs[0]
    assert best.verified and not best.defects.any
    assert best.error.max <= 1e-6
    assert _traced(best, target).max() <= 1e-6
    assert best.full_turn
    # the input reaches the points in order: strictly monotone, less than a turn
    steps = np.diff(np.unwrap(best.inputs))
    assert np.all(steps > 0) or np.all(steps < 0)
    assert abs(np.unwrap(best.inputs)[-1] - best.inputs[0]) < 2 * np.pi
    # ranked: verified first, then by the largest error (to 3 digits, at least 1e-12:
    # cognates trace one curve, and their errors differ in rounding only)
    keys = [(not d.verified, float(f"{max(d.error.max, 1e-12):.3g}")) for d in res.designs]
    assert keys == sorted(keys)
    assert res.stopped == "done" and res.timings["total"] > 0


@pytest.mark.slow
def test_every_returned_design_traces_what_its_label_says():
    target = CurveTarget(_closed_fourbar(18, 1.0), "closed")
    res = pk.synthesis.path(target, designs=4)
    for d in res.designs:
        dist = _traced(d, target)
        # the label's error is the distance to the traced arc (at most the distance at the
        # assigned input), its largest equal to the distances' up to the refinement of the
        # closest points
        assert d.error.max <= dist.max() + 1e-9
        assert math.isclose(
            d.error.rms, float(np.sqrt(np.mean(dist**2))), rel_tol=0.05, abs_tol=1e-9
        )
        assert 0 <= d.min_transmission <= 90


@pytest.mark.slow
def test_a_slider_crank_curve_is_recovered():
    th = 0.2 + np.linspace(0, 2 * np.pi, 20, endpoint=False)
    pts = slider_curve((3.0, -1.0), 0.4, 0.6, 1.0, 3.5, 0.8, 0.9, th)[2]
    target = CurveTarget(pts, "closed")
    res = pk.synthesis.path(target, topology="slider-crank", designs=2)
    best = res.designs[0]
    assert best.topology == "slider-crank" and best.verified
    assert best.error.max <= 1e-6 and _traced(best, target).max() <= 1e-6
    assert "slider" in best.scene.to_dict().get("slots", {})


@pytest.mark.slow
def test_an_open_arc_with_its_timing_is_followed_at_those_inputs():
    th = np.linspace(0.4, 2.4, 9)
    pts = fourbar_curve(*CRANK_ROCKER, th)[2]
    # timing: the crank turns by the given amounts between points (any common offset)
    target = CurveTarget(pts, "open", inputs=th - th[0])
    res = pk.synthesis.path(target, designs=2)
    best = res.designs[0]
    assert best.verified
    assert best.error.max <= 1e-4
    np.testing.assert_allclose(np.diff(best.inputs), np.diff(th), atol=1e-6)


@pytest.mark.slow
def test_a_partial_target_on_part_of_a_closed_curve():
    th = np.linspace(0.3, 2.8, 12)
    target = CurveTarget(fourbar_curve(*CRANK_ROCKER, th)[2], "partial")
    res = pk.synthesis.path(target, designs=2)
    best = res.designs[0]
    assert best.verified and best.full_turn
    assert best.error.max <= 1e-6
    assert _traced(best, target).max() <= 1e-6


@pytest.mark.slow
def test_an_open_arc_is_recovered():
    th = np.linspace(1.0, 2.2, 8)
    target = CurveTarget(fourbar_curve(*CRANK_ROCKER, th)[2], "open")
    best = pk.synthesis.path(target, designs=2).designs[0]
    assert best.verified and not best.defects.any
    assert best.error.max <= 1e-6 and _traced(best, target).max() <= 1e-6


def test_bad_options_name_themselves():
    target = CurveTarget(_closed_fourbar(), "closed")
    with pytest.raises(ValueError, match="topology"):
        pk.synthesis.path(target, topology="five-bar")
    with pytest.raises(ValueError, match="designs"):
        pk.synthesis.path(target, designs=0)
    with pytest.raises(ValueError, match="time_limit"):
        pk.synthesis.path(target, time_limit=-1)
    with pytest.raises(ValueError, match="min_transmission"):
        pk.synthesis.path(target, min_transmission=95)


@pytest.mark.slow
def test_a_time_limit_stops_the_refinement():
    target = CurveTarget(_closed_fourbar(), "closed")
    res = pk.synthesis.path(target, designs=5, refine_count=40, time_limit=0.5)
    assert res.stopped == "time limit"
    assert len(res.designs) <= 5


@pytest.mark.slow
def test_a_dask_cluster_refines_the_same_designs():
    pytest.importorskip("distributed")
    target = CurveTarget(_closed_fourbar(16), "closed")
    here = pk.synthesis.path(target, designs=2, refine_count=4)
    there = pk.synthesis.path(target, designs=2, refine_count=4, scheduler="local")
    assert [d.source["atlas_entry"] for d in here.designs] == [
        d.source["atlas_entry"] for d in there.designs
    ]
    for a, b in zip(here.designs, there.designs, strict=True):
        assert a.error.max == pytest.approx(b.error.max, abs=1e-12)


@pytest.mark.slow
def test_the_command_writes_scene_files_that_trace_the_target(tmp_path, capsys):
    import json

    from planarkin.face.cli import main

    pts = _closed_fourbar(20)
    csv = tmp_path / "target.csv"
    csv.write_text("x,y\n" + "".join(f"{x:.17g},{y:.17g}\n" for x, y in pts))
    out = tmp_path / "out"
    code = main(
        ["synthesize", "path", str(csv), "--kind", "closed", "--designs", "2", "--out", str(out),
         "--box", "-20", "20", "-20", "20", "--no-figures", "-q"]
    )  # fmt: skip
    assert code == 0
    report = json.loads((out / "report.json").read_text())
    first = report["designs"][0]
    assert first["verified"] and first["error"]["max"] <= 1e-6
    assert not any(first["defects"].values())
    # the file is a scene on its own: swept at the report's inputs it passes the points
    sc = pk.Scene.load(out / first["file"])
    sw = sc.sweep(np.asarray(first["inputs"]), outputs=[first["tracer"]])
    size = float(np.hypot(*np.ptp(pts, axis=0)))
    assert np.hypot(*(sw.points[first["tracer"]] - pts).T).max() <= 1e-6 * size
    # and the fixed pivots lie in the box asked for
    d = sc.to_dict()
    for name in d["links"]["ground"]:
        assert all(-20 <= c <= 20 for c in d["points"][name])
    assert main(["analyze", str(out / first["file"]), "--out", str(tmp_path / "fig")]) == 0
