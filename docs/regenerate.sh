#!/usr/bin/env bash
# Regenerates the README's images (docs/*.png, docs/linkage.gif) and the captured
# `planarkin analyze` output (docs/analyze_output.txt) with the CLI itself, at a small
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
from pathlib import Path

from PIL import Image

for png in Path(sys.argv[1]).glob("figure_*.png"):
    with Image.open(png) as im:
        small = im.convert("RGB").quantize(colors=96, method=Image.Quantize.MEDIANCUT)
    small.save(png, optimize=True, dpi=(80, 80))
PY
ls -l "$docs"
