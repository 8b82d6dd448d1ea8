"""
Circuits of a Stephenson III six-bar
====================================

Every real assembly at the drawn input angle, grouped by circuit: one panel per circuit,
and the linkage drawn in each assembly.
"""

import planarkin as pk
from planarkin.face.figures import circuits

sc = pk.scenes.load("stephenson3")
found = sc.circuits()
for c in found:
    print(c, [a.label for a in c.assemblies])
fig = circuits.circuits(sc, found, sc.input_angle)
