"""The scripted suction oracle: its choice of the next action from each factor's status,
where the cup takes an object, the spatula's pushes for piles, the rope carries.

Reads an env through the :class:`~factask.sim.oracle.scripted.OracleView` protocol
(the single env, or one world of a batch) and never imports the env; may import the
robots' primitives, the layout's checks and the layers below :mod:`factask.sim`.
"""
