"""Path targets: checked at construction (one-line errors naming the problem), resampled
and measured by arc length (against the closed forms of a line, a square and a circle),
and read from arrays, CSV, JSON and SVG path data (an SVG cubic's samples against the
Bézier formula with arc lengths by scipy's quad; smooth forms against their reflected
control points; arcs against the circle)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from planarkin.synthesis.path.targets import CurveTarget, load_target
from scipy.integrate import quad
from scipy.optimize import brentq

SQUARE = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]])


def _refused_in_one_line(words: str, call, *args, **kw) -> None:  # noqa: ANN001, ANN003
    """``call(*args, **kw)`` raises a ValueError of one line that holds ``words``."""
    with pytest.raises(ValueError) as e:
        call(*args, **kw)
    assert words in str(e.value) and "\n" not in str(e.value)


# --- construction ------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("points", "kind", "inputs", "words"),
    [
        (SQUARE[:2], "open", None, "at least 3 points, got 2"),
        (np.zeros((4, 3)), "open", None, "(n, 2) array of x, y, got shape (4, 3)"),
        (np.zeros(8), "open", None, "got shape (8,)"),
        ([[0, 0], [1, math.nan], [2, 0]], "open", None, "point 1 is (1.0, nan)"),
        ([[0, 0], [1, math.inf], [2, 0]], "open", None, "points must be finite"),
        ([[0, 0], [1, 0], [1, 0], [2, 0]], "open", None, "points 1 and 2 are the same point"),
        (SQUARE, "loop", None, "kind must be one of closed, open, partial, got 'loop'"),
        (np.vstack([SQUARE, SQUARE[:1]]), "closed", None, "the last point repeats the first"),
        (SQUARE, "closed", [0.0, 1.0, 2.0], "one value per point (4), got shape (3,)"),
        (SQUARE, "closed", [0.0, 1.0, math.nan, 2.0], "inputs[2] is nan"),
        ([["a", 0], [1, 0], [2, 0]], "open", None, "points must be an (n, 2) array of numbers"),
    ],
)
def test_bad_targets_are_refused_in_one_line(points, kind, inputs, words):
    _refused_in_one_line(words, CurveTarget, points, kind, inputs)


def test_a_closed_target_may_cross_itself():
    s = np.linspace(0, math.tau, 40, endpoint=False)
    eight = np.column_stack([np.sin(s), np.sin(s) * np.cos(s)])  # a figure eight
    t = CurveTarget(eight, "closed")
    assert len(t) == 40 and t.closed


def test_size_is_the_bounding_box_diagonal_and_the_points_are_frozen():
    t = CurveTarget([[1.0, 1.0], [4.0, 1.0], [1.0, 5.0]], "open")
    assert t.size == 5.0
    with pytest.raises(ValueError):
        t.points[0, 0] = 9.0  # read-only


# --- arc length --------------------------------------------------------------------------


def test_arc_fractions_of_a_closed_square_count_the_closing_side():
    t = CurveTarget(SQUARE, "closed")
    assert t.length == 8.0
    np.testing.assert_array_equal(t.arc_fractions(), [0.0, 0.25, 0.5, 0.75])


def test_arc_fractions_of_an_open_line_run_from_0_to_1():
    x = np.array([0.0, 0.5, 2.0, 3.0, 7.0])
    t = CurveTarget(np.column_stack([x, 2 * x]), "open")
    np.testing.assert_allclose(t.arc_fractions(), x / 7.0, rtol=0, atol=1e-15)
    assert t.length == pytest.approx(7.0 * math.sqrt(5.0), rel=1e-15)


def test_resampled_line_is_evenly_spaced_with_its_ends_kept():
    x = np.array([0.0, 0.1, 0.5, 3.0, 4.0])
    t = CurveTarget(np.column_stack([x, -x]), "partial", inputs=x / 2).resampled(9)
    assert t.kind == "partial" and len(t) == 9
    np.testing.assert_allclose(t.points[:, 0], np.linspace(0, 4, 9), rtol=0, atol=1e-15)
    np.testing.assert_allclose(t.points[:, 1], -np.linspace(0, 4, 9), rtol=0, atol=1e-15)
    np.testing.assert_allclose(t.inputs, np.linspace(0, 2, 9), rtol=0, atol=1e-15)
    assert t.points[-1].tolist() == [4.0, -4.0]


def test_resampled_closed_square_steps_round_from_the_first_point():
    t = CurveTarget(SQUARE, "closed", inputs=[0.0, 1.0, 2.0, 3.0]).resampled(8)
    want = [[0, 0], [1, 0], [2, 0], [2, 1], [2, 2], [1, 2], [0, 2], [0, 1]]
    np.testing.assert_allclose(t.points, want, rtol=0, atol=1e-15)
    # the closing side runs from the last input to the first plus a turn (3 -> 2 pi)
    np.testing.assert_allclose(t.inputs[:6], [0, 0.5, 1, 1.5, 2, 2.5], atol=1e-15)
    np.testing.assert_allclose(t.inputs[6:], [3.0, 3.0 + (math.tau - 3.0) / 2], atol=1e-15)


def test_resampled_circle_polygon_keeps_the_circle():
    n = 720
    a = np.linspace(0, math.tau, n, endpoint=False)
    t = CurveTarget(np.column_stack([np.cos(a), np.sin(a)]), "closed")
    r = t.resampled(36)
    # the polygon's chords lie inside the circle by at most 1 - cos(pi / n)
    np.testing.assert_allclose(np.hypot(*r.points.T), 1.0, atol=1 - math.cos(math.pi / n))
    step = np.hypot(*np.diff(np.vstack([r.points, r.points[:1]]), axis=0).T)
    np.testing.assert_allclose(step, 2 * math.sin(math.pi / 36), rtol=1e-4)


def test_resampled_refuses_too_few_points():
    with pytest.raises(ValueError, match="m must be >= 3, got 2"):
        CurveTarget(SQUARE, "closed").resampled(2)


# --- loading: arrays, CSV, JSON ------------------------------------------------------------


def test_arrays_closed_when_the_last_point_repeats_the_first():
    t = load_target(np.vstack([SQUARE, SQUARE[:1]]))
    assert t.kind == "closed" and len(t) == 4
    assert load_target(SQUARE).kind == "open"
    t = load_target(np.vstack([SQUARE, SQUARE[:1]]), kind="open")
    assert t.kind == "open" and len(t) == 5
    assert load_target(SQUARE.tolist(), kind="partial").kind == "partial"


def test_a_third_column_is_the_timing_in_radians_used_only_when_asked():
    a = np.column_stack([SQUARE, [0.0, 0.5, 1.0, 1.5]])
    assert load_target(a).inputs is None
    np.testing.assert_array_equal(load_target(a, timing=True).inputs, [0.0, 0.5, 1.0, 1.5])
    with pytest.raises(ValueError, match="timing asked for, but the target gives no input"):
        load_target(SQUARE, timing=True)


def test_csv_with_header_comments_and_degrees(tmp_path):
    p = tmp_path / "t.csv"
    p.write_text(
        "# a target digitised by hand\n"
        "\n"
        "x, y, input_deg\n"
        "0, 0, 0   # the start\n"
        "2, 0, 90\n"
        "# a comment between rows\n"
        "2, 2, 180\n"
        "0, 2, 270\n"
        "0, 0, 360\n",
        encoding="utf-8",
    )
    t = load_target(p, timing=True)
    assert t.kind == "closed"  # the last row repeats the first: dropped
    np.testing.assert_array_equal(t.points, SQUARE)
    np.testing.assert_allclose(t.inputs, np.radians([0, 90, 180, 270]), rtol=0, atol=0)


def test_csv_columns_in_any_order_and_radians(tmp_path):
    p = tmp_path / "t.csv"
    p.write_text("input,y,x\n0.5,1,0\n0.25,2,1\n0.125,4,3\n", encoding="utf-8")
    t = load_target(str(p), timing=True)
    np.testing.assert_array_equal(t.points, [[0, 1], [1, 2], [3, 4]])
    np.testing.assert_array_equal(t.inputs, [0.5, 0.25, 0.125])
    assert t.kind == "open"


def test_csv_without_header(tmp_path):
    p = tmp_path / "t.csv"
    p.write_text("0 0\n1 0\n1 1\n", encoding="utf-8")
    np.testing.assert_array_equal(load_target(p).points, [[0, 0], [1, 0], [1, 1]])


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("x,y\n0,0\n1,zero\n", "t.csv line 3: expected numbers, got '1,zero'"),
        ("0,0\n1,0,3\n", "t.csv line 2: expected 2 numbers"),
        ("0,0,1,2\n", "t.csv line 1: expected x,y or x,y,input"),
        ("x,z\n0,0\n", "unknown column 'z'"),
        ("x,input\n0,0\n", "the header has no column 'y'"),
        ("# nothing\n", "no points"),
        ("0,0\n1,0\n1,0\n2,2\n", "points 1 and 2 are the same point"),
        ("0,0\nnan,0\n1,1\n", "point 1 is (nan, 0.0)"),
    ],
)
def test_bad_csv_is_refused_in_one_line(tmp_path, text, words):
    p = tmp_path / "t.csv"
    p.write_text(text, encoding="utf-8")
    _refused_in_one_line(words, load_target, p)


def test_json_array_and_object(tmp_path):
    p = tmp_path / "a.json"
    p.write_text(json.dumps(SQUARE.tolist()), encoding="utf-8")
    assert load_target(p).kind == "open"
    p = tmp_path / "o.json"
    p.write_text(json.dumps({"points": SQUARE.tolist(), "kind": "partial",
                             "inputs_deg": [0, 10, 20, 30]}), encoding="utf-8")  # fmt: skip
    t = load_target(p, timing=True)
    assert t.kind == "partial"
    np.testing.assert_allclose(t.inputs, np.radians([0, 10, 20, 30]), rtol=0, atol=0)
    assert load_target(p, kind="closed").kind == "closed"  # the caller's word wins


@pytest.mark.parametrize(
    ("data", "words"),
    [
        ({"points": SQUARE.tolist(), "colour": "red"}, "unknown key 'colour'"),
        ({"kind": "open"}, "the object has no 'points'"),
        ({"points": SQUARE.tolist(), "kind": "round"}, "kind must be one of"),
        ({"points": SQUARE.tolist(), "inputs": [1, 2, 3, 4], "inputs_deg": [1, 2, 3, 4]},
         "given twice"),
        ([[0, 0, 0, 0]], "(n, 2) or (n, 3) array"),
    ],
)  # fmt: skip
def test_bad_json_is_refused_in_one_line(tmp_path, data, words):
    p = tmp_path / "t.json"
    p.write_text(json.dumps(data), encoding="utf-8")
    _refused_in_one_line(words, load_target, p, timing=True)


def test_unknown_files_and_kinds_are_refused(tmp_path):
    with pytest.raises(ValueError, match="target file 'none.csv' does not exist"):
        load_target("none.csv")
    (tmp_path / "t.txt").write_text("0 0\n", encoding="utf-8")
    with pytest.raises(ValueError, match=r"must be \.csv, \.json or \.svg"):
        load_target(tmp_path / "t.txt")
    with pytest.raises(ValueError, match="kind must be one of closed, open, partial"):
        load_target(SQUARE, kind="loop")


# --- SVG path data -----------------------------------------------------------------------


def _bezier(p, t):  # noqa: ANN001, ANN202
    """The cubic Bézier's formula (Bernstein form) at t."""
    p0, p1, p2, p3 = (np.asarray(q, dtype=float) for q in p)
    u = 1 - t
    return u**3 * p0 + 3 * u * u * t * p1 + 3 * u * t * t * p2 + t**3 * p3


