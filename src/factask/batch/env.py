"""The batched env: one compiled task, many worlds, stepped together on MuJoCo Warp.

:class:`BatchEnv` compiles a task graph once (the single env's
:func:`~factask.sim.build.compile.compile_graph`), puts the model on a Warp device and
keeps ``num_envs`` worlds of it (``mujoco_warp.put_data(..., nworld=num_envs)``).

* **Reset** of chosen worlds: a world reset with seed *s* runs the single env's
  reset for seed *s* on the CPU (layout sampling, target solving, goal markers,
  robot home, settling: :meth:`factask.sim.env.FactaskEnv.reset`) and copies the
  resulting MuJoCo state into that world (``mujoco_warp.set_state`` on the chosen
  worlds only, after ``mujoco_warp.reset_data`` on them: every tree awake). So the
  world starts from the single env's seed-*s* state (in Warp's float32). Layouts
  are sampled in Python, one world after another: resets cost what the single
  env's cost.
* **Step**: a low-level command for every world — the floating cup's pose
  (x, y, z, yaw) per world, or an arm's actuator controls — then physics steps of
  all worlds at once. The step (command write + ``mujoco_warp.step``) is captured
  once as a graph (Warp captures on CUDA and on its CPU device) and replayed.
* **Status**: every factor's progress, the reward and success per world from the
  batched checks (:mod:`factask.batch.status`), milestones latched per world.

Not yet here: the suction grasp per world, the pick-and-place primitive batched,
auto-reset, a gymnasium ``VectorEnv``, the oracle in lockstep (docs/batch.md).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import mujoco
import numpy as np

from factask.batch.device import announce_cpu_compile, load_backend, resolve_device
from factask.batch.model import batch_model
from factask.batch.primitive import BatchActionResult, pick_and_place
from factask.batch.scene import BatchScene
from factask.batch.status import BatchTaskStatus, check_task_batch
from factask.batch.suction import WorldSuction
from factask.batch.targets import BatchTargets
from factask.geometry import Pose
from factask.graph.taskgraph import TaskGraph
from factask.relations.solving import SolvedFactor
from factask.sim.env import FactaskEnv, ResetNeededError
from factask.sim.robots.floating_cup import FloatingSuctionRobot
from factask.vocabulary.errors import InvalidValueError

#: The MuJoCo state a reset copies into a world: everything that integrates but the
#: equalities' switches (the batch's model has more welds; reset turns them all off).
STATE_SIG = int(mujoco.mjtState.mjSTATE_INTEGRATION) & ~int(mujoco.mjtState.mjSTATE_EQ_ACTIVE)
#: A contact deeper than this (m) at any step, between two geoms not of the robot,
#: is a physics failure: resting contacts in factask's scenes are under 1 mm deep, a
#: held object set down a few mm (the cup and its stem press up to ~2.5 cm into a
#: bowl held by the rim, by design: the robot's contacts are not counted).
DEEP_CONTACT = 0.02
#: Seeds drawn for worlds reset without one are below this.
_SEED_RANGE = 2**31 - 1


def default_capacity(model: mujoco.MjModel) -> tuple[int, int]:
    """Per-world contact and constraint-row capacities (``nconmax``, ``njmax``) for a
    factask scene: four contacts per colliding geom of a free body (a box resting on
    a face touches with four; a bowl is many wall geoms), eight per free body and a
    margin, at least 64; six rows per contact."""
    free_joint = model.jnt_type == mujoco.mjtJoint.mjJNT_FREE
    free = int(np.sum(free_joint))
    roots = {int(model.body_rootid[b]) for b in model.jnt_bodyid[free_joint]}
    colliding = (model.geom_contype != 0) | (model.geom_conaffinity != 0)
    on_free = sum(1 for g in np.flatnonzero(colliding)
                  if int(model.body_rootid[model.geom_bodyid[g]]) in roots)
    nconmax = max(64, 4 * on_free + 8 * (free + 2))
    return nconmax, 6 * nconmax


class BatchEnv:
    """``num_envs`` worlds of one task on a Warp device.

    Args:
        graph: The task (validated and compiled here).
        num_envs: Number of worlds (at least 1).
        robot: A robot of the registry (``"floating"``, ``"ur10e"`` / ``"arm"``, ...).
        device: ``"cpu"``, ``"cuda"``, ``"cuda:N"`` or None (a GPU if there is one).
        nconmax: Contacts per world (default: :func:`default_capacity`).
        njmax: Constraint rows per world (default: :func:`default_capacity`).
        capture: Capture the step as a graph and replay it (much faster; off only
            to debug).

    Raises:
        BatchBackendMissing: the ``gpu`` extra is not installed.
        DeviceUnavailableError: ``device`` asks for a GPU this machine lacks.
        InvalidValueError: ``num_envs`` < 1, a bad device name, or a task with drawers.
        GraphValidationError, CompileError: the graph cannot be compiled.
    """

    def __init__(self, graph: TaskGraph, num_envs: int, robot: str = "floating",
                 device: str | None = None, nconmax: int | None = None,
                 njmax: int | None = None, capture: bool = True) -> None:
        if int(num_envs) < 1:
            raise InvalidValueError(f"num_envs must be at least 1, got {num_envs}")
        self.device = resolve_device(device)
        self._wp, self._mjw = load_backend()
        announce_cpu_compile(self.device)
        from factask.batch import kernels  # imports Warp: only once the backend is there

        self._kernels = kernels
        self.num_envs = int(num_envs)
        self.graph = graph
        #: The single env that resets worlds (its reset is the batch's reset).
        self.cpu_env = FactaskEnv(graph, robot=robot)
        drawers = [n for n, h in self.cpu_env.scene.objects.items() if h.slide is not None]
        if drawers:  # drawers and switches' buttons alike
            raise InvalidValueError(
                f"drawers, doors and switches ({', '.join(drawers)}) are not in the batched "
                "env yet (a drawer's or a switch's pose follows its slide joint, a door's "
                "its hinge, which the batch does not read): run this task in the single env "
                "(FactaskEnv) or gymnasium's sync vector env")
        #: The batch's host model: the scene's, with one inactive weld per free object
        #: and the table top as a plane (factask.batch.model).
        self.model, welds = batch_model(self.cpu_env.scene)
        self.suction = WorldSuction(self.model, welds, int(num_envs))
        self.object_names: list[str] = list(self.cpu_env.object_names)
        self.objects = self.cpu_env.objects
        self.factor_names: list[str] = graph.factor_names()
        handles = [self.cpu_env.scene.objects[n] for n in self.object_names]
        self._body_name = {h.body_id: n for n, h in zip(self.object_names, handles,
                                                          strict=True)}
        self._free = [(k, h.qpos_adr) for k, h in enumerate(handles) if h.mocap_id is None]
        self._fixed = [(k, h.mocap_id) for k, h in enumerate(handles) if h.mocap_id is not None]
        self._tip_site = self.cpu_env.robot.tip_site
        robot_ctl = self.cpu_env.robot
        self._cup_mocap: int | None = (robot_ctl.mocap if isinstance(
            robot_ctl, FloatingSuctionRobot) else None)
        self.command_dim = 4 if self._cup_mocap is not None else int(self.model.nu)
        default_con, default_j = default_capacity(self.model)
        self.nconmax = int(nconmax or default_con)
        self.njmax = int(njmax or default_j)
        wp, mjw = self._wp, self._mjw
        with wp.ScopedDevice(self.device):
            # eq_data per world: each world's grasp writes its own weld pose.
            self.wp_model = mjw.put_model(self.model, batch_sizes={"eq_data": self.num_envs})
            self.wp_data = mjw.put_data(self.model, mujoco.MjData(self.model),
                                        nworld=self.num_envs, nconmax=self.nconmax,
                                        njmax=self.njmax)
            self._command = wp.zeros((self.num_envs, max(self.command_dim, 1)), dtype=float)
            self._mask = wp.zeros(self.num_envs, dtype=bool)
            self._state = wp.zeros((self.num_envs, mujoco.mj_stateSize(self.model, STATE_SIG)),
                                   dtype=float)
            # The sleep tree of each world's held object (-1: none), kept awake each step.
            self._held_tree = wp.full(self.num_envs, -1, dtype=int)
            # The most contacts / constraint rows any step had since the worlds' reset.
            self._peak_nacon = wp.zeros(1, dtype=int)
            self._peak_nefc = wp.zeros(self.num_envs, dtype=int)
            # The deepest contact distance (m, <= 0) any step had since the world's reset.
            self._deepest = wp.zeros(self.num_envs, dtype=float)
            # 1 for the robot's geoms (the cup's tree), whose contacts that test skips.
            root = self.model.body_rootid
            robot_root = root[self.suction.cup_body]
            self._robot_geom = wp.array(
                (root[self.model.geom_bodyid] == robot_root).astype(np.int32), dtype=int)
            self._let_go = wp.full(self.num_envs, -1, dtype=int)
        self._sleep = bool(self.model.opt.enableflags & mujoco.mjtEnableBit.mjENBL_SLEEP)
        self._capture = capture
        self._graph: Any = None
        self._device_obs: Any = None
        self.seeds = np.full(self.num_envs, -1, dtype=np.int64)
        self.solved: list[dict[str, SolvedFactor]] = [{} for _ in range(self.num_envs)]
        self.initial_layouts: list[dict[str, Pose]] = [{} for _ in range(self.num_envs)]
        self._targets: dict[str, BatchTargets] = {}
        self._reached = np.zeros((self.num_envs, len(self.factor_names)), dtype=bool)
        self._seed_rng = np.random.default_rng()
        #: The command each world holds now (num_envs, command_dim): the last one
        #: stepped, or the robot's home after a reset.
        self.command = np.zeros((self.num_envs, self.command_dim))
        self._was_reset = np.zeros(self.num_envs, dtype=bool)

    # ------------------------------------------------------------------ reset
    def _worlds(self, worlds: Sequence[int] | np.ndarray | None) -> np.ndarray:
        if worlds is None:
            return np.arange(self.num_envs)
        idx = np.asarray(worlds)
        if idx.dtype == bool:
            if idx.shape != (self.num_envs,):
                raise InvalidValueError(f"a world mask must have {self.num_envs} entries, "
                                        f"got {idx.shape}")
            return np.flatnonzero(idx)
        idx = idx.astype(int).reshape(-1)
        if idx.size and (idx.min() < 0 or idx.max() >= self.num_envs):
            raise InvalidValueError(f"worlds must be in 0 .. {self.num_envs - 1}, got {worlds}")
        return idx

    def reset(self, seed: int | Sequence[int] | None = None,
              worlds: Sequence[int] | np.ndarray | None = None) -> dict[str, np.ndarray]:
        """Reset chosen worlds (default all), each from the single env's layout for its seed.

        Args:
            seed: An int: the chosen worlds get ``seed, seed + 1, ...`` in order (as
                gymnasium's vector envs seed); a sequence: one seed per chosen world;
                None: fresh random seeds.
            worlds: World indices or a boolean mask (default: every world).

        Returns:
            The observation of every world (see :meth:`observe`).

        Raises:
            InvalidValueError: bad world indices, or not one seed per chosen world.
            LayoutError: a layout cannot be found for a seed.
        """
        idx = self._worlds(worlds)
        if seed is None:
            seeds = self._seed_rng.integers(0, _SEED_RANGE, size=idx.size)
        elif np.ndim(seed) == 0:
            seeds = int(seed) + np.arange(idx.size)
        else:
            seeds = np.asarray(seed, dtype=np.int64).reshape(-1)
            if seeds.size != idx.size:
                raise InvalidValueError(f"{seeds.size} seed(s) for {idx.size} world(s)")
        if idx.size == 0:
            return self.observe()
        state = np.zeros(self._state.shape, dtype=np.float32)
        mask = np.zeros(self.num_envs, dtype=bool)
        m, d = self.cpu_env.model, self.cpu_env.data
        # A seed given to several worlds is reset once (a reset is deterministic in its
        # seed): many worlds from a few layouts cost what those layouts cost.
        done: dict[int, tuple[np.ndarray, dict[str, SolvedFactor], dict[str, Pose]]] = {}
        for w, s in zip(idx, seeds, strict=True):
            if int(s) not in done:
                self.cpu_env.reset(seed=int(s))
                row = np.empty(mujoco.mj_stateSize(m, STATE_SIG))
                mujoco.mj_getState(m, d, row, STATE_SIG)
                done[int(s)] = (row, dict(self.cpu_env.solved),
                                dict(self.cpu_env.initial_layout))
            row, solved, layout = done[int(s)]
            state[w] = row
            mask[w] = True
            self.seeds[w] = int(s)
            self.solved[w] = dict(solved)
            self.initial_layouts[w] = dict(layout)
            self._reached[w] = False
        self._was_reset |= mask
        self.suction.reset(mask)
        self._sync_held()
        wp, mjw = self._wp, self._mjw
        with wp.ScopedDevice(self.device):
            self._mask.assign(mask)
            self._state.assign(state)
            mjw.reset_data(self.wp_model, self.wp_data, reset=self._mask)
            mjw.set_state(self.wp_model, self.wp_data, self._state, STATE_SIG, self._mask)
            mjw.kinematics(self.wp_model, self.wp_data)
            peaks = self._peak_nefc.numpy()
            peaks[mask] = 0
            self._peak_nefc.assign(peaks)
            if mask.all():  # the contact pool is shared: its peak starts again with all
                self._peak_nacon.zero_()
            deepest = self._deepest.numpy()
            deepest[mask] = 0.0
            self._deepest.assign(deepest)
        self.command[mask] = self.home_command()[mask]
        if self._was_reset.all():
            self._targets = {f: BatchTargets.stack([self.solved[w][f]
                                                    for w in range(self.num_envs)])
                             for f in self.factor_names}
        return self.observe()

    # ------------------------------------------------------------------- step
    def _record_step(self) -> None:
        wp, mjw = self._wp, self._mjw
        cmd, data = self._command, self.wp_data
        if self._cup_mocap is not None:
            wp.launch(self._kernels.set_mocap_xyzyaw, dim=self.num_envs,
                      inputs=[cmd, self._cup_mocap, data.mocap_pos, data.mocap_quat])
        elif self.command_dim:
            wp.launch(self._kernels.set_ctrl, dim=(self.num_envs, self.command_dim),
                      inputs=[cmd, data.ctrl])
        if self._sleep:
            self._wake(self._held_tree)
        mjw.step(self.wp_model, data)
        wp.launch(self._kernels.track_peaks, dim=self.num_envs,
                  inputs=[data.nacon, data.nefc], outputs=[self._peak_nacon, self._peak_nefc])
        wp.launch(self._kernels.track_deepest, dim=int(data.contact.dist.shape[0]),
                  inputs=[data.nacon, data.contact.dist, data.contact.worldid,
                          data.contact.geom, self._robot_geom],
                  outputs=[self._deepest])

    def _wake(self, trees: Any) -> None:
        """Wake (keep awake) each world's tree ``trees[w]`` (-1: none)."""
        self._wp.launch(self._kernels.wake_trees, dim=self.num_envs,
                        inputs=[trees, int(self.model.ntree), -(1 + mujoco.mjMINAWAKE)],
                        outputs=[self.wp_data.tree_asleep])

    def _trees_of(self, bodies: np.ndarray) -> np.ndarray:
        tree = self.model.body_treeid[np.maximum(bodies, 0)]
        return np.where(bodies >= 0, tree, -1).astype(np.int32)

    def _sync_held(self) -> None:
        with self._wp.ScopedDevice(self.device):
            self._held_tree.assign(self._trees_of(self.suction.held))

    def step(self, command: np.ndarray, substeps: int = 1) -> None:
        """Hold a low-level command in every world for ``substeps`` physics steps.

        Args:
            command: (num_envs, command_dim): for the floating cup its mocap pose
                (x, y, z, yaw) — the suction tip's position and the tool yaw; for an
                arm its actuator controls (``model.nu`` of them).
            substeps: Physics steps (``model.opt.timestep`` each).

        Raises:
            InvalidValueError: wrong shape, non-finite numbers, or substeps < 1.
            ResetNeededError: a world was never reset.
        """
        if not self._was_reset.all():
            raise ResetNeededError(f"reset every world before step(); never reset: "
                                   f"{np.flatnonzero(~self._was_reset).tolist()}")
        cmd = np.asarray(command, dtype=float)
        if cmd.shape != (self.num_envs, self.command_dim) or not np.isfinite(cmd).all():
            raise InvalidValueError(f"command must be {self.num_envs} x {self.command_dim} "
                                    f"finite numbers, got shape {cmd.shape}")
        if int(substeps) < 1:
            raise InvalidValueError(f"substeps must be at least 1, got {substeps}")
        wp = self._wp
        self.command = cmd.copy()
        with wp.ScopedDevice(self.device):
            if self.command_dim:
                self._command.assign(cmd.astype(np.float32))
            if not self._capture:
                for _ in range(int(substeps)):
                    self._record_step()
                return
            if self._graph is None:
                # Capturing records without running: run the first step directly.
                self._record_step()
                substeps -= 1
                with wp.ScopedCapture() as cap:
                    self._record_step()
                self._graph = cap.graph
            for _ in range(int(substeps)):
                wp.capture_launch(self._graph)

    def home_command(self) -> np.ndarray:
        """A command that holds the robot where it is after a reset (num_envs, dim)."""
        if self._cup_mocap is not None:
            home = self.wp_data.mocap_pos.numpy()[:, self._cup_mocap]
            quat = self.wp_data.mocap_quat.numpy()[:, self._cup_mocap]
            yaw = 2 * np.arctan2(quat[:, 3], quat[:, 0])
            return np.concatenate([home, yaw[:, None]], axis=1).astype(float)
        return self.wp_data.ctrl.numpy()[:, :self.command_dim].astype(float)

    # ---------------------------------------------------------- observation
    def object_poses(self) -> np.ndarray:
        """Every object's pose in every world (num_envs, n, 7): position + quaternion
        (w, x, y, z), in :attr:`object_names` order (fixed objects included)."""
        out = np.zeros((self.num_envs, len(self.object_names), 7))
        if self._free:
            qpos = self.wp_data.qpos.numpy()
            for k, adr in self._free:
                out[:, k] = qpos[:, adr:adr + 7]
        if self._fixed:
            mpos, mquat = self.wp_data.mocap_pos.numpy(), self.wp_data.mocap_quat.numpy()
            for k, mid in self._fixed:
                out[:, k, :3] = mpos[:, mid]
                out[:, k, 3:] = mquat[:, mid]
        return out

    def observe(self) -> dict[str, np.ndarray]:
        """The state-mode observation of every world, the single env's keys batched:
        ``object_poses`` (num_envs, n, 7), ``ee_pose`` (num_envs, 7) (the suction tip,
        as of the last physics step's kinematics), ``suction`` (num_envs, 1)."""
        xpos = self.wp_data.site_xpos.numpy()[:, self._tip_site]
        xmat = self.wp_data.site_xmat.numpy()[:, self._tip_site].reshape(-1, 9)
        quat = np.zeros((self.num_envs, 4))
        for w in range(self.num_envs):
            mujoco.mju_mat2Quat(quat[w], xmat[w].astype(float))
        return {"object_poses": self.object_poses(),
                "ee_pose": np.concatenate([xpos, quat], axis=1).astype(float),
                "suction": (self.suction.held >= 0).astype(float)[:, None]}

    def observe_device(self) -> dict[str, Any]:
        """:meth:`observe` gathered on the device: Warp arrays (float32, reused by the next
        call) that torch, JAX or NumPy take without a copy (``wp.to_torch``, DLPack;
        :mod:`factask.batch.interop`)."""
        if self._device_obs is None:
            from factask.batch.interop import DeviceObservations  # imports Warp

            self._device_obs = DeviceObservations(self, self._free, self._fixed,
                                                  self._tip_site, self._held_tree)
        return self._device_obs.observe()

    def physics_failures(self) -> list[str | None]:
        """Per world, why its simulation is no longer trustworthy, or None: positions or
        velocities not finite, or more contacts or constraint rows than allocated at any
        step since the world's reset (``nconmax``, ``njmax``: MuJoCo Warp drops the rest;
        make a batch with more), or a contact deeper than :data:`DEEP_CONTACT` at any
        step (a narrowphase failure: positions stay finite, objects fly). Contacts are
        counted over all worlds (one pool): an overflow there marks every world.
        """
        data = self.wp_data
        finite = (np.isfinite(data.qpos.numpy()).all(axis=1)
                  & np.isfinite(data.qvel.numpy()).all(axis=1))
        # The peaks of every step since the worlds' reset, not only the last step's.
        nefc = np.maximum(self._peak_nefc.numpy(), data.nefc.numpy())
        contacts = max(int(self._peak_nacon.numpy()[0]), int(data.nacon.numpy()[0]))
        deepest = self._deepest.numpy()
        out: list[str | None] = []
        for w in range(self.num_envs):
            if not finite[w]:
                out.append("physics: positions or velocities are not finite")
            elif deepest[w] < -DEEP_CONTACT:
                out.append(f"physics: a contact {-deepest[w] * 100:.0f} cm deep (more than "
                           f"{DEEP_CONTACT * 100:.0f} cm: the narrowphase failed)")
            elif nefc[w] > data.njmax:
                out.append(f"physics: {int(nefc[w])} constraint rows, more than njmax = "
                           f"{data.njmax}")
            elif contacts > data.naconmax:
                out.append(f"physics: {contacts} contacts in all worlds, more than "
                           f"{data.naconmax} (nconmax = {self.nconmax} per world)")
            else:
                out.append(None)
        return out

    # ---------------------------------------------------------------- suction
    def _world_mask(self, worlds: Sequence[int] | np.ndarray | None) -> np.ndarray:
        mask = np.zeros(self.num_envs, dtype=bool)
        mask[self._worlds(worlds)] = True
        return mask

    def suction_on(self, worlds: Sequence[int] | np.ndarray | None = None) -> np.ndarray:
        """Switch suction on in chosen worlds (default all): each grasps the closest free
        object its cup touches, where it is (the single env's rule, per world).

        Args:
            worlds: World indices or a boolean mask.

        Returns:
            Whether each world holds an object now (num_envs,).
        """
        with self._wp.ScopedDevice(self.device):
            held = self.suction.grasp(self.wp_model, self.wp_data, self._world_mask(worlds))
        self._sync_held()
        return held

    def suction_off(self, worlds: Sequence[int] | np.ndarray | None = None) -> None:
        """Switch suction off in chosen worlds (default all): held objects are let go."""
        before = self.suction.held.copy()
        with self._wp.ScopedDevice(self.device):
            self.suction.release(self.wp_data, self._world_mask(worlds))
            if self._sleep:  # what was let go falls: wake it
                self._let_go.assign(self._trees_of(np.where(self.suction.held < 0, before, -1)))
                self._wake(self._let_go)
        self._sync_held()

    def pick_and_place(self, pick: np.ndarray, place: np.ndarray,
                       worlds: Sequence[int] | np.ndarray | None = None) -> BatchActionResult:
        """One suction pick-and-place per chosen world (default all), in lockstep (see
        :func:`factask.batch.primitive.pick_and_place`; floating cup only).

        Args:
            pick: (num_envs, 4) the tip's (x, y, z, yaw) on the object's top face.
            place: (num_envs, 4) the tip's (x, y, z, yaw) at the release.
            worlds: World indices or a boolean mask of the worlds that act.

        Returns:
            What the action did in every world.

        Raises:
            InvalidValueError: an arm batch, or malformed poses.
        """
        return pick_and_place(self, pick, place, self._world_mask(worlds))

    def held_objects(self) -> list[str | None]:
        """The instance each world's cup holds, or None."""
        return [self._body_name.get(int(b)) for b in self.suction.held]

    def scene(self) -> BatchScene:
        """Every world's poses and held object as the batched checks read them."""
        poses = self.object_poses()
        held = np.array([[n == h for n in self.object_names] for h in self.held_objects()],
                        dtype=bool).reshape(poses.shape[:2])
        return BatchScene(self.objects, tuple(self.object_names), poses[..., :3],
                          poses[..., 3:], held)

    @property
    def reached(self) -> np.ndarray:
        """Factors reached so far per world (num_envs, n_factors), in graph order:
        milestones latch on it (updated by :meth:`status`)."""
        return self._reached.copy()

    @property
    def targets(self) -> dict[str, BatchTargets]:
        """Every factor's solved targets in every world (after every world's reset).

        Raises:
            ResetNeededError: a world was never reset.
        """
        if not self._was_reset.all():
            raise ResetNeededError("reset every world before reading the targets")
        return dict(self._targets)

    def status(self, latch: bool = True) -> BatchTaskStatus:
        """Every factor's status, the reward and success in every world, now.

        Args:
            latch: Keep the milestones reached now for the next call (as the single
                env does after each action).

        Raises:
            ResetNeededError: a world was never reset.
        """
        if not self._was_reset.all():
            raise ResetNeededError("reset every world before status()")
        st = check_task_batch(self.graph, self._targets, self.scene(), self._reached)
        if latch:
            self._reached = st.reached.copy()
        return st

    def close(self) -> None:
        """Release the single env (and its renderer)."""
        self.cpu_env.close()


def make_batch(task: TaskGraph | str, num_envs: int, device: str | None = None,
               robot: str = "floating", **kwargs: Any) -> BatchEnv:
    """A batched env of ``task``: ``num_envs`` worlds on a Warp device.

    Args:
        task: A task graph, or a library task's name.
        num_envs: Number of worlds.
        device: ``"cpu"``, ``"cuda"``, ``"cuda:N"`` or None (a GPU if there is one).
        robot: A robot of the registry.
        **kwargs: Passed to :class:`BatchEnv` (``nconmax``, ``njmax``, ``capture``).

    Returns:
        The :class:`BatchEnv` (reset it before stepping).

    Raises:
        BatchBackendMissing: the ``gpu`` extra is not installed.
        DeviceUnavailableError: ``device`` asks for a GPU this machine lacks.
        UnknownTaskError: an unknown library task name.
    """
    if isinstance(task, str):
        from factask.library import get_task

        task = get_task(task)
    return BatchEnv(task, num_envs, robot=robot, device=device, **kwargs)


__all__ = ["DEEP_CONTACT", "STATE_SIG", "BatchEnv", "default_capacity", "make_batch"]
