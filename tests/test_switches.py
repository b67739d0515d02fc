"""Switches (issue 38, "switch on"): stoves and a lamp with a push button on a slide
joint, the ``switched_on`` / ``switched_off`` relations, the oracle's press and pull
with both robots, the batched check, validation and the library tasks."""

from __future__ import annotations

from typing import Any

import mujoco
import numpy as np
import pytest

from factask.batch.checks import switch_presses
from factask.geometry import Pose
from factask.graph import GraphValidationError, TaskGraph, parse_graph
from factask.library import get_task
from factask.library.catalog_switches import stove
from factask.relations.status import CheckScene
from factask.scene.objects import placement_area
from factask.scene.switch import button_top, switch_pose, switch_pressed
from factask.sim.env import FactaskEnv
from factask.sim.episode import run_episode
from factask.sim.oracle.scripted import Oracle
from factask.sim.robots.switch_press import PressAction
from factask.vocabulary.kinds import SWITCH_HOSTS, switch_size, switch_travel
from factask.vocabulary.tolerances import SWITCH_OFF_FRACTION, SWITCH_ON_FRACTION

#: The library's switch tasks (catalog_switches).
SWITCH_TASKS = ["turn-on-stove", "turn-off-stove", "turn-on-stove-and-put-pot-on-it",
                "put-block-on-stove-and-turn-it-on", "turn-off-stove-and-move-pot-to-zone",
                "turn-on-two-stoves", "turn-on-lamp",
                "put-pot-on-stove-and-turn-it-on"]


def _pressed(env: FactaskEnv, switch: str, host: str) -> float:
    poses = env.object_poses()
    pressed, off_mount = switch_pressed(env.objects[host], poses[host], poses[switch])
    assert off_mount < 1e-6  # its joint keeps it on its mount
    return pressed


def _joint(env: FactaskEnv, switch: str) -> float:
    handle = env.scene.objects[switch].slide
    assert handle is not None
    return float(env.data.qpos[handle.qpos_adr])


def _run_oracle(env: FactaskEnv, seed: int = 0) -> list[Any]:
    """Step the oracle to its end; the actions it planned."""
    oracle = Oracle(env, seed=seed)
    planned_actions = []
    for _ in range(10):
        planned = oracle.plan()
        if planned is None:
            break
        planned_actions.append(planned)
        _, _, terminated, truncated, _ = env.step(planned.as_env_action())
        if terminated or truncated:
            break
    assert oracle.failure is None, oracle.failure
    return planned_actions


# ------------------------------------------------------------------ the joint
def test_switch_pose_follows_its_slide_joint() -> None:
    env = FactaskEnv(get_task("turn-on-stove"))
    env.reset(seed=0)
    assert _pressed(env, "stove_switch", "stove") == pytest.approx(0.0, abs=0.05)
    handle = env.scene.objects["stove_switch"].slide
    assert handle is not None
    env.data.qpos[handle.qpos_adr] = 0.5 * switch_travel()
    assert _pressed(env, "stove_switch", "stove") == pytest.approx(0.5, abs=1e-6)
    mujoco.mj_forward(env.model, env.data)
    body = env.scene.objects["stove_switch"].body_id
    np.testing.assert_allclose(env.object_poses()["stove_switch"].pos, env.data.xpos[body],
                               atol=1e-9)


@pytest.mark.parametrize("on", [False, True])
def test_a_button_left_alone_stays_where_it_is(on: bool) -> None:
    # Three seconds of physics with nothing touching it: its weight must not creep it
    # down (dry friction alone let it sink millimetres).
    env = FactaskEnv(get_task("turn-off-stove" if on else "turn-on-stove"))
    env.reset(seed=0)
    before = _pressed(env, "stove_switch", "stove")
    mujoco.mj_step(env.model, env.data, int(3.0 / env.model.opt.timestep))
    assert _pressed(env, "stove_switch", "stove") == pytest.approx(before, abs=0.03)
    assert (before > SWITCH_ON_FRACTION) if on else (before < SWITCH_OFF_FRACTION)


# ------------------------------------------------------------------ the oracle
@pytest.mark.parametrize("robot", ["floating", "arm"])
def test_oracle_presses_a_switch_on_and_it_reads_on(robot: str) -> None:
    env = FactaskEnv(get_task("turn-on-stove"), robot=robot)
    env.reset(seed=3)
    assert _pressed(env, "stove_switch", "stove") < SWITCH_OFF_FRACTION
    q0 = _joint(env, "stove_switch")
    actions = _run_oracle(env)
    assert [type(a) for a in actions] == [PressAction]
    assert actions[0].to[2] < actions[0].press[2]  # a press: down
    assert env.status().success
    # The joint moved (the cup's contact pushed it): nothing set the state.
    assert _joint(env, "stove_switch") - q0 > 0.8 * switch_travel()
    assert _pressed(env, "stove_switch", "stove") >= SWITCH_ON_FRACTION
    assert "stove_switch" not in env.held_objects()  # a press never holds it


