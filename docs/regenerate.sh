#!/usr/bin/env bash
# Regenerates the images of the README and the site (docs/*.png, docs/linkage.gif) and the
# captured `planarkin analyze` output (docs/analyze_output.txt) with the CLI itself, at a small
# size: figures at 80 dpi instead of 300, palette-quantised; a short, low-dpi animation.
set -euo pipefail
docs=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
planarkin analyze --dpi 80 > "$docs/analyze_output.txt"
planarkin animate --frames 36 --fps 9 --dpi 60 --out anim > /dev/null
cp figures/*.png anim/linkage.gif "$docs/"
python - "$docs" <<'PY'
import sys

import planarkin as pk
from planarkin.face.figures import circuits, scene

docs = sys.argv[1]
for name, file in (("jansen", "scene_jansen"), ("double-butterfly-1", "scene_double_butterfly")):
    sc = pk.scenes.load(name)
    fig = scene.linkage(sc, sc.sweep(outputs="all"), poses=4)
    fig.savefig(f"{docs}/{file}.png", dpi=70)
for name, file in (
    ("stephenson3", "circuits_stephenson3"),
    ("double-butterfly-2", "circuits_double_butterfly"),
):
    sc = pk.scenes.load(name)
    fig = circuits.circuits(sc, sc.circuits(), sc.input_angle)
    fig.savefig(f"{docs}/{file}.png", dpi=60)
PY
python - "$docs" <<'PY'
import sys
from pathlib import Path

from PIL import Image

for png in [*Path(sys.argv[1]).glob("figure_*.png"), *Path(sys.argv[1]).glob("scene_*.png"), *Path(sys.argv[1]).glob("circuits_*.png")]:
    with Image.open(png) as im:
        small = im.convert("RGB").quantize(colors=96, method=Image.Quantize.MEDIANCUT)
    small.save(png, optimize=True, dpi=(80, 80))
PY
ls -l "$docs"
