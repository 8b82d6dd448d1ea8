"""The web page's "draw a path" mode in a real browser (headless Chromium): a path drawn on
the page that is an exact coupler curve of a known four-bar (its points from the closed
form here) comes back as a four-bar whose coupler curve, swept by planarkin in Python,
passes within 2% of the path's size of every drawn point; the design opens as the page's
scene, and the mode also runs where no Web Worker starts."""

from __future__ import annotations

import json
import math
import time

import numpy as np
import planarkin as pk
import pytest
from _support import dyad_point

pytestmark = pytest.mark.slow

#: atlas size the page builds in these tests (the page's default is 100 000)
ATLAS = 20000
#: the design's coupler curve must pass this close to every drawn point (over its size)
TOL = 0.02


def _known_fourbar(closed: bool) -> tuple[np.ndarray, np.ndarray]:
    """A four-bar of the page's atlas (seed 0, among its first ATLAS entries) with a full-
    turn crank and no near dead point: (params r2, r3, r4, u, v; sign). The atlas kernel
    only picks the linkage; its coupler points are computed below from the closed form."""
    from planarkin._kernel import atlas_shard

    params, signs, full, cond, _ = atlas_shard("four-bar", 0, 0, 400)
    i = int(np.flatnonzero(full & (cond > 0.4))[0 if closed else 1])
    return params[i], signs[i]


def _coupler(params: np.ndarray, sign: float, theta: np.ndarray) -> np.ndarray:
    """The coupler point P of the normalised four-bar (O2 (0, 0), O4 (1, 0)) at crank
    angles theta: B where the circles about A (radius r3) and O4 (radius r4) meet, on the
    side `sign` of A -> O4 (+1 to its left); P = A + u (B - A) + v perp(B - A)."""
    r2, r3, r4, u, v = params
    a = r2 * np.column_stack([np.cos(theta), np.sin(theta)])
    ab = dyad_point(a, r3, np.broadcast_to([1.0, 0.0], a.shape), r4, sign) - a
    return a + u * ab + v * np.column_stack([-ab[:, 1], ab[:, 0]])


def _drawn(closed: bool) -> np.ndarray:
    """The path drawn: the known four-bar's coupler curve (a whole turn, or an arc of 150
    degrees), turned, scaled and shifted into the page's units."""
    params, sign = _known_fourbar(closed)
    if closed:
        theta = np.linspace(0.3, 0.3 + 2 * math.pi, 120, endpoint=False)
    else:
        theta = np.linspace(0.3, 2.9, 80)
    z = _coupler(params, float(sign[0]), theta) @ np.array([[0.8, 0.6], [-0.6, 0.8]]) * 4.0
    return z + np.array([1.5, -2.0])


def _size(points: np.ndarray) -> float:
    return float(np.hypot(*(points.max(axis=0) - points.min(axis=0))))


def _distance_to_coupler_curve(scene: dict, points: np.ndarray) -> float:
    """The largest distance from `points` to the scene's tracer P over a whole turn of its
    crank from the drawn pose (planarkin's sweep, 3601 angles), over the points' size."""
    sc = pk.Scene(scene)
    t0 = sc.input_angle
    sw = sc.sweep(np.linspace(t0, t0 + 2 * math.pi, 3601), outputs=["P"])
    ok = np.asarray(sw.status) == 0
    track = np.asarray(sw.points["P"])[ok]
    a, b = track[:-1], track[1:]
    ab = b - a
    worst = 0.0
    for p in points:
        t = np.clip(np.einsum("ij,ij->i", p - a, ab) / np.maximum((ab * ab).sum(1), 1e-300), 0, 1)
        worst = max(worst, float(np.min(np.hypot(*(a + t[:, None] * ab - p).T))))
    return worst / _size(points)


