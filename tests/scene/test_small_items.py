"""Issue 32, items 9 and 10 (the Python side): a scalar input broadcasts to a one-row
sweep, the reference takes a Scene as well as its dict, and a scene file that is not
UTF-8 text is a one-line error naming the file. Values checked against closed forms."""

from __future__ import annotations

import json
import math

import numpy as np
import planarkin as pk
import pytest
from planarkin import reference


def slider_crank_x(r: float, rod: float, e: float, t: float) -> float:
    """The offset slider-crank's piston position along its line (closed form)."""
    return r * math.cos(t) + math.sqrt(rod * rod - (r * math.sin(t) - e) ** 2)


def fourbar_b(t: float) -> np.ndarray:
    """The built-in four-bar's (6, 2, 5, 5) joint B, open mode: the circle intersection
    of |AB| = 5 round A and |O4 B| = 5 round O4, on the drawn (upper-left) side."""
    a, o4 = np.array([2 * math.cos(t), 2 * math.sin(t)]), np.array([6.0, 0.0])
    d = o4 - a
    dist = float(np.hypot(*d))
    h = math.sqrt(25.0 - (dist / 2) ** 2)  # equal radii: the foot is the midpoint
    n = np.array([-d[1], d[0]]) / dist
    return a + d / 2 + h * n


def test_a_scalar_input_is_a_sweep_of_one_row():
    sc = pk.scenes.load("fourbar")
    sw = sc.sweep(0.5, outputs=["B"])
    assert len(sw) == 1 and sw.points["B"].shape == (1, 2)
    np.testing.assert_allclose(sw.points["B"][0], fourbar_b(0.5), atol=1e-12)
    # a linear input too: the boom's s = 0 is its drawn pose
    boom = pk.scenes.load("hydraulic-boom")
    one = boom.sweep(0.0, outputs=["E"])
    assert len(one) == 1
    np.testing.assert_allclose(one.points["E"][0], boom.points["E"], atol=1e-9)


def test_the_reference_takes_a_scene_as_well_as_its_dict():
    sc = pk.scenes.load("slider-crank-offset")
    t = np.radians([30.0, 75.0, 140.0])
    a = reference.scene_sweep(sc, t)
    b = reference.scene_sweep(sc.to_dict(), t)
    np.testing.assert_array_equal(a.points["B"], b.points["B"])
    want = [slider_crank_x(40.0, 160.0, 20.0, float(v)) for v in t]
    np.testing.assert_allclose(a.points["B"][:, 0], want, atol=1e-9)
    assert reference.scene_mobility(sc) == 1


@pytest.mark.parametrize(
    ("name", "content", "says"),
    [
        ("utf16.json", None, "UTF-16"),
        ("binary.json", bytes(range(256)), "not UTF-8 text"),
        ("binary.toml", b"\xff\xd8\xff\xe0 a JPEG", "not UTF-8 text"),
    ],
)
def test_a_file_that_is_not_utf8_names_itself(tmp_path, name, content, says):
    p = tmp_path / name
    if content is None:
        p.write_text(json.dumps(pk.scenes.data("fourbar")), encoding="utf-16")
    else:
        p.write_bytes(content)
    with pytest.raises(ValueError) as e:
        pk.Scene.load(p)
    msg = str(e.value)
    assert msg.startswith(f"{p}: ") and says in msg and "\n" not in msg


def test_the_cli_says_the_same_in_one_line(tmp_path):
    from _support import run_cli

    p = tmp_path / "utf16.json"
    p.write_text(json.dumps(pk.scenes.data("fourbar")), encoding="utf-16")
    code, stdout, err = run_cli("analyze", str(p), "--no-figures", "--out", str(tmp_path))
    assert code == 2 and stdout == ""
    assert err.count("\n") == 1 and str(p) in err and "UTF-16" in err
