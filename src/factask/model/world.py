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
#: Workspace z range (metres).
WORKSPACE_Z = (0.0, 0.3)
#: Robot base position (the origin, as in Ravens).
ROBOT_BASE = (0.0, 0.0, 0.0)
