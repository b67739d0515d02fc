"""The scripted suction oracle (factask.sim.oracle.scripted) and the episode runner
(factask.sim.episode): library sweeps, failure reasons, re-planning, and the
research's success definitions.

The sweep of every library task with both robots is in
``tests/test_library_tasks.py`` (slow).
"""

from __future__ import annotations

import numpy as np
import pytest
from helpers import free_spot, make_graph

from factask.geometry import Pose
from factask.graph import GraphValidationError
from factask.library import get_task, task_names
from factask.sim.build.compile import set_object_pose
from factask.sim.env import FactaskEnv
from factask.sim.episode import (
    EpisodeResult,
    TaskResult,
    check_runtime,
    evaluate_task,
    run_episode,
)
from factask.sim.oracle.scripted import MAX_ATTEMPTS_PER_OBJECT, Oracle
from factask.vocabulary.tolerances import COMPLETION_FRACTION, SUCCESS_REWARD


# ------------------------------------------------------------ library sweeps
def test_library_is_large_enough() -> None:
    assert len(task_names()) >= 30


# ------------------------------------------------------------ failure reasons
def test_unreachable_target_reports_the_factor_without_raising() -> None:
    """A target hanging 15 cm in the air: the oracle keeps dropping the block, gives up
    after its attempts, and the episode's failure names the factor and the object."""
    graph = make_graph(
        [{"name": "cube", "kind": "block", "color": "red"}],
        [{"name": "float_cube", "goal": {"type": "at_pose", "objects": ["cube"],
                                         "poses": [{"x": 0.5, "y": 0.0, "z": 0.15}]}}])
    r = run_episode(graph, 0)
    assert r.success is False
    assert r.failure, r
    assert "float_cube" in r.failure and "cube" in r.failure
    assert f"{MAX_ATTEMPTS_PER_OBJECT} attempts" in r.failure
    assert r.steps == MAX_ATTEMPTS_PER_OBJECT
    assert r.details.get("float_cube"), r.details
    assert r.reward < SUCCESS_REWARD


def test_target_outside_workspace_reports_the_factor_without_raising() -> None:
    """An at_pose target off the table: a world-frame one is rejected by validation;
    one given in another object's frame cannot be solved, and run_episode returns
    the reset failure naming the factor, not an exception."""
    with pytest.raises(GraphValidationError, match=r"far_away.*outside the workspace"):
        make_graph([{"name": "cube", "kind": "block"}],
                   [{"name": "far_away", "goal": {"type": "at_pose", "objects": ["cube"],
                                                  "poses": [{"x": 1.5, "y": 0.0}]}}])
    graph = make_graph(
        [{"name": "cube", "kind": "block"}, {"name": "mark", "kind": "zone"}],
        [{"name": "far_away", "goal": {"type": "at_pose", "objects": ["cube"], "frame": "mark",
                                       "poses": [{"x": 1.5, "y": 0.0}]}}])
    r = run_episode(graph, 0)
    assert r.success is False and r.steps == 0
    assert r.failure and "far_away" in r.failure and "workspace" in r.failure, r.failure


# ------------------------------------------------------------ re-planning
def _free_spot(env: FactaskEnv, half: float = 0.05) -> np.ndarray:
    return free_spot(env, half, seed=1, tries=2000)


def test_oracle_replans_after_a_placed_object_is_displaced() -> None:
    """Once the first factor is done, knock its object away: the oracle notices (the
    factor is unsatisfied again), puts it back, and the episode still succeeds."""
    graph = make_graph(
        [{"name": "cube", "kind": "block", "color": "red"},
         {"name": "zone", "kind": "zone", "color": "green"},
         {"name": "pair", "kind": "block", "color": "blue", "count": 2}],
        [{"name": "in_zone", "goal": {"type": "in_zone", "objects": ["cube"], "zone": "zone"}},
         {"name": "row", "goal": {"type": "row", "objects": ["pair"]}, "after": ["in_zone"]}])
    env = FactaskEnv(graph)
    try:
        env.reset(seed=4)
        oracle = Oracle(env, seed=4)
        planned = oracle.plan()
        assert planned is not None and planned.factor == "in_zone" and planned.obj == "cube"
        _, _, _, _, info = env.step(planned.as_env_action())
        assert info["satisfied"]["in_zone"] and not info["satisfied"]["row"]
        planned = oracle.plan()
        assert planned is not None and planned.factor == "row"
        _, _, _, _, info = env.step(planned.as_env_action())
        assert info["factors"]["row"] > 0.0
        # Knock the cube out of its zone.
        xy = _free_spot(env)
        cube = env.objects["cube"]
        set_object_pose(env.model, env.data, env.scene.objects["cube"],
                        Pose.from_xyz_yaw(xy[0], xy[1], cube.half[2], 0.3))
        status = env.status()
        assert not status.factors["in_zone"].satisfied
        replanned = oracle.plan()
        assert replanned is not None
        assert (replanned.factor, replanned.obj) == ("in_zone", "cube"), replanned
        assert np.allclose(replanned.pick[:2], xy)
        info = {}
        terminated = truncated = False
        env.step(replanned.as_env_action())
        for _ in range(graph.max_actions()):
            planned = oracle.plan()
            if planned is None:
                break
            _, _, terminated, truncated, info = env.step(planned.as_env_action())
            if terminated or truncated:
                break
        final = env.status()
        assert final.success, (oracle.failure, {n: s.detail for n, s in final.factors.items()})
        assert oracle.failure is None
    finally:
        env.close()