def _bezier_speed(p, t):  # noqa: ANN001, ANN202
    p0, p1, p2, p3 = (np.asarray(q, dtype=float) for q in p)
    u = 1 - t
    return float(np.hypot(*(3 * u * u * (p1 - p0) + 6 * u * t * (p2 - p1) + 3 * t * t * (p3 - p2))))


def test_svg_cubic_samples_are_on_the_bezier_at_equal_arc_length():
    ctrl = [(10, 80), (40, 10), (65, 10), (95, 80)]
    m = 11
    t = load_target("M 10 80 C 40 10, 65 10, 95 80", svg_samples=m)
    assert t.kind == "open" and len(t) == m
    length = quad(lambda s: _bezier_speed(ctrl, s), 0, 1, epsabs=1e-13, epsrel=1e-13)[0]
    for k, got in enumerate(t.points):
        s_k = k * length / (m - 1)

        def f(u, s_k=s_k):  # noqa: ANN001, ANN202
            return quad(lambda s: _bezier_speed(ctrl, s), 0, u, epsabs=1e-13)[0] - s_k

        u = 0.0 if k == 0 else 1.0 if k == m - 1 else brentq(f, 0, 1, xtol=1e-14)
        want = _bezier(ctrl, u) * [1, -1]  # SVG's y points down: negated
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-9)


