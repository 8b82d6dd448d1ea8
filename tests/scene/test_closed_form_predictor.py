"""``Scene.sweep(predictor="closed-form")``: every angle on its own, each dyad on its drawn
side, checked against NumPy closed forms (the four-bar's, and circle intersections), against
the continuation where the drawn circuit reaches an angle."""

from __future__ import annotations

import math
import os

import numpy as np
import planarkin as pk
import pytest
from _support import dyad_point
from planarkin.reference import closed_form_vectorized

BUILTIN = os.path.join(os.path.dirname(pk.__file__), "scene", "builtin")
NAMES = sorted(f[: -len(".json")] for f in os.listdir(BUILTIN) if f.endswith(".json"))


def _watt(gamma_deg: float, cd: float, o6d: float) -> dict:
    """The built-in Watt II (the seed four-bar driving a second loop from the ternary's
    corner C to ground O6 = (13, 0)) with C moved to |O4 C| 2.5 at gamma from O4 -> B,
    |C D| = cd and |O6 D| = o6d, D drawn on the left of C -> O6 (crank angle 0)."""
    d = pk.scenes.data("watt2")
    p = {k: np.asarray(v, dtype=float) for k, v in d["points"].items()}
    g = math.atan2(p["B"][1] - p["O4"][1], p["B"][0] - p["O4"][0]) + math.radians(gamma_deg)
    c = p["O4"] + 2.5 * np.array([math.cos(g), math.sin(g)])
    dd = dyad_point(c, cd, p["O6"], o6d, side=+1)
    assert np.isfinite(dd).all(), "the drawing must assemble"
    d["points"].update({"C": c.tolist(), "D": dd.tolist()})
    for k in ("name", "description", "outputs"):  # the built-in's, not this linkage's
        del d[k]
    return d


def test_a_second_loop_that_closes_on_part_of_the_turn():
    """LIMIT where only the other assembly of the first loop lets the second close,
    NOT_ASSEMBLABLE where neither does; D where it closes, on its drawn side: all from
    NumPy's closed form of the first loop and circle intersections of the second."""
    gamma, cd, o6d = -180.0, 8.0, 2.0
    sc = pk.Scene(_watt(gamma, cd, o6d))
    theta = np.radians(np.arange(0.0, 360.0, 0.25))
    sw = sc.sweep(theta, outputs=["D"], predictor="closed-form")

    o4, o6 = np.array([6.0, 0.0]), np.array([13.0, 0.0])
    closes, dists, cs = {}, {}, {}
    for mode in ("open", "crossed"):
        _, t4 = closed_form_vectorized(6.0, 2.0, 5.0, 5.0, theta, mode)
        g = t4 + math.radians(gamma)
        c = o4 + 2.5 * np.stack([np.cos(g), np.sin(g)], axis=1)
        d = np.hypot(*(c - o6).T)
        closes[mode] = (d <= cd + o6d) & (d >= abs(cd - o6d))
        dists[mode], cs[mode] = d, c
    # away from the second loop's toggles (SINGULAR there, by the conditioning threshold)
    d = dists["open"]
    clear = (np.abs(d - (cd + o6d)) > 1e-6) & (np.abs(d - abs(cd - o6d)) > 1e-6)
    expect = np.where(
        closes["open"],
        int(pk.Status.CONVERGED),
        np.where(closes["crossed"], int(pk.Status.LIMIT), int(pk.Status.NOT_ASSEMBLABLE)),
    )
    limit, none = int(pk.Status.LIMIT), int(pk.Status.NOT_ASSEMBLABLE)
    assert set(np.unique(expect[clear])) == {0, limit, none}
    np.testing.assert_array_equal(sw.status[clear], expect[clear])
    assert np.isnan(sw.limit).all()
    assert (sw.nit == 0).all()

    d_exp = dyad_point(cs["open"], cd, np.broadcast_to(o6, cs["open"].shape), o6d, side=+1)
    ok = sw.status == 0
    np.testing.assert_allclose(sw.points["D"][ok], d_exp[ok], rtol=0, atol=1e-12 * 13)
    assert np.isnan(sw.points["D"][~ok]).all()


