"""Cutting sheets read back by their own parsers: ezdxf for DXF (every hole centre where
the part's placement puts the scene's point, to 1e-9; parts rigid and apart), xml.etree
for SVG (one path per part, hairlines, real units)."""

from __future__ import annotations

import itertools
import math
import xml.etree.ElementTree as ET

import numpy as np
import planarkin as pk
import pytest
from planarkin.face.cli import main
from planarkin.interop import _lines, sheet, svg

SCENES = ["fourbar", "slider-crank", "jansen", "double-butterfly-1", "whitworth", "scotch-yoke"]


def expected_holes(sc: pk.Scene, sh: sheet.Sheet) -> dict[str, np.ndarray]:
    """Part -> its hole centres, placed by the part's rotation and shift (written out here)."""
    out = {}
    skip = _lines.helpers(sc)
    for part in sh.parts:
        c, s = math.cos(part.angle), math.sin(part.angle)
        rot = np.array([[c, -s], [s, c]])
        xy = np.array([sc.points[p] for p in sc.links[part.name] if p not in skip])
        out[part.name] = xy @ rot.T + np.array(part.shift)
    return out


def boxes_apart(boxes: list[tuple[float, float, float, float]]) -> bool:
    return all(
        a[2] <= b[0] or b[2] <= a[0] or a[3] <= b[1] or b[3] <= a[1]
        for a, b in itertools.combinations(boxes, 2)
    )


@pytest.mark.parametrize("name", SCENES)
def test_dxf_holes_at_the_scene_points(name: str, tmp_path) -> None:  # noqa: ANN001
    ezdxf = pytest.importorskip("ezdxf", reason="the dxf extra (ezdxf) is not installed")
    from ezdxf import bbox

    sc = pk.scenes.load(name)
    path = tmp_path / f"{name}.dxf"
    assert main(["export", name, "--to", str(path)]) == 0
    sh = sheet.layout(sc)
    doc = ezdxf.readfile(path)
    assert doc.dxfversion == "AC1024"  # R2010
    msp = doc.modelspace()
    cut = msp.query("LWPOLYLINE[layer=='CUT']")
    assert len(cut) == len(sc.links) == len(sh.parts)
    circles = msp.query("CIRCLE[layer=='HOLES']")
    got = np.array([(c.dxf.center.x, c.dxf.center.y) for c in circles])
    want = np.concatenate(list(expected_holes(sc, sh).values()))
    assert got.shape == want.shape
    gap = np.hypot(*(got[:, None, :] - want[None, :, :]).transpose(2, 0, 1))
    assert gap.min(axis=0).max() <= 1e-9 and gap.min(axis=1).max() <= 1e-9  # one to one
    assert all(abs(c.dxf.radius - sh.hole / 2) < 1e-12 for c in circles)
    # each part is the scene's link moved rigidly: its holes keep the link's distances
    skip = _lines.helpers(sc)
    for part, xy in expected_holes(sc, sh).items():
        pts = [sc.points[p] for p in sc.links[part] if p not in skip]
        for i, j in itertools.combinations(range(len(pts)), 2):
            assert math.dist(xy[i], xy[j]) == pytest.approx(math.dist(pts[i], pts[j]), abs=1e-9)
    # outlines do not overlap, each hole lies inside its own outline with the bar around it
    boxes = []
    for e in cut:
        b = bbox.extents([e])
        boxes.append((b.extmin.x, b.extmin.y, b.extmax.x, b.extmax.y))
    assert boxes_apart(boxes)
    assert {t.dxf.text for t in msp.query("TEXT[layer=='LABELS']")} >= set(sc.links)
    assert doc.header["$INSUNITS"] == 4  # mm
    scale = msp.query("LINE[layer=='SCALE']")
    (x0, y0), (x1, _), length = sh.scale
    assert any(abs(ln.dxf.end.x - ln.dxf.start.x - length) < 1e-9 for ln in scale)


