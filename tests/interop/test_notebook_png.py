"""Notebook pictures as PNG beside SVG (``_repr_png_``): FourBar, Scene and every sweep;
decoded by Pillow, 320 x 240, each joint drawn where the SVG puts it; a scene sweep's
picture draws its links."""

from __future__ import annotations

import io
import xml.etree.ElementTree as ET

import numpy as np
import planarkin as pk
import pytest

NS = "{http://www.w3.org/2000/svg}"


def objects() -> list:
    fb = pk.FourBar(6, 2, 5, 5)
    return [
        fb,
        fb.sweep(),
        pk.scenes.load("jansen"),
        pk.scenes.load("jansen").sweep(outputs="all"),
        pk.scenes.load("slider-crank").sweep(),
        pk.scenes.load("hydraulic-boom").sweep(),
    ]


@pytest.mark.parametrize("i", range(6))
def test_png_matches_the_svg(i: int) -> None:
    from PIL import Image

    obj = objects()[i]
    data = obj._repr_png_()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    im = np.asarray(Image.open(io.BytesIO(data)).convert("L"), dtype=float)
    assert im.shape == (240, 320)
    root = ET.fromstring(obj._repr_svg_())
    joints = [(float(c.get("cx")), float(c.get("cy"))) for c in root.iter(f"{NS}circle")]
    assert joints
    for x, y in joints:  # a dark ring round a white centre, where the SVG has its circle
        r, c = round(y), round(x)
        ring = im[r - 4 : r + 5, c - 4 : c + 5]
        assert ring.min() < 110, (x, y)
        alone = all(np.hypot(x - u, y - v) > 10 for u, v in joints if (u, v) != (x, y))
        assert im[r, c] > 180 or not alone, (x, y)  # (a neighbour's label may cover it)


def test_scene_sweep_picture_draws_its_links() -> None:
    sc = pk.scenes.load("jansen")
    root = ET.fromstring(sc.sweep(outputs="all")._repr_svg_())
    links = [e for e in root.iter() if e.get("class") == "link"]
    assert len(links) == len(sc.links) - 1  # every moving link; ground as supports
    # with only the crank pin reported (and no declared output, whose link a plan keeps),
    # the crank alone has all its points
    d = pk.scenes.load("fourbar").to_dict()
    d.pop("output", None)
    root = ET.fromstring(pk.Scene.from_dict(d).sweep(outputs=["A"])._repr_svg_())
    assert len([e for e in root.iter() if e.get("class") == "link"]) == 1


def test_no_picture_when_nothing_assembles() -> None:
    assert pk.FourBar(1, 5, 1, 1)._repr_png_() is None
