"""The web page in a real browser (headless Chromium): what it computes with the core
compiled to WebAssembly equals what the Python API computes (to 1e-12), its inputs
(sliders, dragging points, files) change what it draws, and bad files give Python's
validation message. Truth here is always the Python API, never the page itself."""

from __future__ import annotations

import json
import math
import time

import numpy as np
import planarkin as pk
import pytest

# a browser for the session and seconds a test: out of the inner loop (-m "not slow");
# plain `pytest` runs them where Chromium is installed, and CI again on a fresh build
pytestmark = pytest.mark.slow

TOL = 1e-12


def _python_pose(sc: pk.Scene, theta: float) -> tuple[dict[str, np.ndarray], str]:
    sw = sc.sweep(np.array([theta]), outputs="all")
    return {n: sw.points[n][0] for n in sc.points}, pk.Status(int(sw.status[0])).name


def _as_xy(v: list) -> np.ndarray:
    return np.array([np.nan if c is None else c for c in v], dtype=np.float64)


def _assert_scene_state(state: dict, sc: pk.Scene, theta: float) -> None:
    # an angle the page derives (the drawn input angle, from atan2) may differ in its last
    # bit: the browser's module has its own libm (Rust's, from musl), not the system's
    assert state["theta"] == pytest.approx(theta, rel=0, abs=TOL)
    points, status = _python_pose(sc, theta)
    assert state["status"] == status
    assert list(state["points"]) == list(points)
    for name, xy in points.items():
        np.testing.assert_allclose(
            _as_xy(state["points"][name]), xy, rtol=0, atol=TOL, err_msg=name
        )


def test_loads_with_no_console_error(page):
    state = page.open()
    assert state["scene"] == "four-bar" and state["status"] == "CONVERGED"
    page.open("?scene=jansen")
    logs = page.logs()
    assert not [e for e in logs if e["level"] in ("SEVERE", "WARNING")], logs
    assert page.message() == ""


def _url_theta(sc: pk.Scene) -> tuple[str, float]:
    """A sensible input for a scene: 30 deg for an angle; for a linear input (the URL's
    theta is then the displacement, scene units) half the stroke's upper end."""
    if sc.input_kind == "angle":
        return "30", math.radians(30)
    s = sc.stroke()[1] / 2
    return repr(s), s


@pytest.mark.parametrize("name", pk.scenes.names())
def test_builtin_scene_state_equals_python(page, name):
    sc = pk.scenes.load(name)
    text, theta = _url_theta(sc)
    state = page.open(f"?scene={name}&theta={text}")
    assert state["scene"] == name
    assert state["input_kind"] == sc.input_kind
    _assert_scene_state(state, sc, theta)
    assert not [e for e in page.logs() if e["level"] == "SEVERE"]


@pytest.mark.parametrize("name", ["hydraulic-boom", "elliptic-trammel"])
def test_a_linear_input_has_pythons_stroke(page, name):
    sc = pk.scenes.load(name)
    state = page.open(f"?scene={name}")
    assert state["input_kind"] == "displacement" and state["theta"] == 0
    np.testing.assert_allclose(state["stroke"], sc.stroke(), rtol=0, atol=1e-9)
    _assert_scene_state(state, sc, 0.0)
    # Python's default sweep spans the stroke: the page's path is that sweep
    path = page.d.execute_script("return pk.call({op: 'path'})")
    np.testing.assert_allclose(path["theta"], sc.sweep().theta, rtol=0, atol=1e-9)


def _canvas_pixel(page, x: float, y: float) -> list[int]:
    """RGBA of the canvas at CSS pixel (x, y) (the page draws at devicePixelRatio)."""
    return page.d.execute_script(
        "const c = document.getElementById('canvas'), r = window.devicePixelRatio || 1;"
        "return Array.from(c.getContext('2d').getImageData("
        "Math.round(arguments[0] * r), Math.round(arguments[1] * r), 1, 1).data);",
        x,
        y,
    )


