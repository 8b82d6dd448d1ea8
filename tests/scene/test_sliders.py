"""Slots, prismatic pairs and linear inputs (DESIGN.md, "Prismatic joints"): the built-in
slider scenes against closed forms written here, their invariance under the drawing's
power-of-two scaling, rotation and translation, the NumPy reference, assemblies, statuses
and validation."""

import math

import numpy as np
import planarkin as pk
import pytest
from planarkin.reference import scene_sweep

#: The built-in scenes with slots or prismatic pairs.
SLIDERS = [n for n in pk.scenes.names() if {"slots", "prismatic"} & set(pk.scenes.data(n))]


def pt(sc, name):
    return np.asarray(sc.points[name], dtype=float)


def rel(a, b, size):
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b)))) / size


# --- closed forms ---------------------------------------------------------------------


@pytest.mark.parametrize("name", ["slider-crank", "slider-crank-offset"])
def test_slider_crank_piston_position(name):
    sc = pk.scenes.load(name)
    r = np.hypot(*pt(sc, "A"))
    rod = np.hypot(*(pt(sc, "B") - pt(sc, "A")))
    e = pt(sc, "B")[1]
    sw = sc.sweep(outputs="all", omega=1.0)
    assert sw.success.all() and sw.input == "angle"
    t = sw.theta
    x = r * np.cos(t) + np.sqrt(rod**2 - (r * np.sin(t) - e) ** 2)
    assert rel(sw.points["B"][:, 0], x, rod) < 1e-12
    assert rel(sw.points["B"][:, 1], e, rod) < 1e-12
    # the output: the piston's displacement along the slot from the drawn pose
    assert rel(sw.output, x - x[0], rod) < 1e-12
    # its velocity, d x / d t
    v = -r * np.sin(t) - (r * np.sin(t) - e) * r * np.cos(t) / np.sqrt(
        rod**2 - (r * np.sin(t) - e) ** 2
    )
    assert rel(sw.velocities["B"][:, 0], v, rod) < 1e-12


def test_scotch_yoke_is_r_cos_t():
    sc = pk.scenes.load("scotch-yoke")
    r = np.hypot(*pt(sc, "A"))
    sw = sc.sweep(outputs="all", omega=2.0)
    t = sw.theta
    assert sw.success.all()
    assert rel(sw.output, r * np.cos(t) - r * np.cos(t[0]), r) < 1e-12
    assert (
        rel(sw.points["R"][:, 0] - sw.points["R"][0, 0], r * (np.cos(t) - np.cos(t[0])), r) < 1e-12
    )
    assert rel(sw.points["R"][:, 1], pt(sc, "R")[1], r) < 1e-12  # it only translates
    assert rel(sw.velocities["R"][:, 0], -2.0 * r * np.sin(t), r) < 1e-12
    assert rel(sw.accelerations["R"][:, 0], -4.0 * r * np.cos(t), r) < 1e-12


def test_inverted_slider_crank_cylinder_angle():
    sc = pk.scenes.load("inverted-slider-crank")
    r, d = np.hypot(*pt(sc, "A")), pt(sc, "O4")[0]
    sw = sc.sweep(outputs="all")
    t = sw.theta
    phi = np.arctan2(r * np.sin(t), r * np.cos(t) - d)
    assert sw.success.all()
    assert float(np.max(np.abs(np.angle(np.exp(1j * (sw.angles["cylinder"] - phi)))))) < 1e-12
    np.testing.assert_allclose(sw.output, sw.angles["cylinder"], atol=1e-15)


