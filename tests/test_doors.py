"""Microwaves with hinged doors (issue 38, doors): the kinds, the door's joint state,
``open`` / ``closed`` on doors, the order of put-inside and close, the oracle's swing
along the arc with both robots, the batched check and the validation."""

from __future__ import annotations

import importlib.util
import math
from typing import Any

import mujoco
import numpy as np
import pytest

from factask.batch.checks import door_openings
from factask.geometry import Pose, quat_from_axis_angle, quat_mul
from factask.graph import GraphValidationError, TaskGraph, parse_graph
from factask.library import get_task
from factask.library.catalog_doors import MICROWAVE, microwave
from factask.scene.microwave import door_handle_point, door_opening, door_pose, hinge_point
from factask.scene.objects import objects_by_name
from factask.sim.env import ActionError, FactaskEnv
from factask.sim.episode import run_episode
from factask.sim.oracle.scripted import Oracle
from factask.sim.robots.door_swing import SwingAction, arc_points
from factask.vocabulary.kinds import DOOR_RANGE, door_size
from factask.vocabulary.tolerances import DRAWER_CLOSED_FRACTION, DRAWER_OPEN_FRACTION

DOOR_TASKS = ["open-microwave", "close-microwave", "open-microwave-and-put-bowl-inside",
              "put-bowl-in-microwave-and-close-it", "put-bowl-in-open-microwave-and-close-it",
              "put-bowl-in-open-drawer-and-close-it", "put-mug-in-white-microwave-and-close-it"]


def _opening(env: FactaskEnv) -> float:
    poses = env.object_poses()
    return door_opening(env.objects["microwave"], poses["microwave"],
                        env.objects["microwave_door"], poses["microwave_door"])


def _run_oracle(env: FactaskEnv) -> tuple[dict[str, Any], list[Any]]:
    """Step the oracle to its end; returns the last info and the planned actions."""
    oracle = Oracle(env, seed=0)
    info: dict[str, Any] = {}
    planned_all = []
    for _ in range(10):
        planned = oracle.plan()
        if planned is None:
            break
        planned_all.append(planned)
        _, _, terminated, truncated, info = env.step(planned.as_env_action())
        if terminated or truncated:
            break
    assert oracle.failure is None, oracle.failure
    return info, planned_all


# ----------------------------------------------------------------- geometry
@pytest.mark.parametrize("yaw", [0.0, 0.7, -2.5])
@pytest.mark.parametrize("opening", [0.0, 0.3, 1.0])
def test_door_opening_reads_back_the_pose_it_was_put_at(yaw: float, opening: float) -> None:
    objs = objects_by_name(get_task("open-microwave"))
    mw, door = objs["microwave"], objs["microwave_door"]
    mw_pose = Pose.from_xyz_yaw(0.5, 0.1, MICROWAVE[2] / 2, yaw)
    pose = door_pose(mw, mw_pose, door, opening)
    assert door_opening(mw, mw_pose, door, pose) == pytest.approx(opening, abs=1e-9)
    # The handle stays on the circle about the hinge, at the panel's own radius.
    closed = door_handle_point(door, door_pose(mw, mw_pose, door, 0.0))
    here = door_handle_point(door, pose)
    hinge = hinge_point(mw, mw_pose)
    assert np.linalg.norm(here[:2] - hinge[:2]) == pytest.approx(
        np.linalg.norm(closed[:2] - hinge[:2]), abs=1e-9)
    # Open all the way, the door stands square to the microwave's front, sticking out
    # of it (towards the microwave's -x): it swings outwards, not into the box.
    if opening == 1.0:
        local = (here - mw_pose.pos) @ np.array([math.cos(yaw), math.sin(yaw), 0.0])
        assert local < -MICROWAVE[0] / 2 - 0.1


def test_arc_points_turn_the_shorter_way_at_a_constant_radius() -> None:
    hinge = np.array([0.4, 0.0])
    start = np.array([0.4, 0.2, 0.1])
    points, angles = arc_points(start, np.array([0.2, 0.0]), hinge)
    assert angles[-1] == pytest.approx(math.pi / 2)
    assert all(np.linalg.norm(p[:2] - hinge) == pytest.approx(0.2) for p in points)
    assert all(p[2] == 0.1 for p in points)
    chords = np.linalg.norm(np.diff([start, *points], axis=0), axis=1)
    assert chords.max() <= 0.02 + 1e-9


def test_door_pose_follows_its_hinge_joint() -> None:
    env = FactaskEnv(get_task("open-microwave"))
    env.reset(seed=0)
    handle = env.scene.objects["microwave_door"].slide
    assert handle is not None
    assert _opening(env) == pytest.approx(0.0, abs=1e-3)
    env.data.qpos[handle.qpos_adr] = 0.5 * DOOR_RANGE
    assert _opening(env) == pytest.approx(0.5, abs=1e-6)
    # The pose read from the joint is where MuJoCo puts the body.
    mujoco.mj_forward(env.model, env.data)
    body = env.scene.objects["microwave_door"].body_id
    pose = env.object_poses()["microwave_door"]
    np.testing.assert_allclose(pose.pos, env.data.xpos[body], atol=1e-9)
    assert abs(np.dot(pose.quat, env.data.xquat[body])) == pytest.approx(1.0, abs=1e-9)


