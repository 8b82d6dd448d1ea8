"""The page's input effort curve (the module's forces kernel, in the browser) against
Python's ``Scene.statics()`` on the same default sweep, and no curve without loads."""

from __future__ import annotations

import numpy as np
import planarkin as pk
import pytest


@pytest.mark.parametrize(
    "name", ["engine", "fourbar-loaded", "hydraulic-boom-loaded", "jansen-loaded"]
)
def test_the_effort_curve_equals_pythons_statics(page, name):
    state = page.open(f"?scene={name}")
    assert not page.message(), page.message()
    sc = pk.scenes.load(name)
    r = sc.statics()
    got = state["effort"]
    assert got is not None
    np.testing.assert_allclose(got["theta"], r.theta, rtol=0, atol=1e-12)
    effort = np.array([np.nan if v is None else v for v in got["input"]])
    assert np.array_equal(np.isnan(effort), np.isnan(r.input))
    ok = ~np.isnan(r.input)
    scale = np.abs(r.input[ok]).max()
    np.testing.assert_allclose(effort[ok], r.input[ok], rtol=0, atol=1e-9 * scale)
    assert got["unit"] == r.effort_unit
    assert page.el("forces-panel").is_displayed()
    # the arrows: every pin reaction at every input, as Python's
    f = page.d.execute_script("return window.pk.call({op: 'forces'})")
    names = list(sc.points)
    links = list(sc.links)
    for p in f["pins"][:3]:
        key = (names[p["point"]], links[p["link"]])
        assert key in r.reactions
    assert not [e for e in page.logs() if e["level"] == "SEVERE"]


def test_no_curve_without_loads(page):
    state = page.open("?scene=jansen")
    assert state["effort"] is None
    assert not page.el("forces-panel").is_displayed()