def test_whitworth_ram_and_time_ratio():
    sc = pk.scenes.load("whitworth")
    r, c = np.hypot(*pt(sc, "A")), pt(sc, "O4")[1]
    big_r = np.hypot(*(pt(sc, "C") - pt(sc, "O4")))
    rod = np.hypot(*(pt(sc, "D") - pt(sc, "C")))
    sw = sc.sweep(outputs="all", omega=1.0)
    t = sw.theta
    phi = np.arctan2(r * np.sin(t) - c, r * np.cos(t)) + np.pi  # the arm is opposite the slot
    cx, cy = big_r * np.cos(phi), c + big_r * np.sin(phi)
    ram = cx - np.sqrt(rod**2 - (cy - c) ** 2)
    assert sw.success.all()
    assert rel(sw.points["D"][:, 0], ram, rod) < 1e-12
    # the ram stops where the lever lies along the ram's line: r sin t = c
    t1, t2 = math.asin(c / r), math.pi - math.asin(c / r)
    ends = sc.sweep([t1, t2], outputs="all", omega=1.0)
    assert np.abs(ends.velocities["D"][:, 0]).max() < 1e-12 * rod
    # and the strokes take pi + 2 asin(c / r) and pi - 2 asin(c / r) of the crank's turn
    slow, quick = 2 * math.pi - (t2 - t1), t2 - t1
    assert slow / quick == pytest.approx(
        (math.pi + 2 * math.asin(c / r)) / (math.pi - 2 * math.asin(c / r)), rel=1e-15
    )
    assert slow / quick == pytest.approx(2.0, rel=1e-12)  # as the description says
    assert abs(ends.points["D"][0, 0] - ends.points["D"][1, 0]) == pytest.approx(
        2 * big_r, rel=1e-12
    )


def test_hydraulic_boom_angle_by_the_law_of_cosines():
    sc = pk.scenes.load("hydraulic-boom")
    o, c1, e = pt(sc, "O"), pt(sc, "C1"), pt(sc, "E")
    g, b, rho0 = np.hypot(*(c1 - o)), np.hypot(*(e - o)), np.hypot(*(e - c1))
    lo, hi = sc.stroke()
    # the stroke ends where O, C1 and E fall in line (rho = b - g and b + g), or at the
    # cylinder's limits where those come first
    lim = sc.limits["cylinder"]
    assert lo == pytest.approx(max(b - g - rho0, lim[0]), abs=1e-9 * b)
    assert hi == pytest.approx(min(b + g - rho0, lim[1]), abs=1e-9 * b)
    sw = sc.sweep(outputs="all")
    assert sw.input == "displacement" and sw.success[1:-1].all()
    s = sw.theta[1:-1]
    rho = rho0 + s
    alpha = np.arccos((g * g + b * b - rho**2) / (2 * g * b))  # at O, between O->C1 and O->E
    base = math.atan2(*(c1 - o)[::-1])
    boom = base + alpha
    got = sw.points["E"][1:-1] - o
    want = b * np.stack([np.cos(boom), np.sin(boom)], -1)
    assert rel(got, want, b) < 1e-12
    # away from the stroke's ends, where arccos loses digits, the angle itself
    inner = (s > lo + 0.05 * (hi - lo)) & (s < hi - 0.05 * (hi - lo))
    err = np.angle(np.exp(1j * (sw.angles["boom"][1:-1][inner] - boom[inner])))
    assert np.abs(err).max() < 1e-12


def test_elliptic_trammel_draws_its_ellipse():
    sc = pk.scenes.load("elliptic-trammel")
    big_l = np.hypot(*(pt(sc, "B") - pt(sc, "A")))
    p = np.hypot(*(pt(sc, "P") - pt(sc, "A")))
    a0 = pt(sc, "A")[0]
    lo, hi = sc.stroke()
    assert (lo + a0, hi + a0) == pytest.approx((-big_l, big_l), abs=1e-9 * big_l)
    sw = sc.sweep(outputs="all")
    a = a0 + sw.theta
    inner = sw.success
    assert inner[1:-1].all()
    np.testing.assert_allclose(sw.points["A"][inner, 0], a[inner], rtol=0, atol=1e-12 * big_l)
    b = np.sqrt(big_l**2 - a**2)
    want = np.stack([a * (1 - p / big_l), b * p / big_l], -1)
    assert rel(sw.points["P"][1:-1], want[1:-1], big_l) < 1e-12
    # the stroke's ends are the dead points themselves, where P moves as the square root
    # of the distance to them (unbounded rates): SINGULAR, as an angle input's dead point
    assert (sw.status[[0, -1]] == pk.Status.SINGULAR).all()
    assert np.isnan(sw.points["P"][[0, -1]]).all()


# --- the drawing: scale, rotation, translation -------------------------------------------