def test_oracle_clears_what_a_later_goal_moves_from_under_a_target() -> None:
    """construct-corner-blocks, seed 6: the blue block starts in the open square under
    the green block's target (the green rests on the two red blocks' corners above
    it). Set down there, the green would rest on the blue one too, and taking the blue
    up for its own goal would pull the green off: the oracle moves the blue first."""
    from factask.scene.collision import beneath

    graph = get_task("construct-corner-blocks")
    env = FactaskEnv(graph)
    try:
        env.reset(seed=6)
        target = env.solved["junction_corner"].targets(env.objects)["green_block"]
        assert beneath("green_block", target, env.objects, env.object_poses()) == [
            "blue_block"]
        oracle = Oracle(env, seed=6)
        whys = []
        for _ in range(graph.max_actions()):
            planned = oracle.plan()
            if planned is None:
                break
            whys.append(planned.purpose)
            env.step(planned.as_env_action())
        assert whys[2] == "clear under the target of green_block", whys
        assert env.status().success, oracle.failure
    finally:
        env.close()


# ------------------------------------------------------------ success definitions
def test_episode_success_is_reward_threshold() -> None:
    """EpisodeResult.success is ``reward >= SUCCESS_REWARD`` (0.99)."""
    assert SUCCESS_REWARD == 0.99
    ok = run_episode(get_task("put-block-in-bowl"), 0)
    assert ok.success and ok.reward >= SUCCESS_REWARD
    graph = make_graph(
        [{"name": "cube", "kind": "block"}],
        [{"name": "float_cube", "goal": {"type": "at_pose", "objects": ["cube"],
                                         "poses": [{"x": 0.5, "y": 0.0, "z": 0.15}]}}])
    bad = run_episode(graph, 0)
    assert bad.success is (bad.reward >= SUCCESS_REWARD) is False


def _episodes(successes: list[bool]) -> list[EpisodeResult]:
    return [EpisodeResult(seed=i, reward=1.0 if s else 0.4, success=s, steps=1)
            for i, s in enumerate(successes)]


@pytest.mark.parametrize(("successes", "rate", "completed"), [
    ([], 0.0, False),
    ([False], 0.0, False),
    ([True], 1.0, True),
    ([True, False], 0.5, True),
    ([True, False, False], 1 / 3, False),
    ([True, True, False, False], 0.5, True),
    ([True, False, False, False], 0.25, False),
    ([True] * 9 + [False], 0.9, True),
])
def test_task_completion_definition(successes: list[bool], rate: float,
                                    completed: bool) -> None:
    """A task is completed iff at least half (COMPLETION_FRACTION) of its episodes
    succeed; success_rate is the fraction of successful episodes."""
    assert COMPLETION_FRACTION == 0.5
    result = TaskResult("t", _episodes(successes))
    assert result.success_rate == pytest.approx(rate)
    assert result.completed is completed
    d = result.to_dict()
    assert d["completed"] is completed and d["success_rate"] == pytest.approx(rate)


def test_evaluate_task_runs_seeded_episodes() -> None:
    """evaluate_task runs seeds seed, seed+1, ... and applies the definitions."""
    seen: list[int] = []
    result = evaluate_task(get_task("block-insertion"), episodes=2, seed=7,
                           on_episode=lambda e: seen.append(e.seed))
    assert seen == [7, 8]
    assert [e.seed for e in result.episodes] == [7, 8]
    assert result.task == "block-insertion"
    assert result.success_rate == pytest.approx(
        sum(e.success for e in result.episodes) / 2)
    assert result.success_rate == 1.0 and result.completed
    # Same seed, same episode as a stand-alone run.
    alone = run_episode(get_task("block-insertion"), 7)
    assert alone.to_dict() == result.episodes[0].to_dict()


def test_evaluate_task_of_an_impossible_goal_is_not_completed() -> None:
    """Every episode fails (target in the air): success rate 0, not completed."""
    graph = make_graph(
        [{"name": "cube", "kind": "block"}],
        [{"name": "float_cube", "goal": {"type": "at_pose", "objects": ["cube"],
                                         "poses": [{"x": 0.5, "y": 0.1, "z": 0.15}]}}])
    result = evaluate_task(graph, episodes=2)
    assert result.success_rate == 0.0 and not result.completed
    assert all(e.failure and "float_cube" in e.failure for e in result.episodes)


# ------------------------------------------------------------ check_runtime
def test_check_runtime_accepts_a_library_task() -> None:
    """A library task compiles, resets and steps: no message."""
    assert check_runtime(get_task("stack-boxes-column")) is None


def test_check_runtime_reports_an_impossible_layout() -> None:
    """Fifty 10 cm boxes cannot fit on the workspace: a message, not an exception."""
    graph = make_graph(
        [{"name": "boxes", "kind": "box", "size": [0.1, 0.1, 0.1], "count": 50},
         {"name": "zone", "kind": "zone"}],
        [{"name": "pack", "goal": {"type": "in_zone", "objects": ["boxes"], "zone": "zone"}}])
    message = check_runtime(graph)
    assert isinstance(message, str) and message
    assert message.startswith("reset:"), message