def test_dxf_outlines_are_the_grown_hulls(tmp_path) -> None:  # noqa: ANN001
    """Every outline's arcs are centred on a hole of its part with radius width / 2, its
    straight edges run at width / 2 from the part's holes (a bar between two pins, a plate
    round its three)."""
    ezdxf = pytest.importorskip("ezdxf", reason="the dxf extra (ezdxf) is not installed")
    from planarkin.interop import dxf

    sc = pk.scenes.load("jansen")
    sh = sheet.layout(sc, width=4.0, hole=1.5, margin=2.0)
    doc = ezdxf.readfile(dxf.write(sh, tmp_path / "j.dxf"))
    holes = np.concatenate(list(expected_holes(sc, sh).values()))
    arcs = lines = 0
    for e in doc.modelspace().query("LWPOLYLINE[layer=='CUT']"):
        for piece in e.virtual_entities():
            if piece.dxftype() == "ARC":
                c = np.array([piece.dxf.center.x, piece.dxf.center.y])
                assert np.hypot(*(holes - c).T).min() <= 1e-9
                assert piece.dxf.radius == pytest.approx(2.0, abs=1e-9)
                arcs += 1
            else:
                a = np.array([piece.dxf.start.x, piece.dxf.start.y])
                b = np.array([piece.dxf.end.x, piece.dxf.end.y])
                for q in (a, b):  # its ends stand width / 2 off the nearest hole
                    assert np.hypot(*(holes - q).T).min() == pytest.approx(2.0, abs=1e-9)
                lines += 1
    assert arcs == lines == 2 * 6 + 3 * 2  # six bars, two triangles


@pytest.mark.parametrize("name", SCENES)
def test_svg_reads_back(name: str, tmp_path) -> None:  # noqa: ANN001
    sc = pk.scenes.load(name)
    sh = sheet.layout(sc)
    root = ET.parse(svg.write(sh, tmp_path / "s.svg")).getroot()
    ns = {"s": "http://www.w3.org/2000/svg"}
    w, h = sh.size
    assert root.get("width") == f"{w!r}mm" and root.get("height") == f"{h!r}mm"
    assert root.get("viewBox") == f"0 0 {w!r} {h!r}"
    cut = root.find("s:g[@id='cut']", ns)
    assert cut is not None and cut.get("stroke-width") == "0.01"
    paths = cut.findall("s:path", ns)
    assert sorted(p.get("id") for p in paths) == sorted(f"part-{n}" for n in sc.links)
    holes = root.findall("s:g[@id='holes']/s:circle", ns)
    want = expected_holes(sc, sh)
    seen = 0
    for c in holes:
        part, point = c.get("data-part"), c.get("data-point")
        i = [p for p in sc.links[part] if p not in _lines.helpers(sc)].index(point)
        x, y = want[part][i]
        assert float(c.get("cx")) == pytest.approx(x, abs=1e-9)
        assert float(c.get("cy")) == pytest.approx(h - y, abs=1e-9)  # SVG's y runs down
        seen += 1
    assert seen == sum(len(v) for v in want.values())
    labels = [t.text for t in root.findall("s:g[@id='labels']/s:text", ns)]
    assert sorted(labels) == sorted(sc.links)


def test_slot_cut_out_spans_the_pin_travel() -> None:
    sc = pk.scenes.load("slider-crank")  # piston pin B: x from l - r to l + r on the ground
    ends = sheet.travel(sc)["piston"]
    xs = sorted(p[0] for p in ends)
    assert xs == pytest.approx([120.0, 200.0], abs=1e-9)
    assert all(p[1] == 0.0 for p in ends)


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--width", "2", "--hole", "3"], r"hole \(3\) must be smaller than width \(2\)"),
        (["--width", "-1"], r"--width must be"),
        (["--margin", "nan"], r"--margin must be"),
    ],
)
def test_bad_sizes(args: list, message: str, tmp_path, capsys) -> None:  # noqa: ANN001
    assert main(["export", "fourbar", "--to", str(tmp_path / "a.svg"), *args]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and pytest.importorskip("re").search(message, err)


def test_missing_extra_names_its_pip_command(tmp_path, capsys, monkeypatch) -> None:  # noqa: ANN001
    import sys

    monkeypatch.setitem(sys.modules, "ezdxf", None)  # as if not installed
    assert main(["export", "fourbar", "--to", str(tmp_path / "a.dxf")]) == 1
    err = capsys.readouterr().err
    assert (
        err == 'planarkin: error: a DXF cutting sheet needs ezdxf: pip install "planarkin[dxf]"\n'
    )