def moved(sc, f=1.0, angle=0.0, shift=(0.0, 0.0)):
    d = sc.to_dict()
    c, s = math.cos(angle), math.sin(angle)
    d["points"] = {
        n: [f * (c * x - s * y) + shift[0], f * (s * x + c * y) + shift[1]]
        for n, (x, y) in d["points"].items()
    }
    # a displacement's limits scale with the drawing (an angle's do not)
    for n, v in d.get("limits", {}).items():
        if isinstance(v, list):
            d["limits"][n] = [f * v[0], f * v[1]]
    return pk.Scene.from_dict(d)


@pytest.mark.parametrize("name", SLIDERS)
def test_power_of_two_scaling_is_bit_stable(name):
    assert len(SLIDERS) == 9  # 7, and issue 34's engine and loaded boom
    sc = pk.scenes.load(name)
    ref = sc.sweep(outputs="all")
    for e in (-600, -3, 7, 600):
        f = 2.0**e
        big = moved(sc, f)
        theta = ref.theta * (f if sc.input_kind == "displacement" else 1.0)
        sw = big.sweep(theta, outputs="all")
        np.testing.assert_array_equal(sw.status, ref.status)
        for n, xy in ref.points.items():
            np.testing.assert_array_equal(sw.points[n] / f, xy)


@pytest.mark.parametrize("name", SLIDERS)
def test_rotation_and_translation_move_the_motion_with_the_drawing(name):
    sc = pk.scenes.load(name)
    ref = sc.sweep(outputs="all")
    if sc.input_kind == "displacement":  # not the stroke's ends: exact dead points as drawn,
        ref = sc.sweep(ref.theta[1:-1], outputs="all")  # a rounding either way once turned
    size = max(np.ptp(np.array(list(sc.points.values())), axis=0))
    angle, shift = 0.7, (3.0 * size, -1.5 * size)
    other = moved(sc, 1.0, angle, shift)
    # an angle input turns with the drawing; a displacement does not change
    theta = ref.theta + (angle if sc.input_kind == "angle" else 0.0)
    sw = other.sweep(theta, outputs="all")
    np.testing.assert_array_equal(sw.status, ref.status)
    c, s = math.cos(angle), math.sin(angle)
    for n, xy in ref.points.items():
        want = np.stack(
            [c * xy[:, 0] - s * xy[:, 1] + shift[0], s * xy[:, 0] + c * xy[:, 1] + shift[1]], -1
        )
        assert rel(sw.points[n], want, size) < 1e-12, n


@pytest.mark.parametrize("name", SLIDERS)
def test_kernel_matches_the_numpy_reference(name):
    sc = pk.scenes.load(name)
    sw = sc.sweep(outputs="all")
    # (a linear input's default values run from dead point to dead point; the reference
    # marches there with a linear predictor in substeps of 1 degree of size, which fails
    # within a few tenths of a percent of the stroke from its ends)
    theta = sw.theta[2:-2] if sc.input_kind == "displacement" else sw.theta
    sw = sc.sweep(theta, outputs="all")
    ref = scene_sweep(sc.to_dict(), theta)
    np.testing.assert_array_equal(ref.status, sw.status)
    size = max(np.ptp(np.array(list(sc.points.values())), axis=0))
    for n in sw.points:
        assert rel(sw.points[n], ref.points[n], size) < 1e-10, n


# --- assemblies, statuses, round trips ------------------------------------------------------


def test_slider_crank_has_two_assemblies_mirrored_in_the_slot():
    sc = pk.scenes.load("slider-crank")
    t = 1.0
    both = sc.assemblies(t)
    assert len(both) == 2 and sorted(a.label for a in both) == ["+", "-"]
    r = np.hypot(*pt(sc, "A"))
    rod = np.hypot(*(pt(sc, "B") - pt(sc, "A")))
    xs = sorted(a["B"][0] for a in both)
    h = math.sqrt(rod**2 - (r * math.sin(t)) ** 2)
    assert xs == pytest.approx([r * math.cos(t) - h, r * math.cos(t) + h], rel=1e-14)


def offset_slider_crank(e, t0):
    r, rod = 40.0, 160.0
    a = [r * math.cos(t0), r * math.sin(t0)]
    b = [a[0] + math.sqrt(rod**2 - (a[1] - e) ** 2), e]
    d = pk.scenes.data("slider-crank")
    d["points"].update(A=a, B=b)
    return pk.Scene.from_dict(d)


