"""Every registered relation unit, walked through solve -> place -> check.

Like dm_control's suite test that loads every registered task: a relation added
to :data:`factask.relations.RELATION_TYPES` is covered here with no new test.
"""

from __future__ import annotations

import numpy as np
import pytest

from factask.geometry import Pose
from factask.graph import SubtaskFactor, TaskGraph
from factask.relations import ANCHOR_FIELDS, RELATION_TYPES, Relation, RelationBase
from factask.scene.objects import objects_by_name
from factask.sim.layout.checks import check_task
from factask.sim.layout.reset import reset_layout

KINDS = sorted(RELATION_TYPES)
SEEDS = (0, 1, 2)
#: How far a perturbed object is pushed (m): off every slot, zone and support.
AWAY = 0.6


def _example_graph(kind: str) -> TaskGraph:
    variables, goal = RELATION_TYPES[kind].example()
    factor = SubtaskFactor(name=f"{kind}_goal", description=f"an example of {kind}", goal=goal)
    return TaskGraph(name=f"example-{kind.replace('_', '-')}", variables=variables,
                     factors=[factor]).ensure_valid()


def _solved_scene(kind: str, seed: int):
    graph = _example_graph(kind)
    layout, solved = reset_layout(graph, np.random.default_rng(seed))
    objs = objects_by_name(graph)
    poses: dict[str, Pose] = dict(layout)
    for s in solved.values():
        poses.update(s.targets(objs))
    return graph, solved, objs, poses


def test_registry_is_keyed_by_each_units_kind() -> None:
    assert sorted(["at_pose", "in_zone", "on", "inside", "stack", "row", "circle",
                            "aligned", "pile_in_zone", "rope_along", "open", "closed",
                            "switched_on", "switched_off"]) == KINDS
    for kind, cls in RELATION_TYPES.items():
        assert issubclass(cls, RelationBase)
        assert cls.kind() == kind
        assert cls.__doc__, f"{kind}: the docstring is what the prompts show"
        for field in cls.anchor_fields:
            assert field in cls.model_fields and field in ANCHOR_FIELDS


@pytest.mark.parametrize("kind", KINDS)
def test_example_round_trips_through_json(kind: str) -> None:
    from pydantic import TypeAdapter

    _, goal = RELATION_TYPES[kind].example()
    again = TypeAdapter(Relation).validate_json(goal.model_dump_json())
    assert type(again) is type(goal) and again == goal


@pytest.mark.parametrize("seed", SEEDS)
@pytest.mark.parametrize("kind", KINDS)
def test_objects_on_their_slots_satisfy_the_relation(kind: str, seed: int) -> None:
    graph, solved, _, poses = _solved_scene(kind, seed)
    status = check_task(graph, solved, poses)
    assert status.success, {n: s.detail for n, s in status.factors.items()}
    for name, fs in status.factors.items():
        s = solved[name]
        assert fs.progress == 1.0
        assert set(fs.placed) == set(s.objects)
        assert sorted(fs.placed.values()) == sorted(set(fs.placed.values())), "one per slot"
        assert set(fs.free_slots) == set(range(len(s.slots))) - set(fs.placed.values())
        assert fs.targets == {}


@pytest.mark.parametrize("seed", SEEDS)
@pytest.mark.parametrize("kind", KINDS)
def test_a_perturbed_object_is_missing_and_gets_a_free_slot(kind: str, seed: int) -> None:
    graph, solved, objs, poses = _solved_scene(kind, seed)
    (fname, s), = solved.items()
    for name in s.objects:
        moved = dict(poses)
        p = poses[name]
        moved[name] = Pose(p.pos + np.array([AWAY, 0.0, 0.0]), p.quat)
        fs = check_task(graph, solved, moved).factors[fname]
        assert not fs.satisfied and fs.progress < 1.0
        assert name not in fs.placed
        assert name in fs.detail
        # The status tells the robot where the object goes: a free slot it may take.
        slot = fs.targets[name]
        assert slot in fs.free_slots
        assert s.matches[s.objects.index(name), slot]
        # Put back on that slot, the factor is whole again.
        moved[name] = s.target_pose(objs[name], slot)
        if not s.chain:
            assert check_task(graph, solved, moved).factors[fname].satisfied