def test_svg_circle_from_two_arcs_is_closed_and_evenly_spaced():
    r, cx, cy = 3.0, 5.0, -2.0
    d = f"M {cx + r} {cy} A {r} {r} 0 0 1 {cx - r} {cy} A {r} {r} 0 0 1 {cx + r} {cy} Z"
    t = load_target(d, svg_samples=24)
    assert t.kind == "closed" and len(t) == 24
    # on the circle (y negated), one step of arc 2 pi r / 24 apart: angles 15 deg apart
    np.testing.assert_allclose(np.hypot(t.points[:, 0] - cx, t.points[:, 1] + cy), r, atol=1e-12)
    a = np.unwrap(np.arctan2(-(t.points[:, 1] + cy), t.points[:, 0] - cx))
    np.testing.assert_allclose(np.diff(a), math.tau / 24, atol=1e-10)


def test_svg_an_open_path_drawn_back_to_its_start_is_closed():
    t = load_target("M 2 0 A 2 2 0 1 1 -2 0 A 2 2 0 1 1 2 0", svg_samples=12)
    assert t.kind == "closed" and len(t) == 11


def test_svg_relative_lines_h_v_and_z_make_a_square():
    t = load_target("m 1 1 h 2 v 2 h -2 z", svg_samples=8)
    want = [[1, 1], [2, 1], [3, 1], [3, 2], [3, 3], [2, 3], [1, 3], [1, 2]]
    assert t.kind == "closed"
    np.testing.assert_allclose(t.points, np.array(want) * [1, -1], rtol=0, atol=1e-14)


