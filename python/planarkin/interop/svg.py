"""Cutting sheets as SVG for laser cutters: one path per outline (arcs as SVG arcs),
circles for the pin holes, hairline strokes, names and the scale bar in groups of their
own; ``width``/``height`` in real units, so the sheet prints and cuts at 1:1."""

from __future__ import annotations

import math
from pathlib import Path
from xml.sax.saxutils import escape

from .sheet import Sheet

#: Hairline: what laser cutters read as "cut" (0.01 mm; 0.001 in).
HAIRLINE = {"mm": 0.01, "cm": 0.001, "m": 0.00001, "in": 0.001}
_STYLE = 'fill="none" stroke="{}" stroke-width="{}"'


def _path(sheet: Sheet, outline: tuple[tuple[float, float, float], ...]) -> str:
    h = sheet.size[1]
    n = len(outline)
    x, y, _ = outline[0]
    d = [f"M {x!r} {h - y!r}"]
    for i in range(n):
        x0, y0, bulge = outline[i]
        x1, y1, _ = outline[(i + 1) % n]
        if bulge == 0.0:
            d.append(f"L {x1!r} {h - y1!r}")
            continue
        theta = 4 * math.atan(abs(bulge))
        r = math.hypot(x1 - x0, y1 - y0) / (2 * math.sin(theta / 2))
        large = 1 if theta > math.pi else 0
        sweep = 0 if bulge > 0 else 1  # y flips: counter-clockwise on the sheet is sweep 0
        d.append(f"A {r!r} {r!r} 0 {large} {sweep} {x1!r} {h - y1!r}")
    return " ".join(d) + " Z"


def text(sheet: Sheet) -> str:
    """The sheet as an SVG document."""
    w, h = sheet.size
    u = sheet.units
    hair = HAIRLINE[u]
    font = sheet.width * 0.5
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{w!r}{u}" height="{h!r}{u}" '
        f'viewBox="0 0 {w!r} {h!r}">',
        f"<title>{escape(sheet.title)}: cutting sheet, 1:1 in {u}</title>",
        f'<g id="cut" {_STYLE.format("#ff0000", hair)}>',
    ]
    for part in sheet.parts:
        out.append(f'<path id="part-{escape(part.name)}" d="{_path(sheet, part.outline)}"/>')
    out.append("</g>")
    out.append(f'<g id="holes" {_STYLE.format("#0000ff", hair)}>')
    for part in sheet.parts:
        for p, (x, y) in part.holes.items():
            out.append(
                f'<circle data-part="{escape(part.name)}" data-point="{escape(p)}" '
                f'cx="{x!r}" cy="{h - y!r}" r="{sheet.hole / 2!r}"/>'
            )
        for n, outline in part.slots.items():
            out.append(f'<path data-slot="{escape(n)}" d="{_path(sheet, outline)}"/>')
    out.append("</g>")
    out.append(f'<g id="labels" fill="#00a000" font-size="{font!r}" text-anchor="middle" '
               'dominant-baseline="middle" font-family="sans-serif">')  # fmt: skip
    for part in sheet.parts:
        x, y = part.label
        out.append(
            f'<text x="{x!r}" y="{h - y!r}" font-size="{part.label_size!r}">'
            f"{escape(part.name)}</text>"
        )
    out.append("</g>")
    (x0, y0), (x1, _), length = sheet.scale
    tick = sheet.width * 0.5
    ticks = " ".join(f"M {x!r} {h - y0!r} v {-tick!r}" for x in (x0, (x0 + x1) / 2, x1))
    out.append(f'<g id="scale" {_STYLE.format("#000000", hair)}>')
    out.append(f'<path d="M {x0!r} {h - y0!r} H {x1!r} {ticks}"/>')
    out.append(f'<text x="{x1 + tick!r}" y="{h - y0!r}" font-size="{font!r}" fill="#000000" '
               f'stroke="none">{length:g} {u}</text>')  # fmt: skip
    out.append("</g>")
    out.append("</svg>")
    return "\n".join(out) + "\n"


def write(sheet: Sheet, path: str | Path) -> Path:
    """Writes the sheet as an SVG file; returns the path."""
    p = Path(path)
    p.write_text(text(sheet), encoding="utf-8")
    return p