def test_where_the_rod_cannot_reach_the_slot_it_is_not_assemblable():
    # offset 180 with r = 40, l = 160: the pin reaches the slot only while r sin t >= 20,
    # t in [30, 150] deg; there the rod stands perpendicular to the slot (dead points)
    sc = offset_slider_crank(180.0, math.radians(90.0))
    t = np.radians(np.arange(-179.5, 180.0, 1.0))
    sw = sc.sweep(t)
    inside = (t > math.radians(30.0)) & (t < math.radians(150.0))
    np.testing.assert_array_equal(sw.success, inside)
    assert (sw.status[~inside] == pk.Status.NOT_ASSEMBLABLE).all()
    lim = np.unique(np.round(np.degrees(sw.limit[np.isfinite(sw.limit)]), 4))
    assert set(lim) <= {30.0, 150.0}


def test_a_linear_input_stops_at_its_dead_points():
    sc = pk.scenes.load("elliptic-trammel")
    lo, hi = sc.stroke()
    s = np.array([lo - 10.0, lo / 2, hi / 2, hi + 10.0])
    sw = sc.sweep(s)
    assert sw.success[1:3].all()
    # past the stroke's ends the bar cannot close: no assembly there
    assert (sw.status[[0, 3]] == pk.Status.NOT_ASSEMBLABLE).all()


@pytest.mark.parametrize("name", SLIDERS)
def test_round_trip_through_json_and_toml(name, tmp_path):
    sc = pk.scenes.load(name)
    for suffix in (".json", ".toml"):
        again = pk.Scene.load(sc.save(tmp_path / f"s{suffix}"))
        assert again.to_dict() == sc.to_dict()
        assert again.slots == sc.slots and again.prismatic == sc.prismatic
        assert again.input_kind == sc.input_kind


# --- validation ----------------------------------------------------------------------------


def bad(edit):
    d = pk.scenes.data("slider-crank")
    edit(d)
    return d


def piston(**kw):
    return lambda d: d["slots"]["piston"].update(**kw)


def key(k, v):
    return lambda d: d.update({k: v})


EXTRA_SLOT = {"extra": {"point": "A", "guide": "ground", "line": ["O2", "X"]}}
SELF_GUIDED = {"p": {"link": "rod", "guide": "rod", "line": ["A", "B"]}}


@pytest.mark.parametrize(
    "edit, message",
    [
        (piston(point="Q"), r'slots\.piston\.point: unknown point "Q"'),
        (piston(guide="nope"), r'slots\.piston\.guide: "nope" is not a link'),
        (piston(line=["O2", "A"]), r'slots\.piston\.line: "A" is not a point of the guide'),
        (lambda d: d["points"].update(X=[0.0, 0.0]), r"coincide"),
        (piston(guide="rod"), r'slots\.piston\.point: "B" is a point of its guide'),
        (lambda d: d["slots"].update(EXTRA_SLOT), r"mobility: Gruebler's count gives M = 0"),
        (lambda d: d["slots"]["piston"].pop("guide"), r"slots\.piston: must be a table with keys"),
        (key("input", {"slot": "nope"}), r'input\.slot: "nope" is not a slot'),
        (key("output", {"prismatic": "piston"}), r"output\.prismatic: 'piston' is not a"),
        (key("prismatic", SELF_GUIDED), r'prismatic\.p\.guide: "rod" cannot guide itself'),
        (piston(line="O2"), r"slots\.piston\.line: must be a pair of point names"),
    ],
)
def test_bad_slider_input_is_one_line_naming_the_entry(edit, message):
    with pytest.raises(ValueError, match=message) as e:
        pk.Scene.from_dict(bad(edit))
    assert "\n" not in str(e.value)


def test_a_slot_point_on_ground_only_is_refused():
    d = pk.scenes.data("slider-crank")
    d["points"]["G"] = [5.0, 0.0]
    d["links"]["ground"].append("G")
    d["slots"]["piston"]["point"] = "G"
    with pytest.raises(ValueError, match="slots.piston.point"):
        pk.Scene.from_dict(d)


def test_a_slider_drawn_at_a_dead_point_is_refused():
    d = pk.scenes.data("slider-crank")
    # the rod perpendicular to the slot's line: the circle touches the line (a dead point)
    d["points"]["A"] = [0.0, 40.0]
    d["points"]["B"] = [0.0, 200.0]
    with pytest.raises(ValueError, match="^mobility: "):
        pk.Scene.from_dict(d)
