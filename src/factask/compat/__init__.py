"""Compatibility layers for task code written against other simulators' APIs.

:mod:`factask.compat.cliport` runs GenSim/CLIPort ``Task`` classes (PyBullet code)
against a recording environment and turns what they set up into a factask
:class:`~factask.graph.taskgraph.TaskGraph`. :mod:`factask.compat.libero` reads
LIBERO's BDDL task files into typed values (their mapping to factask comes later).
"""