@pytest.mark.parametrize("robot", ["floating", "arm"])
def test_oracle_pulls_a_switch_off_and_it_reads_off(robot: str) -> None:
    env = FactaskEnv(get_task("turn-off-stove"), robot=robot)
    env.reset(seed=3)
    assert _pressed(env, "stove_switch", "stove") >= SWITCH_ON_FRACTION
    actions = _run_oracle(env)
    assert len(actions) == 1 and actions[0].to[2] > actions[0].press[2]  # a pull: up
    assert env.status().success
    assert _pressed(env, "stove_switch", "stove") <= SWITCH_OFF_FRACTION


def test_on_then_off_by_hand_with_the_env_actions() -> None:
    # Both directions through the env's own action (press, press_to), in a row.
    env = FactaskEnv(get_task("turn-on-stove"))
    env.reset(seed=1)
    obj = env.objects["stove_switch"]
    pose = env.object_poses()["stove_switch"]
    top = button_top(obj, pose)
    yaw = pose.yaw
    down = top - np.array([0.0, 0.0, switch_travel()])
    _, _, _, _, info = env.step({"press": np.array([*top, yaw]),
                                 "press_to": np.array([*down, yaw])})
    assert info["action_ok"] and _pressed(env, "stove_switch", "stove") >= SWITCH_ON_FRACTION
    now = button_top(obj, env.object_poses()["stove_switch"])
    env.step({"press": np.array([*now, yaw]), "press_to": np.array([*top, yaw])})
    assert _pressed(env, "stove_switch", "stove") <= SWITCH_OFF_FRACTION


def test_a_press_with_nothing_under_the_cup_fails_cleanly() -> None:
    env = FactaskEnv(get_task("turn-on-stove"))
    env.reset(seed=0)
    spot = np.array([0.3, 0.4, 0.01, 0.0])  # bare table
    _, _, _, _, info = env.step({"press": spot, "press_to": spot - [0, 0, 0.012, 0]})
    # The table is no switch: the press is refused before it pushes into it.
    assert not info["action_ok"] and "no switch" in info["action_failure"]
    assert info["failure"] is None
    assert _pressed(env, "stove_switch", "stove") < SWITCH_OFF_FRACTION


@pytest.mark.parametrize("robot", ["floating", "arm"])
@pytest.mark.parametrize("task", SWITCH_TASKS)
def test_library_switch_tasks_succeed_with_the_oracle(task: str, robot: str) -> None:
    graph = get_task(task)
    for seed in (10, 11):
        result = run_episode(graph, seed=seed, robot=robot)
        assert result.success, (task, robot, seed, result.failure, result.details)


def test_the_pot_put_on_after_the_press_leaves_the_button_reachable() -> None:
    # The stove's top for 'on' lies behind its control strip: a pot on it never
    # covers the button, so the order of the two goals does not matter physically.
    graph = get_task("turn-on-stove-and-put-pot-on-it")
    env = FactaskEnv(graph)
    env.reset(seed=2)
    _run_oracle(env)
    poses = env.object_poses()
    area = placement_area(env.objects["stove"], poses["stove"])
    button = poses["stove_switch"].pos[:2]
    assert not area.contains(button[None])[0]
    pot = env.objects["blue_pot"]
    assert np.linalg.norm(poses["blue_pot"].pos[:2] - button) > pot.size[0] / 2


# ------------------------------------------------------------------ batched check
def test_batched_press_equals_the_scalar_one() -> None:
    graph = get_task("turn-on-stove")
    env = FactaskEnv(graph)
    env.reset(seed=0)
    host = env.objects["stove"]
    rng = np.random.default_rng(0)
    hp = env.object_poses()["stove"]
    worlds = []
    for _ in range(16):
        p = switch_pose(host, hp, float(rng.uniform(-0.2, 1.2)))
        shift = rng.normal(0.0, 0.01, 3) * (rng.random() < 0.3)
        worlds.append(Pose(p.pos + shift, p.quat))
    pos = np.array([w.pos for w in worlds])
    pressed, lateral = switch_presses(host, np.tile(hp.pos, (16, 1)), np.tile(hp.quat, (16, 1)),
                                      pos)
    for k, w in enumerate(worlds):
        scalar, off = switch_pressed(host, hp, w)
        assert pressed[k] == pytest.approx(scalar, abs=1e-9)
        assert lateral[k] == pytest.approx(off, abs=1e-9)


def test_check_reads_on_off_and_held() -> None:
    graph = get_task("turn-on-stove")
    env = FactaskEnv(graph)
    env.reset(seed=0)
    solved = env.solved["switch_on_stove_switch"]
    goal = graph.factor("switch_on_stove_switch").goal
    poses = dict(env.object_poses())
    host = env.objects["stove"]
    for pressed, placed in ((1.0, True), (0.85, True), (0.5, False), (0.0, False)):
        poses["stove_switch"] = switch_pose(host, poses["stove"], pressed)
        verdict = goal.check(solved, CheckScene(env.objects, poses, frozenset()))
        assert ("stove_switch" in verdict.placed) is placed, pressed
    held = goal.check(solved, CheckScene(env.objects, poses, frozenset({"stove_switch"})))
    assert not held.placed and "held" in held.problems[0]


