"""Scenes from lengths and a sketch (DESIGN.md, "Scenes from a sketch"; issue 17, item 4):
every built-in scene, sketched roughly with its lengths taken from the exact drawing,
assembles to the exact pose at the sketched input (the NumPy reference's, to 1e-12 of its
size); the sketched assembly mode is kept or the sketch is refused, never snapped to
another; the sliders' rule; bad lengths; round trips; `Scene.moved`."""

import copy
import itertools
import json
import math

import numpy as np
import planarkin as pk
import pytest
from planarkin.reference import scene_sweep

NAMES = pk.scenes.names()
#: Seeded sketches per built-in scene.
SEEDS = 12
#: How far a sketched point may be from its exact place (a fraction of the scene's size).
SHIFT = 0.05


def size_of(d):
    return float(np.ptp(np.array(list(d["points"].values()), dtype=float), axis=0).max())


def offset(points, line, q):
    """Signed distance of point q from the line through line[0] -> line[1]."""
    a, b, p = (np.asarray(points[n], dtype=float) for n in (*line, q))
    u = (b - a) / math.dist(a, b)
    return float(u[0] * (p - a)[1] - u[1] * (p - a)[0])


def lengths_of(d):
    """`lengths` from an exact drawing: every pair of points of each moving link, each
    slot's offset where it has one, and for a prismatic pair nothing when its sliding link's
    first two points lie on the line, else the two of its points whose offsets fix its
    rotation best (the pair least square to the line)."""
    pts, size = d["points"], size_of(d)
    out = []
    for link, names in d["links"].items():
        if link != d["ground"]:
            out += [[a, b, math.dist(pts[a], pts[b])] for a, b in itertools.combinations(names, 2)]
    for name, s in d.get("slots", {}).items():
        e = offset(pts, s["line"], s["point"])
        if abs(e) > 1e-9 * size:
            out.append([s["point"], name, abs(e)])
    for name, s in d.get("prismatic", {}).items():
        names = d["links"][s["link"]]
        off = {q: offset(pts, s["line"], q) for q in names}
        if max(abs(off[names[0]]), abs(off[names[1]])) <= 1e-9 * size:
            continue
        pair = min(
            itertools.combinations(names, 2),
            key=lambda ab: abs(off[ab[0]] - off[ab[1]]) / math.dist(pts[ab[0]], pts[ab[1]]),
        )
        out += [[q, name, abs(off[q])] for q in pair]
    return out


def turned_over(d, sketch):
    """Whether the sketch draws some link mirrored (a triangle of its points, not flat, the
    other way round): it then sketches another linkage."""
    flat = 1e-9 * size_of(d) ** 2
    for names in d["links"].values():
        for a, b, c in itertools.combinations(names, 3):
            tri = [
                [np.asarray(p[n], dtype=float) for n in (a, b, c)] for p in (d["points"], sketch)
            ]
            s = [np.linalg.det(np.array([q[1] - q[0], q[2] - q[0]])) for q in tri]
            if abs(s[0]) > flat and s[0] * s[1] < 0:
                return True
    return False


def sketch_of(d, rng, shift=SHIFT):
    """The scene with its moving points shifted by up to ``shift`` of its size (uniform in
    a disc) and its lengths from the exact drawing; drawn again while a link is turned
    over."""
    ground, size = set(d["links"][d["ground"]]), size_of(d)
    while True:
        sk = copy.deepcopy(d)
        sk["lengths"] = lengths_of(d)
        for p, (x, y) in d["points"].items():
            if p not in ground:
                r, a = shift * size * math.sqrt(rng.random()), rng.random() * math.tau
                sk["points"][p] = [x + r * math.cos(a), y + r * math.sin(a)]
        if not turned_over(d, sk["points"]):
            return sk


