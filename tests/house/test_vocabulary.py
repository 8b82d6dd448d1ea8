"""One result vocabulary: the four-bar's Sweep and BatchSweep, the scene's SceneSweep and
Trace and what the two references return share their names and meanings (scipy's
OptimizeResult is the model), for both input kinds (an angle, a linear input's
displacement), and the status codes and names are the core's. docs/site/vocabulary.rst
states it; what each subject's results add is tested in its folder."""

from __future__ import annotations

import importlib
import math

import numpy as np
import planarkin as pk
import pytest
from planarkin._results import InputResult

SEED = (6.0, 2.0, 5.0, 5.0)
TRIPLE_ROCKER = (5.0, 3.0, 4.0, 2.5)
SHARED = ("theta", "status", "success", "nit", "det", "points", "angles")


def results():
    fb = pk.FourBar(*TRIPLE_ROCKER)  # two statuses, so unsolved points too
    sc = pk.scenes.load("stephenson3")
    boom = pk.scenes.load("hydraulic-boom")  # a linear input, in mm
    s = boom.sweep(outputs="all").theta
    return {
        "FourBar.sweep": fb.sweep(),
        "reference.sweep": pk.reference.sweep(fb),
        "Scene.sweep": sc.sweep(outputs="all"),
        "reference.scene_sweep": pk.reference.scene_sweep(sc.to_dict()),
        "Scene.sweep (linear)": boom.sweep(outputs="all"),
        "reference.scene_sweep (linear)": pk.reference.scene_sweep(boom.to_dict(), s[::10]),
    }


@pytest.mark.parametrize("name", list(results()))
def test_every_sweep_result_speaks_the_shared_names(name):
    r = results()[name]
    n = len(r.theta)
    assert len(r) == n > 0
    assert r.status.dtype == np.int8 and r.status.shape == (n,)
    np.testing.assert_array_equal(r.success, r.status == pk.Status.CONVERGED)
    assert r.nit.shape == (n,) and r.det.shape == (n,)
    assert all(v.shape == (n, 2) for v in r.points.values()) and r.points
    assert all(v.shape == (n,) for v in r.angles.values()) and r.angles
    # det: finite and signed where solved, NaN where not
    assert np.isfinite(r.det[r.success]).all() and np.isnan(r.det[~r.success]).all()
    counts = r.statuses()
    assert sum(counts.values()) == n
    codes, k = np.unique(r.status, return_counts=True)
    assert counts == {pk.Status(int(c)).name: int(m) for c, m in zip(codes, k, strict=True)}
    s = r.summary()
    assert (s.points, s.converged, s.statuses) == (n, int(r.success.sum()), counts)
    assert s.nit_total == int(r.nit.sum())
    text = repr(r)
    assert "\n" not in text and len(text) < 250 and f"{n} " in text


def test_the_scene_reference_returns_the_scene_sweep_type():
    ref = pk.reference.scene_sweep(pk.scenes.data("jansen"))
    assert type(ref) is pk.SceneSweep is type(pk.scenes.load("jansen").sweep())
    assert ref.plan is None and ref.limit is None and ref.step_det is None
    assert pk.reference.SceneReference is pk.SceneSweep
    assert isinstance(pk.reference.sweep(pk.FourBar(*SEED)), pk.Sweep)


def test_summaries_keep_the_fourbar_text_and_drop_the_residual_for_scenes():
    s = pk.FourBar(*SEED).sweep().summary()
    assert isinstance(s, pk.SweepSummary) and s.residual_max is not None
    assert str(s).startswith("361/361 converged (CONVERGED=361); iterations total 360, mean ")
    assert "max residual" in str(s)
    t = pk.scenes.load("jansen").sweep().summary()
    assert t.residual_max is None and "residual" not in str(t)
    assert str(t).startswith("361/361 converged (CONVERGED=361); iterations total 0")


def test_theta_is_the_input_coordinate_of_every_result():
    fb = pk.FourBar(*SEED)
    t = np.radians([10.0, 20.0, 30.0])
    np.testing.assert_array_equal(fb.sweep(t).theta, t)
    sc = pk.scenes.load("fourbar")
    np.testing.assert_array_equal(sc.sweep(t).theta, t)
    np.testing.assert_array_equal(pk.reference.scene_sweep(sc.to_dict(), t).theta, t)
    assert math.isclose(sc.sweep().theta[0], sc.input_angle)


