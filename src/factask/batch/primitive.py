"""A suction pick-and-place in lockstep: every world its own pick and place, all moving
together (the floating cup).

The batched twin, in outline, of the single env's primitive
(:mod:`factask.sim.robots.primitive`): the same action — the tip's (x, y, z, yaw) at the
grasp and at the release — and the same phases: up to a height that clears every
object, over the pick, down to just above it, a guarded descent until the cup
touches, suction on, up (clearing the held object too), over the place, a guarded
descent until the held object touches or the tip reaches the place, a wait until
everything is still, suction off, a short retreat and a wait for the objects to
rest (the single env's rest tests). The moves are straight lines at the tool's speed
limit rather than the single env's blended minimum-time profiles, and a phase lasts
as long as its longest world (the others hold still meanwhile): the same action
ends in a similar, not the same, state.

Contacts are read on the host between steps of the guarded moves only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from factask.batch.geometry import box_z_range
from factask.batch.worlds import LockstepWorlds
from factask.sim.robots.primitive import (
    APPROACH_HEIGHT,
    CLEARANCE,
    GUARDED_SPEED,
    MIN_TRAVEL_HEIGHT,
    PICK_OVERSHOOT,
    RELEASE_MAX_TIME,
    RELEASE_SPEED,
    RELEASE_SPEED_FLAT,
    REST_EVERY,
    REST_MAX_TIME,
    REST_SPEED,
    RETREAT,
    ROUND_TURN_RADIUS,
    TOOL_SPEED,
    YAW_RATE,
)
from factask.sim.robots.suction import REST_RADIUS
from factask.vocabulary.errors import InvalidValueError

#: Physics steps between two contact reads during a guarded move.
GUARD_EVERY = 2


@dataclass(frozen=True)
class BatchActionResult:
    """What one batched pick-and-place did in every world.

    Attributes:
        ok: Picked, carried and released at the place (num_envs,).
        reasons: Why each world failed (None where ok, or where it did not act).
        acted: The worlds that took the action.
        sim_steps: Physics steps the action took (the same in every world).
    """

    ok: np.ndarray
    reasons: list[str | None]
    acted: np.ndarray
    sim_steps: int


def _move(batch: LockstepWorlds, end: np.ndarray, active: np.ndarray, speed: float) -> int:
    """Straight lines from every active world's command to ``end`` at ``speed``; the
    others hold. Returns the physics steps taken."""
    start = batch.command.copy()
    delta = np.where(active[:, None], end - start, 0.0)
    dt = float(batch.model.opt.timestep)
    need = np.maximum(np.linalg.norm(delta[:, :3], axis=1) / speed,
                      np.abs(delta[:, 3]) / YAW_RATE)
    n = max(1, math.ceil(float(need.max()) / dt)) if active.any() else 0
    for k in range(1, n + 1):
        batch.step(start + delta * (k / n))
    return n


def _guarded(batch: LockstepWorlds, bottom: np.ndarray, active: np.ndarray, touching: str) -> int:
    """Down at the guarded speed in every active world until ``touching`` (a
    :class:`~factask.batch.suction.WorldSuction` method) says so or its ``bottom``
    height is reached. Returns the physics steps taken."""
    moving = active.copy()
    dz = GUARDED_SPEED * float(batch.model.opt.timestep)
    steps = 0
    check = getattr(batch.suction, touching)
    while moving.any():
        for _ in range(GUARD_EVERY):
            cmd = batch.command.copy()
            cmd[moving, 2] = np.maximum(cmd[moving, 2] - dz, bottom[moving])
            batch.step(cmd)
            steps += 1
        moving &= ~check(batch.wp_data) & (batch.command[:, 2] > bottom + 1e-9)
    return steps


def _free_dofs(model: mujoco.MjModel) -> tuple[np.ndarray, np.ndarray]:
    """The linear and the angular velocity indices of every free joint."""
    adr = model.jnt_dofadr[model.jnt_type == mujoco.mjtJoint.mjJNT_FREE]
    return ((adr[:, None] + np.arange(3)).reshape(-1),
            (adr[:, None] + 3 + np.arange(3)).reshape(-1))


def _rolls(model: mujoco.MjModel) -> np.ndarray:
    """Per body: its tree has a round geom (sphere, capsule, ellipsoid, cylinder) and,
    set down while moving, may roll on."""
    round_types = [mujoco.mjtGeom.mjGEOM_SPHERE, mujoco.mjtGeom.mjGEOM_CAPSULE,
                   mujoco.mjtGeom.mjGEOM_ELLIPSOID, mujoco.mjtGeom.mjGEOM_CYLINDER]
    out = np.zeros(model.nbody, dtype=bool)
    for g in np.flatnonzero(np.isin(model.geom_type, round_types)):
        out[model.body_rootid[model.geom_bodyid[g]]] = True
    return out


def _wait_for_rest(batch: LockstepWorlds, active: np.ndarray, speed: np.ndarray,
                   radius: np.ndarray, max_time: float) -> int:
    """Hold every command until, in every active world, no free object moves faster
    than its world's ``speed`` (m/s; turning counts at ``radius``), at most
    ``max_time`` seconds, tested every REST_EVERY steps: the single env's rest test,
    a phase as long as its slowest world. Returns the physics steps taken."""
    total = max(1, math.ceil(max_time / float(batch.model.opt.timestep)))
    linear, angular = _free_dofs(batch.model)
    done = 0
    while done < total:
        k = min(REST_EVERY, total - done)
        batch.step(batch.command, substeps=k)
        done += k
        if not active.any() or not len(linear):
            break
        qvel = batch.wp_data.qvel.numpy()
        moving = ((np.abs(qvel[:, linear]).max(axis=1) >= speed)
                  | (np.abs(qvel[:, angular]).max(axis=1) * radius >= speed))
        if not (moving & active).any():
            break
    return done


def travel_heights(batch: LockstepWorlds) -> np.ndarray:
    """Per world, the tool height that clears every object not held by
    :data:`~factask.sim.robots.primitive.CLEARANCE` (at least ``MIN_TRAVEL_HEIGHT``), plus
    the held object's height hanging below the cup."""
    scene = batch.scene()
    tops = np.stack([box_z_range(scene.objects[n], scene.pos[:, k], scene.quat[:, k])[1]
                     for k, n in enumerate(scene.names)], axis=1)
    tops = np.where(scene.held, -np.inf, tops)
    heights = np.stack([np.full(batch.num_envs, scene.objects[n].height)
                        for n in scene.names], axis=1)
    hanging = np.where(scene.held, heights, 0.0).max(axis=1)
    return np.maximum(tops.max(axis=1) + CLEARANCE, MIN_TRAVEL_HEIGHT) + hanging


