"""In a notebook a Scene, a FourBar and a sweep show themselves as a small picture
(``_repr_svg_``, a few KB of SVG) beside a short one-line repr (issue 20, item 17)."""

from __future__ import annotations

import itertools
import xml.etree.ElementTree as ET

import numpy as np
import planarkin as pk
import pytest

NS = "{http://www.w3.org/2000/svg}"


def parse(svg: str) -> ET.Element:
    assert len(svg) < 8_000  # small: a few KB
    root = ET.fromstring(svg)
    assert root.tag == f"{NS}svg"
    return root


def circles(root: ET.Element) -> dict[str, np.ndarray]:
    """Point name -> its circle's centre, from each circle and the label after it."""
    kids = list(root)
    out = {}
    for a, b in itertools.pairwise(kids):
        if a.tag == f"{NS}circle" and b.tag == f"{NS}text":
            out[b.text] = np.array([float(a.get("cx")), -float(a.get("cy"))])
    return out


@pytest.mark.parametrize("name", ["jansen", "double-butterfly-2", "fourbar"])
def test_scene_picture_draws_every_link_and_point_to_scale(name):
    sc = pk.scenes.load(name)
    root = parse(sc._repr_svg_())
    links = [e for e in root.iter() if e.get("class") == "link"]
    assert len(links) == len(sc.links) - 1  # every moving link; ground as supports
    drawn = circles(root)
    assert set(drawn) == set(sc.points)
    # one scale for every distance (y flipped back above): the picture is the drawing
    names = sorted(sc.points)
    scales = [
        np.hypot(*(drawn[a] - drawn[b])) / np.hypot(*np.subtract(sc.points[a], sc.points[b]))
        for a, b in itertools.combinations(names, 2)
        if np.hypot(*np.subtract(sc.points[a], sc.points[b])) > 0.2 * np.ptp(
            np.array(list(sc.points.values())), axis=0).max()
    ]  # fmt: skip
    assert max(scales) / min(scales) < 1.02  # coordinates written to 0.1 px


def test_fourbar_and_sweeps_show_pictures():
    fb = pk.FourBar(6, 2, 5, 5)
    root = parse(fb._repr_svg_())
    assert len([e for e in root.iter() if e.get("class") == "link"]) == 3
    assert repr(fb) == "FourBar(r1=6.0, r2=2.0, r3=5.0, r4=5.0)"
    for sw in (fb.sweep(), pk.scenes.load("jansen").sweep(outputs="all")):
        root = parse(sw._repr_svg_())
        assert root.findall(f"{NS}polyline")  # the paths of the moving points
        assert "\n" not in repr(sw) and len(repr(sw)) < 200
    assert pk.FourBar(1, 5, 1, 1)._repr_svg_() is None  # cannot assemble: no picture
