"""
Path synthesis: a four-bar for a drawn curve
============================================

A target path drawn as SVG path data (a closed, kidney-shaped loop of cubic Béziers) is
sampled at equal arc length; ``planarkin.synthesis.path.path`` retrieves candidates from
the default four-bar atlas, refines them with exact gradients and verifies each on the
real linkage. The best design's tracer follows the drawing on one circuit, with no dead
point, in the drawn order.
"""

import planarkin as pk
from planarkin.face.figures import path as figures
from planarkin.synthesis.path import path
from planarkin.synthesis.path.targets import load_target

target = load_target(
    "M 0 0 C 20 -25, 60 -25, 80 0 C 95 20, 70 45, 40 30 C 10 45, -15 20, 0 0 Z",
    svg_samples=48,
)
print(target)

res = path(target, topology="four-bar", designs=3, seed=0)
for k, d in enumerate(res.designs, 1):
    print(
        f"design {k}: error max {d.error.max:.2e}, rms {d.error.rms:.2e} of the size; "
        f"defects {d.defects}; min transmission {d.min_transmission:.1f} deg; "
        f"verified {d.verified}"
    )
print("timings [s]:", {k: round(v, 3) for k, v in res.timings.items()})

# %%
# The best design over its coupler curve: the target's points (red circles), each joined
# to where the tracer reaches it, the traced arc in blue, the linkage at the first point.
best = res.designs[0]
fig = figures.design(target, best, 1)

# %%
# The error along the target, for every design returned: the distance from each target
# point to the tracer at that point's input value, over the target's size.
fig_error = figures.error(target, res.designs)

# %%
# A design is a scene: save it and open it with ``planarkin analyze`` or ``planarkin web``.
assert isinstance(best.scene, pk.Scene)
print(best.scene)
