"""The gymnasium environment of a task graph.

One :class:`FactaskEnv` per task graph. The graph is compiled once; each reset
samples a collision-free initial layout, solves every relation into target
poses (shown by translucent goal markers), and lets the scene settle. An action
is one pick-and-place primitive executed by the suction robot in simulated time;
the reward is the *change* of the task's total reward (the weighted sum of
factor progress) that the action caused, so without outside interference the
return of an episode equals its final total reward; ``info["total_reward"]``
carries the total itself. Every factor is re-checked
after every action: undoing a finished subtask lowers the reward.

Physics failures (NaN, MuJoCo instability warnings) end the episode with
``info["failure"]`` set; they never raise.
"""

from __future__ import annotations

import weakref
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, ClassVar

import gymnasium as gym
import mujoco
import numpy as np
from gymnasium import spaces

from factask.geometry import Pose
from factask.graph.taskgraph import TaskGraph
from factask.relations.solving import SolvedFactor
from factask.scene.objects import SceneObject, objects_by_name
from factask.sim.build.compile import (
    CompiledScene,
    compile_graph,
    get_object_pose,
    set_marker,
    set_object_poses,
)
from factask.sim.layout.checks import TaskStatus, check_task
from factask.sim.layout.reset import reset_layout
from factask.sim.robots.attach import SuctionRobot, make_robot
from factask.sim.robots.door_swing import door_swing
from factask.sim.robots.health import physics_problem
from factask.sim.robots.low_carry import low_pick_and_place
from factask.sim.robots.slide_pull import slide_pull
from factask.sim.robots.spatula import push
from factask.sim.robots.switch_press import press_switch
from factask.vocabulary.errors import FactaskError, InvalidValueError
from factask.vocabulary.world import WORKSPACE_X, WORKSPACE_Y, WORKSPACE_Z

#: Simulated seconds the scene settles after a reset at most (objects placed
#: exactly resting may still shift by a fraction of a millimetre) ...
SETTLE_SECONDS = 0.3
#: ... and at least; it has settled when no object moves faster than
#: SETTLE_SPEED (m/s), tested every SETTLE_EVERY physics steps.
SETTLE_MIN_SECONDS = 0.04
SETTLE_SPEED = 0.001
SETTLE_EVERY = 10
#: Default rendering size (width, height) and camera.
RENDER_SIZE = (320, 240)
RENDER_CAMERA = "front"


class ActionError(FactaskError):
    """An action that is not one primitive's keys (:data:`ACTION_KINDS`) of finite numbers."""


@dataclass(frozen=True)
class ActionKind:
    """One action primitive ``step`` takes: the keys that select it and what they hold.

    Attributes:
        name: The primitive ("pick_place", "low_carry", "push", "slide", "swing", "press").
        code: Its stable number (the ``primitive`` column of recorded datasets,
            :mod:`factask.datasets.actions`; never renumber, append new kinds).
        poses: The two (x, y, z, yaw) keys, in order (the "pick" and the "place").
        extras: The other keys and how many numbers each holds (``lift``: metres;
            ``hinge``: x, y).
    """

    name: str
    code: int
    poses: tuple[str, str]
    extras: tuple[tuple[str, int], ...] = ()

    @property
    def keys(self) -> frozenset[str]:
        """Every key the action must hold."""
        return frozenset(self.poses) | {k for k, _ in self.extras}


#: The action primitives, in the order ``step`` tries them (the first whose keys all
#: are in the action runs; a plain pick-and-place last).
ACTION_KINDS: tuple[ActionKind, ...] = (
    ActionKind("push", 2, ("start", "end")),
    ActionKind("swing", 4, ("grasp", "swing_to"), (("hinge", 2),)),
    ActionKind("slide", 3, ("grasp", "slide_to")),
    ActionKind("press", 5, ("press", "press_to")),
    ActionKind("low_carry", 1, ("pick", "place"), (("lift", 1),)),
    ActionKind("pick_place", 0, ("pick", "place")),
)


