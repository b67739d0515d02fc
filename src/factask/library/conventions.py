"""Sizes, colour sets and start regions that the GenSim catalogue modules share.

One place for the asset conventions of :mod:`factask.vocabulary.kinds` as the library
uses them (a Ravens block is a 4 cm cube, a bowl 12 cm across, ...), so a task
module states only what is particular to its tasks.
"""

from __future__ import annotations

from factask.library.builders import region

BLOCK = (0.04, 0.04, 0.04)
BALL = (0.04, 0.04, 0.04)
#: An upright cylinder: 4 cm across, 6 cm high.
CYLINDER = (0.04, 0.04, 0.06)
#: A cylinder lying on its side (a ``log``): 14 cm long, 4 cm across -- long enough
#: to span a bridge's two 4 cm pillars 8 cm apart (templates.BRIDGE_PILLAR_SPACING).
LOG = (0.14, 0.04, 0.04)
BOWL = (0.12, 0.12, 0.05)
#: GenSim's "cylinder with an opening on top" that things are inserted into: an open
#: tube, which is what a ``bowl`` is (straight round walls on a floor) when it is
#: taller than wide: 9 cm across (7 cm inside: a 4 cm block fits turned any way),
#: 8 cm tall.
TUBE = (0.09, 0.09, 0.08)
ZONE = (0.12, 0.12, 0.001)
CORNER = (0.055, 0.055, 0.001)
LINE = (0.30, 0.01, 0.001)
ELL = (0.08, 0.08, 0.04)
#: A fixture for an ell (the kind's default: 2 cm of wall and clearance around it).
ELL_FIXTURE = (0.12, 0.12, 0.04)
#: A fixture whose square hollow takes one 4 cm block (or a 4 cm cylinder).
BLOCK_FIXTURE = (0.08, 0.08, 0.04)
#: A fixture whose hollow takes a LOG lying in it (2 cm of wall and clearance around
#: it, as ELL_FIXTURE), its walls as high as the log is thick.
LOG_FIXTURE = (LOG[0] + 0.04, LOG[1] + 0.04, LOG[2])

THREE = ("red", "blue", "green")
FOUR = ("red", "blue", "green", "yellow")
FIVE = ("red", "blue", "green", "yellow", "orange")

#: The strip nearest the robot: where objects start when their targets stand in a
#: row at the far side (beyond a barrier, or away from markers they must not start on).
NEAR = region((0.27, 0.42), (-0.42, 0.42))
