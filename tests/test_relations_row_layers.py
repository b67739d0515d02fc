"""``row ... on`` a list of variables: a layer resting on a row of mixed colours.

The schema accepts one name or a list of names (property-tested), renaming and
templates rewrite every name of the list, and the solver lays the layer on the
instances of all the listed variables, sorted along the row below.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from pydantic import TypeAdapter, ValidationError

from factask.geometry import Pose
from factask.graph import Row, StateVariable, SubtaskFactor, TaskGraph, rename
from factask.library.templates import get_template
from factask.relations import Relation
from factask.scene.objects import objects_by_name
from factask.sim.layout.checks import check_task
from factask.sim.layout.reset import reset_layout

names = st.from_regex(r"[a-z][a-z0-9]{0,6}(_[a-z0-9]{1,4})?", fullmatch=True)
below_lists = st.lists(names, min_size=1, max_size=6, unique=True)


@given(below_lists)
def test_on_takes_a_name_or_a_list_and_round_trips(below: list[str]) -> None:
    for on in (below[0], below):
        goal = Row(objects=["layer_x"], on=on)
        again = TypeAdapter(Relation).validate_json(goal.model_dump_json())
        assert again == goal
        assert again.anchors() == ([on] if isinstance(on, str) else below)
        assert goal.variable_names() == ["layer_x", *goal.anchors()]


@given(below_lists, st.integers(1, 6))
def test_rename_rewrites_every_name_of_the_list(below: list[str], k: int) -> None:
    # New names no strategy draws (an 8-letter head), so none collides with an old one.
    mapping = {old: f"renamedx_{i}" for i, old in enumerate(below[:k])}
    variables = [StateVariable(name=n, kind="block") for n in below]
    layer = StateVariable(name="layer_x", kind="block")
    graph = TaskGraph(name="g", variables=[*variables, layer], factors=[SubtaskFactor(
        name="f", description="d", goal=Row(objects=["layer_x"], on=below))])
    renamed = rename(graph, mapping).factors[0].goal
    assert renamed.anchors() == [mapping.get(n, n) for n in below]


@pytest.mark.parametrize("bad", [[], ["Bad"], ["a__b"], "x" * 70])
def test_bad_lists_are_rejected(bad: object) -> None:
    with pytest.raises(ValidationError):
        Row(objects=["layer_x"], on=bad)


def test_a_name_listed_twice_is_a_problem() -> None:
    a = StateVariable(name="a", kind="block")
    graph = TaskGraph(name="g", variables=[a, StateVariable(name="top", kind="block")],
                      factors=[SubtaskFactor(name="f", description="d",
                                             goal=Row(objects=["top"], on=["a", "a"]))])
    assert any("listed twice" in p.message for p in graph.problems())


def test_an_anchor_of_the_wrong_kind_is_named() -> None:
    zone = StateVariable(name="zone", kind="zone")
    graph = TaskGraph(name="g", variables=[zone, StateVariable(name="b", kind="block"),
                                           StateVariable(name="top", kind="block")],
                      factors=[SubtaskFactor(name="f", description="d",
                                             goal=Row(objects=["top"], on=["b", "zone"]))])
    assert any(p.field == "goal.on" and "'zone'" in p.message for p in graph.problems())


def test_template_binds_one_variable_as_a_name_and_several_as_a_list() -> None:
    tpl = get_template("pyramid_layer")
    green = StateVariable(name="greens", kind="block", count=2)
    blue = StateVariable(name="blue", kind="block")
    red = StateVariable(name="reds", kind="block", count=2)
    one = tpl.instantiate(layer=StateVariable(name="top", kind="block"), below=red)
    assert one.factors[0].goal.on == "reds"  # the JSON of one-variable layers unchanged
    two = tpl.instantiate(layer=red, below=[green, blue])
    assert two.factors[0].goal.on == ["greens", "blue"]
    assert {"greens", "blue", "reds"} <= set(two.factors[0].scope_names)


def _pyramid() -> TaskGraph:
    """Two green blocks and a blue one in a row, two red blocks bridging them."""
    from factask.library.builders import assemble, use, var

    greens = var("greens", "block", "green", (0.04, 0.04, 0.04), count=2)
    blue = var("blue", "block", "blue", (0.04, 0.04, 0.04))
    reds = var("reds", "block", "red", (0.04, 0.04, 0.04), count=2)
    return assemble("mixed-pyramid", "a mixed layer carries the next",
                    use("build_row", objects=[greens, blue]),
                    use("pyramid_layer", layer=reds, below=[greens, blue]))


def _solved(seed: int) -> tuple[TaskGraph, dict, dict[str, Pose]]:
    graph = _pyramid()
    layout, solved = reset_layout(graph, np.random.default_rng(seed))
    objs = objects_by_name(graph)
    poses = dict(layout)
    for s in solved.values():
        poses.update(s.targets(objs))
    return graph, solved, poses


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_layer_bridges_the_mixed_row_below(seed: int) -> None:
    graph, solved, poses = _solved(seed)
    layer = solved["pyramid_layer_reds"]
    base = [poses[n] for n in ("greens__0", "greens__1", "blue")]
    for j, slot in enumerate(layer.slots):
        below = [p for p in base if np.linalg.norm(p.pos[:2] - slot.pos[:2]) < 0.03]
        assert len(below) == 2, f"slot {j} bridges two blocks of the row"
        assert slot.pos[2] == pytest.approx(0.06)  # on 4 cm blocks: 4 + 2 cm
    assert check_task(graph, solved, poses).success


@pytest.mark.parametrize("seed", [0, 1])
def test_check_is_satisfied_only_with_every_block_on_its_slot(seed: int) -> None:
    graph, solved, poses = _solved(seed)
    name = "pyramid_layer_reds"
    full = check_task(graph, solved, poses).factors[name]
    assert full.satisfied and full.progress == 1.0
    # Slide one red block off the row, a little at a time: placed while within the
    # 1 cm tolerance, then not; progress never jumps by more than one block's share.
    last = 1.0
    for dx in np.linspace(0.0, 0.1, 21):
        moved = dict(poses)
        p = poses["reds__0"]
        moved["reds__0"] = Pose(p.pos + np.array([dx, 0.0, 0.0]), p.quat)
        fs = check_task(graph, solved, moved).factors[name]
        assert fs.satisfied == (dx < 0.0099)
        assert abs(fs.progress - last) <= 0.5 + 1e-9 and fs.progress in (0.5, 1.0)
        last = fs.progress
    assert last == 0.5


def test_a_centred_layer_rests_on_the_blocks_beneath_it() -> None:
    """5-3: the middle layer stands one on each of the inner three; each slot's
    support is the block under it."""
    from factask.library import get_task

    graph = get_task("pyramid-blocks-assemble")
    poses, solved = reset_layout(graph, np.random.default_rng(3))
    objs = objects_by_name(graph)
    targets = dict(poses)
    for s in solved.values():
        targets.update(s.targets(objs))
    middle = next(s for s in solved.values() if s.factor.startswith("layer_on"))
    for j, slot in enumerate(middle.slots):
        host = targets[middle.supports[j]]
        assert np.linalg.norm(host.pos[:2] - slot.pos[:2]) < 1e-6
    assert middle.supports[1] == "bottom_green"