def action_kind(action: Any) -> ActionKind:
    """The primitive an action dict selects (:data:`ACTION_KINDS`).

    Raises:
        ActionError: not a dict, or no primitive's keys are all in it.
    """
    if isinstance(action, dict):
        for kind in ACTION_KINDS:
            if kind.keys <= set(action):
                return kind
    shapes = " or ".join("{" + ", ".join(repr(k) for k in (*kind.poses, *dict(kind.extras)))
                         + "}" for kind in ACTION_KINDS)
    got = sorted(map(str, action)) if isinstance(action, dict) else type(action).__name__
    raise ActionError(f"action must be a dict with the keys of one primitive ({shapes}), "
                      f"got {got}: {action!r}")


class ResetNeededError(FactaskError, RuntimeError):
    """``step`` was called before the first ``reset`` (a ``RuntimeError`` too)."""


@dataclass(frozen=True)
class ActionRecord:
    """What one action did (kept in ``env.history``)."""

    action: int
    ok: bool
    reason: str | None
    sim_steps: int
    total_reward: float


@dataclass(frozen=True)
class _StateKey:
    """The state a status was checked in (see :meth:`FactaskEnv._state_key`)."""

    time: float
    qpos: np.ndarray
    mocap_pos: np.ndarray
    mocap_quat: np.ndarray
    held: int | None