def drive_of(d, points):
    """The input coordinate of a pose: the input link's angle, or a linear input's place
    along its line."""
    inp = d["input"]
    if "link" in inp:
        pivot = inp["pivot"]
        tip = next(q for q in d["links"][inp["link"]] if q != pivot)
        v = np.subtract(points[tip], points[pivot])
        return math.atan2(v[1], v[0])
    ((kind, name),) = inp.items()
    j = d["slots" if kind == "slot" else "prismatic"][name]
    q = j["point"] if kind == "slot" else d["links"][j["link"]][0]
    a, b = (np.asarray(points[n], dtype=float) for n in j["line"])
    return float(np.dot(np.subtract(points[q], a), (b - a) / math.dist(a, b)))


def signs(sc):
    """The signs of a scene's plan steps' conditioning at its drawn pose (its mode)."""
    t = sc.input_angle if sc.input_kind == "angle" else 0.0
    return np.sign(sc.sweep([t], outputs="all").step_det[0])


def gap(sc, pose, size):
    return max(math.dist(sc.points[n], pose[n]) for n in pose) / size


# --- every built-in, sketched -------------------------------------------------------------


@pytest.mark.parametrize("name", NAMES)
def test_a_sketched_builtin_assembles_to_its_exact_pose(name):
    d = pk.scenes.data(name)
    size = size_of(d)
    exact = pk.Scene.from_dict(d)
    kept = 0
    for seed in range(SEEDS):
        sk = sketch_of(d, np.random.default_rng(seed))
        t = drive_of(d, sk["points"])
        if exact.input_kind == "displacement":
            t -= drive_of(d, d["points"])
        ref = scene_sweep(d, [t], tol=1e-13)
        if ref.status[0] != 0:
            # the sketched input is past what the drawn circuit reaches: nothing near
            with pytest.raises(ValueError, match="no assembly near the sketch"):
                pk.Scene.from_dict(sk)
            continue
        own = pk.Scene.from_dict({k: v for k, v in sk.items() if k != "lengths"})
        drawn_mode = np.sign(exact.sweep([t], outputs="all").step_det[0])
        if not (signs(own) == drawn_mode).all():
            # the sketch draws another assembly mode: kept, or refused; never the drawn one
            try:
                sc = pk.Scene.from_dict(sk)
            except ValueError as e:
                assert "no assembly near the sketch" in str(e)
            else:
                assert (signs(sc) == signs(own)).all()
            continue
        sc = pk.Scene.from_dict(sk)
        truth = {n: ref.points[n][0] for n in d["points"]}
        assert gap(sc, truth, size) < 1e-12, seed
        assert (signs(sc) == signs(own)).all()
        for n in d["points"]:
            assert sc.moved[n] == pytest.approx(
                math.dist(sk["points"][n], truth[n]), abs=1e-12 * size
            )
        kept += 1
    assert kept >= SEEDS // 2, f"only {kept} of {SEEDS} sketches drew the scene's own mode"


# --- the assembly mode: the sketch's own, or refused ----------------------------------------


def circles(p, rp, q, rq, side):
    """The intersection of circle (p, rp) with circle (q, rq) on the left (side 1) or right
    (side -1) of p -> q."""
    p, q = np.asarray(p, dtype=float), np.asarray(q, dtype=float)
    u = q - p
    d = math.hypot(*u)
    a = (rp * rp - rq * rq + d * d) / (2 * d)
    h = math.sqrt(rp * rp - a * a)
    return p + a * u / d + side * h * np.array([-u[1], u[0]]) / d


def cross(u, v):
    return float(u[0] * v[1] - u[1] * v[0])


def fourbar(a, b):
    return {
        "points": {"O2": [0.0, 0.0], "O4": [6.0, 0.0], "A": list(a), "B": list(b)},
        "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"],
                  "rocker": ["O4", "B"]},
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O2"},
        "lengths": [["O2", "A", 2.0], ["A", "B", 5.0], ["O4", "B", 5.0]],
    }  # fmt: skip


