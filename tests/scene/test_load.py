"""Loading a JSON scene file in the core (issue 36, item 4): a large scene loads to the
model its file describes, numbers read as Python's ``json`` reads them; names, escapes
and the default name as before; every error the same words, naming the file."""

from __future__ import annotations

import json

import numpy as np
import planarkin as pk
import pytest
from planarkin import _kernel

N = 16_000


def big_link(n: int, seed: int = 36) -> dict:
    """One link carrying ``n`` points at random places (no two coincide) besides its pivot
    O and first point A; the ground O-X."""
    rng = np.random.default_rng(seed)
    xy = rng.uniform(-5.0, 5.0, size=(n, 2))
    points = {"O": [0.0, 0.0], "X": [1.0, 0.0], "A": [0.3, 0.4]}
    points |= {f"p{i}": [float(x), float(y)] for i, (x, y) in enumerate(xy)}
    return {
        "points": points,
        "links": {"ground": ["O", "X"], "crank": ["O", "A", *(f"p{i}" for i in range(n))]},
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O"},
    }


def test_a_16000_point_link_loads_to_the_files_numbers(tmp_path):
    p = tmp_path / "link.json"
    p.write_text(json.dumps(big_link(N)), encoding="utf-8")
    text = p.read_text(encoding="utf-8")
    assert _kernel.load_scene_json(text, "link") is not None  # read by the core's reader
    want = json.loads(text)  # Python's reading of the same text
    sc = pk.Scene.load(p)
    assert sc.name == "link"
    assert list(sc.points) == list(want["points"])
    assert sc.points == {n: (x, y) for n, (x, y) in want["points"].items()}  # bit for bit
    assert sc.links == {n: tuple(v) for n, v in want["links"].items()}
    assert sc.input_angle == np.arctan2(0.4, 0.3)
    # a rigid body turning about O: every point is its drawn place turned by the input
    theta = sc.input_angle + np.radians(np.arange(0.0, 360.0, 30.0))
    sw = sc.sweep(theta, outputs="all")
    assert sw.success.all()
    turn = theta - sc.input_angle
    c, s = np.cos(turn)[:, None], np.sin(turn)[:, None]
    for name in ("A", "p0", f"p{N // 2}", f"p{N - 1}"):
        x, y = want["points"][name]
        np.testing.assert_allclose(
            sw.points[name], np.hstack([c * x - s * y, s * x + c * y]), rtol=0, atol=1e-12
        )


@pytest.mark.parametrize(
    "given, name", [(None, "stem"), ("absent", "stem"), ("a scene", "a scene")]
)
def test_the_default_name_is_the_files_stem(tmp_path, given, name):
    d = pk.scenes.data("fourbar")
    d.pop("name", None)
    if given != "absent":
        d["name"] = given
    p = tmp_path / "stem.json"
    p.write_text(json.dumps(d), encoding="utf-8")
    assert pk.Scene.load(p).name == name


def test_names_and_numbers_read_as_pythons_json_reads_them(tmp_path):
    text = json.dumps(pk.scenes.data("fourbar"))
    # escaped names, a surrogate pair, integers, an exponent, a number written long
    for old, new in (('"A"', '"\\u00c0\\ud83d\\ude00\\t"'), ("2.0, 0.0]", "2, 0E0]")):
        text = text.replace(old, new)
    text = text.replace('"B": [4.0', '"B": [4.00000000000000000000000000000000000001')
    p = tmp_path / "escapes.json"
    p.write_text(text, encoding="utf-8")
    assert _kernel.load_scene_json(text, "escapes") is not None  # read by the core's reader
    want = json.loads(text)
    sc = pk.Scene.load(p)
    assert sc.points == {n: (float(x), float(y)) for n, (x, y) in want["points"].items()}
    assert sc.links == {n: tuple(v) for n, v in want["links"].items()}


@pytest.mark.parametrize(
    "edit",
    [
        lambda d: d["points"].update(A=["x", 0.0]),
        lambda d: d["points"].update(A=[float("nan"), 0.0]),
        lambda d: d["points"].update(A=[2**70, 0.0]),  # past 64 bits: Python's reader
        lambda d: d["points"].update(A=[True, 0.0]),
        lambda d: d["points"].update(A=[1.0]),
        lambda d: d["links"].update(crank=["O2", "nowhere"]),
        lambda d: d.update(extra=1),
        lambda d: d.update(points=[]),
        lambda d: d.update(input={"link": "crank"}),
    ],
)
def test_a_file_is_refused_in_the_words_of_its_data(tmp_path, edit):
    d = pk.scenes.data("fourbar")
    edit(d)
    with pytest.raises(ValueError) as want:
        pk.Scene.from_dict(d)
    p = tmp_path / "bad.json"
    p.write_text(json.dumps(d), encoding="utf-8")
    with pytest.raises(ValueError) as got:
        pk.Scene.load(p)
    assert str(got.value) == f"{p}: {want.value}"


def test_a_list_is_not_a_scene(tmp_path):
    p = tmp_path / "list.json"
    p.write_text("[1, 2]", encoding="utf-8")
    with pytest.raises(ValueError) as e:
        pk.Scene.load(p)
    assert str(e.value) == f"{p}: scene: must be a mapping, got list"
