"""Robots and their motion: the registry, the suction cup, the UR-type arm with its IK
and controller, the floating cup, minimum-time motions, the primitives every robot
shares (pick-and-place, the spatula's push, the low carry) and the one physics-health
test they stop on.

May import the graph model, the vocabulary and :mod:`factask.geometry`; never the
scene build, rendering, the env or the oracle.
"""
