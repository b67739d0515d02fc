"""Cabinets with sliding drawers (issue 38, first slice): the kinds, their joint state,
the ``open`` / ``closed`` relations, the oracle's slide and the library tasks."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from factask.graph import GraphValidationError, TaskGraph, parse_graph
from factask.library import get_task
from factask.library.catalog_articulated import TWO_DRAWERS, cabinet
from factask.scene.cabinet import drawer_opening
from factask.sim.env import FactaskEnv
from factask.sim.episode import run_episode
from factask.sim.oracle.scripted import Oracle
from factask.vocabulary.kinds import drawer_size, drawer_travel
from factask.vocabulary.tolerances import DRAWER_CLOSED_FRACTION, DRAWER_OPEN_FRACTION


def _opening(env: FactaskEnv, drawer: str) -> float:
    poses = env.object_poses()
    return drawer_opening(env.objects["cabinet"], poses["cabinet"], env.objects[drawer],
                          poses[drawer])


def _run_oracle(env: FactaskEnv, after_step: Any = None) -> dict[str, Any]:
    """Step the oracle to its end; ``after_step(action, info)`` sees every step."""
    oracle = Oracle(env, seed=0)
    info: dict[str, Any] = {}
    for _ in range(10):
        planned = oracle.plan()
        if planned is None:
            break
        _, _, terminated, truncated, info = env.step(planned.as_env_action())
        if after_step is not None:
            after_step(planned, info)
        if terminated or truncated:
            break
    assert oracle.failure is None, oracle.failure
    return info


def test_drawer_pose_follows_its_slide_joint() -> None:
    env = FactaskEnv(get_task("open-drawer"))
    env.reset(seed=0)
    handle = env.scene.objects["middle_drawer"].slide
    assert handle is not None
    travel = drawer_travel(env.objects["middle_drawer"].size)
    assert _opening(env, "middle_drawer") == pytest.approx(0.0, abs=1e-3)
    env.data.qpos[handle.qpos_adr] = 0.5 * travel
    assert _opening(env, "middle_drawer") == pytest.approx(0.5, abs=1e-6)
    # The pose read from the joint is where MuJoCo puts the body.
    import mujoco

    mujoco.mj_forward(env.model, env.data)
    body = env.scene.objects["middle_drawer"].body_id
    np.testing.assert_allclose(env.object_poses()["middle_drawer"].pos, env.data.xpos[body],
                               atol=1e-9)


def test_oracle_opens_a_drawer_and_it_reads_open() -> None:
    env = FactaskEnv(get_task("open-drawer"))
    _, info = env.reset(seed=1)
    assert not info["success"]
    info = _run_oracle(env)
    assert info["success"]
    assert _opening(env, "middle_drawer") >= DRAWER_OPEN_FRACTION
    # Its neighbours stayed shut.
    assert _opening(env, "top_drawer") <= DRAWER_CLOSED_FRACTION
    assert _opening(env, "bottom_drawer") <= DRAWER_CLOSED_FRACTION


def test_oracle_closes_a_drawer_and_it_reads_closed() -> None:
    env = FactaskEnv(get_task("close-drawer"))
    _, info = env.reset(seed=2)
    assert _opening(env, "middle_drawer") == pytest.approx(1.0, abs=0.02)
    assert not info["satisfied"]["close_middle_drawer"]
    info = _run_oracle(env)
    assert info["success"]
    assert _opening(env, "middle_drawer") <= DRAWER_CLOSED_FRACTION


def test_block_put_in_an_open_drawer_stays_inside_when_it_is_closed() -> None:
    env = FactaskEnv(get_task("put-block-in-drawer-and-close-it"))
    env.reset(seed=3)
    seen: list[tuple[str, bool, bool]] = []

    def watch(planned: Any, info: dict[str, Any]) -> None:
        seen.append((planned.purpose, info["satisfied"]["put_in_red_block"],
                     info["satisfied"]["close_top_drawer"]))

    info = _run_oracle(env, watch)
    assert info["success"]
    # Open, then put (inside, drawer still open), then close (still inside).
    assert [s[0].split()[0] for s in seen] == ["slide", "place", "slide"]
    assert seen[1][1:] == (True, False)
    assert seen[2][1:] == (True, True)
    block = env.object_poses()["red_block"].pos
    drawer = env.object_poses()["top_drawer"].pos
    assert _opening(env, "top_drawer") <= DRAWER_CLOSED_FRACTION
    assert np.linalg.norm(block[:2] - drawer[:2]) < 0.1  # it rode in with the drawer


def test_put_inside_is_solved_where_the_opened_drawer_will_be() -> None:
    graph = get_task("open-drawer-and-put-block-inside")
    assert graph.factor_order() == ["open_top_drawer", "put_in_red_block"]
    env = FactaskEnv(graph)
    env.reset(seed=0)
    target = env.solved["put_in_red_block"].targets(env.objects)["red_block"]
    opened = env.solved["open_top_drawer"].targets(env.objects)["top_drawer"]
    closed = env.object_poses()["top_drawer"]
    # The block's slot lies in the drawer pulled out, beyond the closed drawer's box.
    assert np.linalg.norm(target.pos[:2] - opened.pos[:2]) < 0.1
    assert np.linalg.norm(target.pos[:2] - closed.pos[:2]) > 0.1


def _graph(variables: list[dict[str, Any]], goal: dict[str, Any]) -> dict[str, Any]:
    return {"name": "t", "description": "d", "variables": variables,
            "factors": [{"name": "f", "goal": goal}]}


def _cabinet_vars(**drawer: Any) -> list[dict[str, Any]]:
    size = drawer_size(TWO_DRAWERS, 1)
    return [{"name": "cab", "kind": "cabinet", "size": list(TWO_DRAWERS)},
            {"name": "dr", "kind": "drawer", "size": list(size),
             "initial": {"type": "in_cabinet", "cabinet": "cab", "level": 0}, **drawer}]


def _problems(data: dict[str, Any]) -> list[tuple[str, str, str]]:
    with pytest.raises(GraphValidationError) as err:
        parse_graph(data).ensure_valid()
    return [(p.node, p.field, p.fix) for p in err.value.problems]


def test_valid_cabinet_graph_passes() -> None:
    parse_graph(_graph(_cabinet_vars(), {"type": "open", "objects": ["dr"]})).ensure_valid()


@pytest.mark.parametrize(("change", "node", "field"), [
    ({"initial": {"type": "table"}}, "dr", "initial"),
    ({"size": [0.1, 0.1, 0.05]}, "dr", "size"),
    ({"initial": {"type": "in_cabinet", "cabinet": "cab", "level": 1}}, "dr", "initial.level"),
    ({"count": 2}, "dr", "count"),
])
def test_bad_drawer_is_refused_naming_the_field(change: dict[str, Any], node: str,
                                                field: str) -> None:
    problems = _problems(_graph(_cabinet_vars(**change), {"type": "open", "objects": ["dr"]}))
    assert any(n == node and f == field and fix for n, f, fix in problems), problems


def test_open_refuses_what_is_not_a_drawer() -> None:
    variables = [*_cabinet_vars(), {"name": "b", "kind": "block"}]
    problems = _problems(_graph(variables, {"type": "open", "objects": ["b"]}))
    assert ("f", "goal.objects") in [(n, f) for n, f, _ in problems]


def test_in_cabinet_must_name_a_cabinet() -> None:
    variables = [{"name": "c", "kind": "container"},
                 {"name": "dr", "kind": "drawer",
                  "initial": {"type": "in_cabinet", "cabinet": "c", "level": 0}}]
    problems = _problems(_graph(variables, {"type": "open", "objects": ["dr"]}))
    assert ("dr", "initial.cabinet") in [(n, f) for n, f, _ in problems]


def test_library_cabinet_builder_gives_valid_drawers() -> None:
    box, drawers = cabinet(TWO_DRAWERS, opened={"top": 1.0})
    graph = TaskGraph(name="t", variables=[box, *drawers.values()])
    assert not [p for p in graph.problems() if p.field != "factors"]


#: The cabinet tasks beyond the first four: other drawers, two drawers, blocks
#: taken out of a drawer, a bowl put on the cabinet's top.
MORE_DRAWER_TASKS = ["open-top-drawer", "open-bottom-drawer", "close-top-drawer",
                     "open-two-drawers", "put-two-blocks-in-open-drawer",
                     "open-drawer-and-take-block-out", "take-block-out-of-drawer-to-zone",
                     "take-block-out-of-shut-drawer",
                     "put-bowl-on-cabinet-and-close-drawer"]


@pytest.mark.parametrize("task", ["open-drawer", "close-drawer",
                                  "open-drawer-and-put-block-inside",
                                  "put-block-in-drawer-and-close-it", *MORE_DRAWER_TASKS])
def test_library_drawer_tasks_succeed_with_the_oracle(task: str) -> None:
    graph = get_task(task)
    for seed in (10, 11):
        assert run_episode(graph, seed=seed).success, (task, seed)


def test_arm_opens_a_drawer_and_puts_a_block_inside() -> None:
    result = run_episode(get_task("open-drawer-and-put-block-inside"), seed=4, robot="arm")
    assert result.success


@pytest.mark.parametrize("task", MORE_DRAWER_TASKS)
def test_arm_does_the_other_drawer_tasks(task: str) -> None:
    assert run_episode(get_task(task), seed=4, robot="arm").success, task


def _open_bottom_of_three() -> TaskGraph:
    """Open the bottom drawer of a three-drawer cabinet: its handle, 7 cm up, lies under
    17 cm more of cabinet."""
    from factask.library.builders import assemble, use
    from factask.library.catalog_articulated import THREE_DRAWERS

    box, drawers = cabinet(THREE_DRAWERS)
    return assemble("open-bottom-of-three", "Open the bottom drawer of the cabinet.",
                    use("open_drawer", drawer=drawers["bottom"]),
                    extra=[box, drawers["middle"], drawers["top"]])


def _link_hits(env: FactaskEnv) -> set[tuple[str, str]]:
    """(link geom, furniture body) pairs of the arm's links (the cup aside) touching the
    cabinet or its drawers now."""
    import mujoco

    m, d = env.model, env.data
    furniture = {env.scene.objects[n].body_id for n in env.objects}
    hits = set()
    for c in d.contact[:d.ncon]:
        for mine, other in ((c.geom1, c.geom2), (c.geom2, c.geom1)):
            name = mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_GEOM, mine) or ""
            body = int(m.body_rootid[m.geom_bodyid[other]])
            if name.startswith("link") and (body in furniture
                                            or int(m.geom_bodyid[other]) in furniture):
                hits.add((name, mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_BODY, body) or ""))
    return hits


@pytest.mark.parametrize("seed", [0, 1])
def test_arm_opens_the_bottom_drawer_of_three_clear_of_the_cabinet(seed: int) -> None:
    # Straight down on the handle, the wrist's last link (a 4 cm cylinder round the
    # tool, 12 cm above the tip) came down on the cabinet's top: "no drawer handle
    # under the cup" every time. The arm now leans its tool out of the face.
    env = FactaskEnv(_open_bottom_of_three(), robot="arm")
    hits: set[tuple[str, str]] = set()
    env.frame_callback = lambda: hits.update(_link_hits(env))
    result = run_episode(env.graph, seed=seed, robot="arm", env=env)
    assert result.success, result.failure
    assert not hits
    env.close()


def test_the_arm_leans_only_over_a_handle_under_its_cabinet() -> None:
    env = FactaskEnv(_open_bottom_of_three(), robot="arm")
    env.reset(seed=0)
    action = Oracle(env, seed=0).plan()
    grasp, yaw = action.grasp[:3], float(action.grasp[3])  # type: ignore[union-attr]
    lean = env.robot.lean_clear_of(grasp, yaw)
    assert lean is not None
    from factask.geometry import rotate
    from factask.sim.robots.ik import tool_quat

    axis = rotate(tool_quat(yaw, lean), np.array([0.0, 0.0, 1.0]))  # the tool's upper end leans ...
    outward = grasp[:2] - env.object_poses()["cabinet"].pos[:2]
    assert axis[2] < 0.97  # ... at least 14 degrees ...
    assert axis[:2] @ outward > 0.7 * np.linalg.norm(axis[:2]) * np.linalg.norm(outward)  # ... out
    assert env.robot.lean_clear_of(grasp + np.array([0.0, 0.0, 0.2]), yaw) is None  # above it
    env.close()
    top = FactaskEnv(get_task("open-top-drawer"), robot="arm")
    top.reset(seed=0)
    above = Oracle(top, seed=0).plan()
    assert top.robot.lean_clear_of(above.grasp[:3], above.grasp[3]) is None  # type: ignore[union-attr]
    top.close()
    floating = FactaskEnv(_open_bottom_of_three())
    floating.reset(seed=0)
    assert floating.robot.lean_clear_of(grasp, yaw) is None
    floating.close()
