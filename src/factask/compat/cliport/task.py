"""Stand-in for ``cliport.tasks.task``: the ``Task`` base class GenSim code extends.

It keeps what task code reads and writes (attributes, ``goals`` as CLIPort's
8-tuples, ``lang_goals``) and implements the helpers that only compute or record
(``add_goal``, ``get_random_pose``, ``fill_template``, ...). Helpers that need a
running PyBullet world (the oracle, rewards) raise
:class:`~factask.compat.cliport.errors.Unsupported` naming the call.

Randomness: ``get_random_pose``/``get_random_size`` draw from the load's seeded
generator; task code calling ``np.random``/``random`` directly gets the global
generators, which the loader seeds with the same seed (and restores afterwards).
"""

from __future__ import annotations

import math
import os
from typing import Any

import numpy as np

from factask.compat.cliport import cameras, primitives
from factask.compat.cliport import utils as cutils
from factask.compat.cliport.errors import Unsupported
from factask.compat.cliport.grippers import Spatula, Suction
from factask.compat.cliport.piles import make_piles
from factask.compat.cliport.recorder import active_session
from factask.compat.cliport.ropes import make_ropes
from factask.compat.cliport.scoring import pose_match
from factask.compat.cliport.transforms import split_pose, yaw_of_xyzw
from factask.vocabulary.errors import InvalidValueError
from factask.vocabulary.palette import rgba
from factask.vocabulary.world import RAVENS_Z, WORKSPACE_X, WORKSPACE_Y

#: Ravens' XY tolerance of a pose goal, metres, and yaw tolerance, radians.
RAVENS_POS_EPS = 0.01
RAVENS_ROT_EPS = math.radians(15)
#: GenSim widens the XY tolerance to this for tasks about bowls.
BOWL_POS_EPS = 0.05
ROPE_POS_EPS = 0.02
#: Attempts of ``get_random_pose`` to find a spot clear of every recorded object.
RANDOM_POSE_ATTEMPTS = 200
#: Spacing of CLIPort's object sample points (``get_box_object_points``), metres.
OBJECT_POINT_SPACING = 0.02
#: Yaw symmetry (radians) of Ravens' 20 kitting shapes, by shape index.
KIT_SHAPE_SYMMETRY = (
    2 * math.pi, 2 * math.pi, 2 * math.pi / 3, math.pi / 2, math.pi / 2, 2 * math.pi,
    math.pi, 2 * math.pi / 5, math.pi, math.pi / 2, 2 * math.pi / 5, 0.0, 2 * math.pi,
    2 * math.pi, 2 * math.pi, 2 * math.pi, 0.0, 2 * math.pi / 6, 2 * math.pi, 2 * math.pi,
)


def _as_size(obj_size: Any) -> tuple[float, ...]:
    if np.ndim(obj_size) == 0:
        s = float(obj_size)
        return (s, s, s)
    return tuple(float(v) for v in np.asarray(obj_size, dtype=float).reshape(-1))


