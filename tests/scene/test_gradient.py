"""Exact derivatives of a sweep by the drawn coordinates (``Scene.gradient``, issue 19's
exact gradients): against central finite differences of real sweeps of the redrawn
linkage, on random designs (the built-ins with their moving points moved at random)."""

import numpy as np
import planarkin as pk
import pytest

H = 1e-6


def redrawn(data: dict, moves: dict[tuple[str, int], float]) -> dict:
    pts = {n: list(map(float, v)) for n, v in data["points"].items()}
    for (p, k), dv in moves.items():
        pts[p][k] += dv
    return {**data, "points": pts}


def random_design(name: str, seed: int) -> dict:
    """A built-in with its moving points moved by up to 3% of its size (a new linkage,
    drawn assembled: its lengths come from the drawing)."""
    data = pk.scenes.data(name)
    rng = np.random.default_rng(seed)
    ground = set(data["links"][data["ground"]])
    size = max(np.ptp(np.array(list(data["points"].values()), dtype=float), axis=0))
    moves = {
        (p, k): 0.03 * size * rng.uniform(-1, 1)
        for p in data["points"]
        if p not in ground
        for k in (0, 1)
    }
    return redrawn(data, moves)


@pytest.mark.parametrize(
    "name", ["fourbar", "stephenson3", "watt2", "jansen", "klann", "double-butterfly-1"]
)
@pytest.mark.parametrize("seed", [1, 2])
def test_exact_gradient_matches_central_differences_on_random_designs(name, seed):
    data = random_design(name, seed)
    try:
        sc = pk.Scene(data)
    except ValueError:
        pytest.skip("this random redrawing is not a valid linkage")
    free = list(sc.points)  # every coordinate, ground pivots included
    theta = sc.sweep().theta[::15]
    g = sc.gradient(free, theta)
    ok = g.sweep.success
    assert ok.sum() >= 5
    assert np.isfinite(g.point_array[ok]).all()
    assert np.isnan(g.point_array[~ok]).all()
    for f, label in enumerate(g.free):
        p, axis = label.split(".")
        k = "xy".index(axis)
        up = pk.Scene(redrawn(data, {(p, k): H})).sweep(theta, outputs="all")
        down = pk.Scene(redrawn(data, {(p, k): -H})).sweep(theta, outputs="all")
        both = ok & up.success & down.success
        for n in g.points:
            fd = (up.points[n][both] - down.points[n][both]) / (2 * H)
            exact = g.points[n][both, :, f]
            np.testing.assert_allclose(exact, fd, rtol=1e-6, atol=1e-6, err_msg=f"{n} by {label}")
        if g.output is not None:
            fd = (up.output[both] - down.output[both]) / (2 * H)
            np.testing.assert_allclose(g.output[both, f], fd, rtol=1e-6, atol=1e-6, err_msg=label)


def test_a_point_moves_one_for_one_with_its_own_ground_drawing():
    # a ground pivot's position is its drawing: d(O2)/d(O2.x) = (1, 0), and a point on no
    # link through the moved coordinate's links is unaffected by a ground point far away
    sc = pk.scenes.load("fourbar")
    g = sc.gradient(["O2.x"])
    ok = g.sweep.success
    np.testing.assert_array_equal(g.points["O2"][ok, :, 0], np.tile([1.0, 0.0], (ok.sum(), 1)))
    np.testing.assert_array_equal(g.points["O4"][ok, :, 0], 0.0)


def test_free_names_are_checked():
    sc = pk.scenes.load("fourbar")
    with pytest.raises(ValueError, match="free: 'Q.x': no point 'Q'"):
        sc.gradient(["Q.x"])
    with pytest.raises(ValueError, match="the coordinate must be x or y"):
        sc.gradient(["A.z"])
    with pytest.raises(ValueError, match="names a coordinate twice"):
        sc.gradient(["A", "A.x"])
    with pytest.raises(ValueError, match="must name coordinates"):
        sc.gradient([3])


@pytest.mark.parametrize(
    "name", ["slider-crank-offset", "inverted-slider-crank", "scotch-yoke", "whitworth"]
)
def test_slot_and_prismatic_scenes_match_central_differences_of_the_sweep(name):
    # slots (on ground and on a moving guide) and prismatic pairs: every drawn coordinate
    # moved both ways, the scene swept again at the same absolute input angles
    data = pk.scenes.data(name)
    sc = pk.Scene(data)
    theta = sc.input_angle + np.radians([-20.0, 5.0, 30.0])
    names = list(sc.points)
    g = sc.gradient(names, theta)
    assert np.all(np.isfinite(g.point_array))
    h = 1e-6 * sc._core.size
    for j, f in enumerate(g.free):
        p, axis = f.split(".")
        swept = []
        for sign in (1, -1):
            d = sc.to_dict()
            d["points"][p]["xy".index(axis)] += sign * h
            swept.append(pk.Scene(d).sweep(theta, outputs="all", tol=1e-14).coords)
        fd = (swept[0] - swept[1]) / (2 * h)
        np.testing.assert_allclose(g.point_array[..., j], fd, atol=1e-6, err_msg=f)


def test_linear_input_scenes_are_refused_with_a_message():
    with pytest.raises(ValueError, match="a linear input are not available yet"):
        pk.scenes.load("elliptic-trammel").gradient(["A"])


def test_relative_gradient_holds_the_input_rotation_from_the_drawn_pose():
    # moving the crank tip's drawing turns the drawn input angle: at a fixed rotation from
    # the drawn pose, the sweep's angles move with it (central differences of that)
    data = pk.scenes.data("stephenson3")
    sc = pk.Scene(data)
    rotation = np.radians(np.arange(-40.0, 41.0, 10.0))
    g = sc.gradient(["j6", "j1"], sc.input_angle + rotation, relative=True)  # j6: the crank tip
    for f, label in enumerate(g.free):
        p, axis = label.split(".")
        k = "xy".index(axis)
        sweeps = []
        for h in (H, -H):
            moved = pk.Scene(redrawn(data, {(p, k): h}))
            sweeps.append(moved.sweep(moved.input_angle + rotation, outputs="all"))
        for n in g.points:
            fd = (sweeps[0].points[n] - sweeps[1].points[n]) / (2 * H)
            np.testing.assert_allclose(g.points[n][:, :, f], fd, rtol=1e-6, atol=1e-6, err_msg=n)
