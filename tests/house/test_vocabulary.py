"""One result vocabulary: the four-bar's Sweep, the scene's SceneSweep and what the two
references return share their names and meanings (scipy's OptimizeResult is the model),
and the status codes are the kernel's. What each subject's results add is tested in its
folder (fourbar/test_results.py, scene/test_scene.py)."""

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


def test_theta_is_the_input_coordinate_of_every_result():
    fb = pk.FourBar(*SEED)
    t = np.radians([10.0, 20.0, 30.0])
    np.testing.assert_array_equal(fb.sweep(t).theta, t)
    sc = pk.scenes.load("fourbar")
    np.testing.assert_array_equal(sc.sweep(t).theta, t)
    np.testing.assert_array_equal(pk.reference.scene_sweep(sc.to_dict(), t).theta, t)
    assert math.isclose(sc.sweep().theta[0], sc.input_angle)


def test_status_vocabulary_matches_the_kernel():
    from planarkin import _core

    assert [(s.value, s.message) for s in pk.Status] == [(c, m) for c, _, m in _core.STATUSES]
    assert pk.SINGULAR_THRESHOLD == _core.SINGULAR_THRESHOLD
