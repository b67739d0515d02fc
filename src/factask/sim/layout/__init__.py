"""A reset's layout and the checks that read it, in pure NumPy: the sampler, piles' and
ropes' starts, the relations solved in factor order, the resample loop, factor status.

May import the graph model, the relations, :mod:`factask.scene` and
:mod:`factask.geometry`; never MuJoCo or the rest of :mod:`factask.sim`.
"""
