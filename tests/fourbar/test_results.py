"""The four-bar's results in the shared vocabulary (house/test_vocabulary.py): det, points
and angles of the kernel's and the reference's sweeps against independent formulas; the
lazy members cost nothing until read; a batch has the names that make sense for many
linkages."""

from __future__ import annotations

import numpy as np
import planarkin as pk
import pytest

SEED = (6.0, 2.0, 5.0, 5.0)
TRIPLE_ROCKER = (5.0, 3.0, 4.0, 2.5)


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


def test_batch_sweep_has_the_names_that_make_sense_for_many_linkages():
    links = np.array([SEED, TRIPLE_ROCKER])
    b = pk.sweep_batch(links)
    assert b.theta is b.theta2 and b.theta.shape == (361,)
    assert b.success.shape == (2, 361)
    counts = b.statuses()
    assert sum(counts.values()) == 2 * 361 and counts["CONVERGED"] == int(b.success.sum())
    text = repr(b)
    assert "\n" not in text and "2 linkages" in text and "361 crank angles" in text
