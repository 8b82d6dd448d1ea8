"""
A cutting sheet of Jansen's leg, and the leg as Pyslvs writes it
================================================================

``planarkin export jansen --to leg.dxf`` (or ``leg.svg``) lays every link out as a part to
cut: rounded bars between pins, plates with rounded corners, pin holes, at 1:1. Here the
same sheet (``planarkin.interop.sheet.layout``) drawn with matplotlib, and the leg written
as a Pyslvs expression and read back.
"""

import math

import matplotlib.pyplot as plt
import numpy as np
import planarkin as pk
from planarkin.interop import pyslvs, sheet

sc = pk.scenes.load("jansen")
sh = sheet.layout(sc)


def outline_xy(outline, n=24):
    """The outline's points, each arc (a bulge) drawn as n segments."""
    out = []
    for i, (x0, y0, bulge) in enumerate(outline):
        x1, y1, _ = outline[(i + 1) % len(outline)]
        if bulge == 0:
            out.append((x0, y0))
            continue
        theta = 4 * math.atan(bulge)  # the arc's angle, + counter-clockwise
        chord = math.hypot(x1 - x0, y1 - y0)
        r = chord / (2 * math.sin(theta / 2))
        mx, my = (x0 + x1) / 2, (y0 + y1) / 2
        h = r * math.cos(theta / 2)  # from the chord's middle to the centre
        cx, cy = mx - h * (y1 - y0) / chord, my + h * (x1 - x0) / chord
        a0 = math.atan2(y0 - cy, x0 - cx)
        out += [(cx + r * math.cos(a0 + theta * k / n), cy + r * math.sin(a0 + theta * k / n))
                for k in range(n)]  # fmt: skip
    return np.array(out + out[:1])


fig, ax = plt.subplots(figsize=(6, 7))
for part in sh.parts:
    xy = outline_xy(part.outline)
    ax.plot(xy[:, 0], xy[:, 1], color="tab:red", lw=0.8)
    for x, y in part.holes.values():
        ax.add_patch(plt.Circle((x, y), sh.hole / 2, fill=False, color="tab:blue", lw=0.8))
    ax.text(*part.label, part.name, ha="center", va="center", fontsize=8, color="tab:green")
(x0, y0), (x1, _), length = sh.scale
ax.plot([x0, x1], [y0, y0], color="black")
ax.text(x1 + 2, y0, f"{length:g} {sh.units}", va="center", fontsize=8)
ax.set_aspect("equal")
ax.set_title(f"{sc.name}: {len(sh.parts)} parts, {sh.size[0]:.0f} x {sh.size[1]:.0f} mm")
ax.set_axis_off()

text = sc.to_pyslvs()
print(text)
back = pk.Scene.from_pyslvs(text, inputs=[pyslvs.pyslvs_input(sc)])
foot = back.sweep(outputs=["J7"]).points["J7"]
print("the foot's path read back from Pyslvs matches:",
      np.allclose(foot, sc.sweep(outputs=["foot"]).points["foot"], atol=1e-9))  # fmt: skip
