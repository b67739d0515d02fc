"""Suction cup: its spec elements (tool geometry, tip site, weld) and the runtime gripper.

Suction is ONE weld equality constraint named ``suction`` whose ``body1`` is the
cup body. It is compiled with ``body2`` = the world and inactive. When suction
switches on, the gripper rewrites ``model.eq_obj2id`` to the touched object's
root body and writes the *current* cup-to-object relative pose into
``model.eq_data`` before activating it, so the object does not snap. Editing
``eq_obj2id`` at runtime was checked on mujoco 3.17 (the constraint rows are
rebuilt from the model at every step); it means the scene compiler does not have
to know about suction and needs no weld per object.

Weld ``eq_data`` layout (mujoco 3.x): ``[0:3]`` anchor in body2's frame,
``[3:6]`` body2's position in body1's frame, ``[6:10]`` body2's orientation in
body1's frame (w, x, y, z), ``[10]`` torque scale.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from factask.sim.robots.registry import RobotError

#: Name of the site at the cup's contact face (z axis points up the tool, x = tool yaw).
TIP_SITE = "suction_tip"
#: Name of the weld equality constraint used for suction.
SUCTION_WELD = "suction"
#: Name of the cup's collision geom (the only geom that can grasp).
CUP_GEOM = "suction_cup"
#: Cup radius and height (m): a 3 cm wide, 1 cm tall pad.
CUP_RADIUS = 0.015
CUP_HALF_HEIGHT = 0.005
#: Stem between the flange (or mocap handle) and the cup (m).
STEM_RADIUS = 0.01
STEM_LENGTH = 0.09
#: Flange-to-tip distance of the tool (stem + cup), metres.
TOOL_LENGTH = STEM_LENGTH + 2 * CUP_HALF_HEIGHT
#: A contact counts as "touching" when its signed distance is below this (m).
TOUCH_DISTANCE = 0.002
#: Weld stiffness: time constant 5 ms (>= 2 x the 2 ms timestep, MuJoCo's safe
#: minimum) so a held block sags under 1 mm; damping ratio 1 (no oscillation).
WELD_SOLREF = (0.005, 1.0)
WELD_SOLIMP = (0.95, 0.99, 0.001, 0.5, 2.0)
#: Distance (m) from an object's centre at which its turning is measured: an
#: object rests when its centre moves slower than the speed asked for, and its
#: points this far out too (|angular velocity| x this).
REST_RADIUS = 0.05
#: Geom types that can roll.
_ROUND_GEOMS = np.array([int(mujoco.mjtGeom.mjGEOM_SPHERE), int(mujoco.mjtGeom.mjGEOM_CAPSULE),
                         int(mujoco.mjtGeom.mjGEOM_ELLIPSOID), int(mujoco.mjtGeom.mjGEOM_CYLINDER)])
#: Collision bits of robot geoms: they collide with ordinary geoms (bit 0) but
#: not with each other (no self-collision among the simplified link shapes).
ROBOT_CONTYPE = 2
ROBOT_CONAFFINITY = 1


def add_tool(body: mujoco.MjsBody, down: bool) -> mujoco.MjsGeom:
    """Add the suction tool (stem, cup geom, ``suction_tip`` site) to ``body``.

    Args:
        body: The spec body that carries the tool (arm flange or floating cup body).
        down: True when ``body``'s z axis points out of the tool (arm flange: the
            tip lies at +z); False when the body frame IS the tip frame with z up
            (floating cup: the stem lies at +z above the tip).

    Returns:
        The cup geom.
    """
    sign = 1.0 if down else -1.0
    tip = TOOL_LENGTH if down else 0.0
    cylinder = mujoco.mjtGeom.mjGEOM_CYLINDER
    # Stem from the tool's base to the back of the cup.
    stem_c = tip - sign * (2 * CUP_HALF_HEIGHT + STEM_LENGTH / 2)
    body.add_geom(
        name="suction_stem", type=cylinder, size=[STEM_RADIUS, STEM_LENGTH / 2, 0.0],
        pos=[0, 0, stem_c], rgba=[0.3, 0.3, 0.3, 1], mass=0.05,
        contype=ROBOT_CONTYPE, conaffinity=ROBOT_CONAFFINITY,
    )
    cup = body.add_geom(
        name=CUP_GEOM, type=cylinder, size=[CUP_RADIUS, CUP_HALF_HEIGHT, 0.0],
        pos=[0, 0, tip - sign * CUP_HALF_HEIGHT], rgba=[0.1, 0.1, 0.1, 1], mass=0.02,
        contype=ROBOT_CONTYPE, conaffinity=ROBOT_CONAFFINITY, friction=[1.0, 0.01, 0.001],
    )
    # Tip frame: z up the tool, so a top-down tool at yaw y has quat = quat_from_yaw(y).
    body.add_site(
        name=TIP_SITE, pos=[0, 0, tip], quat=[0, 1, 0, 0] if down else [1, 0, 0, 0],
        size=[0.004, 0.0, 0.0], rgba=[1, 0, 0, 1], group=4,
    )
    return cup


def add_suction_weld(spec: mujoco.MjSpec, cup_body: mujoco.MjsBody) -> mujoco.MjsEquality:
    """Add the inactive ``suction`` weld between ``cup_body`` and the world.

    Args:
        spec: The spec to add the equality to.
        cup_body: The body carrying the cup geom.

    Returns:
        The weld.
    """
    return spec.add_equality(
        name=SUCTION_WELD, type=mujoco.mjtEq.mjEQ_WELD, objtype=mujoco.mjtObj.mjOBJ_BODY,
        name1=cup_body.name, active=False, solref=list(WELD_SOLREF), solimp=list(WELD_SOLIMP),
    )


def find_id(model: mujoco.MjModel, objtype: mujoco.mjtObj, name: str) -> int:
    """Id of a named element, also when a parent MJCF prefixed it (``robot/name``).

    Args:
        model: Compiled model.
        objtype: Element type (``mujoco.mjtObj.mjOBJ_BODY`` ...).
        name: Element name as the robot builder wrote it.

    Returns:
        The element id.

    Raises:
        RobotError: No element of that name (or ``*/name``) exists.
    """
    i = mujoco.mj_name2id(model, objtype, name)
    if i >= 0:
        return i
    count = {
        mujoco.mjtObj.mjOBJ_BODY: model.nbody, mujoco.mjtObj.mjOBJ_GEOM: model.ngeom,
        mujoco.mjtObj.mjOBJ_SITE: model.nsite, mujoco.mjtObj.mjOBJ_JOINT: model.njnt,
        mujoco.mjtObj.mjOBJ_EQUALITY: model.neq, mujoco.mjtObj.mjOBJ_ACTUATOR: model.nu,
    }.get(objtype, 0)
    for j in range(count):
        full = mujoco.mj_id2name(model, objtype, j) or ""
        if full.endswith("/" + name):
            return j
    raise RobotError(
        f"model has no {objtype.name.removeprefix('mjOBJ_').lower()} named {name!r} "
        "(fix: build the scene with factask.sim.robots.attach.attach_robot before compiling)"
    )


def _is_free_root(model: mujoco.MjModel, body: int) -> bool:
    """True when ``body`` is a root body moved by a free joint (a loose object)."""
    if model.body_jntnum[body] < 1:
        return False
    return int(model.jnt_type[model.body_jntadr[body]]) == int(mujoco.mjtJoint.mjJNT_FREE)


class SuctionGripper:
    """Runtime suction on a compiled model: contact tests, grasp and release.

    Args:
        model: Compiled model containing the tool and the ``suction`` weld.
        data: Its data.

    Raises:
        RobotError: The tool or the weld is missing.
    """

    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        self.model = model
        self.data = data
        self.cup_geom = find_id(model, mujoco.mjtObj.mjOBJ_GEOM, CUP_GEOM)
        self.cup_body = int(model.geom_bodyid[self.cup_geom])
        self.weld = find_id(model, mujoco.mjtObj.mjOBJ_EQUALITY, SUCTION_WELD)
        if int(model.eq_type[self.weld]) != int(mujoco.mjtEq.mjEQ_WELD):
            raise RobotError(f"equality {SUCTION_WELD!r} is not a weld")
        # Every body of the robot's own tree: never a grasp candidate or obstacle.
        root = int(model.body_rootid[self.cup_body])
        self.robot_bodies = frozenset(
            b for b in range(model.nbody) if int(model.body_rootid[b]) == root and b != 0
        )
        self._held: int | None = None
        # Per-geom arrays, built once, so that the per-step tests are NumPy only.
        self._robot_body = np.zeros(model.nbody, dtype=bool)
        self._robot_body[list(self.robot_bodies)] = True
        self.geom_root = model.body_rootid[model.geom_bodyid].astype(np.int64)
        collides = (model.geom_contype != 0) | (model.geom_conaffinity != 0)
        not_robot = ~np.isin(self.geom_root, list(self.robot_bodies))
        #: Colliding geoms of objects (not the robot, not the static world).
        self.object_geoms = np.flatnonzero(collides & not_robot & (self.geom_root != 0))
        self._aabb_c = model.geom_aabb[self.object_geoms, :3].copy()
        self._aabb_h = model.geom_aabb[self.object_geoms, 3:].copy()
        #: Each object geom's box in its own frame: centre and half extents (n, 3).
        self.local_box_centre, self.local_box_half = self._aabb_c, self._aabb_h
        #: Bool per object geom: part of furniture (fixed, or on a joint in a fixed host:
        #: a drawer), not of a loose object.
        self.furniture = np.array([not _is_free_root(model, int(model.body_rootid[b]))
                                   for b in model.geom_bodyid[self.object_geoms]], dtype=bool)
        #: Colliding geoms that are not the robot's (objects and the static world): what
        #: a guarded move can touch (:meth:`clearance`).
        self.solid_geoms = np.flatnonzero(collides & not_robot)
        self._solid_root = self.geom_root[self.solid_geoms]
        self._solid_c = model.geom_aabb[self.solid_geoms, :3].copy()
        self._solid_h = model.geom_aabb[self.solid_geoms, 3:].copy()
        self._solid_plane = model.geom_type[self.solid_geoms] == int(mujoco.mjtGeom.mjGEOM_PLANE)
        self._cup_c = model.geom_aabb[self.cup_geom, :3].copy()
        self._cup_h = model.geom_aabb[self.cup_geom, 3:].copy()
        #: Contacts are generated this far apart at most (m; the largest geom margin).
        self.contact_reach = float(model.geom_margin.max(initial=0.0))
        free = [j for j in range(model.njnt)
                if int(model.jnt_type[j]) == int(mujoco.mjtJoint.mjJNT_FREE)
                and int(model.body_rootid[model.jnt_bodyid[j]]) not in self.robot_bodies]
        #: qvel indices of the free objects' linear and angular velocities.
        self.object_dofs = np.array([int(model.jnt_dofadr[j]) + k for j in free for k in range(6)],
                                    dtype=np.int64)
        self._linear_dofs = self.object_dofs.reshape(-1, 6)[:, :3].ravel()
        self._angular_dofs = self.object_dofs.reshape(-1, 6)[:, 3:].ravel()
        #: Root bodies tied to another by an equality other than the suction weld (a
        #: rope's segments, linked by connect constraints): a held one drags the rest.
        self.linked_bodies = frozenset(
            int(model.body_rootid[_eq_body(model, e, k)])
            for e in range(model.neq) if e != self.weld for k in (1, 2))

    @property
    def held(self) -> int | None:
        """Root body id of the object held, or None."""
        return self._held

    @property
    def holds_linked(self) -> bool:
        """True when the object held is linked to others (a rope's segment)."""
        return self._held is not None and self._held in self.linked_bodies

    def touched_objects(self) -> list[int]:
        """Free root bodies whose geoms touch the cup geom now (closest first).

        Returns:
            Body ids (roots moved by a free joint), without duplicates.
        """
        found: list[tuple[float, int]] = []
        d = self.data
        for k in range(d.ncon):
            c = d.contact[k]
            if c.dist > TOUCH_DISTANCE:
                continue
            if c.geom1 == self.cup_geom:
                other = int(c.geom2)
            elif c.geom2 == self.cup_geom:
                other = int(c.geom1)
            else:
                continue
            root = int(self.model.body_rootid[self.model.geom_bodyid[other]])
            if _is_free_root(self.model, root) and root not in self.robot_bodies:
                found.append((float(c.dist), root))
        found.sort()
        out: list[int] = []
        for _, b in found:
            if b not in out:
                out.append(b)
        return out

    def _touching(self) -> np.ndarray:
        """Geom pairs (ncon', 2) of the contacts closer than TOUCH_DISTANCE."""
        d = self.data
        if d.ncon == 0:
            return np.zeros((0, 2), dtype=np.int64)
        con = d.contact
        return con.geom[con.dist <= TOUCH_DISTANCE]

    def cup_in_contact(self) -> bool:
        """True when the cup geom touches anything (object, table, fixture)."""
        return bool((self._touching() == self.cup_geom).any())

    def held_in_contact(self) -> bool:
        """True when the held object touches something other than the robot."""
        if self._held is None:
            return False
        roots = self.geom_root[self._touching()]
        mine = roots == self._held
        one = mine[:, 0] ^ mine[:, 1]  # exactly one side is the held object
        if not one.any():
            return False
        other = np.where(mine[:, 0], roots[:, 1], roots[:, 0])[one]
        return bool((~self._robot_body[other]).any())

    def object_boxes(self) -> tuple[np.ndarray, np.ndarray]:
        """Centres and half extents (n, 3) of every object geom's world-aligned box
        (``object_geoms`` order): computed once, they can be passed to the queries
        below that take ``boxes``."""
        d = self.data
        ids = self.object_geoms
        rot = d.geom_xmat[ids].reshape(-1, 3, 3)
        centre = d.geom_xpos[ids] + np.einsum("nij,nj->ni", rot, self._aabb_c)
        half = np.einsum("nij,nj->ni", np.abs(rot), self._aabb_h)
        return centre, half

    def obstacle_top(self, start: np.ndarray | None = None, goal: np.ndarray | None = None,
                     margin: float = 0.0) -> float:
        """Highest point (m) of the objects other than the held one (0: the table).

        Args:
            start: With ``goal``: only objects within ``margin`` of the straight
                line from ``start`` to ``goal`` (x, y) count.
            goal: See ``start``.
            margin: Half width (m) of that corridor beyond each object's box.

        Returns:
            The height of the highest object top that counts.
        """
        if start is not None and goal is not None:
            top = self.corridor_obstacles(start, goal, margin)[2]
        else:
            centre, half = self.object_boxes()
            top = (centre[:, 2] + half[:, 2])[self._not_held()]
        return float(top.max()) if len(top) else 0.0

    def _not_held(self) -> np.ndarray:
        """Bool per object geom: not a geom of the held object."""
        if self._held is None:
            return np.ones(len(self.object_geoms), dtype=bool)
        return self.geom_root[self.object_geoms] != self._held

    def corridor_obstacles(self, start: np.ndarray, goal: np.ndarray, margin: float,
                           boxes: tuple[np.ndarray, np.ndarray] | None = None,
                           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The object geoms (not the held object's) within ``margin`` of the straight
        line from ``start`` to ``goal`` (x, y): where along it and how high.

        Args:
            start: Start of the line (its x, y count).
            goal: End of the line.
            margin: Half width (m) of the corridor beyond each geom's box.
            boxes: :meth:`object_boxes` of the current state (computed if None).

        Returns:
            ``(t_lo, t_hi, top)``, one entry per geom in the corridor: the part
            ``[t_lo, t_hi]`` of the line (0 at ``start``, 1 at ``goal``) that its box,
            grown by ``margin``, spans, and the height of its top (m).
        """
        if len(self.object_geoms) == 0:
            return np.zeros(0), np.zeros(0), np.zeros(0)
        centre, half = boxes if boxes is not None else self.object_boxes()
        a, b = np.asarray(start[:2], float), np.asarray(goal[:2], float)
        ab = b - a
        length2 = max(float(ab @ ab), 1e-12)
        t = np.clip((centre[:, :2] - a) @ ab / length2, 0.0, 1.0)
        gap = np.abs(centre[:, :2] - (a + t[:, None] * ab)) - half[:, :2]
        keep = self._not_held() & ((np.maximum(gap, 0.0) ** 2).sum(axis=1) <= margin ** 2)
        # The box's shadow on the line: centre +- (its extent along the line + margin).
        unit = np.abs(ab) / math.sqrt(length2)
        reach = (half[keep, :2] @ unit + margin) / math.sqrt(length2)
        tc = (centre[keep, :2] - a) @ ab / length2
        return (np.clip(tc - reach, 0.0, 1.0), np.clip(tc + reach, 0.0, 1.0),
                centre[keep, 2] + half[keep, 2])

    def clearance(self, held: bool, margin: float,
                  move: tuple[np.ndarray, np.ndarray] | None = None) -> float:
        """Vertical gap (m) under the cup (``held`` False) or under the held object:
        from its lowest point down to the highest top of the other solids (objects,
        the table, fixtures) whose world-aligned boxes come within ``margin`` of its
        own sideways. Nothing closer than this below it can touch it while it moves
        straight down by less (a guarded descent need not test contacts before).

        Args:
            held: Measure under the held object (else under the cup geom).
            margin: Sideways distance (m) within which a solid counts as below.
            move: (the tip now, the tip later): the gap the part would have with
                the tip there, the solids where they are now; the part's box is
                then widened to the square that holds it at any yaw about the tip.

        Returns:
            The gap (negative when something is already level with it; -inf when
            ``held`` and nothing is held, or a plane is not level).
        """
        d = self.data
        ids = self.solid_geoms
        rot = d.geom_xmat[ids].reshape(-1, 3, 3)
        centre = d.geom_xpos[ids] + np.einsum("nij,nj->ni", rot, self._solid_c)
        half = np.einsum("nij,nj->ni", np.abs(rot), self._solid_h)
        if self._solid_plane.any():  # an infinite plane: its height, everywhere
            if (rot[self._solid_plane, 2, 2] < 1.0 - 1e-9).any():
                return -math.inf
            centre[self._solid_plane, 2] = d.geom_xpos[ids[self._solid_plane], 2]
            half[self._solid_plane] = (math.inf, math.inf, 0.0)
        if held:
            mine = self._solid_root == (-1 if self._held is None else self._held)
            if not mine.any():
                return -math.inf
            lo = (centre[mine] - half[mine]).min(axis=0)
            hi = (centre[mine] + half[mine]).max(axis=0)
        else:
            mine = np.zeros(len(ids), dtype=bool)
            cup_rot = d.geom_xmat[self.cup_geom].reshape(3, 3)
            c = d.geom_xpos[self.cup_geom] + cup_rot @ self._cup_c
            h = np.abs(cup_rot) @ self._cup_h
            lo, hi = c - h, c + h
        if move is not None:
            now, later = (np.asarray(p, dtype=float) for p in move)
            reach = float(np.linalg.norm(np.maximum(np.abs(lo[:2] - now[:2]),
                                                    np.abs(hi[:2] - now[:2]))))
            lo = np.array([later[0] - reach, later[1] - reach, lo[2] + later[2] - now[2]])
            hi = np.array([later[0] + reach, later[1] + reach, hi[2] + later[2] - now[2]])
        near = (~mine & (centre[:, 0] + half[:, 0] >= lo[0] - margin)
                & (centre[:, 0] - half[:, 0] <= hi[0] + margin)
                & (centre[:, 1] + half[:, 1] >= lo[1] - margin)
                & (centre[:, 1] - half[:, 1] <= hi[1] + margin))
        top = (centre[near, 2] + half[near, 2]).max(initial=-math.inf)
        return float(lo[2] - top)

    def held_footprint(self, boxes: tuple[np.ndarray, np.ndarray] | None = None) -> float:
        """Largest horizontal distance (m) from the tip axis to the held object's box
        (0 when nothing is held; ``boxes``: :meth:`object_boxes`, computed if None)."""
        if self._held is None:
            return 0.0
        centre, half = boxes if boxes is not None else self.object_boxes()
        mine = self.geom_root[self.object_geoms] == self._held
        if not mine.any():
            return 0.0
        tip = self.data.xpos[self.cup_body, :2]
        reach = np.abs(centre[mine, :2] - tip) + half[mine, :2]
        return float(np.sqrt((reach ** 2).sum(axis=1)).max())

    def held_can_roll(self) -> bool:
        """True when the held object has a round geom (sphere, capsule, ellipsoid,
        cylinder): set down while moving, it may roll on."""
        if self._held is None:
            return False
        mine = self.object_geoms[self.geom_root[self.object_geoms] == self._held]
        return bool(np.isin(self.model.geom_type[mine], _ROUND_GEOMS).any())

    def held_bottom(self, boxes: tuple[np.ndarray, np.ndarray] | None = None) -> float | None:
        """Lowest point (m) of the held object, or None when nothing is held
        (``boxes``: :meth:`object_boxes`, computed if None)."""
        if self._held is None:
            return None
        centre, half = boxes if boxes is not None else self.object_boxes()
        low = centre[:, 2] - half[:, 2]
        mine = self.geom_root[self.object_geoms] == self._held
        return float(low[mine].min()) if mine.any() else None

    def objects_resting(self, speed: float, turn_radius: float = REST_RADIUS) -> bool:
        """True when no free object moves faster than ``speed`` (m/s): neither its
        centre nor its points ``turn_radius`` out, as it turns.

        Args:
            speed: Largest speed (m/s) that counts as resting.
            turn_radius: Distance (m) from the centre at which turning is weighed.

        Returns:
            Whether every free object rests.
        """
        if len(self.object_dofs) == 0:
            return True
        qvel = self.data.qvel
        return (float(np.abs(qvel[self._linear_dofs]).max()) < speed
                and float(np.abs(qvel[self._angular_dofs]).max()) * turn_radius < speed)

    def touched_sliders(self) -> list[int]:
        """Bodies moved by a slide or hinge joint of their own (drawers, doors) whose
        geoms touch the cup geom now, closest first."""
        found: list[tuple[float, int]] = []
        m, d = self.model, self.data
        for k in range(d.ncon):
            c = d.contact[k]
            if c.dist > TOUCH_DISTANCE or self.cup_geom not in (c.geom1, c.geom2):
                continue
            body = int(m.geom_bodyid[c.geom2 if c.geom1 == self.cup_geom else c.geom1])
            if m.body_jntnum[body] == 1 and int(m.jnt_type[m.body_jntadr[body]]) in (
                    int(mujoco.mjtJoint.mjJNT_SLIDE), int(mujoco.mjtJoint.mjJNT_HINGE)):
                found.append((float(c.dist), body))
        return list(dict.fromkeys(b for _, b in sorted(found)))

    def grasp(self, slider: bool = False) -> bool:
        """Switch suction on: weld the closest touching free object where it is.

        Args:
            slider: Hold a body that slides on a joint of its own (a drawer, by its
                handle) instead of a free object.

        Returns:
            True when an object is held after the call.
        """
        if self._held is not None:
            return True
        touched = self.touched_sliders() if slider else self.touched_objects()
        if not touched:
            return False
        obj = touched[0]
        m, d = self.model, self.data
        # Relative pose of the object in the cup frame, from the current state.
        q_cup_inv = np.zeros(4)
        mujoco.mju_negQuat(q_cup_inv, d.xquat[self.cup_body])
        rel_pos = np.zeros(3)
        mujoco.mju_rotVecQuat(rel_pos, d.xpos[obj] - d.xpos[self.cup_body], q_cup_inv)
        rel_quat = np.zeros(4)
        mujoco.mju_mulQuat(rel_quat, q_cup_inv, d.xquat[obj])
        m.eq_obj2id[self.weld] = obj
        m.eq_data[self.weld, 0:3] = 0.0
        m.eq_data[self.weld, 3:6] = rel_pos
        m.eq_data[self.weld, 6:10] = rel_quat
        m.eq_data[self.weld, 10] = 1.0
        d.eq_active[self.weld] = 1
        self._held = obj
        return True

    def release(self) -> None:
        """Switch suction off (the weld goes inactive and points back at the world)."""
        self.data.eq_active[self.weld] = 0
        self.model.eq_obj2id[self.weld] = 0
        self._held = None


def _eq_body(model: mujoco.MjModel, eq: int, side: int) -> int:
    """Body id of side 1 or 2 of equality ``eq`` (a site's body for site-based ones)."""
    obj = int(model.eq_obj1id[eq] if side == 1 else model.eq_obj2id[eq])
    if int(model.eq_objtype[eq]) == int(mujoco.mjtObj.mjOBJ_SITE):
        return int(model.site_bodyid[obj])
    return max(obj, 0)