def _transfer(batch: LockstepWorlds, target: np.ndarray, active: np.ndarray) -> int:
    """Up to the travel height, over ``target`` (turning to its yaw), down to
    ``APPROACH_HEIGHT`` above it, in every active world. Returns the physics steps."""
    up = np.maximum(travel_heights(batch), batch.command[:, 2])
    steps = 0
    for z in (None, up, target[:, 2] + APPROACH_HEIGHT):
        end = batch.command.copy()
        if z is None:  # straight up first
            end[:, 2] = up
        else:
            end[:, :2], end[:, 2], end[:, 3] = target[:, :2], z, target[:, 3]
        steps += _move(batch, end, active, TOOL_SPEED)
    return steps


def pick_and_place(batch: LockstepWorlds, pick: np.ndarray, place: np.ndarray,
                   worlds: np.ndarray | None = None) -> BatchActionResult:
    """One top-down suction pick-and-place in chosen worlds, all in lockstep.

    Args:
        batch: A floating-cup batch, every world reset.
        pick: (num_envs, 4) tip position on the object's top face and tool yaw.
        place: (num_envs, 4) tip position and tool yaw at the release.
        worlds: Boolean mask of the worlds that act (default all); the others hold.

    Returns:
        The :class:`BatchActionResult`.

    Raises:
        InvalidValueError: not a floating-cup batch, or wrong shapes / non-finite numbers.
    """
    if batch.command_dim != 4:
        raise InvalidValueError("the batched pick-and-place drives the floating cup only")
    pick = np.asarray(pick, dtype=float)
    place = np.asarray(place, dtype=float)
    w = batch.num_envs
    for name, a in (("pick", pick), ("place", place)):
        if a.shape != (w, 4) or not np.isfinite(a).all():
            raise InvalidValueError(f"{name} must be {w} x 4 finite numbers, got {a.shape}")
    acted = np.ones(w, dtype=bool) if worlds is None else np.asarray(worlds, dtype=bool)
    reasons: list[str | None] = [None] * w
    if not acted.any():
        return BatchActionResult(np.zeros(w, dtype=bool), reasons, acted, 0)
    steps = 0
    batch.suction_off(acted)

    steps += _transfer(batch, pick, acted)
    steps += _guarded(batch, pick[:, 2] - PICK_OVERSHOOT, acted, "cup_touching")
    held = batch.suction_on(acted) & acted
    for k in np.flatnonzero(acted & ~held):
        reasons[k] = "nothing to grasp at the pick pose"
    carrying = acted & held
    steps += _transfer(batch, place, carrying)
    steps += _guarded(batch, place[:, 2], carrying, "held_touching")
    still = batch.suction.held >= 0
    for k in np.flatnonzero(carrying & ~still):
        reasons[k] = "lost the object on the way"
    # Let go only once everything is still (the single env's rule): a carried object
    # hangs from a compliant weld and trails a fast move, tilted; let go as it first
    # touches, it drops tilted and slides (a bowl held by its rim, 4 cm).
    rolls = _rolls(batch.model)[np.maximum(batch.suction.held, 0)] & still
    w = batch.num_envs
    steps += _wait_for_rest(batch, carrying & still,
                            np.where(rolls, RELEASE_SPEED, RELEASE_SPEED_FLAT),
                            np.where(rolls, ROUND_TURN_RADIUS, REST_RADIUS),
                            RELEASE_MAX_TIME)
    batch.suction_off(acted)
    retreat = batch.command.copy()
    retreat[:, 2] += RETREAT
    steps += _move(batch, retreat, acted, TOOL_SPEED)
    steps += _wait_for_rest(batch, acted, np.full(w, REST_SPEED), np.full(w, REST_RADIUS),
                            REST_MAX_TIME)
    ok = carrying & still
    return BatchActionResult(ok, reasons, acted, steps)


__all__ = ["GUARD_EVERY", "BatchActionResult", "pick_and_place", "travel_heights"]
