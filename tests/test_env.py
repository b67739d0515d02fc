"""The gymnasium environment (factask.sim.env.FactaskEnv) with the floating suction cup.

Covers seeded reproducibility, the spaces, the info dict, malformed actions,
physics failures, the action budget, the reward as a change of the total reward,
real re-checking (a knocked-over stack loses its reward) and goal markers.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

import mujoco
import numpy as np
import pytest
from helpers import free_spot

from factask.geometry import Pose
from factask.graph import TaskGraph
from factask.library import get_task
from factask.sim.build.compile import get_object_pose, set_object_pose
from factask.sim.env import ActionError, FactaskEnv
from factask.sim.episode import run_episode
from factask.sim.oracle.scripted import Oracle


def make_graph(variables: list[dict[str, Any]], factors: list[dict[str, Any]],
               name: str = "t", limits: dict[str, Any] | None = None) -> TaskGraph:
    """A validated graph; factor weights default to equal shares."""
    for f in factors:
        f.setdefault("weight", 1.0 / len(factors))
    data: dict[str, Any] = {"name": name, "variables": variables, "factors": factors}
    if limits is not None:
        data["limits"] = limits
    return TaskGraph.model_validate(data).ensure_valid()


def stack_graph(limits: dict[str, Any] | None = None) -> TaskGraph:
    """Three blocks in one column, red at the bottom."""
    return make_graph(
        [{"name": "red", "kind": "block", "color": "red"},
         {"name": "green", "kind": "block", "color": "green"},
         {"name": "blue", "kind": "block", "color": "blue"}],
        [{"name": "stack", "goal": {"type": "stack", "objects": ["red", "green", "blue"]}}],
        name="three-stack", limits=limits)


def zone_graph() -> TaskGraph:
    """Two factors: a block in a zone, two blocks in a row (fixed + free objects)."""
    return make_graph(
        [{"name": "cube", "kind": "block", "color": "red"},
         {"name": "zone", "kind": "zone", "color": "green"},
         {"name": "pair", "kind": "block", "color": "blue", "count": 2}],
        [{"name": "in_zone", "goal": {"type": "in_zone", "objects": ["cube"], "zone": "zone"}},
         {"name": "row", "goal": {"type": "row", "objects": ["pair"]}}],
        name="zone-and-row")


@pytest.fixture(scope="module")
def stack_env() -> Iterator[FactaskEnv]:
    """One compiled environment of :func:`stack_graph`, shared (each test resets it)."""
    env = FactaskEnv(stack_graph())
    yield env
    env.close()


def _state(env: FactaskEnv) -> dict[str, np.ndarray]:
    """Everything that must be identical after identically seeded resets."""
    out = {"qpos": env.data.qpos.copy(), "qvel": env.data.qvel.copy(),
           "mocap_pos": env.data.mocap_pos.copy(), "mocap_quat": env.data.mocap_quat.copy()}
    for name, pose in env.object_poses().items():
        out[f"pose:{name}"] = np.array(pose.to_list())
    for fname, solved in env.solved.items():
        for inst, pose in solved.targets(env.objects).items():
            out[f"target:{fname}:{inst}"] = np.array(pose.to_list())
        out[f"slots:{fname}"] = np.array([s.to_list() for s in solved.slots])
    return out


def _free_spot(env: FactaskEnv, half: float = 0.04) -> np.ndarray:
    return free_spot(env, half, seed=0, tries=1000)


def _noop_action(env: FactaskEnv) -> dict[str, np.ndarray]:
    """Pick at an empty table spot (nothing to grasp) and 'place' beside it."""
    xy = _free_spot(env)
    return {"pick": np.array([xy[0], xy[1], 0.0, 0.0]),
            "place": np.array([xy[0], xy[1], 0.05, 0.0])}


# ------------------------------------------------------------ reproducibility
def test_same_seed_is_bit_for_bit_identical(stack_env: FactaskEnv) -> None:
    """Two environments (and one environment reset twice) with one seed agree exactly."""
    other = FactaskEnv(stack_graph())
    try:
        obs_a, info_a = stack_env.reset(seed=123)
        state_a = _state(stack_env)
        obs_b, info_b = other.reset(seed=123)
        state_b = _state(other)
        assert state_a.keys() == state_b.keys()
        for key in state_a:
            assert np.array_equal(state_a[key], state_b[key]), key
        for key in obs_a:
            assert np.array_equal(obs_a[key], obs_b[key]), key
        assert info_a["targets"] == info_b["targets"]
        # Reset something else in between, then the same seed again.
        stack_env.reset(seed=5)
        stack_env.reset(seed=123)
        state_c = _state(stack_env)
        for key in state_a:
            assert np.array_equal(state_a[key], state_c[key]), key
    finally:
        other.close()


def test_different_seeds_give_different_layouts(stack_env: FactaskEnv) -> None:
    """Different seeds sample different initial layouts and targets."""
    stack_env.reset(seed=1)
    layout_1 = {n: p.pos.copy() for n, p in stack_env.initial_layout.items()}
    target_1 = stack_env.solved["stack"].slots[0].pos.copy()
    stack_env.reset(seed=2)
    layout_2 = {n: p.pos.copy() for n, p in stack_env.initial_layout.items()}
    target_2 = stack_env.solved["stack"].slots[0].pos.copy()
    assert any(not np.allclose(layout_1[n], layout_2[n]) for n in layout_1)
    assert not np.allclose(target_1, target_2)


# ------------------------------------------------------------ spaces and info
def test_spaces_contain_what_reset_and_step_return() -> None:
    """Observations of reset and step lie in the observation space; an oracle action
    lies in the action space; the info dict carries the documented keys."""
    env = FactaskEnv(zone_graph())
    try:
        obs, info = env.reset(seed=0)
        assert env.observation_space.contains(obs), obs
        assert obs["object_poses"].shape == (len(env.object_names), 7)
        assert obs["suction"][0] == 0.0
        for key in ("factors", "satisfied", "language_goals", "total_reward", "success",
                    "failure", "details", "targets"):
            assert key in info, key
        assert set(info["factors"]) == {"in_zone", "row"}
        assert set(info["satisfied"]) == {"in_zone", "row"}
        assert info["language_goals"] == {f.name: f.description for f in env.graph.factors}
        assert info["total_reward"] == 0.0 and info["success"] is False
        assert info["failure"] is None
        action = Oracle(env, seed=0).act()
        assert action is not None
        action = {k: np.asarray(v, dtype=np.float64) for k, v in action.items()}
        assert env.action_space.contains(action), action
        obs, reward, terminated, truncated, info = env.step(action)
        assert env.observation_space.contains(obs), obs
        assert isinstance(reward, float)
        assert isinstance(terminated, bool) and isinstance(truncated, bool)
        assert info["total_reward"] == pytest.approx(
            sum(f.weight * info["factors"][f.name] for f in env.graph.factors))
        assert info["action_ok"] is True and info["action_failure"] is None
        assert 0.0 < info["total_reward"] < 1.0
        # The observation matches the environment's own pose accessors.
        for i, name in enumerate(env.object_names):
            assert np.array_equal(obs["object_poses"][i], env.object_poses()[name].to_list())
    finally:
        env.close()


# ------------------------------------------------------------ errors
def test_step_before_reset_raises() -> None:
    """``step`` before any ``reset`` is a usage error."""
    env = FactaskEnv(stack_graph())
    try:
        with pytest.raises(RuntimeError, match="reset"):
            env.step({"pick": [0.5, 0.0, 0.02, 0.0], "place": [0.5, 0.1, 0.02, 0.0]})
    finally:
        env.close()


@pytest.mark.parametrize("action", [
    {"pick": [0.5, 0.0, 0.02, 0.0]},
    {"place": [0.5, 0.0, 0.02, 0.0]},
    {"pick": [0.5, 0.0, 0.02], "place": [0.5, 0.1, 0.02, 0.0]},
    {"pick": [0.5, 0.0, 0.02, 0.0], "place": [0.5, 0.1, 0.02, 0.0, 1.0]},
    {"pick": [[0.5, 0.0], [0.02, 0.0]], "place": [0.5, 0.1, 0.02]},
    {"pick": [0.5, float("nan"), 0.02, 0.0], "place": [0.5, 0.1, 0.02, 0.0]},
    {"pick": [0.5, 0.0, 0.02, 0.0], "place": [0.5, 0.1, float("inf"), 0.0]},
    {"pick": "here", "place": [0.5, 0.1, 0.02, 0.0]},
    [0.5, 0.0, 0.02, 0.0, 0.5, 0.1, 0.02, 0.0],
    None,
], ids=["no-place", "no-pick", "short-pick", "long-place", "2d-pick", "nan", "inf",
        "string", "flat-list", "none"])
def test_malformed_actions_raise_action_error(stack_env: FactaskEnv, action: Any) -> None:
    """Missing keys, wrong shapes and non-finite numbers raise ActionError and do not
    count as an action nor move anything."""
    stack_env.reset(seed=0)
    before = _state(stack_env)
    with pytest.raises(ActionError):
        stack_env.step(action)
    assert stack_env.actions_taken == 0
    after = _state(stack_env)
    for key in before:
        assert np.array_equal(before[key], after[key]), key


def test_physics_failure_terminates_without_raising(stack_env: FactaskEnv) -> None:
    """NaN velocities end the episode with ``failure`` set, not with an exception."""
    stack_env.reset(seed=0)
    handle = stack_env.scene.objects["red"]
    assert handle.qvel_adr is not None
    stack_env.data.qvel[handle.qvel_adr] = np.nan
    _, reward, terminated, truncated, info = stack_env.step(_noop_action(stack_env))
    assert terminated is True
    assert truncated is False
    assert info["failure"], info
    assert "physics" in info["failure"]
    assert info["success"] is False
    assert math.isfinite(reward)
    # Further steps keep reporting the failure and do nothing.
    _, reward2, terminated2, _, info2 = stack_env.step(_noop_action(stack_env))
    assert terminated2 is True and reward2 == 0.0 and info2["failure"] == info["failure"]
    # A fresh reset recovers.
    _, info3 = stack_env.reset(seed=0)
    assert info3["failure"] is None
    assert np.all(np.isfinite(stack_env.data.qvel))


def test_action_budget_truncates() -> None:
    """With ``limits.max_actions = 2`` useless actions truncate on the second one."""
    env = FactaskEnv(stack_graph(limits={"max_actions": 2}))
    try:
        env.reset(seed=0)
        assert env.graph.max_actions() == 2
        _, reward, terminated, truncated, info = env.step(_noop_action(env))
        assert (terminated, truncated) == (False, False)
        assert info["action_ok"] is False and info["action_failure"]
        assert reward == 0.0
        _, reward, terminated, truncated, info = env.step(_noop_action(env))
        assert (terminated, truncated) == (False, True)
        assert info["actions"] == 2
        assert info["failure"] is None
    finally:
        env.close()


# ------------------------------------------------------------ reward
def test_step_rewards_sum_to_final_total_reward() -> None:
    """The reward is the change of the total reward: the return equals the final total,
    including a deliberate undo in the middle (negative reward)."""
    env = FactaskEnv(stack_graph())
    try:
        _, info = env.reset(seed=3)
        start = info["total_reward"]
        rewards: list[float] = []
        totals = [start]
        oracle = Oracle(env, seed=3)
        undone = False
        for _ in range(12):
            action = oracle.act()
            if action is None:
                break
            _, r, terminated, truncated, info = env.step(action)
            rewards.append(r)
            totals.append(info["total_reward"])
            assert r == pytest.approx(totals[-1] - totals[-2], abs=1e-12)
            if not undone and 0.0 < info["total_reward"] < 1.0:
                # Undo: move the bottom block (already placed) away from the column.
                red = env.object_poses()["red"]
                xy = _free_spot(env)
                _, r, terminated, truncated, info = env.step({
                    "pick": [red.pos[0], red.pos[1], red.pos[2] + 0.02, red.yaw],
                    "place": [xy[0], xy[1], 0.04, red.yaw]})
                rewards.append(r)
                totals.append(info["total_reward"])
                assert r < 0.0, "undoing a placed block must lower the reward"
                undone = True
            if terminated or truncated:
                break
        assert undone
        assert info["success"] is True
        assert start + sum(rewards) == pytest.approx(info["total_reward"], abs=1e-9)
        assert info["total_reward"] == pytest.approx(1.0)
    finally:
        env.close()


# ------------------------------------------------------------ re-checking
def test_knocked_over_stack_loses_reward_and_success() -> None:
    """After the oracle builds the library's box column, laying the top box on the
    table beside the column lowers the total reward and ends success."""
    graph = get_task("stack-boxes-column")
    env = FactaskEnv(graph)
    try:
        result = run_episode(graph, seed=0, env=env)
        assert result.success, result.failure
        status = env.status()
        assert status.success and status.reward == pytest.approx(1.0)
        (fname,) = [f.name for f in graph.factors if f.goal.type == "stack"]
        column = env.solved[fname]
        objs = env.objects
        top = max(column.objects, key=lambda n: env.object_poses()[n].pos[2])
        obj = objs[top]
        # Lying on its side (turned 90 deg about x) on the table, beside the column.
        xy = _free_spot(env, half=float(np.max(obj.size)))
        lying = Pose(np.array([xy[0], xy[1], obj.size[1] / 2]),
                     np.array([math.cos(math.pi / 4), math.sin(math.pi / 4), 0.0, 0.0]))
        set_object_pose(env.model, env.data, env.scene.objects[top], lying)
        mujoco.mj_forward(env.model, env.data)
        knocked = env.status()
        assert knocked.success is False
        assert knocked.reward < status.reward - 0.1
        assert not knocked.factors[fname].satisfied
        # Physics does not put it back either.
        for _ in range(250):
            mujoco.mj_step(env.model, env.data)
        after = env.status()
        assert after.success is False
        assert after.reward == pytest.approx(knocked.reward)
        pose = get_object_pose(env.data, env.scene.objects[top])
        assert np.linalg.norm(pose.pos[:2] - xy) < 0.02
    finally:
        env.close()


# ------------------------------------------------------------ markers
def test_markers_are_at_the_solved_targets() -> None:
    """Every goal marker's mocap pose is the solved target of its object."""
    env = FactaskEnv(zone_graph())
    try:
        for seed in (0, 1):
            env.reset(seed=seed)
            assert env.scene.markers
            for (factor, slot), mocap in env.scene.markers.items():
                inst = env.scene.marker_objects[(factor, slot)]
                target = env.solved[factor].targets(env.objects)[inst]
                assert np.array_equal(env.data.mocap_pos[mocap], target.pos), (factor, slot)
                assert np.array_equal(env.data.mocap_quat[mocap], target.quat), (factor, slot)
    finally:
        env.close()
