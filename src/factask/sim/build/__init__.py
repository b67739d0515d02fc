"""Scenes built in code: what every asset is made of (parts), MjSpec bodies, MJCF
export, and ``compile_graph`` (graph -> MjSpec -> MjModel, with the robot attached).

May import :mod:`factask.sim.robots`, :mod:`factask.sim.layout` and the layers below
:mod:`factask.sim`; never rendering, the env or the oracle.
"""
