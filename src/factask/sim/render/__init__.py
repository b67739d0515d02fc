"""Pictures of a scene: offscreen RGB / depth / segmentation and videos, the
observation cameras, CLIPort's heightmaps, the observation modes.

May import :mod:`factask.sim.build` (parts, for colours) and the layers below
:mod:`factask.sim`; never the env or the oracle.
"""