@pytest.mark.parametrize("side", [1, -1])
def test_a_fourbar_sketched_in_either_mode_assembles_in_that_mode(side):
    rng = np.random.default_rng(7)
    done, modes = 0, set()
    for t in np.radians(np.arange(0.0, 360.0, 20.0)):
        a_s = 2.0 * np.array([math.cos(t), math.sin(t)]) + rng.uniform(-0.3, 0.3, 2)
        ts = math.atan2(a_s[1], a_s[0])  # the sketched input angle
        a = 2.0 * np.array([math.cos(ts), math.sin(ts)])
        o4 = np.array([6.0, 0.0])
        b = circles(a, 5.0, o4, 5.0, side)  # B left (1) or right (-1) of A -> O4
        b_s = b + rng.uniform(-0.6, 0.6, 2)  # up to 10% of the size
        height = cross(o4 - a, b_s - a)
        if abs(height) < 1.5:  # too near the dead point to say a side
            continue
        assert np.sign(height) == side
        sc = pk.Scene.from_dict(fourbar(a_s, b_s))
        assert math.dist(sc.points["B"], b) < 1e-12 * 6
        assert math.dist(sc.points["A"], a) < 1e-12 * 6
        assert sc.input_angle == pytest.approx(ts, abs=1e-14)
        assert sc.moved["B"] == pytest.approx(math.dist(b_s, b), abs=1e-12)
        # the four-bar's own name for it: open where sin(theta4 - theta3) > 0
        assert sc.as_fourbar().mode == ("open" if cross(b - a, b - o4) > 0 else "crossed")
        modes.add(sc.as_fourbar().mode)
        done += 1
    assert done >= 10 and len(modes) == 1


def test_each_assembly_of_a_stephenson_six_bar_is_what_its_sketch_gives():
    d = pk.scenes.data("stephenson3")
    exact = pk.Scene.from_dict(d)
    size = size_of(d)
    found = exact.assemblies()
    assert len(found) >= 2
    ground = set(d["links"][d["ground"]])
    rng = np.random.default_rng(3)
    for k, asm in enumerate(found):
        others = [o for j, o in enumerate(found) if j != k]
        sep = min(max(math.dist(asm[n], o[n]) for n in d["points"]) for o in others)
        noise = min(0.02 * size, sep / 8)
        sk = copy.deepcopy(d)
        sk["lengths"] = lengths_of(d)
        for n, (x, y) in asm.items():
            if n not in ground:
                sk["points"][n] = [x + noise * rng.uniform(-1, 1), y + noise * rng.uniform(-1, 1)]
        sc = pk.Scene.from_dict(sk)
        # the sketched input angle moved too: that assembly, carried to it by the reference
        ref = scene_sweep(pk.Scene.from_dict({**d, "points": asm}).to_dict(), [sc.input_angle],
                          tol=1e-13)  # fmt: skip
        assert ref.status[0] == 0
        assert gap(sc, {n: ref.points[n][0] for n in d["points"]}, size) < 1e-12, k


def six_bar(b, p, c):
    """A four-bar (crank O2-A at 0 rad, coupler A-B-P, rocker O4-B) with a dyad P-C-O6 on
    its coupler point, which closes only in the mode where B is above the ground."""
    return {
        "points": {"O2": [0.0, 0.0], "O4": [4.0, 0.0], "O6": [2.0, 3.0], "A": [1.0, 0.0],
                   "B": list(b), "P": list(p), "C": list(c)},
        "links": {"ground": ["O2", "O4", "O6"], "crank": ["O2", "A"], "coupler": ["A", "B", "P"],
                  "rocker": ["O4", "B"], "l5": ["P", "C"], "l6": ["O6", "C"]},
        "ground": "ground",
        "input": {"link": "crank", "pivot": "O2"},
        "lengths": [["O2", "A", 1.0], ["A", "B", 3.0], ["A", "P", 2.5], ["B", "P", 2.7],
                    ["O4", "B", 3.0], ["P", "C", 1.6], ["O6", "C", 1.6]],
    }  # fmt: skip


