"""The MuJoCo backend of factask: assets, compilation, robot, layout, checks, rendering.

Imports only the graph model (:mod:`factask.model`) and :mod:`factask.geometry`;
never the generation side. Submodules are imported explicitly
(``from factask.sim.compile import compile_graph``) so that importing this
package stays cheap and does not pull in MuJoCo's GL stack.
"""