def test_the_slider_cranks_slot_is_drawn(page):
    sc = pk.scenes.load("slider-crank")
    state = page.open("?scene=slider-crank&theta=30")
    (slot,) = state["slots"]
    assert slot["name"] == "piston" and state["prismatic"] == []
    # the block sits on B; the rail lies on the ground line y = 0 and covers B's travel
    np.testing.assert_allclose(slot["block"], state["points"]["B"], rtol=0, atol=TOL)
    (x0, y0), (x1, y1) = slot["rail"]
    xb = sc.sweep().points["B"][:, 0]
    assert y0 == pytest.approx(0, abs=1e-9) and y1 == pytest.approx(0, abs=1e-9)
    assert min(x0, x1) < xb.min() and max(x0, x1) > xb.max()
    # on the canvas: the block's colour beside the pin, the rail's edges along its length
    # (the view maps scene units to CSS pixels: screen = (ox + k x, oy - k y))
    scr, pts = state["screen"], state["points"]
    k = (scr["B"][0] - scr["O2"][0]) / (pts["B"][0] - pts["O2"][0])
    ox, oy = scr["O2"][0] - k * pts["O2"][0], scr["O2"][1] + k * pts["O2"][1]
    bx, by = scr["B"]
    assert _canvas_pixel(page, bx + 10, by) == [255, 210, 127, 255]
    xm = ox + k * (xb.min() + xb.max()) / 2
    column = [_canvas_pixel(page, xm, oy + dy) for dy in range(5, 12)]
    assert any(p[3] == 255 and max(p[:3]) < 128 for p in column), column
    beyond = ox + k * max(x0, x1) + 20
    assert all(_canvas_pixel(page, beyond, oy + dy)[3] == 0 for dy in range(-12, 13))


def test_the_booms_sleeve_is_drawn(page):
    state = page.open("?scene=hydraulic-boom")
    (pair,) = state["prismatic"]
    assert pair["name"] == "cylinder" and state["slots"] == []
    # on the cylinder's line C1 -> C2, the direction of travel
    c1, c2 = (np.array(state["points"][n]) for n in ("C1", "C2"))
    u = (c2 - c1) / np.linalg.norm(c2 - c1)
    np.testing.assert_allclose(pair["direction"], u, rtol=0, atol=1e-12)
    for end in pair["sleeve"]:
        d = np.array(end) - c1
        assert abs(d[0] * u[1] - d[1] * u[0]) < 1e-6 * np.linalg.norm(c2 - c1)


def test_the_input_slider_moves_the_slider_cranks_piston(page):
    from selenium.webdriver.common.keys import Keys

    sc = pk.scenes.load("slider-crank")
    state0 = page.open("?scene=slider-crank&theta=30")
    page.el("theta").send_keys(Keys.ARROW_RIGHT * 50)  # 0.1 deg each
    state = page.state()
    assert state["theta"] == pytest.approx(math.radians(35), abs=1e-9)
    _assert_scene_state(state, sc, state["theta"])
    assert state["points"]["B"][0] != state0["points"]["B"][0]
    # the piston's displacement along its slot is Python's output
    sw = sc.sweep([state0["theta"], state["theta"]])
    moved = state["points"]["B"][0] - state0["points"]["B"][0]
    assert moved == pytest.approx(sw.output[1] - sw.output[0], abs=TOL)
    assert moved < 0  # the crank turning on past 30 deg draws the piston in


def test_a_linear_inputs_slider_works_in_length_units(page):
    from selenium.webdriver.common.keys import Keys

    sc = pk.scenes.load("elliptic-trammel")
    lo, hi = sc.stroke()
    page.open("?scene=elliptic-trammel")
    slider = page.el("theta")
    assert float(slider.get_attribute("min")) == pytest.approx(lo, abs=1e-9)
    assert float(slider.get_attribute("max")) == pytest.approx(hi, abs=1e-9)
    slider.send_keys(Keys.ARROW_LEFT * 20)
    state = page.state()
    assert state["theta"] == pytest.approx(float(slider.get_attribute("value")), abs=1e-12)
    assert state["theta"] == pytest.approx(-20 * (hi - lo) / 1000, rel=1e-6)
    _assert_scene_state(state, sc, state["theta"])
    # the displacement is A's, along x from the drawn 60 mm
    assert state["points"]["A"][0] == pytest.approx(60 + state["theta"], abs=TOL)