def test_a_sketch_whose_mode_cannot_close_is_refused_not_snapped_to_the_other():
    a, o4, o6 = [1.0, 0.0], [4.0, 0.0], [2.0, 3.0]
    # B above: P and C close (the truth by circle intersections)
    b = circles(a, 3.0, o4, 3.0, 1)
    p = circles(a, 2.5, b, 2.7, 1)
    c = circles(p, 1.6, o6, 1.6, 1)
    sc = pk.Scene.from_dict(six_bar(b + [0.2, -0.1], p + [-0.15, 0.2], c + [0.1, 0.1]))
    for n, q in (("B", b), ("P", p), ("C", c)):
        assert math.dist(sc.points[n], q) < 1e-12 * 4
    # B below: P is 3.46 from O6, beyond the dyad's reach (3.2). There is an assembly (B
    # above), but not in the mode sketched: refused, naming a link that cannot close.
    b2 = circles(a, 3.0, o4, 3.0, -1)
    p2 = circles(a, 2.5, b2, 2.7, 1)
    assert math.dist(p2, o6) > 3.2
    with pytest.raises(
        ValueError, match=r"^links\.(l5|l6|coupler|rocker): no assembly near the sketch"
    ):
        pk.Scene.from_dict(six_bar(b2 + [0.1, 0.1], p2, (p2 + o6) / 2 + [-0.5, -0.3]))


# --- lengths that cannot close, links left loose ----------------------------------------


def test_lengths_that_cannot_close_name_the_link():
    d = fourbar([2.0, 0.5], [4.0, 4.0])
    d["lengths"] = [["O2", "A", 2.0], ["A", "B", 1.5], ["O4", "B", 1.5]]  # 3 < |A O4|
    with pytest.raises(ValueError, match=r"^links\.(coupler|rocker): no assembly near the sketch"):
        pk.Scene.from_dict(d)
    sl = pk.scenes.data("slider-crank")
    sl["lengths"] = [["O2", "A", 40.0], ["A", "B", 10.0]]  # the rod cannot reach the slot
    with pytest.raises(ValueError, match=r"^links\.rod: no assembly near the sketch"):
        pk.Scene.from_dict(sl)


def test_a_triangle_that_cannot_close_names_its_link():
    d = pk.scenes.data("fourbar")
    d["lengths"] = [["O2", "A", 2], ["A", "B", 5], ["O4", "B", 5], ["A", "P", 1], ["B", "P", 1]]
    with pytest.raises(
        ValueError, match=r"^links\.coupler: its lengths cannot close: .* make no triangle"
    ):
        pk.Scene.from_dict(d)


@pytest.mark.parametrize(
    ("lengths", "message"),
    [
        ([["O2", "A", 2], ["A", "B", 5], ["O4", "B", 5], ["A", "P", 3]],
         r"^links\.coupler: its lengths leave it non-rigid: \[\"P\"\] not fixed"),
        ([["O2", "A", 2], ["A", "B", 5], ["A", "P", 3], ["B", "P", 3]],
         r"^links\.rocker: has no lengths"),
        ([], r"^links\.crank: has no lengths"),
    ],
)  # fmt: skip
def test_a_link_left_non_rigid_is_named(lengths, message):
    d = pk.scenes.data("fourbar")
    d["lengths"] = lengths
    with pytest.raises(ValueError, match=message):
        pk.Scene.from_dict(d)


def test_a_sketch_drawn_at_a_dead_point_is_refused():
    d = fourbar([2.0, 0.0], [4.0, 0.0])  # A, B and O4 in line: which side B goes is unsaid
    with pytest.raises(
        ValueError, match=r"^links\.(coupler|rocker): the sketch is drawn at a dead point.*\"B\""
    ):
        pk.Scene.from_dict(d)


# --- bad lengths: one line naming the entry, nothing made ----------------------------------

GOOD = [["O2", "A", 2], ["A", "B", 5], ["O4", "B", 5], ["A", "P", 3], ["B", "P", 3]]


