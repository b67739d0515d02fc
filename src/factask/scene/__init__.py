"""The scene as geometry (pure numpy; never imports MuJoCo).

:mod:`factask.scene.objects` gives every object instance of a graph its shape and
footprint; :mod:`factask.scene.collision` is the one collision rule and the
free-spot searches built on it. Layout, relation solving, checks and the oracle
all stand on these two modules.
"""