@pytest.mark.parametrize("kind", KINDS)
def test_held_objects_never_count_as_placed(kind: str) -> None:
    graph, solved, _, poses = _solved_scene(kind, 0)
    (fname, s), = solved.items()
    held = {s.objects[0]}
    fs = check_task(graph, solved, poses, held=held).factors[fname]
    assert not fs.satisfied and s.objects[0] not in fs.placed
    assert "held by the robot" in fs.detail


def test_aligned_needs_an_instance_of_the_reference_per_object_before_any_reset() -> None:
    from factask.graph import GraphValidationError
    from factask.relations import Aligned
    from factask.vocabulary.variables import StateVariable

    def graph(corners: int) -> TaskGraph:
        return TaskGraph(
            name="t",
            variables=[StateVariable(name="balls", kind="ball", count=3),
                       StateVariable(name="corner", kind="corner", count=corners)],
            factors=[SubtaskFactor(name="f", goal=Aligned(objects=["balls"],
                                                          reference="corner", mode="corner"))])

    with pytest.raises(GraphValidationError, match=r"3 object.*'corner' has 1 instance") as err:
        graph(1).ensure_valid()
    assert (err.value.problems[0].node, err.value.problems[0].field) == ("f", "goal.objects")
    graph(3).ensure_valid()


@pytest.mark.parametrize(("goal", "initial"), [
    ({"type": "on", "objects": ["b"], "support": "p"}, {"type": "on", "support": "p"}),
    ({"type": "inside", "objects": ["b"], "container": "c"}, {"type": "inside", "container": "c"}),
    ({"type": "in_zone", "objects": ["b"], "zone": "c"}, {"type": "inside", "container": "c"}),
])
def test_a_first_goal_its_objects_meet_by_their_start_is_refused_before_any_reset(
        goal: dict, initial: dict) -> None:
    from factask.graph import GraphValidationError, parse_graph

    def graph(start: dict | None, after: list[str]) -> dict:
        block = {"name": "b", "kind": "block", **({"initial": start} if start else {})}
        return {"name": "t", "variables": [block, {"name": "p", "kind": "pallet"},
                                           {"name": "c", "kind": "container"},
                                           {"name": "z", "kind": "zone"}],
                "factors": ([{"name": "first", "weight": 0.5, "milestone": True,
                              "goal": {"type": "in_zone", "objects": ["b"], "zone": "z"}}]
                            if after else [])
                + [{"name": "f", "goal": goal, "after": after, "weight": 0.5 if after else 1}]}

    with pytest.raises(GraphValidationError, match="met at the start") as err:
        parse_graph(graph(initial, [])).ensure_valid()
    assert (err.value.problems[0].node, err.value.problems[0].field) == ("f", "goal")
    parse_graph(graph(None, [])).ensure_valid()  # starts on the table
    parse_graph(graph(initial, ["first"])).ensure_valid()  # moved away first, then back


def test_a_deck_on_two_pillars_nothing_arranged_is_refused_at_reset() -> None:
    """A bar ``on`` a two-block support rests on both blocks; blocks that start
    apart (no goal puts them side by side) hold nothing between them: refused at
    reset, naming the fix, instead of a target the oracle cannot reach."""
    from factask.scene.collision import LayoutError

    variables = [{"name": "pillars", "kind": "block", "count": 2},
                 {"name": "deck", "kind": "log", "size": [0.14, 0.04, 0.04]}]
    deck_on = {"name": "deck_on", "description": "the log across the blocks",
               "goal": {"type": "on", "objects": ["deck"], "support": "pillars"}}
    alone = TaskGraph.model_validate({"name": "t", "description": "d", "variables": variables,
                                      "factors": [deck_on]})
    with pytest.raises(LayoutError, match="cannot rest on every instance of 'pillars'"):
        reset_layout(alone, np.random.default_rng(0))
    row = {"name": "pillars_row", "description": "the blocks in a row",
           "goal": {"type": "row", "objects": ["pillars"], "spacing": 0.08}}
    bridge = TaskGraph.model_validate({"name": "t", "description": "d", "variables": variables,
                                       "factors": [row, deck_on]})
    _, solved = reset_layout(bridge, np.random.default_rng(0))
    assert solved["deck_on"].support_group == ["pillars__0", "pillars__1"]