def test_dragging_a_slot_point_edits_a_linear_scene(page):
    from selenium.webdriver.common.action_chains import ActionChains

    state0 = page.open("?scene=elliptic-trammel&theta=-20")
    canvas = page.el("canvas")
    x, y = state0["screen"]["B"]
    w, h = canvas.size["width"], canvas.size["height"]
    ActionChains(page.d).move_to_element_with_offset(canvas, round(x - w / 2), round(y - h / 2)) \
        .click_and_hold().move_by_offset(15, 0).release().perform()  # fmt: skip
    state = page.state()
    assert state["error"] is None and state["drawn"]["B"] != state0["points"]["B"]
    # the new drawing keeps its slots (B now off its line by a drawn offset): Python solves
    # the same edited scene, from s = 0 at the new drawing
    data = pk.scenes.data("elliptic-trammel")
    data["points"] = state["drawn"]
    sc = pk.Scene.from_dict(data)
    assert state["theta"] == 0 and [s["name"] for s in state["slots"]] == ["a", "b"]
    _assert_scene_state(state, sc, 0.0)
    np.testing.assert_allclose(state["stroke"], sc.stroke(), rtol=0, atol=1e-9)


def test_auto_advance_bounces_between_the_strokes_ends(page):
    sc = pk.scenes.load("elliptic-trammel")
    lo, hi = sc.stroke()
    page.open("?scene=elliptic-trammel&auto=1&speed=10")
    seen = []
    for _ in range(400):
        s = page.state()
        seen.append(s["theta"])
        assert s["status"] == "CONVERGED"
        assert lo - 1e-9 <= s["theta"] <= hi + 1e-9
        if min(seen) < lo + 10 and max(seen) > hi - 10 and seen[-1] > min(seen) + 20:
            break
        time.sleep(0.02)
    else:
        raise AssertionError(f"did not bounce: {min(seen)}, {max(seen)}")
    page.el("auto").click()


def test_jansen_at_the_drawn_angle_by_default(page):
    sc = pk.scenes.load("jansen")
    state = page.open("?scene=jansen")
    _assert_scene_state(state, sc, sc.input_angle)


@pytest.mark.parametrize(
    ("r", "theta", "mode"),
    [
        ((6, 2, 5, 5), 45, "open"),
        ((6, 2, 5, 5), 45, "crossed"),
        ((6, 2, 5, 5), -170.5, "open"),
        ((2, 6, 5, 5), 120, "crossed"),  # double crank
        ((4, 3, 2, 1.5), 120, "open"),  # non-Grashof: a crank angle it cannot reach
        ((4, 3, 2, 1.5), 80, "open"),
    ],
)
def test_fourbar_state_equals_python(page, r, theta, mode):
    p, delta = 2.5, -40.0
    state = page.open(
        f"?fourbar={','.join(map(str, r))}&theta={theta}&mode={mode}&p={p}&delta={delta}"
    )
    t2 = math.radians(theta)
    assert state["theta"] == t2 and state["mode"] == mode
    fb = pk.FourBar(*r)
    t3, t4 = fb.closed_form(t2, mode)
    status = pk.Status(int(fb.closed_form_status(t2, mode))).name
    assert state["status"] == status
    truth = {
        "O2": (0.0, 0.0),
        "O4": (r[0], 0.0),
        "A": fb.coupler_point(t2, 0.0, 0.0, 0.0),
        "B": fb.coupler_point(t2, t3, r[2], 0.0),
        "P": fb.coupler_point(t2, t3, p, math.radians(delta)),
    }
    for k, xy in truth.items():
        np.testing.assert_allclose(_as_xy(state["points"][k]), xy, rtol=0, atol=TOL, err_msg=k)
    g = fb.grashof()
    assert (state["grashof"], state["barker"]) == (g.condition, g.barker)
    info = page.el("info").text
    assert g.barker in info and g.kind in info and status in info