# ------------------------------------------------------------------ validation
def _graph(variables: list[dict[str, Any]], goal: dict[str, Any]) -> dict[str, Any]:
    return {"name": "t", "description": "d", "variables": variables,
            "factors": [{"name": "f", "goal": goal}]}


def _stove_vars(**switch: Any) -> list[dict[str, Any]]:
    return [{"name": "hob", "kind": "stove"},
            {"name": "knob", "kind": "switch",
             "initial": {"type": "mounted_on", "host": "hob"}, **switch}]


def _problems(data: dict[str, Any]) -> list[tuple[str, str, str]]:
    with pytest.raises(GraphValidationError) as err:
        parse_graph(data).ensure_valid()
    return [(p.node, p.field, p.fix) for p in err.value.problems]


def test_valid_stove_graph_passes() -> None:
    parse_graph(_graph(_stove_vars(), {"type": "switched_on", "objects": ["knob"]})
                ).ensure_valid()


@pytest.mark.parametrize(("variables", "node", "field"), [
    (_stove_vars(initial={"type": "table"}), "knob", "initial"),
    (_stove_vars(size=[0.05, 0.05, 0.02]), "knob", "size"),
    (_stove_vars(count=2), "knob", "count"),
    (_stove_vars(fixed=False), "knob", "fixed"),
    ([{"name": "hob", "kind": "stove"}], "hob", "kind"),  # a stove without its switch
    ([*_stove_vars(), {"name": "k2", "kind": "switch",
                       "initial": {"type": "mounted_on", "host": "hob"}}], "hob", "kind"),
    ([{"name": "hob", "kind": "stove", "size": [0.06, 0.24, 0.04]},
      *_stove_vars()[1:]], "hob", "size"),
    ([{"name": "hob", "kind": "stove", "size": [0.22, 0.24, 0.012]},
      *_stove_vars()[1:]], "hob", "size"),
    ([{"name": "c", "kind": "container"}, {"name": "knob", "kind": "switch",
                                            "initial": {"type": "mounted_on", "host": "c"}}],
     "knob", "initial.host"),
    ([*_stove_vars(), {"name": "b", "kind": "block",
                       "initial": {"type": "mounted_on", "host": "hob"}}], "b", "initial"),
])
def test_bad_switch_is_refused_naming_the_field(variables: list[dict[str, Any]], node: str,
                                                field: str) -> None:
    problems = _problems(_graph(variables, {"type": "switched_on", "objects": ["knob"]}
                                if any(v["name"] == "knob" for v in variables)
                                else {"type": "on", "objects": ["b"], "support": "hob"}))
    assert any(n == node and f == field and fix for n, f, fix in problems), problems


@pytest.mark.parametrize(("relation", "on"), [("switched_on", True), ("switched_off", False)])
def test_a_switch_that_starts_as_the_goal_asks_is_refused(relation: str, on: bool) -> None:
    variables = _stove_vars(initial={"type": "mounted_on", "host": "hob", "on": on})
    problems = _problems(_graph(variables, {"type": relation, "objects": ["knob"]}))
    assert [(n, f) for n, f, _ in problems] == [("f", "goal")]
    assert f'"on": {str(not on).lower()}' in problems[0][2]


@pytest.mark.parametrize("relation", ["switched_on", "switched_off"])
def test_switch_relations_refuse_what_is_not_a_switch(relation: str) -> None:
    # The stove itself is not what is pressed: its switch is.
    problems = _problems(_graph(_stove_vars(), {"type": relation, "objects": ["hob"]}))
    found = [(n, f, fix) for n, f, fix in problems if f == "goal.objects"]
    assert found and "switch" in found[0][2]
    variables = [*_stove_vars(), {"name": "b", "kind": "block"}]
    problems = _problems(_graph(variables, {"type": relation, "objects": ["b"]}))
    assert ("f", "goal.objects") in [(n, f) for n, f, _ in problems]


def test_switch_kinds_table_and_library_builder() -> None:
    assert set(SWITCH_HOSTS) >= {"stove", "lamp"}
    for kind in SWITCH_HOSTS:
        assert switch_size(kind) == SWITCH_HOSTS[kind].button
        host, switch = stove("thing", kind=kind)
        graph = TaskGraph(name="t", variables=[host, switch])
        assert not [p for p in graph.problems() if p.field != "factors"]


# ------------------------------------------------------------------ the batch
def test_switch_tasks_are_left_to_the_scalar_oracle_in_a_batch() -> None:
    from factask.batch.agreement import NOT_BATCHED, batched

    assert {"switched_on", "switched_off"} <= NOT_BATCHED
    assert not any(batched(get_task(t)) for t in SWITCH_TASKS)


def test_a_switch_task_is_refused_by_the_batched_env_with_a_typed_error() -> None:
    import importlib.util

    if importlib.util.find_spec("mujoco_warp") is None or importlib.util.find_spec("warp") is None:
        pytest.skip("the gpu extra is not installed")
    from factask.batch import make_batch
    from factask.vocabulary.errors import InvalidValueError

    with pytest.raises(InvalidValueError, match=r"switch's pose follows its slide joint"):
        make_batch("turn-on-stove", 1, device="cpu")