def test_the_scene_mjcf_keeps_the_door_on_its_hinge() -> None:
    from factask.sim.build.compile import compile_graph

    scene = compile_graph(get_task("put-bowl-in-microwave-and-close-it"), robot="arm")
    model = mujoco.MjModel.from_xml_string(scene.xml)
    joint = model.joint("microwave_door:hinge")
    assert int(joint.type[0]) == int(mujoco.mjtJoint.mjJNT_HINGE)
    # MuJoCo writes the range with 6 significant digits (1.5708).
    np.testing.assert_allclose(joint.range, [0.0, DOOR_RANGE], atol=1e-5)
    assert model.nq == scene.model.nq
    # The same joint angle puts the door's body at the same place in both models.
    for m in (model, scene.model):
        data = mujoco.MjData(m)
        data.qpos[m.jnt_qposadr[m.joint("microwave_door:hinge").id]] = 0.7
        mujoco.mj_forward(m, data)
        if m is model:
            exported = data.xpos[m.body("microwave_door").id].copy()
        else:
            np.testing.assert_allclose(data.xpos[m.body("microwave_door").id], exported,
                                       atol=1e-9)


# ------------------------------------------------------------ the oracle
@pytest.mark.parametrize("robot", ["floating", "arm"])
def test_oracle_swings_the_door_open_and_it_reads_open(robot: str) -> None:
    env = FactaskEnv(get_task("open-microwave"), robot=robot)
    env.reset(seed=3)
    info, planned = _run_oracle(env)
    assert isinstance(planned[0], SwingAction)
    assert info["success"]
    assert _opening(env) >= DRAWER_OPEN_FRACTION
    assert env.held_objects() == frozenset()


@pytest.mark.parametrize("robot", ["floating", "arm"])
def test_bowl_put_in_the_microwave_reads_inside_once_the_door_is_shut(robot: str) -> None:
    env = FactaskEnv(get_task("put-bowl-in-microwave-and-close-it"), robot=robot)
    env.reset(seed=5)
    info, planned = _run_oracle(env)
    assert [type(p).__name__ for p in planned] == ["SwingAction", "OracleAction",
                                                   "SwingAction"]
    assert info["success"]
    assert _opening(env) <= DRAWER_CLOSED_FRACTION
    status = env.status()
    assert status.factors["put_in_blue_bowl"].satisfied
    # Inside the microwave's walls for real: between its side panels and on its floor.
    poses = env.object_poses()
    yaw = poses["microwave"].yaw
    rel = poses["blue_bowl"].pos - poses["microwave"].pos
    x = math.cos(yaw) * rel[0] + math.sin(yaw) * rel[1]
    y = -math.sin(yaw) * rel[0] + math.cos(yaw) * rel[1]
    assert abs(x) < MICROWAVE[0] / 2 and abs(y) < MICROWAVE[1] / 2
    assert poses["blue_bowl"].pos[2] < MICROWAVE[2]


@pytest.mark.parametrize("task", DOOR_TASKS)
@pytest.mark.parametrize("robot", ["floating", "arm"])
def test_library_door_tasks_succeed_with_the_oracle(task: str, robot: str) -> None:
    assert run_episode(get_task(task), seed=7, robot=robot).success, (task, robot)


def test_a_swing_action_is_checked() -> None:
    env = FactaskEnv(get_task("open-microwave"))
    env.reset(seed=0)
    with pytest.raises(ActionError, match="hinge"):
        env.step({"grasp": [0.5, 0, 0.1, 0], "swing_to": [0.4, 0, 0.1, 0],
                  "hinge": [float("nan"), 0.0]})


# ------------------------------------------------------------------ order
def test_put_inside_comes_after_the_open_and_before_the_close() -> None:
    graph = get_task("put-bowl-in-microwave-and-close-it")
    assert graph.factor_order() == ["open_microwave_door", "put_in_blue_bowl",
                                    "close_microwave_door"]
    d = graph.dependency_graph()
    assert d.has_edge("open_microwave_door", "put_in_blue_bowl")  # through the door's gate
    assert d.has_edge("put_in_blue_bowl", "close_microwave_door")


@pytest.mark.parametrize("task", ["put-bowl-in-open-microwave-and-close-it",
                                  "put-bowl-in-open-drawer-and-close-it"])