def test_svg_pairs_after_m_are_lines():
    t = load_target("M0,0 1,0 1,1", svg_samples=3)
    np.testing.assert_allclose(t.points, [[0, 0], [1, 0], [1, -1]], rtol=0, atol=1e-15)
    t = load_target("M0 0L4 0 4 3", svg_samples=8)  # 7 steps of 1 along 4 + 3
    np.testing.assert_allclose(t.points[:, 0], [0, 1, 2, 3, 4, 4, 4, 4], atol=1e-14)
    np.testing.assert_allclose(-t.points[:, 1], [0, 0, 0, 0, 0, 1, 2, 3], atol=1e-14)


def test_svg_smooth_quadratic_reflects_the_control_point():
    # Q 1 1 2 0 then T 4 0: the second control point is (3, -1), so on that piece
    # x = 2 + 2u and y = -2 u (1 - u) (SVG coordinates)
    t = load_target("M 0 0 Q 1 1 2 0 T 4 0", svg_samples=41)
    x, y = t.points[:, 0], -t.points[:, 1]
    on = x > 2 + 1e-9
    u = (x[on] - 2) / 2
    np.testing.assert_allclose(y[on], -2 * u * (1 - u), rtol=0, atol=1e-12)
    u = x[~on] / 2  # the first piece: x = 2u, y = 2u(1 - u)
    np.testing.assert_allclose(y[~on], 2 * u * (1 - u), rtol=0, atol=1e-12)


