"""
Jansen's leg as a scene
=======================

A scene is a linkage written as data. Jansen's Strandbeest leg is built in: the drawn
pose alone with every point named, beside four poses over the path of its foot.
"""

import planarkin as pk
from planarkin.face.figures import scene as figures

sc = pk.scenes.load("jansen")
print(sc)
print(sc.plan(["foot"]))
sweep = sc.sweep(outputs="all", omega=1.0)
fig = figures.linkage(sc, sweep)

# %%
# The foot's coordinates and speed against the crank angle (at 1 rad/s).
fig_tracers = figures.tracers(sc, sweep)
