"""One result vocabulary: the four-bar's Sweep, the scene's SceneSweep and what the two
references return share their names and meanings (scipy's OptimizeResult is the model);
the four-bar's det, points and angles against independent formulas; the lazy members
cost nothing until read."""

from __future__ import annotations

import math

import numpy as np
import planarkin as pk
import pytest

SEED = (6.0, 2.0, 5.0, 5.0)
TRIPLE_ROCKER = (5.0, 3.0, 4.0, 2.5)
SHARED = ("theta", "status", "success", "nit", "det", "points", "angles")


def results():
    fb = pk.FourBar(*TRIPLE_ROCKER)  # two statuses, so unsolved points too
    sc = pk.scenes.load("stephenson3")
    return {
        "FourBar.sweep": fb.sweep(),
        "reference.sweep": pk.reference.sweep(fb),
        "Scene.sweep": sc.sweep(outputs="all"),
        "reference.scene_sweep": pk.reference.scene_sweep(sc.to_dict()),
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


@pytest.mark.parametrize("mode", ["open", "crossed"])
@pytest.mark.parametrize("links", [SEED, TRIPLE_ROCKER, (4.0, 3.0, 1.5, 2.0)], ids=str)
def test_fourbar_det_points_and_angles_against_formulas(links, mode):
    fb = pk.FourBar(*links)
    r1, r2, r3, r4 = links
    for s in (fb.sweep(mode=mode), pk.reference.sweep(fb, mode=mode)):
        assert s.theta is s.theta2
        t2, t3, t4 = s.theta2, s.theta3, s.theta4
        np.testing.assert_allclose(s.det, np.sin(t4 - t3), rtol=0, atol=1e-15)
        p = s.points
        np.testing.assert_array_equal(p["O2"], np.zeros((len(s), 2)))
        np.testing.assert_array_equal(p["O4"], np.tile([r1, 0.0], (len(s), 1)))
        a = np.column_stack((r2 * np.cos(t2), r2 * np.sin(t2)))
        np.testing.assert_allclose(p["A"], a, rtol=0, atol=1e-14)  # finite where unsolved too
        b = np.column_stack((r1 + r4 * np.cos(t4), r4 * np.sin(t4)))  # through the rocker
        np.testing.assert_allclose(p["B"], b, rtol=0, atol=1e-12)
        assert np.isnan(p["B"][~s.success]).all()
        assert s.angles == {"crank": t2, "coupler": t3, "rocker": t4}
    # the kernel's lazy members against the reference's NumPy ones
    api, ref = fb.sweep(mode=mode), pk.reference.sweep(fb, mode=mode)
    np.testing.assert_allclose(api.det, ref.det, rtol=0, atol=1e-12)
    for n in api.points:
        np.testing.assert_allclose(api.points[n], ref.points[n], rtol=0, atol=1e-12)


def test_lazy_members_are_computed_once_on_first_access():
    s = pk.FourBar(*SEED).sweep()
    assert not {"det", "points", "angles"} & set(vars(s))  # a sweep computes none of them
    assert s.det is s.det and s.points is s.points and s.angles is s.angles
    assert {"det", "points", "angles"} <= set(vars(s))
    hand_made = pk.Sweep(s.lengths, s.mode, s.theta2, s.theta3, s.theta4, s.status, s.nit,
                         s.residual)  # fmt: skip
    with pytest.raises(ValueError, match="no det"):
        _ = hand_made.det
    assert hand_made.angles["rocker"] is s.theta4  # plain renaming needs no geometry


def test_the_scene_reference_det_is_signed_and_vanishes_at_dead_points():
    """The reference's det is the Hadamard ratio of its own Jacobian: not the kernel's
    number, but the same branch (a fixed sign relation) and the same zeros."""
    fb = pk.FourBar(*TRIPLE_ROCKER)
    sc = fb.to_scene(mode="crossed")
    theta = sc.input_angle + np.linspace(-1.5, 1.5, 301)
    api = sc.sweep(theta)
    ref = pk.reference.scene_sweep(sc.to_dict(), theta)
    both = api.success & ref.success
    assert both.sum() > 250
    assert len(set(np.sign(api.det[both] * ref.det[both]))) == 1
    assert np.all(np.abs(ref.det[both]) <= 1.0)
    # towards a toggle both go to zero together
    toggle = max(fb.limits("crossed").toggles)
    near = sc.input_angle + toggle - 10.0 ** -np.arange(1.0, 9.0)
    a, r = sc.sweep(near).det, pk.reference.scene_sweep(sc.to_dict(), near).det
    assert np.isfinite(a).all() and np.isfinite(r).all()
    assert np.all(np.diff(np.abs(a)) < 0) and np.all(np.diff(np.abs(r)) < 0)
    assert abs(a[-1]) < 1e-3 and abs(r[-1]) < 1e-3


def test_batch_sweep_has_the_names_that_make_sense_for_many_linkages():
    links = np.array([SEED, TRIPLE_ROCKER])
    b = pk.sweep_batch(links)
    assert b.theta is b.theta2 and b.theta.shape == (361,)
    assert b.success.shape == (2, 361)
    counts = b.statuses()
    assert sum(counts.values()) == 2 * 361 and counts["CONVERGED"] == int(b.success.sum())
    text = repr(b)
    assert "\n" not in text and "2 linkages" in text and "361 crank angles" in text


def test_theta_is_the_input_coordinate_of_every_result():
    fb = pk.FourBar(*SEED)
    t = np.radians([10.0, 20.0, 30.0])
    np.testing.assert_array_equal(fb.sweep(t).theta, t)
    sc = pk.scenes.load("fourbar")
    np.testing.assert_array_equal(sc.sweep(t).theta, t)
    np.testing.assert_array_equal(pk.reference.scene_sweep(sc.to_dict(), t).theta, t)
    assert math.isclose(sc.sweep().theta[0], sc.input_angle)