def test_status_vocabulary_matches_the_kernel():
    """Codes, names and messages: Python's enum is the core's table (Status::name, the
    spelling the page's JSON uses too)."""
    from planarkin import _core

    assert [(s.value, s.name, s.message) for s in pk.Status] == list(_core.STATUSES)
    assert pk.SINGULAR_THRESHOLD == _core.SINGULAR_THRESHOLD
    # the message names no input kind: a slider's input is no crank angle
    assert "input value" in pk.Status.NOT_ASSEMBLABLE.message


@pytest.mark.parametrize(
    ("lengths", "condition"),
    [(SEED, "grashof"), (TRIPLE_ROCKER, "non-grashof"), ((2.0, 1.0, 2.0, 1.0), "change-point")],
)
def test_grashof_condition_names_are_the_cores(lengths, condition):
    g = pk.FourBar(*lengths).grashof()
    assert g.condition == condition and g.is_grashof == (condition == "grashof")


def test_every_result_names_its_input_kind_and_unit():
    """input_kind and units on every result over the input, and one repr sentence: the
    count, the coordinate's symbol and its span in its unit."""
    boom, jansen = pk.scenes.load("hydraulic-boom"), pk.scenes.load("jansen")
    assert (boom.input_kind, boom.units, jansen.input_kind) == ("displacement", "mm", "angle")
    sw = boom.sweep()
    assert (sw.input_kind, sw.units) == ("displacement", "mm")
    text = repr(sw)
    lo, hi = sw.theta[0], sw.theta[-1]
    assert f"361 input values, s from {lo:.6g} to {hi:.6g} mm;" in text
    assert "rad" not in text and "angle" not in text
    tr = boom.trace()
    assert isinstance(tr, InputResult) and (tr.input_kind, tr.units) == ("displacement", "mm")
    assert f"{len(tr)} input values, s from " in repr(tr) and repr(tr).endswith(" mm>")
    ref = pk.reference.scene_sweep(boom.to_dict(), sw.theta[:3])
    assert (ref.input_kind, ref.units) == ("displacement", "mm") and " mm;" in repr(ref)
    unnamed = pk.Scene.from_dict({**boom.to_dict(), "units": None}).sweep(sw.theta[:3])
    assert unnamed.units is None and "3 input values, s from " in repr(unnamed)
    assert repr(unnamed).split(";")[0].endswith(" length units")
    for r in (jansen.sweep(), jansen.trace(), pk.reference.scene_sweep(jansen.to_dict())):
        assert r.input_kind == "angle" and ", theta from " in repr(r) and " rad" in repr(r)
    fb = pk.FourBar(*SEED)
    for r in (fb.sweep(), pk.sweep_batch(np.array([SEED]))):
        assert r.input_kind == "angle"
        assert "361 crank angles, theta2 from 0 to 6.28319 rad;" in repr(r)


def test_the_input_kind_and_rate_have_one_name_and_keep_their_old_ones():
    sc = pk.scenes.load("slider-crank")
    t = np.radians([10.0, 20.0, 30.0])
    new, old = sc.sweep(t, outputs="all", rate=2.0), sc.sweep(t, outputs="all", omega=2.0)
    assert new.rate == new.omega == old.rate == old.omega == 2.0
    np.testing.assert_array_equal(new.velocity_array, old.velocity_array)
    assert new.input == new.input_kind == sc.input_kind == "angle"
    with pytest.raises(TypeError, match="rate or its former name omega"):
        sc.sweep(t, rate=1.0, omega=1.0)
    with pytest.raises(ValueError, match="rate"):
        sc.sweep(t, rate=math.nan)
    boom = pk.scenes.load("hydraulic-boom")
    lin = boom.sweep(boom.sweep().theta[:4], rate=5.0)  # mm/s
    assert lin.input == lin.input_kind == "displacement" and lin.rate == 5.0
    assert lin.velocities is not None