def test_unreachable_fourbar_shows_its_dead_points(page):
    page.open("?fourbar=4,3,2,1.5&theta=120")
    info = page.el("info").text
    lim = pk.FourBar(4, 3, 2, 1.5).limits("open")
    assert not lim.full_rotation
    assert "NOT_ASSEMBLABLE" in info and "dead points:" in info
    for t in lim.dead_points:
        assert f"{math.degrees(t):.2f}" in info


def test_moving_the_input_slider_changes_the_pose(page):
    from selenium.webdriver.common.keys import Keys

    state0 = page.open("?scene=jansen&theta=30")
    shot0 = page.d.get_screenshot_as_png()
    slider = page.el("theta")
    slider.send_keys(Keys.ARROW_RIGHT * 50)  # a real input event per key: 0.1 deg each
    state = page.state()
    assert state["theta"] != state0["theta"]
    assert state["points"]["foot"] != state0["points"]["foot"]
    _assert_scene_state(state, pk.scenes.load("jansen"), state["theta"])
    assert page.d.get_screenshot_as_png() != shot0


def test_a_length_slider_changes_the_fourbar(page):
    from selenium.webdriver.common.keys import Keys

    state0 = page.open("?fourbar=6,2,5,5&theta=45")
    page.el("r3").send_keys(Keys.ARROW_RIGHT * 20)  # 0.01 each
    state = page.state()
    assert state["r"][2] == pytest.approx(5.2) and state["r"][:2] == [6, 2]
    fb = pk.FourBar(*state["r"])
    t3, _ = fb.closed_form(state["theta"], "open")
    b = fb.coupler_point(state["theta"], t3, state["r"][2], 0.0)
    np.testing.assert_allclose(state["points"]["B"], b, rtol=0, atol=TOL)
    assert state["points"]["B"] != state0["points"]["B"]


def test_dragging_a_point_edits_the_linkage(page):
    from selenium.webdriver.common.action_chains import ActionChains

    state0 = page.open("?scene=jansen&theta=30")
    shot0 = page.d.get_screenshot_as_png()
    canvas = page.el("canvas")
    x, y = state0["screen"]["B"]
    w, h = canvas.size["width"], canvas.size["height"]
    # selenium's offsets are from the element's centre
    chain = ActionChains(page.d).move_to_element_with_offset(
        canvas, round(x - w / 2), round(y - h / 2)
    )
    chain.click_and_hold().move_by_offset(12, -9).move_by_offset(6, -4).release().perform()
    state = page.state()
    assert state["error"] is None
    moved = state["drawn"]["B"]
    assert moved != state0["points"]["B"]
    # the page's new drawing is the pose it showed, with B where it was dropped: the
    # lengths are re-derived from it, and Python solves the same edited scene
    data = pk.scenes.data("jansen")
    data["points"] = state["drawn"]
    sc = pk.Scene.from_dict(data)
    assert state["theta"] == sc.input_angle
    _assert_scene_state(state, sc, state["theta"])
    for n in ("O", "Z", "M", "C", "D", "E", "foot"):
        np.testing.assert_allclose(state["drawn"][n], state0["points"][n], rtol=0, atol=TOL)
    assert page.d.get_screenshot_as_png() != shot0


def test_the_edited_scene_saves_as_json_that_python_loads(page, downloads):
    from selenium.webdriver.common.action_chains import ActionChains

    state0 = page.open("?scene=jansen&theta=30")
    canvas = page.el("canvas")
    x, y = state0["screen"]["D"]
    w, h = canvas.size["width"], canvas.size["height"]
    ActionChains(page.d).move_to_element_with_offset(canvas, round(x - w / 2), round(y - h / 2)) \
        .click_and_hold().move_by_offset(-10, 8).release().perform()  # fmt: skip
    state = page.state()
    target = downloads / "jansen-edited.json"
    target.unlink(missing_ok=True)
    page.el("save").click()
    for _ in range(100):
        if target.exists() and target.stat().st_size > 0:
            break
        time.sleep(0.05)
    sc = pk.Scene.load(target)
    assert sc.points == {k: tuple(v) for k, v in state["drawn"].items()}
    assert sc.links == pk.scenes.load("jansen").links
    _assert_scene_state(state, sc, state["theta"])


