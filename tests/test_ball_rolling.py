"""A ball let go on a 4 cm block's flat top with a little drift stays on it.

A real ball stops rolling (rolling resistance); MuJoCo gives a sphere that only
with condim 6 and a rolling coefficient (a length: torque = coefficient x normal
force). With the default 0.1 mm a ball at 20 mm/s on a fixed block rolled 26 cm
and fell off; the oracle's arm leaves a few mm/s to 2 cm/s at release, so
``color-coordinated-sphere-on-pallet-pyramid`` lost half its arm episodes.
"""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

import factask as ft
from factask.sim.build.compile import compile_graph
from factask.sim.build.parts import BALL_FRICTION, ROLLING_CONDIM

BALL_RADIUS = 0.02


def _ball_on_block() -> tuple[ft.TaskGraph, object]:
    block = ft.StateVariable(name="block", kind="block", color="red", fixed=True)
    ball = ft.StateVariable(name="ball", kind="ball", color="blue")
    graph = ft.TaskGraph(
        name="ball-on-block", description="put the ball on the block",
        variables=[block, ball],
        factors=[ft.SubtaskFactor(name="on", description="the ball on the block",
                                  goal=ft.On(objects=["ball"], support="block"))])
    return graph, compile_graph(graph, robot=None)


@pytest.mark.parametrize("speed", [0.005, 0.02, 0.04])
def test_ball_released_on_block_comes_to_rest_on_it(speed: float) -> None:
    """Rolling at ``speed`` (m/s) from the block's centre, the ball stops within
    5 mm and is still on the top after 3 s."""
    _, scene = _ball_on_block()
    model, data = scene.model, mujoco.MjData(scene.model)
    block, ball = scene.objects["block"], scene.objects["ball"]
    mujoco.mj_forward(model, data)
    centre = data.xpos[block.body_id].copy()
    top = centre[2] + block.size[2] / 2
    q, v = ball.qpos_adr, ball.qvel_adr
    data.qpos[q:q + 7] = [centre[0], centre[1], top + BALL_RADIUS, 1, 0, 0, 0]
    # Rolling without slipping along +x: spin about +y at speed / radius.
    data.qvel[v:v + 6] = [speed, 0, 0, 0, speed / BALL_RADIUS, 0]
    for _ in range(int(3.0 / model.opt.timestep)):
        mujoco.mj_step(model, data)
    pos = data.xpos[ball.body_id]
    assert np.linalg.norm(pos[:2] - centre[:2]) < 0.005
    assert pos[2] == pytest.approx(top + BALL_RADIUS, abs=0.002)
    assert np.linalg.norm(data.qvel[v:v + 3]) < 1e-3


def _log_on_table() -> object:
    log = ft.StateVariable(name="log", kind="log", color="green", size=(0.12, 0.04, 0.04))
    zone = ft.StateVariable(name="zone", kind="zone", color="blue")
    graph = ft.TaskGraph(
        name="log-in-zone", description="put the log in the zone", variables=[log, zone],
        factors=[ft.SubtaskFactor(name="in_zone", description="the log in the zone",
                                  goal=ft.InZone(objects=["log"], zone="zone"))])
    return compile_graph(graph, robot=None)


def test_only_round_rollers_get_rolling_friction() -> None:
    """Balls and lying cylinders (logs) have condim 6 and the rolling coefficient; a
    block keeps condim 4 (its flat faces need none, and rolling constraints cost
    solver time)."""
    _, scene = _ball_on_block()
    ball_geom = scene.objects["ball"].geom_ids[0]
    block_geom = scene.objects["block"].geom_ids[0]
    assert scene.model.geom_condim[ball_geom] == ROLLING_CONDIM
    np.testing.assert_allclose(scene.model.geom_friction[ball_geom], BALL_FRICTION)
    assert scene.model.geom_condim[block_geom] == 4
    logs = _log_on_table()
    assert logs.model.geom_condim[logs.objects["log"].geom_ids[0]] == ROLLING_CONDIM


@pytest.mark.parametrize("speed", [0.005, 0.02])
def test_log_rolling_across_comes_to_rest(speed: float) -> None:
    """A log let go rolling across its axis at ``speed`` (m/s) stops within 5 mm,
    still lying on its side."""
    scene = _log_on_table()
    model, data = scene.model, mujoco.MjData(scene.model)
    log = scene.objects["log"]
    q, v = log.qpos_adr, log.qvel_adr
    radius = 0.02
    data.qpos[q:q + 7] = [0.5, 0.0, radius, 1, 0, 0, 0]
    # Its axis lies along x: rolling without slipping along +y spins it about -x.
    data.qvel[v:v + 6] = [0, speed, 0, -speed / radius, 0, 0]
    for _ in range(int(3.0 / model.opt.timestep)):
        mujoco.mj_step(model, data)
    pos = data.xpos[log.body_id]
    assert abs(pos[1]) < 0.005
    assert abs(pos[0] - 0.5) < 0.005
    assert pos[2] == pytest.approx(radius, abs=0.002)
    assert np.linalg.norm(data.qvel[v:v + 3]) < 1e-3


def test_a_rolled_log_reads_lying_flat_with_its_yaw() -> None:
    """A log is the same lying cylinder however far it has rolled about its axis: its
    pose reads without the roll (tilt 0, the axis's yaw), so the checks and the oracle
    do not take a rolled log for one tipped over."""
    from factask.geometry import quat_from_axis_angle, quat_from_yaw, quat_mul, tilt_deg, yaw_of
    from factask.sim.build.compile import get_object_pose

    scene = _log_on_table()
    data = mujoco.MjData(scene.model)
    log = scene.objects["log"]
    q = log.qpos_adr
    for roll in (0.0, 2.1, -2.9, np.pi):
        quat = quat_mul(quat_from_yaw(0.7), quat_from_axis_angle((1.0, 0.0, 0.0), roll))
        data.qpos[q:q + 7] = [0.5, 0.0, 0.02, *quat]
        pose = get_object_pose(data, log)
        assert tilt_deg(pose.quat) == pytest.approx(0.0, abs=1e-6)
        assert yaw_of(pose.quat) == pytest.approx(0.7, abs=1e-9)
    # A log whose axis is raised keeps the slope: that tilt is real.
    quat = quat_mul(quat_from_yaw(0.3), quat_from_axis_angle((0.0, 1.0, 0.0), -0.4))
    data.qpos[q:q + 7] = [0.5, 0.0, 0.05, *quat_mul(quat, quat_from_axis_angle((1, 0, 0), 1.0))]
    assert tilt_deg(get_object_pose(data, log).quat) == pytest.approx(np.degrees(0.4), abs=1e-6)
