"""Options are checked once, by the core's validating constructors, on the API's path;
the NumPy reference, which may not call the kernel, mirrors those rules. Both must refuse
the same inputs with the same message, word for word."""

from __future__ import annotations

import math

import numpy as np
import planarkin as pk
import pytest
from planarkin import reference as ref

SEED = (6.0, 2.0, 5.0, 5.0)

BAD = {
    "tol": [0, -1e-9, math.nan, math.inf, -math.inf, 1e-320 * -1, "x", None],
    "max_iter": [0, -1, 2**32, 2**63, 2**70, 1.5, True, "3"],
    "mode": ["bogus", "", "OPEN", None, 0, b"open"],
    "predictor": ["linear", "", None, 3],
    "method": ["closed_form", "Newton", None],
    "omega2": [math.nan, math.inf, "fast"],
    "guess": [(1.0,), "ab", (1.0, "x"), 3],
}


def _message(call) -> str:
    with pytest.raises(ValueError) as e:
        call()
    return str(e.value)


@pytest.mark.parametrize(
    ("name", "bad"), [(n, b) for n, values in BAD.items() for b in values], ids=repr
)
def test_api_and_reference_refuse_alike(name, bad):
    fb = pk.FourBar(*SEED)
    kw = {name: bad}
    api, reference = _message(lambda: fb.sweep(**kw)), _message(lambda: ref.sweep(fb, **kw))
    assert api == reference
    assert api.startswith(name)
    if name not in ("omega2", "guess", "predictor", "method"):
        assert _message(lambda: fb.solve(0.3, **kw)) == _message(lambda: ref.solve(fb, 0.3, **kw))


@pytest.mark.parametrize("bad", [0.0, -1.0, math.nan, math.inf], ids=repr)
def test_lengths_refused_alike(bad):
    class Lengths:
        r1, r2, r3, r4 = SEED[0], bad, SEED[2], SEED[3]

    assert _message(lambda: pk.FourBar(*SEED[:1], bad, *SEED[2:])) == _message(
        lambda: ref.sweep(Lengths())
    )


def test_the_kernel_words_the_values_as_python_does():
    """The core writes a real as repr() does (1e-09, nan) and quotes a string as repr()."""
    fb = pk.FourBar(*SEED)
    assert _message(lambda: fb.sweep(tol=-1e-9)) == "tol must be finite and > 0, got -1e-09"
    assert _message(lambda: fb.sweep(mode="x")) == "mode must be 'open' or 'crossed', got 'x'"
    assert _message(lambda: fb.velocity(0.1, 1.0, 2.0, np.nan)) == "omega2 must be finite, got nan"
    sc = pk.scenes.load("fourbar")
    assert _message(lambda: sc.assemblies(runs=17)) == "runs must be an integer in 1..=16, got 17"
    assert _message(lambda: sc.trace(max_points=1)) == "max_points must be an integer >= 2, got 1"
    assert _message(lambda: pk.sweep_batch(np.array([SEED]), threads=0)) == (
        "threads must be >= 1 or None, got 0"
    )