BAD = {
    "missing-ground": lambda d: d.pop("ground"),
    "unknown-point": lambda d: d["links"]["j"].append("Q"),
    "mobility": lambda d: d["links"].update({"brace": ["M", "Z"]}),
    "not-a-pair": lambda d: d["points"].update({"M": [15.0]}),
    "unknown-key": lambda d: d.update({"colour": "red"}),
}


@pytest.mark.parametrize("kind", sorted(BAD))
def test_a_bad_scene_file_gives_pythons_message(page, tmp_path, kind):
    data = pk.scenes.data("jansen")
    BAD[kind](data)
    path = tmp_path / f"{kind}.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    with pytest.raises(ValueError) as e:
        pk.Scene.load(path)
    page.open()
    page.el("file").send_keys(str(path))
    for _ in range(100):
        if page.message():
            break
        time.sleep(0.05)
    # Python names the file it read; the page shows the validation message itself
    said = str(e.value).removeprefix(f"{path}: ")
    assert page.message() == said
    assert page.state()["error"] == said


def test_a_good_scene_file_opens(page, tmp_path):
    path = tmp_path / "klann.json"
    path.write_text(json.dumps(pk.scenes.data("klann")), encoding="utf-8")
    page.open()
    page.el("file").send_keys(str(path))
    for _ in range(100):
        if page.state()["scene"] == "klann.json":
            break
        time.sleep(0.05)
    sc = pk.scenes.load("klann")
    _assert_scene_state(page.state(), sc, sc.input_angle)


def _sketched(name: str, shift: float) -> dict:
    """A built-in as a sketch: its lengths from the exact drawing, its moving points
    shifted by `shift` of its size (a fixed pattern)."""
    data = pk.scenes.data(name)
    pts = {n: np.asarray(v, dtype=float) for n, v in data["points"].items()}
    ground = set(data["links"][data["ground"]])
    size = max(np.ptp(np.array(list(pts.values())), axis=0))
    lengths = []
    for link in data["links"].values():
        for i, a in enumerate(link):
            for b in link[i + 1 :]:
                lengths.append([a, b, float(np.linalg.norm(pts[a] - pts[b]))])
    moved = {
        n: (v if n in ground else v + shift * size * np.array([0.6, -0.8]) * (-1) ** k).tolist()
        for k, (n, v) in enumerate(pts.items())
    }
    return {**data, "points": moved, "lengths": lengths}


def test_a_sketch_file_opens_at_its_exact_pose(page, tmp_path):
    # the module assembles a sketch as Python does: the same exact pose
    data = _sketched("fourbar", 0.02)
    path = tmp_path / "sketch.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    sc = pk.Scene(data)
    page.open()
    page.el("file").send_keys(str(path))
    for _ in range(100):
        if page.state()["scene"] == "sketch.json":
            break
        time.sleep(0.05)
    assert page.message() == ""
    _assert_scene_state(page.state(), sc, sc.input_angle)


def test_assemblies_and_circuits_match_python(page):
    theta = math.radians(30)
    page.open("?scene=jansen&theta=30")
    sc = pk.scenes.load("jansen")
    page.el("assemblies-btn").click()
    buttons = page.el("list").find_elements("tag name", "button")
    found = sc.assemblies(theta)
    assert len(buttons) == len(found) > 1
    assert [b.text.split()[1] for b in buttons] == [a.label for a in found]
    page.el("circuits-btn").click()
    circuits = sc.circuits(theta)
    buttons = page.el("list").find_elements("tag name", "button")
    assert len(buttons) == len(circuits)
    for b, c in zip(buttons, circuits, strict=True):
        assert ("full turn" in b.text) == c.full_turn
    # switch to another assembly: the page is then drawn in it, and solves from it
    page.el("assemblies-btn").click()
    page.el("list").find_elements("tag name", "button")[-1].click()
    state = page.state()
    data = pk.scenes.data("jansen")
    data["points"] = {n: list(found[-1][n]) for n in sc.points}
    np.testing.assert_allclose(
        np.array(list(state["drawn"].values())),
        np.array(list(data["points"].values())),
        rtol=0,
        atol=TOL,
    )
    _assert_scene_state(state, pk.Scene.from_dict(data), state["theta"])


