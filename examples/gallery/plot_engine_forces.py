"""
Forces in a single-cylinder engine
==================================

The ``engine`` built-in (a centred slider-crank with a gas-force table on its piston,
crank and rod masses) at 3000 rpm: the crank torque that drives it at constant speed,
by Newton-Euler and by virtual work, and the force on each pin.
"""

import planarkin as pk
from planarkin.face.figures import forces

sc = pk.scenes.load("engine")
r = sc.dynamics(omega=3000 * 2 * 3.141592653589793 / 60)
print(r.summary())
fig = forces.effort(sc, r)
fig2 = forces.reactions(sc, r)
