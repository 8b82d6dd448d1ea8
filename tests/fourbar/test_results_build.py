"""FourBar.sweep builds its result without the frozen dataclass's __init__ (one
object.__setattr__ per field costs a sixth of a small sweep): the result must read, field
by field, as the dataclass's own __init__ would have made it."""

import dataclasses

import numpy as np
import planarkin as pk
import pytest
from planarkin.fourbar._results import Sweep


@pytest.mark.parametrize(
    "kw", [{}, {"omega2": 2.0}, {"omega2": 2.0, "alpha2": -1.0}, {"method": "closed-form"}]
)
def test_the_fast_sweep_has_every_field(kw):
    fb = pk.FourBar(6.0, 2.0, 5.0, 5.0)
    sw = fb.sweep(**kw)
    again = dataclasses.replace(sw)  # through the dataclass's __init__
    for f in dataclasses.fields(Sweep):
        assert getattr(sw, f.name) is getattr(again, f.name), f.name
    np.testing.assert_array_equal(sw.det, again.det)
    np.testing.assert_array_equal(sw.points["B"], again.points["B"])
    with pytest.raises(dataclasses.FrozenInstanceError):
        sw.status = None  # type: ignore[misc]
    with pytest.raises(TypeError, match="unexpected"):
        Sweep.build(*(getattr(sw, n) for n in ("lengths", "mode", "theta2", "theta3", "theta4",
                                                "status", "nit", "residual")), bogus=1)  # fmt: skip
