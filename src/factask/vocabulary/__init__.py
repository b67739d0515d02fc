"""The base vocabulary every layer above builds on: errors, kinds, palette, names,
tolerances, limits, world facts and state variables.

Imports only :mod:`factask.geometry` and the standard libraries (pydantic); never the
relations, the graph, MuJoCo or litellm. Submodules are imported by name
(``from factask.vocabulary.kinds import kind_spec``); the public names are re-exported
by :mod:`factask.graph` and :mod:`factask`.
"""