def test_svg_smooth_cubic_reflects_the_control_point():
    # C 0 1 1 1 1 0 then S 2 -1 2 0: the second piece's first control is (1, -1)
    t = load_target("M 0 0 C 0 1 1 1 1 0 S 2 -1 2 0", svg_samples=31)
    second = [(1, 0), (1, -1), (2, -1), (2, 0)]
    for x, y in t.points * [1, -1]:
        if x > 1 + 1e-9:
            u = brentq(lambda s, x=x: _bezier(second, s)[0] - x, 0, 1, xtol=1e-15)
            assert y == pytest.approx(_bezier(second, u)[1], abs=1e-10)


def test_svg_file_with_xml_and_a_file_of_path_data(tmp_path):
    p = tmp_path / "drawn.svg"
    p.write_text(
        '<?xml version="1.0"?><svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 9 9">'
        '<g><rect width="9" height="9"/><path id="curve" d="M 0 0 L 3 0 L 3 4 Z"/>'
        '<path d="M 0 0 L 1 1"/></g></svg>',
        encoding="utf-8",
    )
    t = load_target(p, svg_samples=12)  # perimeter 12: one point per unit
    assert t.kind == "closed" and len(t) == 12
    np.testing.assert_allclose(t.points[3], [3, 0], atol=1e-14)
    np.testing.assert_allclose(t.points[7], [3, -4], atol=1e-14)
    q = tmp_path / "d.svg"
    q.write_text("M 0 0 L 3 0 L 3 4 Z\n", encoding="utf-8")
    np.testing.assert_array_equal(load_target(q, svg_samples=12).points, t.points)
    assert load_target(q, kind="open", svg_samples=12).kind == "open"


@pytest.mark.parametrize(
    ("d", "words"),
    [
        ("L 1 1", "must start with M or m"),
        ("M 0 0 L 1", "'L' needs 2 numbers"),
        ("M 0 0 L 1 1 M 2 2 L 3 3", "a second subpath"),
        ("M 0 0 L 1 1 Z L 2 2", "after Z"),
        ("M 0 0 L 1 1 X 2 2", "d.svg: SVG path: cannot read 'X' at character 12"),
        ("M 0 0 A 1 1 0 2 0 1 1", "an arc flag must be 0 or 1, got 2"),
        ("M 0 0 L 0 0", "the path has no length"),
    ],
)
def test_bad_svg_path_data_is_refused_in_one_line(tmp_path, d, words):
    p = tmp_path / "d.svg"  # a file holding only path data (a string must start with M)
    p.write_text(d, encoding="utf-8")
    _refused_in_one_line(words, load_target, p)


def test_svg_files_refused(tmp_path):
    p = tmp_path / "t.svg"
    p.write_text('<svg><path transform="scale(2) wobble(3)" d="M 0 0 L 1 1 L 2 0"/></svg>',
                 "utf-8")  # fmt: skip
    with pytest.raises(ValueError, match="t.svg: SVG transform: cannot read 'wobble"):
        load_target(p)
    p.write_text('<svg><path transform="rotate(1, 2)" d="M 0 0 L 1 1 L 2 0"/></svg>', "utf-8")
    with pytest.raises(ValueError, match="rotate takes 1 or 3 numbers, got 2"):
        load_target(p)
    p.write_text("<svg><rect/></svg>", "utf-8")
    with pytest.raises(ValueError, match="no <path> with a 'd' attribute"):
        load_target(p)
    p.write_text("<svg><path d='M 0 0'", "utf-8")
    with pytest.raises(ValueError, match="not an SVG file"):
        load_target(p)
    with pytest.raises(ValueError, match="svg_samples must be >= 3"):
        load_target("M 0 0 L 1 1", svg_samples=2)


