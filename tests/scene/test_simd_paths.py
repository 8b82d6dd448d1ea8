"""A scene sweep with the SIMD kernels on (polynomial sin/cos for the input and the groups,
polynomial atan2 for the link angles, dyads 4 angles at a time) against the scalar path
(libm throughout, the NumPy reference's numbers): the same statuses on every built-in,
and positions and link angles that agree to rounding."""

import numpy as np
import planarkin as pk
import pytest

pytestmark = pytest.mark.skipif(
    not pk.simd_available(), reason="the SIMD kernels need AVX2 and FMA"
)


def _sweep(sc, simd):
    with pk.use_simd(simd):
        return sc.sweep(outputs="all", omega=1.0)


@pytest.mark.parametrize("name", pk.scenes.names())
def test_simd_and_scalar_paths_agree(name):
    sc = pk.scenes.load(name)
    on, off = _sweep(sc, True), _sweep(sc, False)
    np.testing.assert_array_equal(on.status, off.status)
    np.testing.assert_array_equal(on.step_status, off.step_status)
    np.testing.assert_allclose(on.coords, off.coords, rtol=0, atol=1e-12 * sc._size())
    # the link angles: both wrapped to (-pi, pi]; a link at +-pi may read either end
    gap = np.angle(np.exp(1j * (on.angle_array - off.angle_array)))
    np.testing.assert_array_equal(np.isnan(on.angle_array), np.isnan(off.angle_array))
    assert np.nanmax(np.abs(gap), initial=0.0) < 1e-12
