"""Cutting sheets as DXF (R2010, through ezdxf: the optional extra ``dxf``): each part's
outline a closed LWPOLYLINE on layer CUT, its pin holes CIRCLEs on layer HOLES, names on
LABELS, the scale bar on SCALE; 1:1 in the scene's unit ($INSUNITS)."""

from __future__ import annotations

from pathlib import Path

from ._extras import need
from .sheet import Sheet

#: $INSUNITS codes of the units a sheet may be in.
INSUNITS = {"in": 1, "mm": 4, "cm": 5, "m": 6}
LAYERS = {"CUT": 1, "HOLES": 5, "LABELS": 3, "SCALE": 7}  # ACI colours: red, blue, green


def write(sheet: Sheet, path: str | Path) -> Path:
    """Writes the sheet as a DXF file; returns the path."""
    ezdxf = need("ezdxf", "dxf", "a DXF cutting sheet")
    doc = ezdxf.new("R2010", setup=True)
    doc.header["$INSUNITS"] = INSUNITS[sheet.units]
    doc.header["$MEASUREMENT"] = 0 if sheet.units == "in" else 1
    for name, colour in LAYERS.items():
        doc.layers.add(name, color=colour)
    msp = doc.modelspace()
    text_h = sheet.width * 0.5
    for part in sheet.parts:
        msp.add_lwpolyline(part.outline, format="xyb", close=True, dxfattribs={"layer": "CUT"})
        for x, y in part.holes.values():
            msp.add_circle((x, y), sheet.hole / 2, dxfattribs={"layer": "HOLES"})
        for outline in part.slots.values():
            msp.add_lwpolyline(outline, format="xyb", close=True, dxfattribs={"layer": "HOLES"})
        size = part.label_size
        label = msp.add_text(part.name, height=size, dxfattribs={"layer": "LABELS"})
        label.set_placement(part.label, align=ezdxf.enums.TextEntityAlignment.MIDDLE_CENTER)
    (x0, y0), (x1, y1), length = sheet.scale
    tick = sheet.width * 0.5
    msp.add_line((x0, y0), (x1, y1), dxfattribs={"layer": "SCALE"})
    for x in (x0, (x0 + x1) / 2, x1):
        msp.add_line((x, y0), (x, y0 + tick), dxfattribs={"layer": "SCALE"})
    label = msp.add_text(f"{length:g} {sheet.units}", height=text_h, dxfattribs={"layer": "SCALE"})
    label.set_placement((x1 + tick, y0), align=ezdxf.enums.TextEntityAlignment.MIDDLE_LEFT)
    title = msp.add_text(sheet.title, height=text_h, dxfattribs={"layer": "LABELS"})
    title.set_placement((x0, y0 + 2.5 * tick), align=ezdxf.enums.TextEntityAlignment.BOTTOM_LEFT)
    p = Path(path)
    doc.saveas(p)
    return p