def _find(page, points: np.ndarray, closed: bool, timeout: float = 20.0) -> dict:
    page.d.execute_script("pk.drawPath(arguments[0], arguments[1])", points.tolist(), closed)
    page.el("find-btn").click()
    t_end = time.time() + timeout
    while time.time() < t_end:
        draw = page.state()["draw"]
        if draw and draw["results"] and not draw["busy"]:
            return draw
        time.sleep(0.1)
    raise AssertionError(f"no linkage found: {page.message()!r} {page.state()['draw']}")


def test_a_drawn_closed_coupler_curve_comes_back_as_a_fourbar(page, downloads):
    points = _drawn(closed=True)
    page.open(f"?draw=1&atlas={ATLAS}")
    draw = _find(page, points, closed=True)
    assert draw["atlas"]["size"] == ATLAS and draw["where"] == "worker"
    best = draw["results"][0]
    got = _distance_to_coupler_curve(best["scene"], points)
    assert got < TOL, (got, best)
    # the page's own measure of the same error (its path at 1-degree steps)
    assert best["error"]["max"] == pytest.approx(got, abs=0.005)
    assert len(draw["results"]) == 4
    assert list(best["scene"]["points"]) == ["O2", "O4", "A", "B", "P"]
    # the drawn input angle is the placed entry's at the first point, turned by arg(a)
    sc = pk.Scene(best["scene"])
    assert sc.input_angle == pytest.approx(best["input_angle"], abs=1e-9)
    # its JSON downloads as the scene file Python reads
    saved = downloads / "path-design-1.json"
    saved.unlink(missing_ok=True)
    page.el("save-design-0").click()
    for _ in range(100):
        if saved.is_file() and saved.stat().st_size:
            break
        time.sleep(0.05)
    assert pk.Scene.load(saved).input_angle == pytest.approx(sc.input_angle, abs=1e-12)
    assert json.loads(saved.read_text()) == best["scene"]
    # opened as the page's scene: drawn as the design says, solved there
    page.el("open-design-0").click()
    state = page.state()
    assert state["scene"] == "path-design-1.json" and state["draw"]["mode"] is False
    for name, xy in best["scene"]["points"].items():
        np.testing.assert_allclose(state["drawn"][name], xy, rtol=0, atol=1e-12, err_msg=name)
    assert state["status"] == "CONVERGED" and page.message() == ""
    assert not [e for e in page.logs() if e["level"] == "SEVERE"]


def test_a_drawn_open_arc_comes_back_as_a_fourbar(page):
    points = _drawn(closed=False)
    page.open(f"?draw=1&atlas={ATLAS}")
    draw = _find(page, points, closed=False)
    got = _distance_to_coupler_curve(draw["results"][0]["scene"], points)
    assert got < TOL, (got, draw["results"][0])


def test_the_pointer_draws_and_without_a_worker_the_page_builds_the_atlas(page):
    from selenium.webdriver.common.action_chains import ActionChains

    page.open("?atlas=2000")
    page.d.execute_script("window.Worker = undefined")
    page.el("drawpath-btn").click()
    canvas = page.el("canvas")
    # a circle drawn with the mouse (pointer events), from the canvas's centre
    chain = ActionChains(page.d, duration=10)
    chain.move_to_element_with_offset(canvas, 120, 0).click_and_hold()
    for k in range(1, 41):
        t = 2 * math.pi * k / 40
        chain.move_to_element_with_offset(canvas, int(120 * math.cos(t)), int(-90 * math.sin(t)))
    chain.release().perform()
    draw = page.state()["draw"]
    assert draw["mode"] is True and draw["points"] > 20
    page.el("find-btn").click()
    t_end = time.time() + 20
    while time.time() < t_end and not (page.state()["draw"] or {}).get("results"):
        time.sleep(0.1)
    draw = page.state()["draw"]
    assert draw["where"] == "page" and draw["atlas"]["size"] == 2000, draw
    assert draw["results"] and draw["results"][0]["error"]["max"] < 0.2
    assert "on the page's own thread" in page.el("atlas-status").get_attribute("textContent")
