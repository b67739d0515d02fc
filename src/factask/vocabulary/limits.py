"""Physical and practical bounds of a task graph, each with the fix in its message.

Sizes come from the world (the workspace is 0.5 m deep, 1 m wide and 0.3 m high;
MuJoCo needs positive, representable sizes); counts keep a reset, a check and an
error report bounded in time and length. Every bound is one constant here; the
graph model checks them at parse time and every entry point that takes a graph
(compile, env, oracle, generation) checks again (:meth:`TaskGraph.ensure_valid`),
so a graph changed after it was built is caught where it enters. The table of
limits and what a user sees is in ``docs/limits.md``.
"""

from __future__ import annotations

from typing import Annotated

from pydantic import StringConstraints

from factask.vocabulary.world import RAVENS_Z, WORKSPACE_DEPTH, WORKSPACE_WIDTH

#: Smallest size along any axis, metres (a zone's or line's thickness is 1 mm).
MIN_LENGTH = 0.0005
#: Largest horizontal size, metres: the workspace's width.
MAX_HORIZONTAL = WORKSPACE_WIDTH
#: The shorter horizontal side must fit the workspace's depth (turned to fit).
MAX_SHORT_SIDE = WORKSPACE_DEPTH
#: Largest height of one object, metres: CLIPort's workspace height (taller things on
#: the table are built of several objects, up to the workspace's top, WORKSPACE_Z).
MAX_HEIGHT = RAVENS_Z[1] - RAVENS_Z[0]
#: Variables per graph.
MAX_VARIABLES = 100
#: Factors per graph.
MAX_FACTORS = 100
#: Objects per scene (the sum of the variables' counts).
MAX_OBJECTS = 100
#: Identical objects one variable stands for.
MAX_COUNT = 64
#: Characters of a description (of a graph, variable or factor) or initial setup.
MAX_TEXT = 2000
#: Entries of a factor's ``after`` list or scope.
MAX_REFERENCES = MAX_VARIABLES


#: Free text of bounded length (descriptions, language goals).
Text = Annotated[str, StringConstraints(max_length=MAX_TEXT)]


def size_problem(size: tuple[float, float, float]) -> tuple[str, str] | None:
    """Why no object can have ``size`` in this world, as (message, fix), or None."""
    x, y, z = size
    if min(size) < MIN_LENGTH:
        return (f"size {tuple(size)} has a side under {MIN_LENGTH * 1000:g} mm",
                f"give every side at least {MIN_LENGTH} m")
    if max(x, y) > MAX_HORIZONTAL:
        return (f"size {tuple(size)} is longer than the workspace is wide "
                f"({MAX_HORIZONTAL:g} m)", f"keep size x and y at most {MAX_HORIZONTAL:g} m")
    if min(x, y) > MAX_SHORT_SIDE:
        return (f"size {tuple(size)} does not fit the workspace's depth ({MAX_SHORT_SIDE:g} m) "
                "at any yaw", f"keep the shorter of size x and y at most {MAX_SHORT_SIDE:g} m")
    if z > MAX_HEIGHT:
        return (f"size {tuple(size)} is taller than one object may be ({MAX_HEIGHT:g} m)",
                f"keep size z at most {MAX_HEIGHT:g} m")
    return None


__all__ = ["MAX_COUNT", "MAX_FACTORS", "MAX_HEIGHT", "MAX_HORIZONTAL", "MAX_OBJECTS",
           "MAX_REFERENCES", "MAX_SHORT_SIDE", "MAX_TEXT", "MAX_VARIABLES", "MIN_LENGTH", "Text",
           "size_problem"]