class Task:
    """Base class of CLIPort/GenSim tasks (recording stand-in)."""

    def __init__(self) -> None:
        self.ee: Any = Suction
        self.mode = "train"
        self.sixdof = False
        self.primitive: Any = primitives.PickPlace()
        self.oracle_cams = cameras.Oracle.CONFIG
        self.rng: Any = None
        self.pos_eps = RAVENS_POS_EPS
        self.rot_eps = RAVENS_ROT_EPS
        self.num_blocks = 50
        self.pix_size = 0.003125
        self.bounds = np.array([list(WORKSPACE_X), list(WORKSPACE_Y), list(RAVENS_Z)])
        self.zone_bounds = np.copy(self.bounds)
        self.goals: list[Any] = []
        self.lang_goals: list[str] = []
        self.obj_points_cache: dict[int, Any] = {}
        self.task_completed_desc = "task completed."
        self.progress: float = 0
        self._rewards: float = 0
        self.train_set = np.arange(0, 14)
        self.test_set = np.arange(14, 20)
        self.assets_root: str | None = None
        self.homogeneous = False
        self.max_steps = 10
        self.lang_template = ""
        # (goal tuple, language) of every add_goal call, matched by identity later.
        self._factask_goal_lang: list[tuple[Any, str | None]] = []

    # ----------------------------------------------------------------- reset
    def reset(self, env: Any) -> None:
        """Start a new episode: clear goals (subclasses then add objects and goals).

        Raises:
            InvalidValueError: ``assets_root`` not set (a ``ValueError``, as CLIPort's).
        """
        if not self.assets_root:
            raise InvalidValueError("assets_root must be set for task, call set_assets_root().")
        self.goals = []
        self.lang_goals = []
        self.progress = 0
        self._rewards = 0
        self.obj_points_cache = {}
        self._factask_goal_lang = []

    def additional_reset(self) -> None:
        """GenSim's adjustments from the language template (bowls, piles, ropes)."""
        template = getattr(self, "lang_template", "") or ""
        if "bowl" in template:
            self.pos_eps = BOWL_POS_EPS
        if "piles" in template:
            self.ee = Spatula
            self.primitive = primitives.push
        if "rope" in template:
            self.primitive = primitives.PickPlace(height=0.02, speed=0.001)
            self.pos_eps = ROPE_POS_EPS

    def set_assets_root(self, assets_root: str) -> None:
        self.assets_root = assets_root

    def get_asset_full_path(self, path: str) -> str:
        return path

    # ----------------------------------------------------------------- goals
    def zip_obj_ids(self, obj_ids: Any, symmetries: Any) -> list[Any]:
        """Pair object ids with their symmetry: [(id, (symmetry, None)), ...]."""
        obj_ids = list(obj_ids)
        if obj_ids and isinstance(obj_ids[0], tuple):
            return obj_ids
        if symmetries is None:
            symmetries = [0.0] * len(obj_ids)
        if np.ndim(symmetries) == 0:
            # One number for every object (GenSim's zip would raise on it).
            active_session().warn(f"add_goal: symmetries={symmetries!r} is one number; it "
                                  "is every object's symmetry")
            symmetries = [symmetries] * len(obj_ids)
        symmetries = list(symmetries)
        if len(symmetries) < len(obj_ids):
            # GenSim zips the two lists: the objects past the symmetries drop out of
            # the goal (Ravens never checks them), whatever the author meant.
            active_session().warn(
                f"add_goal: {len(symmetries)} symmetr{'y' if len(symmetries) == 1 else 'ies'} "
                f"for {len(obj_ids)} objects; as in GenSim (zip_obj_ids) the goal keeps the "
                f"first {len(symmetries)} object(s) only")
        return [(oid, (sym, None)) for oid, sym in zip(obj_ids, symmetries, strict=False)]

    def add_goal(self, objs: Any, matches: Any, targ_poses: Any, replace: bool,
                 rotations: bool, metric: str, params: Any, step_max_reward: float,
                 symmetries: Any = None, language_goal: Any = None, **kwargs: Any) -> None:
        """Append one goal (CLIPort's 8-tuple) and its language goal.

        Args:
            objs: Object ids, or (id, (symmetry, None)) pairs.
            matches: len(objs) x len(targ_poses) 0/1 matrix.
            targ_poses: Target poses (position, quaternion xyzw).
            replace: Whether a target may take several objects (oracle only).
            rotations: Whether the placement rotates the object.
            metric: ``'pose'`` or ``'zone'``.
            params: For ``'zone'``: [(zone_pose, zone_size)].
            step_max_reward: This goal's share of the reward.
            symmetries: Yaw symmetry (radians) per object, if ``objs`` are ids.
            language_goal: The goal in language (a string or a list of strings).
        """
        objs = self.zip_obj_ids(objs, symmetries)
        goal = (objs, matches, targ_poses, replace, rotations, metric, params, step_max_reward)
        self.goals.append(goal)
        text: str | None = None
        if isinstance(language_goal, str):
            self.lang_goals.append(language_goal)
            text = language_goal
        elif isinstance(language_goal, (list, tuple)):
            self.lang_goals.extend(language_goal)
            text = "; ".join(str(g) for g in language_goal)
        self._factask_goal_lang.append((goal, text))

    def get_lang_goal(self) -> str:
        return self.lang_goals[0] if self.lang_goals else self.task_completed_desc

    def get_reward(self) -> float:
        return float(self._rewards)

    def is_match(self, pose0: Any, pose1: Any, symmetry: float) -> bool:
        """Ravens' pose check: XY within ``pos_eps``, yaw within ``rot_eps`` mod symmetry."""
        p0, q0 = split_pose(pose0)
        p1, q1 = split_pose(pose1)
        return pose_match(p0, q0, p1, q1, float(symmetry), self.pos_eps, self.rot_eps)

    # ----------------------------------------------------------- placement
    def get_random_pose(self, env: Any, obj_size: Any = 0.1, **kwargs: Any
                        ) -> tuple[list[float], tuple[float, ...]]:
        """A free spot in the workspace for an object of ``obj_size`` (x, y, z).

        Returns:
            ([x, y, z], quaternion xyzw) with z = half the height and a random yaw.
        """
        s = active_session()
        size = _as_size(obj_size)
        radius = math.hypot(size[0], size[1] if len(size) > 1 else size[0]) / 2
        lo = self.bounds[:2, 0] + radius
        hi = np.maximum(self.bounds[:2, 1] - radius, lo)
        centres = np.array([o.pos[:2] for o in s.objects.values()]).reshape(-1, 2)
        radii = np.array([math.hypot(o.size[0], o.size[1]) / 2 for o in s.objects.values()])
        # All attempts drawn at once (as one loop would draw them) and measured against
        # every object in one array operation: a task adding hundreds of objects stays
        # quick. The first clear spot wins, else the clearest.
        spots = s.rng.uniform(lo, hi, size=(RANDOM_POSE_ATTEMPTS, 2))
        if len(radii):
            gaps = np.linalg.norm(spots[:, None, :] - centres[None, :, :], axis=2)
            clear = (gaps - radii[None, :] - radius).min(axis=1)
        else:
            clear = np.full(len(spots), np.inf)
        free = np.flatnonzero(clear > 0)
        pick = int(free[0]) if len(free) else int(np.argmax(clear))
        best, best_clear = spots[pick], float(clear[pick])
        if best_clear <= 0:
            s.warn(f"get_random_pose found no free spot for size {size}; the object "
                   "overlaps another at the start")
        z = size[2] / 2 if len(size) >= 3 else 0.05
        yaw = float(s.rng.uniform(0, 2 * math.pi))
        pos = [float(best[0]), float(best[1]), z]
        s.random_spots.add(s.spot_key(pos))
        return pos, cutils.eulerXYZ_to_quatXYZW((0, 0, yaw))

    def get_random_size(self, min_x: float, max_x: float, min_y: float, max_y: float,
                        min_z: float, max_z: float) -> tuple[float, float, float]:
        """A random box size within the given ranges."""
        r = active_session().rng.random(3)
        return (float(r[0] * (max_x - min_x) + min_x), float(r[1] * (max_y - min_y) + min_y),
                float(r[2] * (max_z - min_z) + min_z))

    # ------------------------------------------------------------- assets
    def fill_template(self, template: str, replace: dict[str, Any]) -> str:
        """Record a filled URDF template; return a token path ``add_object`` understands."""
        return active_session().register_template(template, replace)

    def check_require_obj(self, path: str) -> bool:
        return False

    def get_colors(self, mode: str | None = None, n_colors: int = -1
                   ) -> tuple[list[list[float]], list[str]]:
        """``n_colors`` colours of the task's mode (see ``utils.get_colors``)."""
        return cutils.get_colors(mode or self.mode, n_colors)

    def get_kitting_shapes(self, n_objects: int) -> np.ndarray:
        """Indices of ``n_objects`` kitting shapes from the mode's split."""
        if self.mode == "train":
            return np.random.choice(self.train_set, n_objects)
        if self.homogeneous:
            return np.array([np.random.choice(self.test_set)] * n_objects)
        return np.random.choice(self.test_set, n_objects)

    def make_kitting_objects(self, env: Any, targets: Any, obj_shapes: Any, n_objects: int,
                             colors: Any) -> tuple[list[Any], list[np.ndarray]]:
        """Add ``n_objects`` kitting shapes; return (objects with symmetry, match rows)."""
        objects, matches = [], []
        shapes = np.asarray(obj_shapes)
        for i in range(n_objects):
            shape = int(shapes[i])
            pose = self.get_random_pose(env, (0.08, 0.08, 0.02))
            fname = os.path.join(self.assets_root or "", "kitting", f"{shape:02d}.obj")
            urdf = self.fill_template("kitting/object-template.urdf",
                                      {"FNAME": (fname,), "SCALE": [0.003, 0.003, 0.001],
                                       "COLOR": colors[i]})
            block_id = env.add_object(urdf, pose)
            objects.append((block_id, (KIT_SHAPE_SYMMETRY[shape], None)))
            match = np.zeros(len(targets))
            match[np.argwhere(shapes == shape).reshape(-1)] = 1
            matches.append(match)
        return objects, matches

    def add_corner_anchor_for_pose(self, env: Any, pose: Any) -> None:
        """Add a fixed corner marker at ``pose``."""
        urdf = self.fill_template("corner/corner-template.urdf",
                                  {"DIMX": (0.04,), "DIMY": (0.04,)})
        if len(pose) != 2:
            pose = [pose, (0, 0, 0, 1)]
        env.add_object(urdf, pose, "fixed")

    def get_box_object_points(self, obj: int) -> np.ndarray:
        """Sample points (3, N) of an object's box, in its frame, as CLIPort does."""
        dims = active_session().obj(obj).size
        axes = [np.arange(-d / 2, d / 2, OBJECT_POINT_SPACING) for d in dims]
        xv, yv, zv = np.meshgrid(*axes, sparse=False, indexing="xy")
        return np.vstack((xv.reshape(1, -1), yv.reshape(1, -1), zv.reshape(1, -1)))

    get_sphere_object_points = get_box_object_points

    def color_random_brown(self, obj: int) -> None:
        active_session().obj(obj).color = "brown"

    # ------------------------------------------------------ not recordable
    def _unsupported(self, what: str) -> Any:
        raise Unsupported(f"Task.{what} is not supported by factask's CLIPort layer")

    def oracle(self, env: Any) -> Any:
        return self._unsupported("oracle (factask runs its own oracle)")

    def reward(self) -> Any:
        return self._unsupported("reward (see factask.compat.cliport.scoring.ravens_reward)")

    def done(self) -> Any:
        return self._unsupported("done")

    def get_true_image(self, env: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Ravens' oracle top-down view of the workspace, computed from the recorded
        objects' boxes instead of rendered (nothing renders while recording).

        Returns:
            (colour uint8 (H, W, 3), height float32 (H, W), object id int32 (H, W), 0
            where nothing is), H along y and W along x at ``pix_size``, as Ravens'
            height maps; each pixel shows the highest box top over it.
        """
        return top_down_view(active_session().objects.values(), self.bounds, self.pix_size)

    def get_mesh_object_points(self, obj: int) -> np.ndarray:
        """Points (3, N) over the object's mesh bounds, as GenSim samples them; factask's
        assets are built to their recorded size, so the bounds are the object's box."""
        return self.get_box_object_points(obj)

    def get_target_sample_surface_points(self, *args: Any, **kwargs: Any) -> Any:
        return self._unsupported("get_target_sample_surface_points (meshes)")

    def make_piles(self, env: Any, block_color: Any = None, *args: Any, **kwargs: Any) -> Any:
        """GenSim's piles: ``num_blocks`` small blocks (one ``pile`` variable once
        a pushing goal names them, :mod:`factask.compat.cliport.piles`)."""
        self._factask_made_piles = True  # GenSim sweeps what make_piles adds
        return make_piles(env, self.bounds, int(self.num_blocks), block_color)

    def make_ropes(self, env: Any, corners: Any, radius: float = 0.005, n_parts: int = 20,
                   color_name: str = "red", *args: Any, **kwargs: Any
                   ) -> tuple[list[Any], list[Any], np.ndarray]:
        """GenSim's ropes: ``n_parts`` beads linked in a chain (one ``rope`` variable,
        :mod:`factask.compat.cliport.ropes`), dropped at a random spot, each with a
        target on the line from ``corners[0]`` to ``corners[1]``.

        Returns:
            (objects, targets, matches) for ``add_goal``: ``(id, (0, None))`` per bead,
            a target pose per bead, ``eye + flipped eye`` (either end first).
        """
        return make_ropes(self, env, corners, radius, int(n_parts), color_name)

    make_rope = make_ropes

    def spawn_box(self) -> Any:
        return self._unsupported("spawn_box (needs a running simulation)")


def top_down_view(objects: Any, bounds: np.ndarray, pix_size: float
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Colour, height and object-id maps of boxes seen from straight above.

    Args:
        objects: :class:`~factask.compat.cliport.recorder.RecordedObject` items.
        bounds: Workspace bounds ``[[x0, x1], [y0, y1], [z0, z1]]``.
        pix_size: Metres per pixel.
    """
    width = round(float(bounds[0, 1] - bounds[0, 0]) / pix_size)
    height = round(float(bounds[1, 1] - bounds[1, 0]) / pix_size)
    xs = bounds[0, 0] + (np.arange(width) + 0.5) * pix_size
    ys = bounds[1, 0] + (np.arange(height) + 0.5) * pix_size
    gx, gy = np.meshgrid(xs, ys)  # (H, W): rows along y, columns along x
    hmap = np.zeros((height, width), dtype=np.float32)
    mask = np.zeros((height, width), dtype=np.int32)
    cmap = np.zeros((height, width, 3), dtype=np.uint8)
    for o in sorted(objects, key=lambda o: float(o.pos[2]) + o.size[2] / 2):
        yaw = yaw_of_xyzw(o.quat)
        c, sn = np.cos(yaw), np.sin(yaw)
        dx, dy = gx - o.pos[0], gy - o.pos[1]
        inside = ((np.abs(c * dx + sn * dy) <= o.size[0] / 2)
                  & (np.abs(-sn * dx + c * dy) <= o.size[1] / 2))
        top = float(o.pos[2]) + o.size[2] / 2 - bounds[2, 0]
        over = inside & (top >= hmap)
        hmap[over] = top
        mask[over] = o.obj_id
        cmap[over] = np.round(np.asarray(rgba(o.color)[:3]) * 255).astype(np.uint8)
    return cmap, hmap, mask
