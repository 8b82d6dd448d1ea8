"""Pyslvs expressions in and out: mechanisms written in Pyslvs's grammar load as scenes
whose sweeps match closed forms (four-bar, slider-crank) or the same linkage built in
(Watt II, Jansen); texts and scenes round-trip exactly; bad expressions are one line."""

from __future__ import annotations

import math

import numpy as np
import planarkin as pk
import pytest
from _support import dyad_point
from planarkin.face.cli import main
from planarkin.interop import _lines, pyslvs

FOURBAR = """M[
  J[R, color[Green], P[0.0, 0.0], L[ground, crank]],
  J[R, color[Green], P[6.0, 0.0], L[ground, rocker]],
  J[R, color[Green], P[2.0, 0.0], L[crank, coupler]],
  J[R, color[Green], P[4.0, 4.58257569495584], L[coupler, rocker]],
  J[R, color[Green], P[1.6644577760545747, 2.9811761799581316], L[coupler]]
]"""

# r = 40, l = 160, drawn at 30 deg: the piston pin J2 in a slot along the ground (A[0])
SLIDER = """M[
  J[R, color[Green], P[0.0, 0.0], L[ground, link_1]],
  J[R, color[Green], P[34.64101615137755, 19.999999999999996], L[link_1, link_2]],
  J[RP, A[0.0], color[Green], P[193.386094815253, 0.0], L[ground, link_2]]
]"""

WATT2 = """M[
  J[R, color[Green], P[0.0, 0.0], L[ground, crank]],
  J[R, color[Green], P[6.0, 0.0], L[ground, ternary]],
  J[R, color[Green], P[13.0, 0.0], L[ground, rocker]],
  J[R, color[Green], P[2.0, 0.0], L[crank, coupler1]],
  J[R, color[Green], P[4.0, 4.58257569495584], L[coupler1, ternary]],
  J[R, color[Green], P[8.484313483298443, -0.27961851995452064], L[ternary, coupler2]],
  J[R, color[Green], P[11.051684505775135, 5.143351702437169], L[coupler2, rocker]]
]"""

JANSEN = """M[
  J[R, color[Green], P[0.0, 0.0], L[ground, crank]],
  J[R, color[Green], P[-38.0, -7.8], L[ground, upper, c]],
  J[R, color[Green], P[15.0, 0.0], L[crank, j, k]],
  J[R, color[Green], P[-24.013535097127793, 31.272097454842683], L[j, upper]],
  J[R, color[Green], P[-26.952107031572957, -45.51517017008116], L[k, c, lower]],
  J[R, color[Green], P[-74.79436538093606, 8.143170205896139], L[upper, f]],
  J[R, color[Green], P[-59.231514961414995, -28.052930230747762], L[f, lower]],
  J[R, color[Green], P[-43.16011052410472, -91.75693292612323], L[lower]]
]"""

# a Scotch yoke: the crank pin J1 in the yoke's slot at 90 deg, the yoke (P at J2) sliding
# along the ground at 0 deg
YOKE = """M[
  J[R, color[Green], P[0.0, 0.0], L[ground, crank]],
  J[RP, A[90.0], color[Green], P[45.31538935183249, 21.130913087034973], L[yoke, crank]],
  J[P, A[0.0], color[Green], P[165.3153893518325, 0.0], L[ground, yoke]]
]"""

TEXTS = {"fourbar": FOURBAR, "slider": SLIDER, "watt2": WATT2, "jansen": JANSEN, "yoke": YOKE}
INPUTS = {"fourbar": (0, 2), "slider": (0, 1), "watt2": (0, 3), "jansen": (0, 2), "yoke": (0, 1)}
THETA = np.linspace(0.0, 2 * math.pi, 73)


def load(key: str) -> pk.Scene:
    return pk.Scene.from_pyslvs(TEXTS[key], inputs=[INPUTS[key]])


def test_fourbar_sweep_matches_the_circle_intersection() -> None:
    sw = load("fourbar").sweep(THETA)
    assert sw.success.all()
    a = np.stack([2 * np.cos(THETA), 2 * np.sin(THETA)], -1)
    b = dyad_point(a, 5.0, np.array([6.0, 0.0]), 5.0, +1)  # B left of A -> O4, as drawn
    np.testing.assert_allclose(sw.points["J2"], a, atol=1e-12)
    np.testing.assert_allclose(sw.points["J3"], b, atol=1e-9)