@pytest.mark.parametrize(
    ("lengths", "message"),
    [
        (5, r"^lengths: must be a list of \[name, name, length\]"),
        ({"A": 1}, r"^lengths: must be a list"),
        ([["A", "B"]], r"^lengths\[0\]: must be \[name, name, length\]"),
        ([["A", "B", 5, 6]], r"^lengths\[0\]: must be \[name, name, length\]"),
        ([["A", 3, 5]], r"^lengths\[0\]: must be \[name, name, length\]"),
        ("AB5", r"^lengths: must be a list"),
        ([["A", "B", "5"]], r"^lengths\[0\]: the length must be a real number"),
        ([["A", "B", True]], r"^lengths\[0\]: the length must be a real number"),
        ([["A", "B", 2**2000]], r"^lengths\[0\]: the length must be a real number within the"),
        (GOOD + [["A", "Q", 1]], r"^lengths\[5\]: unknown point \"Q\""),
        (GOOD + [["A", "A", 1]], r"^lengths\[5\]: names \"A\" twice"),
        (GOOD + [["O2", "B", 4]], r"^lengths\[5\]: \"O2\" and \"B\" are on no common link"),
        ([["O2", "A", 0]] + GOOD[1:],
         r"^lengths\[0\]: the distance between \"O2\" and \"A\" must be > 0, got 0"),
        ([["O2", "A", -2]] + GOOD[1:], r"^lengths\[0\]: .* must be > 0, got -2"),
        ([["O2", "A", math.nan]] + GOOD[1:], r"^lengths\[0\]: the length must be finite, got NaN"),
        ([["O2", "A", math.inf]] + GOOD[1:], r"^lengths\[0\]: the length must be finite, got inf"),
        (GOOD + [["B", "A", 5.5]], r"^lengths\[5\]: gives \|B A\| = 5.5, but lengths\[1\] gave 5"),
        (GOOD + [["O2", "O4", 7]],
         r"^lengths\[5\]: \"O2\" and \"O4\" are ground points, which stay as drawn \(6 apart\)"),
        (GOOD + [["A", "B", "P"]], r"^lengths\[5\]: the length must be a real number"),
    ],
)  # fmt: skip
def test_bad_lengths_name_the_entry(lengths, message):
    d = pk.scenes.data("fourbar")
    d["lengths"] = lengths
    before = json.dumps(d)
    with pytest.raises(ValueError, match=message) as e:
        pk.Scene.from_dict(d)
    assert "\n" not in str(e.value)
    assert json.dumps(d) == before  # the data given is left as it was


def test_equal_duplicates_and_agreeing_ground_lengths_are_accepted():
    d = pk.scenes.data("fourbar")
    d["lengths"] = GOOD + [["B", "A", 5.0], ["O4", "O2", 6.0]]
    sc = pk.Scene.from_dict(d)
    assert sc.lengths[-1] == ("O4", "O2", 6.0)


@pytest.mark.parametrize(
    ("name", "extra", "message"),
    [
        ("slider-crank", [["A", "piston", 1.0]],
         r"^lengths\[2\]: \"A\" is not the pin of slot \"piston\""),
        ("slider-crank", [["B", "piston", -1.0]],
         r"^lengths\[2\]: the distance of \"B\" from the line of \"piston\" must be >= 0"),
        ("slider-crank", [["B", "piston", 1.0], ["piston", "B", 2.0]],
         r"^lengths\[3\]: gives the distance of \"B\" from the line of \"piston\" as 2"),
        ("scotch-yoke", [["A", "guide", 1.0], ["R", "guide", 0.0]],
         r"^lengths\[\d\]: \"A\" is not a point of \"yoke\""),
        ("scotch-yoke", [["Y1", "guide", 60.0]],
         r"^prismatic\.guide: a sketch holds two points of its sliding link \"yoke\""),
        ("scotch-yoke", [["pin", "guide", 60.0]], r"^lengths\[\d\]: names two joints"),
    ],
)  # fmt: skip
def test_bad_slider_lengths_name_the_entry(name, extra, message):
    d = pk.scenes.data(name)
    d["lengths"] = [
        e for e in lengths_of(d) if e[1] not in d.get("slots", {}) | d.get("prismatic", {})
    ]
    d["lengths"] += extra
    with pytest.raises(ValueError, match=message):
        pk.Scene.from_dict(d)


