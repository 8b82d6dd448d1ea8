"""The core's forces kernel against the NumPy reference (the same algorithm, written
plainly): every output of statics and dynamics on every loaded built-in and on every
built-in under loads of every kind, to 1e-12 of its scale, with the same statuses."""

from __future__ import annotations

import numpy as np
import planarkin as pk
import pytest
from forces_cases import random_loads

TOL = 1e-12


def _agree(a, b, scale: float, what: str) -> None:
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape, what
    assert np.array_equal(np.isnan(a), np.isnan(b)), what
    ok = ~np.isnan(b)
    err = float(np.max(np.abs(a[ok] - b[ok]), initial=0.0))
    assert err <= TOL * scale, (what, err, scale)


def _same(rust, ref, size: float) -> None:
    assert np.array_equal(rust.status, ref.status)
    fin = ~np.isnan(ref.input)
    force = max(
        [float(np.nanmax(np.abs(v), initial=0.0)) for v in ref.reactions.values()]
        + [float(np.nanmax(np.abs(v), initial=0.0)) for v in ref.normal.values()]
        + [float(np.nanmax(np.abs(ref.shaking_force), initial=0.0)), 1e-300]
    )
    effort = float(np.max(np.abs(ref.input[fin]), initial=0.0))
    effort_scale = effort + force * (size if ref.input_kind == "angle" else 1.0)
    _agree(rust.input, ref.input, effort_scale, "input")
    _agree(rust.input_virtual_work, ref.input_virtual_work, effort_scale, "virtual work")
    for k, v in ref.reactions.items():
        _agree(rust.reactions[k], v, force, f"reaction {k}")
    for k, v in ref.normal.items():
        _agree(rust.normal[k], v, force, f"normal {k}")
    for k, v in ref.moment.items():
        _agree(rust.moment[k], v, force * size, f"moment {k}")
    _agree(rust.shaking_force, ref.shaking_force, force, "shaking force")
    _agree(rust.shaking_moment, ref.shaking_moment, force * size, "shaking moment")
    for name in ("kinetic_energy", "potential_energy", "input_power"):
        b = getattr(ref, name)
        _agree(getattr(rust, name), b, float(np.nanmax(np.abs(b), initial=0.0)) + 1e-300, name)
    if ref.mechanical_advantage is None:
        assert rust.mechanical_advantage is None
    else:
        b = ref.mechanical_advantage
        a = rust.mechanical_advantage
        assert np.array_equal(np.isnan(a), np.isnan(b))
        ok = np.isfinite(b)
        assert np.all(np.abs(a[ok] - b[ok]) <= TOL * np.abs(b[ok]))
    assert set(rust.checks) == set(ref.checks)
    for k, v in ref.checks.items():
        assert rust.checks[k] < 1e-10 and v < 1e-10, (k, rust.checks, ref.checks)


def _size(sc: pk.Scene) -> float:
    return float(np.ptp(np.array(list(sc.points.values())), axis=0).max())


LOADED = [n for n in pk.scenes.names() if pk.scenes.load(n).loads is not None]


@pytest.mark.parametrize("name", LOADED)
def test_kernel_matches_the_reference_on_the_loaded_builtins(name):
    sc = pk.scenes.load(name)
    sw = sc.sweep(outputs="all", rate=2.5)
    _same(sc.statics(sw), sc.statics(sw, engine="numpy"), _size(sc))
    omega = 2.5 + np.linspace(0.0, 1.0, len(sw.theta))
    _same(
        sc.dynamics(sw, omega=omega, alpha=0.3),
        sc.dynamics(sw, omega=omega, alpha=0.3, engine="numpy"),
        _size(sc),
    )


@pytest.mark.parametrize("name", pk.scenes.names())
def test_kernel_matches_the_reference_under_every_kind_of_load(name):
    rng = np.random.default_rng(7 + sum(map(ord, name)))
    sc = pk.scenes.load(name)
    loaded = pk.Scene.from_dict({**sc.to_dict(), "loads": random_loads(sc, rng)})
    sw = loaded.sweep(outputs="all", rate=1.3)
    _same(loaded.statics(sw), loaded.statics(sw, engine="numpy"), _size(sc))
    _same(loaded.dynamics(sw, alpha=-0.6), loaded.dynamics(sw, alpha=-0.6, engine="numpy"),
          _size(sc))  # fmt: skip


def test_tables_over_the_input_match_the_reference():
    # a periodic table over a crank's turn and a held table over a cylinder's stroke
    sc = pk.scenes.load("fourbar-loaded")
    loads = sc.loads
    xs = [0.5, 2.0, 4.0, 6.0]
    loads["forces"].append({"point": "B", "force": [[1, 2], [3, -1], [0, 0], [-2, 5]], "input": xs})
    loads["torques"].append(
        {"link": sc.to_dict()["input"]["link"], "torque": [1.0, -3.0, 2.0, 0.5], "input": xs}
    )
    sw = sc.sweep(outputs="all", rate=1.0)
    _same(sc.statics(sw, loads=loads), sc.statics(sw, loads=loads, engine="numpy"), _size(sc))
    boom = pk.scenes.load("hydraulic-boom-loaded")
    bl = boom.loads
    lo, hi = boom.sweep().theta[[0, -1]]
    cyl = next(iter(boom.slots or boom.prismatic))
    key = "slot" if boom.slots else "prismatic"
    bl["forces"].append(
        {key: cyl, "force": [5.0, -2.0, 7.0], "input": [lo, 0.5 * (lo + hi), hi - 1]}
    )
    sw = boom.sweep(outputs="all", rate=1.0)
    _same(boom.statics(sw, loads=bl), boom.statics(sw, loads=bl, engine="numpy"), _size(boom))


def test_engine_is_checked():
    sc = pk.scenes.load("fourbar-loaded")
    with pytest.raises(ValueError, match="engine"):
        sc.statics(engine="fortran")