def test_put_in_what_starts_open_then_close_it_is_expressible(task: str) -> None:
    # Was a cycle: the goal anchored to the drawer was ordered after its only move
    # (the close), and the author's 'after' closed the loop.
    graph = get_task(task)
    put, close = graph.factor_order()
    assert put.startswith("put_in") and close.startswith("close")
    explicit = graph.model_copy(update={"factors": [
        graph.factor(put), graph.factor(close).model_copy(update={"after": [put]})]})
    explicit.ensure_valid()
    assert explicit.factor_order() == [put, close]


# --------------------------------------------------------------- batched
def test_batched_door_opening_equals_the_scalar_one() -> None:
    objs = objects_by_name(get_task("open-microwave"))
    mw, door = objs["microwave"], objs["microwave_door"]
    rng = np.random.default_rng(0)
    mw_quats, door_quats, want = [], [], []
    for _ in range(50):
        mw_pose = Pose.from_xyz_yaw(0.5, 0.0, 0.06, float(rng.uniform(-math.pi, math.pi)))
        pose = door_pose(mw, mw_pose, door, float(rng.uniform(-0.3, 1.3)))
        tilt = quat_from_axis_angle((1.0, 0.0, 0.0), float(rng.uniform(-0.2, 0.2)))
        pose = Pose(pose.pos, quat_mul(pose.quat, tilt))
        mw_quats.append(mw_pose.quat)
        door_quats.append(pose.quat)
        want.append(door_opening(mw, mw_pose, door, pose))
    got = door_openings(np.array(mw_quats), np.array(door_quats))
    np.testing.assert_allclose(got, want, atol=1e-9)


@pytest.mark.skipif(importlib.util.find_spec("mujoco_warp") is None
                    or importlib.util.find_spec("warp") is None,
                    reason="the gpu extra is not installed")
def test_a_task_with_a_door_is_refused_by_the_batch_with_a_typed_error() -> None:
    from factask.batch import make_batch
    from factask.vocabulary.errors import InvalidValueError

    with pytest.raises(InvalidValueError, match=r"doors .*microwave_door.* not in the batched"):
        make_batch("open-microwave", 1, device="cpu")


# ------------------------------------------------------------- validation
def _vars(**door: Any) -> list[dict[str, Any]]:
    return [{"name": "mw", "kind": "microwave", "size": list(MICROWAVE)},
            {"name": "door", "kind": "door", "size": list(door_size(MICROWAVE)),
             "initial": {"type": "in_cabinet", "cabinet": "mw"}, **door}]


def _graph(variables: list[dict[str, Any]], goal: dict[str, Any]) -> dict[str, Any]:
    return {"name": "t", "variables": variables,
            "factors": [{"name": "f", "description": "d", "goal": goal}]}


def _problems(data: dict[str, Any]) -> list[tuple[str, str, str]]:
    with pytest.raises(GraphValidationError) as err:
        parse_graph(data).ensure_valid()
    return [(p.node, p.field, p.fix) for p in err.value.problems]


def test_valid_microwave_graph_passes() -> None:
    parse_graph(_graph(_vars(), {"type": "open", "objects": ["door"]})).ensure_valid()


@pytest.mark.parametrize(("change", "field", "fix"), [
    ({"initial": {"type": "table"}}, "initial", "in_cabinet"),
    ({"size": [0.045, 0.1, 0.1]}, "size", "give size"),
    ({"initial": {"type": "in_cabinet", "cabinet": "mw", "level": 1}}, "initial.level", "level"),
    ({"count": 2}, "count", "own variable"),
    ({"fixed": False}, "fixed", "fixed"),
])
def test_bad_door_is_refused_naming_the_field_and_fix(change: dict[str, Any], field: str,
                                                      fix: str) -> None:
    problems = _problems(_graph(_vars(**change), {"type": "open", "objects": ["door"]}))
    assert any(n == "door" and f == field and fix in x for n, f, x in problems), problems


def test_a_door_hangs_on_a_microwave_and_a_microwave_has_one() -> None:
    variables = [{"name": "cab", "kind": "cabinet"}, *_vars()]
    variables[2]["initial"] = {"type": "in_cabinet", "cabinet": "cab"}
    problems = _problems(_graph(variables, {"type": "closed", "objects": ["door"]}))
    fields = [(n, f) for n, f, _ in problems]
    assert ("door", "initial.cabinet") in fields
    assert ("mw", "kind") in fields  # the microwave is left without its door


def test_open_refuses_what_is_neither_a_drawer_nor_a_door() -> None:
    variables = [*_vars(), {"name": "b", "kind": "block"}]
    problems = _problems(_graph(variables, {"type": "open", "objects": ["b"]}))
    assert any(n == "f" and f == "goal.objects" and "door" in fix for n, f, fix in problems)


def test_library_microwave_builder_gives_a_valid_pair() -> None:
    box, door = microwave(opening=0.5)
    graph = TaskGraph(name="t", variables=[box, door])
    assert not [p for p in graph.problems() if p.field != "factors"]