def test_a_bad_sketch_file_names_the_file(tmp_path):
    d = pk.scenes.data("fourbar")
    d["lengths"] = GOOD[:-1]
    path = tmp_path / "loose.json"
    path.write_text(json.dumps(d))
    with pytest.raises(
        ValueError, match=r"loose\.json: links\.coupler: its lengths leave it non-rigid"
    ):
        pk.Scene.load(path)


def test_more_moving_points_than_a_sketch_may_have_are_refused():
    from test_scale_and_size import dyad_chain

    d = dyad_chain(600)
    d["lengths"] = lengths_of(d)
    with pytest.raises(
        ValueError,
        match=r"^lengths: the sketch has 603 moving points; a sketch may have at most 500",
    ):
        pk.Scene.from_dict(d)


# --- sliders in a sketch --------------------------------------------------------------------


def test_a_slot_pin_lies_on_its_line_unless_lengths_give_its_offset():
    d = pk.scenes.data("slider-crank-offset")  # e = 20 as built
    d["points"]["A"] = [30.0, 25.0]
    d["points"]["B"] = [185.0, -14.0]  # sketched below the line
    r, rod = 40.0, 160.0
    d["lengths"] = [["O2", "A", r], ["A", "B", rod]]
    t = math.atan2(25.0, 30.0)
    for e, lengths in ((0.0, []), (-20.0, [["B", "piston", 20.0]])):
        sc = pk.Scene.from_dict({**d, "lengths": d["lengths"] + lengths})
        x = r * math.cos(t) + math.sqrt(rod**2 - (r * math.sin(t) - e) ** 2)
        assert math.dist(sc.points["B"], (x, e)) < 1e-12 * rod
    d["points"]["B"] = [185.0, 0.0]  # on the line: which side is unsaid
    with pytest.raises(ValueError, match=r"^slots\.piston: \"B\" is sketched on the line"):
        pk.Scene.from_dict({**d, "lengths": d["lengths"] + [["B", "piston", 20.0]]})


def test_a_scotch_yoke_sketch_holds_the_two_points_lengths_place():
    d = pk.scenes.data("scotch-yoke")
    r = math.hypot(*d["points"]["A"])
    rng = np.random.default_rng(5)
    for p in ("A", "Y1", "Y2", "R"):
        d["points"][p] = list(np.add(d["points"][p], rng.uniform(-8, 8, 2)))
    side = math.hypot(120, 60)
    d["lengths"] = [["O2", "A", r], ["Y1", "Y2", 120.0], ["Y1", "R", side], ["Y2", "R", side],
                    ["R", "guide", 0.0], ["Y1", "guide", 60.0]]  # fmt: skip
    sc = pk.Scene.from_dict(d)
    t = math.atan2(d["points"]["A"][1], d["points"]["A"][0])
    x = r * math.cos(t)  # the yoke moves exactly r cos t
    assert math.dist(sc.points["A"], (x, r * math.sin(t))) < 1e-12 * r
    for n, q in (("Y1", (x, -60.0)), ("Y2", (x, 60.0)), ("R", (x + 120.0, 0.0))):
        assert math.dist(sc.points[n], q) < 1e-12 * r


def test_a_cylinder_rod_lies_in_its_barrel_by_default():
    d = pk.scenes.data("hydraulic-boom")
    assert not any(e[1] == "cylinder" for e in lengths_of(d))  # rod R-E on the barrel line
    size = size_of(d)
    sk = sketch_of(d, np.random.default_rng(11))
    sc = pk.Scene.from_dict(sk)
    for q in ("R", "E"):
        assert abs(offset(sc.points, ("C1", "C2"), q)) < 1e-12 * size
    # O, E and T of the boom are in line: the flat triangle stays flat
    assert abs(offset(sc.points, ("O", "T"), "E")) < 1e-12 * size


# --- what the loaded scene holds ---------------------------------------------------------