def _rigid(sc: pk.Scene, sw, size: float) -> None:
    """Every link keeps its drawn shape at every solved value: each pair of its points at
    its drawn distance (the scene's own data, no solver)."""
    ok = sw.status == 0
    for pts in sc.links.values():
        for i, a in enumerate(pts):
            for b in pts[i + 1 :]:
                drawn = math.dist(sc.points[a], sc.points[b])
                d = np.hypot(*(sw.points[b][ok] - sw.points[a][ok]).T)
                np.testing.assert_allclose(d, drawn, rtol=0, atol=1e-12 * size, err_msg=f"{a}-{b}")


@pytest.mark.parametrize("name", NAMES)
def test_the_same_motion_as_the_continuation_where_the_drawn_circuit_goes(name):
    """Where the continuation solves a value, the closed forms give the same pose,
    velocities and accelerations, and the same status where neither solves it. The closed
    forms also solve the values where the drawn sides close but the drawn circuit does
    not go (LIMIT to the continuation: the hydraulic boom's cylinder shortened past zero
    length, beyond a gap where it cannot assemble), with every link rigid there. Plans with
    a group are refused."""
    sc = pk.scenes.load(name)
    if sc.limits:  # the linkage itself (limits stop both predictors alike: tested apart)
        sc = pk.Scene.from_dict({k: v for k, v in sc.to_dict().items() if k != "limits"})
    size = float(np.ptp(np.array(list(sc.points.values())), axis=0).max())
    if sc.input_kind == "angle":
        theta, omega = sc.input_angle + np.radians(np.arange(0.0, 360.5, 0.5)), 1.3
    else:
        theta, omega = np.linspace(-0.6, 0.6, 241) * size, 0.7
    if any(s.kind == "group" for s in sc.plan("all").steps):
        with pytest.raises(ValueError, match="predictor must be 'continuation'"):
            sc.sweep(theta, outputs="all", predictor="closed-form")
        return
    cf = sc.sweep(theta, outputs="all", predictor="closed-form", omega=omega)
    co = sc.sweep(theta, outputs="all", omega=omega)
    ok = co.status == 0
    assert ok.sum() > 100
    differ = cf.status != co.status
    assert ((cf.status[differ] == 0) & (co.status[differ] == pk.Status.LIMIT)).all()
    if name == "hydraulic-boom":
        assert differ.sum() > 10
    for a, b, scale in [
        (cf.coords, co.coords, size),
        (cf.velocity_array, co.velocity_array, size * omega),
        (cf.acceleration_array, co.acceleration_array, size * omega**2),
    ]:
        np.testing.assert_allclose(a[ok], b[ok], rtol=0, atol=1e-11 * scale)
    np.testing.assert_allclose(cf.angle_array[ok], co.angle_array[ok], rtol=0, atol=1e-11)
    _rigid(sc, cf, size)


def test_the_four_bar_scene_is_the_four_bar_closed_form():
    """A triple rocker's scene (its crank cannot turn): the closed-form sweep is NumPy's
    closed form of the drawn mode, NOT_ASSEMBLABLE where it has none."""
    fb = pk.FourBar(2.0, 5.0, 2.5, 2.0)
    sc = fb.to_scene(theta2=0.3, mode="crossed")
    theta = np.radians(np.arange(-180.0, 180.0, 0.5))
    sw = sc.sweep(theta, outputs="all", predictor="closed-form")
    t3, t4 = closed_form_vectorized(2.0, 5.0, 2.5, 2.0, theta, "crossed")
    solved = np.isfinite(t3)
    assert 0 < solved.sum() < theta.size
    gap = ~solved
    assert (sw.status[gap] == pk.Status.NOT_ASSEMBLABLE).all()
    ok = sw.status == 0
    assert ok.sum() >= solved.sum() - 4  # the toggles themselves may be SINGULAR
    assert not (ok & gap).any()
    np.testing.assert_allclose(sw.angles["rocker"][ok], t4[ok], atol=1e-12)


@pytest.mark.parametrize("bad", ["newton", "", "Closed-Form"])
def test_a_predictor_it_does_not_know_is_named(bad):
    sc = pk.scenes.load("jansen")
    with pytest.raises(ValueError, match="predictor must be 'continuation' or 'closed-form'"):
        sc.sweep(predictor=bad)
    with pytest.raises(ValueError, match="predictor must be a string"):
        sc.sweep(predictor=1)  # type: ignore[arg-type]
