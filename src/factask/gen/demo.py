"""Scripted answers for a small two-step task, for the loopback server.

The task: put a red block in a green zone, then put a blue block on the red
block. :func:`demo_responder` answers every step of the three strategies with
real, physically sensible JSON; with ``broken=True`` the first answer of one
step per strategy is wrong (junk, an unknown colour, a conflicting shared
variable, a goal outside the subtask's variables), so each strategy has to
recover through feedback. Used by the tests, the example and offline demos.
"""

from __future__ import annotations

import json
from typing import Any

from factask.gen.loopback import ScriptedResponder

#: The proposal the demo answers fit.
DEMO_PROPOSAL = ("stack-blue-on-red-in-zone: put the red block in the green zone, then "
                 "put the blue block on top of the red block")

# Every field is given: the step schemas (factask.gen.answers.step_schemas) require them all.
_TABLE = {"type": "table"}
RED = {"name": "red_block", "description": "block that goes into the zone", "kind": "block",
       "size": [0.04, 0.04, 0.04], "color": "red", "count": 1, "initial": _TABLE}
BLUE = {"name": "blue_block", "description": "block that goes on the red block",
        "kind": "block", "size": [0.04, 0.04, 0.04], "color": "blue", "count": 1,
        "initial": _TABLE}
ZONE = {"name": "green_zone", "description": "target zone", "kind": "zone",
        "size": [0.12, 0.12, 0.001], "color": "green", "count": 1, "initial": _TABLE}
IN_ZONE = {"type": "in_zone", "objects": ["red_block"], "zone": "green_zone"}
ON_RED = {"type": "on", "objects": ["blue_block"], "support": "red_block"}
_FACTOR = {"after": [], "initial_setup": "", "milestone": False}


def demo_graph(name: str = "stack-blue-on-red-in-zone") -> dict[str, Any]:
    """The whole task graph as JSON data (a fresh copy: callers may mutate it)."""
    return _copy({
        "name": name,
        "description": "Put the red block in the green zone, then the blue block on it.",
        "variables": [RED, BLUE, ZONE],
        "factors": [
            {"name": "place_red_in_zone", "description": "put the red block in the green zone",
             "goal": IN_ZONE, "weight": 0.5, **_FACTOR},
            {"name": "stack_blue_on_red", "description": "put the blue block on the red block",
             "goal": ON_RED, "weight": 0.5, **_FACTOR},
        ],
    })


def _copy(data: Any) -> Any:
    return json.loads(json.dumps(data))


def _j(data: Any) -> str:
    return json.dumps(data)


def demo_answers() -> dict[str, str]:
    """Correct answers, keyed by step (``step`` or ``step:subtask``)."""
    return {
        "one_shot": "Here is the task graph:\n```json\n" + _j(demo_graph()) + "\n```",
        "assembly": _j(demo_graph()),
        "variables": _j({"variables": [RED, BLUE, ZONE]}),
        "subtask_plan": _j({"subtasks": [
            {"name": "place_red_in_zone", "description": "put the red block in the green zone",
             "variables": ["red_block", "green_zone"], "initial_setup": ""},
            {"name": "stack_blue_on_red", "description": "put the blue block on the red block",
             "variables": ["blue_block", "red_block"],
             "initial_setup": "the red block is in the green zone"},
        ]}),
        "subtask_goal:place_red_in_zone": _j({"goal": IN_ZONE, "description": ""}),
        "subtask_goal:stack_blue_on_red": _j({"goal": ON_RED, "description": ""}),
        "subtask_outline": _j({"subtasks": [
            {"name": "place_red_in_zone", "description": "the red block is in the green zone"},
            {"name": "stack_blue_on_red", "description": "the blue block is on the red block"},
        ]}),
        "subtask_design:place_red_in_zone": _j({"variables": [RED, ZONE], "goal": IN_ZONE,
                                                "description": ""}),
        "subtask_design:stack_blue_on_red": _j({"variables": [BLUE, RED], "goal": ON_RED,
                                                "description": ""}),
    }


def broken_answers() -> dict[str, str]:
    """One wrong first answer per strategy (the correct one follows on repair)."""
    bad_graph = demo_graph()
    bad_graph["variables"] = [dict(RED, color="sparkly"), BLUE, ZONE]
    return {
        # one-shot: not JSON at all, then an unknown colour.
        "one_shot": ["I would put the red block in the zone first.", _j(bad_graph)],
        # variables-first: the goal anchors on a variable outside the subtask.
        "subtask_goal:stack_blue_on_red": [_j({"goal": {"type": "on", "objects": ["blue_block"],
                                                        "support": "green_zone"},
                                               "description": ""})],
        # subtasks-first: the shared red block is redefined with another colour.
        "subtask_design:stack_blue_on_red": [_j({"variables": [BLUE, dict(RED, color="orange")],
                                                 "goal": ON_RED, "description": ""})],
    }


def demo_responder(broken: bool = True) -> ScriptedResponder:
    """A responder for :class:`~factask.gen.loopback.LoopbackServer` answering the demo task.

    Args:
        broken: Start each strategy with one wrong answer it must repair.
    """
    good = demo_answers()
    script: dict[str, Any] = dict(good)
    if broken:
        for key, bad in broken_answers().items():
            script[key] = [*bad, good[key]]
    return ScriptedResponder(script)