@pytest.mark.parametrize("name", ["jansen", "scotch-yoke", "slider-crank-offset", "hydraulic-boom"])
@pytest.mark.parametrize("suffix", [".json", ".toml"])
def test_round_trips_keep_the_lengths_and_the_exact_pose(name, suffix, tmp_path):
    sk = sketch_of(pk.scenes.data(name), np.random.default_rng(2))
    sc = pk.Scene.from_dict(sk)
    assert sc.lengths == tuple((a, b, float(v)) for a, b, v in sk["lengths"])
    back = pk.Scene.load(sc.save(tmp_path / f"s{suffix}"))
    assert back.lengths == sc.lengths
    assert back.points == sc.points  # the exact pose, read back as it was written
    assert max(back.moved.values()) == 0.0
    assert back.to_dict() == {**sc.to_dict(), "name": sc.name or "s"}
    d = sc.to_dict()
    assert d["lengths"] == [list(e) for e in sc.lengths]
    assert d["points"] == {n: list(p) for n, p in sc.points.items()}


def test_a_scene_without_lengths_moved_nothing():
    sc = pk.scenes.load("jansen")
    assert sc.lengths is None and "lengths" not in sc.to_dict()
    assert set(sc.moved) == set(sc.points) and not any(sc.moved.values())


def test_moved_says_how_far_each_point_went():
    d = pk.scenes.data("fourbar")
    d["lengths"] = lengths_of(d)
    d["points"]["B"] = [4.3, 4.2]
    d["points"]["P"] = [1.0, 3.5]
    sc = pk.Scene.from_dict(d)
    exact = pk.scenes.load("fourbar")  # drawn at this input angle with these lengths
    for n in d["points"]:
        assert sc.moved[n] == pytest.approx(math.dist(d["points"][n], exact.points[n]), abs=1e-12)
        assert math.dist(sc.points[n], exact.points[n]) < 1e-12 * 6
    assert sc.moved["O2"] == sc.moved["O4"] == sc.moved["A"] == 0.0


def test_a_sketched_scene_moves_and_redraws_like_the_exact_one():
    d = pk.scenes.data("watt2")
    sc = pk.Scene.from_dict(sketch_of(d, np.random.default_rng(4)))
    exact = pk.Scene.from_dict(d)
    size = size_of(d)
    t = sc.input_angle + np.linspace(0.0, 1.0, 5)
    a, b = sc.sweep(t, outputs="all"), exact.sweep(t, outputs="all")
    for n in d["points"]:
        assert float(np.abs(a.points[n] - b.points[n]).max()) < 1e-12 * size
    other = sc.at({n: tuple(b.points[n][2]) for n in d["points"]})
    assert other.lengths == sc.lengths and max(other.moved.values()) < 1e-12 * size


# --- the drawing's scale and placement --------------------------------------------------


def test_a_sketch_scaled_by_a_power_of_two_assembles_bit_for_bit_scaled():
    d = pk.scenes.data("jansen")
    sk = sketch_of(d, np.random.default_rng(9))
    base = pk.Scene.from_dict(sk)
    for f in (2.0**-30, 2.0**40):
        sc = pk.Scene.from_dict({
            **sk,
            "points": {n: [x * f, y * f] for n, (x, y) in sk["points"].items()},
            "lengths": [[a, b, v * f] for a, b, v in sk["lengths"]],
        })  # fmt: skip
        assert sc.points == {n: (x * f, y * f) for n, (x, y) in base.points.items()}


def test_a_sketch_turned_and_moved_assembles_turned_and_moved():
    d = pk.scenes.data("whitworth")
    sk = sketch_of(d, np.random.default_rng(6))
    base = pk.Scene.from_dict(sk)
    c, s, shift = math.cos(0.7), math.sin(0.7), np.array([1e3, -2e3])

    def move(p):
        return [c * p[0] - s * p[1] + shift[0], s * p[0] + c * p[1] + shift[1]]

    sc = pk.Scene.from_dict({**sk, "points": {n: move(p) for n, p in sk["points"].items()}})
    size = size_of(d)
    for n in d["points"]:
        assert math.dist(sc.points[n], move(base.points[n])) < 1e-12 * size