def test_slider_crank_sweep_matches_the_piston_formula() -> None:
    sc = load("slider")
    assert sc.slots == {"J2": ("J2", "ground", ("S2a", "S2b"))}
    sw = sc.sweep(THETA)
    x = 40 * np.cos(THETA) + np.sqrt(160**2 - (40 * np.sin(THETA)) ** 2)
    np.testing.assert_allclose(sw.points["J2"][:, 0], x, atol=1e-9)
    np.testing.assert_allclose(sw.points["J2"][:, 1], 0.0, atol=1e-9)


def test_yoke_moves_r_cos_t() -> None:
    sc = load("yoke")
    assert set(sc.prismatic) == {"J2"} and set(sc.slots) == {"J1"}
    sw = sc.sweep(THETA)
    r = math.hypot(45.31538935183249, 21.130913087034973)
    np.testing.assert_allclose(sw.points["J2"][:, 0], 120 + r * np.cos(THETA), atol=1e-9)


@pytest.mark.parametrize(
    ("key", "name", "names"),
    [
        ("watt2", "watt2", ["O2", "O4", "O6", "A", "B", "C", "D"]),
        ("jansen", "jansen", ["O", "Z", "M", "B", "C", "D", "E", "foot"]),
    ],
)
def test_six_and_eight_bar_sweeps_match_the_built_in(key: str, name: str, names: list) -> None:
    sw = load(key).sweep(THETA)
    ref = pk.scenes.load(name).sweep(THETA)
    assert sw.success.all() and ref.success.all()
    for k, p in enumerate(names):
        np.testing.assert_allclose(sw.points[f"J{k}"], ref.points[p], atol=1e-9)


@pytest.mark.parametrize("key", sorted(TEXTS))
def test_text_round_trip_is_exact(key: str) -> None:
    sc = load(key)
    assert sc.to_pyslvs() == TEXTS[key]
    assert pyslvs.pyslvs_input(sc) == INPUTS[key]
    again = pk.Scene.from_pyslvs(sc.to_pyslvs(), inputs=[INPUTS[key]])
    assert again == sc


@pytest.mark.parametrize("name", pk.scenes.names())
def test_built_in_scenes_round_trip(name: str) -> None:
    sc = pk.scenes.load(name)
    if sc.input_kind != "angle":
        with pytest.raises(ValueError, match=r"^input: a linear input .* has no Pyslvs form$"):
            sc.to_pyslvs()
        return
    back = pk.Scene.from_pyslvs(sc.to_pyslvs(), inputs=[pyslvs.pyslvs_input(sc)])
    assert back.to_pyslvs() == sc.to_pyslvs()
    assert pk.Scene.from_pyslvs(back.to_pyslvs(), inputs=[pyslvs.pyslvs_input(back)]) == back
    theta = sc.input_angle + np.linspace(-0.2, 0.2, 5)
    a = sc.sweep(theta, outputs=list(sc.points))
    b = back.sweep(theta, outputs=list(back.points))
    assert a.success.sum() >= 3 and (b.success == a.success).all()
    size = max(np.ptp(np.array(list(sc.points.values())), axis=0))
    joints = [p for p in sc.points if p not in _lines.helpers(sc)]  # J0, J1, ... in order
    for k, p in enumerate(joints):
        ok = a.success
        np.testing.assert_allclose(b.points[f"J{k}"][ok], a.points[p][ok], atol=1e-9 * size)