def test_svg_rotated_elliptical_arcs_stay_on_the_ellipse():
    # an ellipse of radii 3 and 1 turned 30 deg about the origin, as two half arcs
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    x0, y0 = 3 * c, 3 * s
    d = f"M {x0} {y0} A 3 1 30 0 1 {-x0} {-y0} a 3 1 30 1 1 {2 * x0} {2 * y0} z"
    t = load_target(d, svg_samples=40)
    x, y = t.points[:, 0], -t.points[:, 1]  # back to SVG coordinates
    u, v = (x * c + y * s) / 3, (-x * s + y * c) / 1  # in the ellipse's own axes
    np.testing.assert_allclose(u * u + v * v, 1.0, rtol=0, atol=1e-12)
    assert t.kind == "closed" and len(t) == 40
    # the arc is swept one way round: the angle in the ellipse's axes moves monotonically
    a = np.unwrap(np.arctan2(v, u))
    assert np.all(np.diff(a) > 0) or np.all(np.diff(a) < 0)


def test_svg_transforms_on_the_path_and_its_groups_are_applied(tmp_path):
    # the triangle (0,0) (3,0) (3,4) rotated 90 deg about (1, 1), then scaled by 2 and
    # moved by (10, 20): each vertex by hand
    p = tmp_path / "t.svg"
    p.write_text(
        '<svg xmlns="http://www.w3.org/2000/svg"><g transform="translate(10 20) scale(2)">'
        '<path transform="rotate(90 1 1)" d="M 0 0 L 3 0 L 3 4 Z"/></g></svg>',
        encoding="utf-8",
    )
    t = load_target(p, svg_samples=12)  # the perimeter stays 12 units before the scale

    def by_hand(x, y):  # noqa: ANN001, ANN202
        rx, ry = 1 - (y - 1), 1 + (x - 1)  # rotate(90) about (1, 1)
        return 10 + 2 * rx, -(20 + 2 * ry)  # scale(2), translate(10, 20); y negated

    for k, (x, y) in {0: (0, 0), 3: (3, 0), 7: (3, 4)}.items():
        np.testing.assert_allclose(t.points[k], by_hand(x, y), atol=1e-12)
    step = np.hypot(*np.diff(np.vstack([t.points, t.points[:1]]), axis=0).T)
    np.testing.assert_allclose(step, 2.0, atol=1e-12)  # 24 units round, 12 equal steps
    # skews and a matrix: the matrix (2, 0, 0, 3, 1, 1) maps (x, y) to (2x + 1, 3y + 1)
    p.write_text('<svg><path transform="matrix(2 0 0 3 1 1) skewX(0)" '
                 'd="M 0 0 L 1 0 L 1 1"/></svg>', "utf-8")  # fmt: skip
    t = load_target(p, svg_samples=6)  # 2 + 3 units long: one point per unit
    want = [[1, 1], [2, 1], [3, 1], [3, 2], [3, 3], [3, 4]]
    np.testing.assert_allclose(t.points, np.array(want) * [1, -1], atol=1e-12)


def test_svg_compact_arc_flags_and_numbers_read_as_svg_says():
    # "a2 2 0 011 2" is the minifiers' form of "a 2 2 0 0 1 1 2"; "1.5.5" is 1.5 then .5
    wide = load_target("M 0 0 a 2 2 0 0 1 1 2 L 1.5 0.5 Z", svg_samples=16)
    tight = load_target("M0 0a2 2 0 011 2L1.5.5z", svg_samples=16)
    np.testing.assert_array_equal(tight.points, wide.points)
    assert tight.kind == "closed"