def test_auto_rotate_moves_and_rocks_at_limits(page):
    # a non-Grashof four-bar: the crank rocks between its dead points, never leaving them
    page.open("?fourbar=4,3,2,1.5&theta=30&auto=1&speed=10")
    seen = set()
    for _ in range(40):
        s = page.state()
        seen.add(round(s["theta"], 6))
        assert s["status"] != "NOT_ASSEMBLABLE"
        time.sleep(0.02)
    assert len(seen) > 5
    page.el("auto").click()


@pytest.mark.parametrize("name", ["slider-crank", "scotch-yoke"])
def test_a_linear_output_is_the_cores_as_pythons(page, name):
    # the declared output along a slot or prismatic pair: one computation in the core,
    # read by Python's sw.output and shown by the page
    sc = pk.scenes.load(name)
    text, theta = _url_theta(sc)
    page.open(f"?scene={name}&theta={text}")
    reply = page.d.execute_script(f"return pk.call({{op: 'pose', theta: {theta!r}}})")
    want = float(sc.sweep([theta]).output[0])
    assert reply["output"] == pytest.approx(want, rel=0, abs=TOL)
    assert f"output: {want:.2f}" in page.el("info").text


HAND_TOML = """# a slider-crank typed by hand: comments, a literal string, dotted keys, an inline
# table, a sub-table header, an array over several lines, an underscore in a number
name = 'slider-crank, by hand'
units = "mm"
ground = "ground"
input = { link = "crank", pivot = "O2" }
output.slot = "piston"

[points]
O2 = [0, 0]
X = [1_000, 0.0]
A = [34.64101615137755, 19.999999999999996]
B = [
  193.386094815253,  # x
  0.0,
]

[links]
ground = ["O2", "X"]
crank = ["O2", "A"]
rod = ["A", "B"]

[slots.piston]
point = "B"
guide = "ground"
line = ["O2", "X"]
"""


def _open_file(page, path, name):
    page.open()
    page.el("file").send_keys(str(path))
    for _ in range(100):
        if page.state()["scene"] == name:
            break
        time.sleep(0.05)


@pytest.mark.parametrize("how", ["saved", "by-hand"])
def test_a_toml_scene_file_opens_as_the_command_line_reads_it(page, tmp_path, how):
    """The page's file input takes TOML as the CLI does (issue 32, item 10): the state is
    Python's for the same file (read by tomllib)."""
    path = tmp_path / f"{how}.toml"
    if how == "saved":
        pk.scenes.load("whitworth").save(path)
    else:
        path.write_text(HAND_TOML, encoding="utf-8")
    sc = pk.Scene.load(path)
    _open_file(page, path, path.name)
    assert page.message() == ""
    _assert_scene_state(page.state(), sc, sc.input_angle)


def test_a_bad_toml_file_says_so_in_one_line(page, tmp_path):
    path = tmp_path / "twice.toml"
    path.write_text('name = "a"\nname = "b"\n', encoding="utf-8")
    with pytest.raises(ValueError):
        pk.Scene.load(path)  # Python refuses it too
    _open_file(page, path, path.name)
    for _ in range(100):
        if page.message():
            break
        time.sleep(0.05)
    msg = page.message()
    assert msg.startswith("twice.toml is not TOML: ") and "name" in msg and "\n" not in msg


def test_a_slots_direction_point_is_no_pivot(page):
    """Whitworth's X only gives the ram's line its direction: no ground pivot is drawn
    there (issue 32, item 10); O2 and O4 carry the crank and the lever."""
    state = page.open("?scene=whitworth")
    assert state["pivots"] == ["O2", "O4"] and "X" in state["drawn"]