def test_det_is_one_name():
    fb = pk.FourBar(*SEED)
    sw = fb.sweep()
    # what DESIGN defines: sin(theta4 - theta3), the determinant over r3 r4 (sign flipped)
    np.testing.assert_allclose(sw.det, np.sin(sw.theta4 - sw.theta3), rtol=0, atol=1e-15)
    np.testing.assert_array_equal(fb.det(sw.theta3, sw.theta4), sw.det)
    np.testing.assert_array_equal(fb.branch_indicator(sw.theta3, sw.theta4), sw.det)  # kept
    assert pk.FourBar.det(0.1, 0.5) == pytest.approx(math.sin(0.4), abs=1e-16)


def test_a_batch_speaks_the_shared_names_row_by_row():
    """BatchSweep: theta (N,) shared by every linkage (the documented exception), every
    other shared name with a first axis of M, each row what FourBar.sweep gives."""
    links = np.array([SEED, TRIPLE_ROCKER])
    b = pk.sweep_batch(links)
    m, n = links.shape[0], len(b.theta)
    assert len(b) == m and b.theta.shape == (n,)
    assert b.status.shape == b.success.shape == b.nit.shape == b.det.shape == (m, n)
    assert all(v.shape == (m, n, 2) for v in b.points.values())
    assert all(v.shape == (m, n) for v in b.angles.values())
    for i, r in enumerate(links):
        one = pk.FourBar(*r).sweep()
        np.testing.assert_array_equal(b.det[i], one.det)
        assert list(b.points) == list(one.points)
        for k, v in one.points.items():
            np.testing.assert_array_equal(b.points[k][i], v)
        for k, v in one.angles.items():
            np.testing.assert_array_equal(b.angles[k][i], v)
    s = b.summary()
    assert isinstance(s, pk.SweepSummary) and (s.points, s.converged) == (m * n, b.success.sum())
    assert s.statuses == b.statuses() and s.nit_total == int(b.nit.sum())


def test_synthesis_names_scipys_code_as_such():
    from planarkin.synthesis.driver import StartResult

    x = np.zeros(2)
    r = StartResult(
        x0=x, x=x, fun=0.0, max_error=0.0, rms_error=0.0, min_abs_det=1.0, feasible=True,
        optimizer_status=9, message="Iteration limit reached", nit=1,
    )  # fmt: skip
    assert r.optimizer_status == r.status == 9 and not isinstance(r.status, pk.Status)


def test_one_angle_wrap():
    from planarkin import _angles

    # the truth: w = a - 2 pi k for the integer k that puts w in (-pi, pi], in mpmath
    mp = pytest.importorskip("mpmath")
    a = np.array([-7.0, -3.0, 0.5, math.pi, 4.0, 1e3, -25.0])
    with mp.workdps(40):
        want = [float(x - 2 * mp.pi * mp.ceil((x - mp.pi) / (2 * mp.pi))) for x in map(mp.mpf, a)]
    np.testing.assert_allclose(_angles.wrap_array(a), want, rtol=0, atol=4e-13)
    assert [_angles.wrap(float(x)) for x in a] == pytest.approx(want, abs=4e-13)
    assert np.isnan(_angles.wrap_array(np.nan)) and math.isnan(_angles.wrap(math.nan))
    assert _angles.wrap(-math.pi) == math.pi and _angles.wrap(0.5) == 0.5
    for name in ("generated", "problem", "verify"):
        mod = importlib.import_module(f"planarkin.synthesis.{name}")
        assert mod.wrap_array is _angles.wrap_array


@pytest.mark.parametrize(
    ("name", "kind", "unit", "at", "shown"),
    [
        ("fourbar", "angle", "deg", math.radians(30.0), 30.0),
        ("hydraulic-boom", "displacement", "mm", 12.5, 12.5),
    ],
)
def test_the_circuits_report_names_its_input_alike_for_both_kinds(name, kind, unit, at, shown):
    # the same three keys for an angle and a linear input (the former ones kept beside them)
    from planarkin.scene import report

    sc = pk.scenes.load(name)
    axis = report.input_axis(sc.input_kind, sc.units)
    d = report.circuits_summary(sc, axis, at, [], [], None, "", 0.0)
    assert (d["input_kind"], d["input_unit"]) == (kind, unit)
    assert d["input"] == pytest.approx(shown, abs=1e-12)
    former = "theta_deg" if kind == "angle" else "theta"
    assert d[former] == d["input"]