@pytest.mark.parametrize(
    ("expr", "inputs", "message"),
    [
        (FOURBAR, [(0, 2), (1, 3)], r"^inputs: 2 input pairs given; a scene has one input"),
        (FOURBAR, None, r"^inputs: give the input pair"),
        (FOURBAR, [(0, 9)], r"^inputs: the driver J9 is not a joint \(J0 \.\. J4\)$"),
        (FOURBAR, [(2, 3)], r"^inputs: the base J2 must be a pin \(R\) on ground$"),
        (FOURBAR, [(0, 3)], r"^inputs: J0 and J3 share no moving link$"),
        (FOURBAR.replace("color[", "colr["), [(0, 2)], r"^J0: unknown field 'colr'"),
        (FOURBAR.replace("J[R,", "J[RR,", 1), [(0, 2)], r"^J0: the joint type must come"),
        (FOURBAR.replace("P[6.0, 0.0]", "P[6.0]"), [(0, 2)], r"^J1: needs its position P"),
        (FOURBAR[:-1], [(0, 2)], r"^pyslvs expression: expected .\]., found the end$"),
        (FOURBAR.replace("L[ground, crank]", "L[ground, crank, ground]"), [(0, 2)],
         r"^J0: link 'ground' listed twice"),
        (SLIDER.replace("A[0.0], ", ""), [(0, 1)], r"^J2: a RP joint needs its slot angle"),
        (YOKE.replace("L[ground, yoke]", "L[ground, yoke, crank]"), [(0, 1)],
         r"^J2: a P joint on more than two links is not supported$"),
        ("M[J[R, P[0.0, 0.0], L[]]]", [(0, 0)], r"^J0: on no link"),
        ("N[]", [(0, 1)], r"^pyslvs expression must be M\[\.\.\.\]"),
        ("M[J[R, P[0.0, 0.0], L[a, b]] ; ]", [(0, 1)], r"^pyslvs expression: unexpected ';'"),
    ],
)  # fmt: skip
def test_bad_input_is_one_line(expr: str, inputs: object, message: str) -> None:
    with pytest.raises(ValueError, match=message) as e:
        pk.Scene.from_pyslvs(expr, inputs=inputs)  # type: ignore[arg-type]
    assert "\n" not in str(e.value)


def test_project_file_round_trip_and_cli(tmp_path, capsys) -> None:  # noqa: ANN001
    path = tmp_path / "jansen.pyslvs"
    assert main(["scenes", "--export", "jansen", "--to", str(path)]) == 0
    text = path.read_text()
    assert text.startswith("mechanism: 'M[J[R, color[Green], P[0.0, 0.0], L[ground, crank]], ")
    assert "input:\n- [0, 2]\n" in text
    assert pyslvs.load(path).to_pyslvs() == JANSEN
    capsys.readouterr()
    assert main(["scenes", "--import", str(path)]) == 0
    import json

    d = json.loads(capsys.readouterr().out)
    assert d["points"]["J7"] == [-43.16011052410472, -91.75693292612323]
    out = tmp_path / "leg.json"
    assert main(["scenes", "--import", str(path), "--to", str(out)]) == 0
    assert pk.Scene.load(out).to_pyslvs() == JANSEN


def test_pyslvs_yaml_forms_of_input(tmp_path) -> None:  # noqa: ANN001
    # Pyslvs's own files: other keys, the input written block style (a list of tuples)
    src = (
        "pyslvs_ver: 21.12.0\nfile_type: 0\nmechanism: " + SLIDER.replace("\n", " ") +
        "\nlinks:\n  ground: Gray\ninput:\n- - 0\n  - 1\nstorage: {}\n"
    )  # fmt: skip
    sc = pyslvs.loads(src)
    assert sc.input == ("link_1", "J0")
    with pytest.raises(ValueError, match=r"^x.pyslvs: no input pair"):
        pyslvs.loads("mechanism: " + SLIDER, "x.pyslvs")


def test_colours_and_link_orders_pyslvs_may_write() -> None:
    # RGB colours, hyphenated colour names, no colour; L[...] orders that no single link
    # order matches (J3 lists c before ground): the scene round-trips, the text up to them
    e = (
        "M[J[R, color[(255, 0, 0)], P[0.0, 0.0], L[ground, a]], "
        "J[R, color[Dark-Orange], P[1.0, 0.0], L[a, b]], J[R, P[3.0, 1.0], L[b, c]], "
        "J[R, P[4, 0], L[c, ground]]]  # a four-bar"
    )
    sc = pk.Scene.from_pyslvs(e, inputs=[(0, 1)])
    assert sc.links == {"ground": ("J0", "J3"), "a": ("J0", "J1"), "b": ("J1", "J2"),
                        "c": ("J2", "J3")}  # fmt: skip
    assert pk.Scene.from_pyslvs(sc.to_pyslvs(), inputs=[(0, 1)]) == sc
    assert "J[R, color[Green], P[4.0, 0.0], L[ground, c]]" in sc.to_pyslvs()
