"""
A four-bar swept through a full turn
====================================

The textbook crank-rocker r = (6, 2, 5, 5): every crank angle solved on the open assembly
mode, its coupler curve, and the linkage at six crank angles.
"""

import numpy as np
import planarkin as pk
from planarkin.face.figures import fourbar as figures

fb = pk.FourBar(6, 2, 5, 5)
print(fb.grashof().description)
sweep = fb.sweep(omega2=100 * 2 * np.pi / 60, alpha2=0.0)
print(sweep.summary())

# %%
# The rocker and coupler angles against the crank angle, with its limits marked.
fig_position = figures.position(sweep, limits=fb.limits())

# %%
# The linkage at six crank angles over its coupler curve (p = 3, delta = 30 deg).
fig_linkage = figures.linkage(sweep, 3.0, np.radians(30))