def _pose4(value: Any, what: str) -> Pose:
    try:
        arr = np.asarray(value, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        arr = np.full(1, np.nan)  # not numbers at all: reported below
    if arr.shape != (4,) or not np.all(np.isfinite(arr)):
        raise ActionError(f"{what} must be 4 finite numbers (x, y, z, yaw in radians), "
                          f"got {value!r}")
    return Pose.from_xyz_yaw(*arr)


def _xy(value: Any, what: str) -> np.ndarray:
    """A point (x, y) of an action, checked (two finite numbers; a third is ignored)."""
    try:
        arr = np.asarray(value, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        arr = np.full(1, np.nan)  # not numbers at all: reported below
    if arr.shape not in ((2,), (3,)) or not np.all(np.isfinite(arr)):
        raise ActionError(f"{what} must be 2 finite numbers (x, y in metres), got {value!r}")
    return arr[:2]


class FactaskEnv(gym.Env):
    """A task graph as a gymnasium environment with a suction pick-and-place action.

    Args:
        graph: The task (validated and compiled here).
        robot: A name of the robot registry (:mod:`factask.sim.robots.registry`): "floating"
            (mocap suction cup, fast), "ur10e" (alias "arm") or "ur5e".
        render_mode: None or "rgb_array" (``render()`` returns an RGB image).
        render_size: (width, height) of rendered images.
        camera: Camera name for ``render()`` ("front" or "top").

    Observation (dict): ``object_poses`` (n, 7) position + quaternion (w, x, y, z)
    of every object instance in ``env.object_names`` order, ``ee_pose`` (7,),
    ``suction`` (1,) 1 while holding an object.

    Action (dict): ``pick`` and ``place``, each (x, y, z, yaw): the suction tip's
    position at the grasp (on the object's top) and at the release, and the tool
    yaw; the object turns with the tool by ``place yaw - pick yaw``. A task that
    pushes (a ``pile_in_zone`` goal: the robot has a spatula) also takes
    ``start`` and ``end`` (x, y, z, yaw; only x, y are used): a push along the
    table (:mod:`factask.sim.robots.spatula`). A pick-and-place with ``lift`` (metres)
    carries the object only that high (:mod:`factask.sim.robots.low_carry`: a rope's
    segment, Ravens' ``PickPlace(height=0.02)``). An action with ``grasp`` and
    ``slide_to`` (x, y, z, yaw) holds a drawer's handle at ``grasp`` and slides it
    level until the tip is over ``slide_to``'s x, y (:mod:`factask.sim.robots.slide_pull`).
    An action with ``press`` and ``press_to`` (x, y, z, yaw) presses a switch's button
    whose top is at ``press`` down until its top is at ``press_to``'s z, or (above)
    holds it and pulls it up there (:mod:`factask.sim.robots.switch_press`).
    An action with ``grasp``, ``swing_to`` (x, y, z, yaw) and ``hinge`` (x, y) holds a
    door's handle at ``grasp`` and swings it level about the hinge's vertical axis
    until the tip is on ``swing_to``'s bearing (:mod:`factask.sim.robots.door_swing`).

    Raises:
        GraphValidationError, CompileError: the graph cannot be compiled.
    """

    metadata: ClassVar[dict[str, Any]] = {"render_modes": ["rgb_array"], "render_fps": 10}

    def __init__(self, graph: TaskGraph, robot: str = "floating",
                 render_mode: str | None = None,
                 render_size: tuple[int, int] = RENDER_SIZE,
                 camera: str = RENDER_CAMERA) -> None:
        if render_mode not in (None, "rgb_array"):
            raise InvalidValueError(
                f"render_mode must be None or 'rgb_array', got {render_mode!r}")
        self.graph = graph
        self.robot_kind = robot
        self.scene: CompiledScene = compile_graph(graph, robot=robot)
        self.model = self.scene.model
        self.data = mujoco.MjData(self.model)
        self.robot: SuctionRobot = make_robot(robot, self.model, self.data)
        self.objects: dict[str, SceneObject] = objects_by_name(graph)
        self.object_names: list[str] = list(self.scene.objects)
        self._body_to_object = {h.body_id: n for n, h in self.scene.objects.items()}
        self.render_mode = render_mode
        self.render_size = render_size
        self.camera = camera
        self._renderer: Any = None
        n = len(self.object_names)
        self.observation_space = spaces.Dict({
            "object_poses": spaces.Box(-np.inf, np.inf, (n, 7), np.float64),
            "ee_pose": spaces.Box(-np.inf, np.inf, (7,), np.float64),
            "suction": spaces.Box(0.0, 1.0, (1,), np.float64),
        })
        low = np.array([WORKSPACE_X[0], WORKSPACE_Y[0], WORKSPACE_Z[0], -np.pi])
        high = np.array([WORKSPACE_X[1], WORKSPACE_Y[1], WORKSPACE_Z[1], np.pi])
        self.action_space = spaces.Dict({
            "pick": spaces.Box(low, high, dtype=np.float64),
            "place": spaces.Box(low, high, dtype=np.float64),
        })
        self.solved: dict[str, SolvedFactor] = {}
        self.initial_layout: dict[str, Pose] = {}
        self.history: list[ActionRecord] = []
        self.actions_taken = 0
        self.failure: str | None = None
        self._status: TaskStatus | None = None
        # The state ``_status`` was checked in (:meth:`_state_key`; None: not a check,
        # a physics failure's zero status): an unchanged state needs no second check
        # (the oracle plans on it, the next action's baseline is its reward).
        self._status_state: _StateKey | None = None
        # info["targets"] of the current reset (the solved targets do not move).
        self._targets_info: dict[str, dict[str, Any]] = {}
        # Factors reached so far (milestones latch on it); updated after each action.
        self._reached: frozenset[str] = frozenset()
        #: Called every few physics steps during actions (e.g. to record video).
        self.frame_callback: Callable[[], None] | None = None

    # ------------------------------------------------------------ state access
    def object_poses(self) -> dict[str, Pose]:
        """Current pose of every object instance."""
        return {n: get_object_pose(self.data, h) for n, h in self.scene.objects.items()}

    def held_objects(self) -> set[str]:
        """Instances the robot holds now."""
        body = self.robot.grasped()
        if body is None:
            return set()
        name = self._body_to_object.get(int(body))
        return {name} if name else set()

    def status(self) -> TaskStatus:
        """Check every factor now (milestones reached at earlier actions stay latched).

        The status of the last ``reset``/``step`` is returned as it is while the
        state it was checked in is unchanged (same time, positions, mocap poses and
        held object): the checks depend on nothing else.
        """
        if self._status is not None and self._unchanged():
            return self._status
        return check_task(self.graph, self.solved, self.object_poses(), self.held_objects(),
                          self.objects, self._reached)

    def _obs(self) -> dict[str, np.ndarray]:
        poses = self.object_poses()
        return {
            "object_poses": np.array([poses[n].to_list() for n in self.object_names],
                                     dtype=np.float64).reshape(len(self.object_names), 7),
            "ee_pose": np.array(self.robot.ee_pose().to_list(), dtype=np.float64),
            "suction": np.array([1.0 if self.robot.grasped() is not None else 0.0]),
        }

    def _info(self, status: TaskStatus) -> dict[str, Any]:
        return {
            "total_reward": status.reward,
            "success": status.success,
            "factors": {n: s.progress for n, s in status.factors.items()},
            "satisfied": {n: s.satisfied for n, s in status.factors.items()},
            # Milestones reached so far (they keep progress 1 from then on).
            "reached": [n for n in self.graph.factor_names() if n in status.reached],
            "details": {n: s.detail for n, s in status.factors.items()},
            # Each factor's status as the checks found it: placed objects with their
            # slots, and the free slot each object still to place should take.
            "placed": {n: dict(s.placed) for n, s in status.factors.items()},
            "next_slots": {n: dict(s.targets) for n, s in status.factors.items()},
            "language_goals": {f.name: f.description for f in self.graph.factors},
            "language_goal": self.graph.description,
            "actions": self.actions_taken,
            "failure": self.failure,
            "targets": {name: {"objects": list(t["objects"]),
                               "targets": {o: list(p) for o, p in t["targets"].items()}}
                        for name, t in self._targets_info.items()},
        }

    def physics_failure(self) -> str | None:
        """Why the simulation state is no longer trustworthy, or None."""
        problem = physics_problem(self.data)
        return None if problem is None else f"physics: {problem}"

    # ------------------------------------------------------------- gym API
    def reset(self, *, seed: int | None = None,
              options: dict[str, Any] | None = None) -> tuple[dict[str, np.ndarray], dict]:
        """Sample the initial layout and solve the targets.

        Same seed, same initial state (bit for bit).

        Raises:
            LayoutError: no feasible layout after bounded retries.
        """
        super().reset(seed=seed)
        rng = np.random.default_rng(self.np_random.integers(0, 2**63 - 1))
        layout, solved = reset_layout(self.graph, rng)
        self.initial_layout, self.solved = layout, solved
        # Every factor's targets, once (the markers and each info show them).
        targets = {name: s.targets(self.objects) for name, s in solved.items()}
        self._targets_info = {
            name: {"objects": list(s.objects),
                   "targets": {o: p.to_list() for o, p in targets[name].items()}}
            for name, s in solved.items()}
        mujoco.mj_resetData(self.model, self.data)
        set_object_poses(self.model, self.data, self.scene.objects, layout)
        for (factor, slot), mocap in self.scene.markers.items():
            inst = self.scene.marker_objects[(factor, slot)]
            if inst in targets[factor]:
                set_marker(self.data, mocap, targets[factor][inst])
        self.robot.reset()
        self._settle()
        self.history = []
        self.actions_taken = 0
        self.failure = self.physics_failure()
        self._reached = frozenset()
        self._status = None
        status = self.status() if self.failure is None else TaskStatus(0.0, False, {})
        self._keep_status(status, checked=self.failure is None)
        return self._obs(), self._info(status)

    def _settle(self) -> None:
        """Step until the objects rest (settle detection, not a fixed wait)."""
        dt = self.model.opt.timestep
        least, most = round(SETTLE_MIN_SECONDS / dt), round(SETTLE_SECONDS / dt)
        mujoco.mj_step(self.model, self.data, least)
        done = least
        while done < most and not self.robot.gripper.objects_resting(SETTLE_SPEED):
            k = min(SETTLE_EVERY, most - done)
            mujoco.mj_step(self.model, self.data, k)
            done += k

    def step(self, action: dict[str, Any]) -> tuple[dict[str, np.ndarray], float, bool, bool,
                                                    dict[str, Any]]:
        """Execute one pick-and-place.

        Returns:
            (observation, reward change, terminated, truncated, info). ``terminated``
            when the task succeeds or physics failed; ``truncated`` when the action
            budget (``graph.max_actions()``) is used up.

        Raises:
            ActionError: the action is malformed (missing keys, wrong shape, NaN).
            ResetNeededError: ``step`` before ``reset``.
        """
        if self._status is None:
            raise ResetNeededError("call reset() before step()")
        kind = action_kind(action)
        first, second = kind.poses
        pushing, sliding, pressing = (kind.name == k for k in ("push", "slide", "press"))
        pick = _pose4(action[first], first)
        place = _pose4(action[second], second)
        hinge = _xy(action["hinge"], "hinge") if kind.name == "swing" else None
        if self.failure is not None:
            return self._obs(), 0.0, True, False, self._info(self._status)
        # The reward is what *this action* changed: measure the baseline now, so
        # changes made from outside between steps are not credited to the action.
        prev = self.status().reward  # the kept status when nothing moved since
        max_steps = int(self.graph.limits.max_sim_seconds_per_action / self.model.opt.timestep)
        if pushing:  # a spatula's push (factask.sim.robots.spatula)
            result = push(self.robot, pick, place, on_step=self.frame_callback,
                          max_steps=max_steps)
        elif hinge is not None:  # a door held by its handle (factask.sim.robots.door_swing)
            result = door_swing(self.robot, pick, place, hinge, on_step=self.frame_callback,
                                max_steps=max_steps)
        elif sliding:  # a drawer held by its handle (factask.sim.robots.slide_pull)
            result = slide_pull(self.robot, pick, place, on_step=self.frame_callback,
                                max_steps=max_steps)
        elif pressing:  # a switch's button (factask.sim.robots.switch_press)
            result = press_switch(self.robot, pick, place, on_step=self.frame_callback,
                                  max_steps=max_steps)
        elif kind.name == "low_carry":  # a rope's segment (factask.sim.robots.low_carry)
            lift = float(np.asarray(action["lift"], dtype=float).reshape(-1)[0])
            if not np.isfinite(lift) or not 0.0 < lift <= WORKSPACE_Z[1]:
                raise ActionError(f"lift must be in (0, {WORKSPACE_Z[1]}] m, got {lift}")
            result = low_pick_and_place(self.robot, pick, place, lift,
                                        on_step=self.frame_callback, max_steps=max_steps)
        else:
            result = self.robot.pick_and_place(pick, place, on_step=self.frame_callback,
                                               max_steps=max_steps)
        self.actions_taken += 1
        self.failure = self.physics_failure()
        status = self.status() if self.failure is None else TaskStatus(0.0, False, {})
        self._keep_status(status, checked=self.failure is None)
        self.history.append(ActionRecord(self.actions_taken, result.ok, result.reason,
                                       result.sim_steps, status.reward))
        info = self._info(status)
        info["action_ok"] = result.ok
        info["action_failure"] = result.reason
        terminated = status.success or self.failure is not None
        truncated = not terminated and self.actions_taken >= self.graph.max_actions()
        return self._obs(), status.reward - prev, terminated, truncated, info

    def _keep_status(self, status: TaskStatus, checked: bool = True) -> None:
        """Remember ``status`` as the current one, with the state it was checked in
        (``checked`` False: a stand-in, never returned by :meth:`status`)."""
        self._status, self._reached = status, status.reached
        self._status_state = self._state_key() if checked else None

    def _state_key(self) -> _StateKey:
        """What the checks read: time, positions, mocap poses (fixed objects) and
        the held object."""
        d = self.data
        return _StateKey(float(d.time), d.qpos.copy(), d.mocap_pos.copy(), d.mocap_quat.copy(),
                         self.robot.grasped())

    def _unchanged(self) -> bool:
        """True when the state is the one the kept status was checked in."""
        kept, d = self._status_state, self.data
        return (kept is not None and kept.time == d.time and kept.held == self.robot.grasped()
                and np.array_equal(kept.qpos, d.qpos)
                and np.array_equal(kept.mocap_pos, d.mocap_pos)
                and np.array_equal(kept.mocap_quat, d.mocap_quat))

    # ------------------------------------------------------------- rendering
    def render(self) -> np.ndarray | None:
        """RGB image of the scene (``render_mode="rgb_array"``), else None."""
        if self.render_mode != "rgb_array":
            return None
        return self.render_rgb()

    def render_rgb(self, camera: str | mujoco.MjvCamera | None = None,
                   markers: bool = True) -> np.ndarray:
        """RGB image (height, width, 3) uint8, whatever the render mode.

        Args:
            camera: Camera name, or a free camera such as
                :func:`factask.sim.render.offscreen.framed_camera` gives (default: the env's).
            markers: Draw the translucent goal markers.
        """
        if self._renderer is None:
            from factask.sim.render.offscreen import SceneRenderer

            self._renderer = SceneRenderer(self.model, *self.render_size,
                                           geom_object=self.scene.geom_object)
            # Free the GL context before interpreter shutdown tears EGL down.
            weakref.finalize(self, self._renderer.close)
        return self._renderer.rgb(self.data, camera or self.camera, show_markers=markers)

    def close(self) -> None:
        """Release the renderer's GL context."""
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None
