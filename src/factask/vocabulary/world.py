"""Fixed facts about the simulated world (Ravens/CLIPort conventions)."""

from __future__ import annotations

#: Table top height (metres); the table surface is the plane z = 0.
TABLE_Z = 0.0
#: Extent of the table top (metres): x range and y range, around the workspace.
TABLE_X = (-0.30, 1.20)
TABLE_Y = (-0.70, 0.70)
#: Reachable, visible workspace on the table: x range (metres).
WORKSPACE_X = (0.25, 0.75)
#: Workspace y range (metres).
WORKSPACE_Y = (-0.5, 0.5)
#: Highest point (metres) the default arm's suction tip reaches pointing straight down
#: over every point of the workspace (the UR10e, tested in tests/test_world_reach.py
#: with its IK; the floating cup reaches anywhere).
TIP_REACH_Z = 0.85
#: Room (metres) kept above the workspace's top to carry an object over it: a 15 cm
#: object held 5 cm above the tallest thing on the table, plus a margin.
CARRY_ROOM = 0.25
#: Workspace z range (metres): what may stand on the table, from what the arm reaches
#: (a tower of ten 4 cm blocks is 40 cm tall). Not CLIPort's 0.3 m: see RAVENS_Z.
WORKSPACE_Z = (0.0, TIP_REACH_Z - CARRY_ROOM)
#: The z range of CLIPort's ``bounds`` and height maps (metres): its observations, and
#: what task code reads as ``self.bounds``; taller things are clipped in its maps.
RAVENS_Z = (0.0, 0.3)
#: The workspace's depth (x), width (y) and height (z), and its longest straight line.
WORKSPACE_DEPTH = WORKSPACE_X[1] - WORKSPACE_X[0]
WORKSPACE_WIDTH = WORKSPACE_Y[1] - WORKSPACE_Y[0]
WORKSPACE_HEIGHT = WORKSPACE_Z[1] - WORKSPACE_Z[0]
WORKSPACE_DIAGONAL = (WORKSPACE_DEPTH**2 + WORKSPACE_WIDTH**2) ** 0.5
#: Robot base position (the origin, as in Ravens).
ROBOT_BASE = (0.0, 0.0, 0.0)
