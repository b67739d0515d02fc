"""The suction grasp per world: one inactive weld per free object, switched per world.

The single env has ONE ``suction`` weld and rewrites ``model.eq_obj2id`` to the
object it grasps (:mod:`factask.sim.robots.suction`). A batch shares one model between
its worlds, and MuJoCo Warp cannot give ``eq_obj2id`` a value per world; it can
give ``eq_data`` (the weld's relative pose) and ``eq_active`` one. So the batch's
model is the scene's spec with one more weld per free object — cup body to that
object, inactive (:func:`factask.batch.model.batch_model`) — and a grasp in world *w*
writes the current cup-to-object pose into that world's ``eq_data`` row and
switches that world's weld on (:class:`WorldSuction`). Inactive welds add no
constraint rows: the physics of a world that grasps nothing is the single env's.

The grasp rule is the single env's: the closest free object whose geom touches
the cup geom within :data:`~factask.sim.robots.suction.TOUCH_DISTANCE` (contacts of the
last physics step). Contacts are read on the host, world by world (NumPy over the
contact list); a device kernel is for later.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import mujoco
import numpy as np

from factask.sim.robots.suction import CUP_GEOM, TOUCH_DISTANCE
from factask.vocabulary.errors import InvalidValueError


class WorldSuction:
    """Suction on and off per world, on a batch's MuJoCo Warp model and data.

    Args:
        model: The batch's host model (:func:`factask.batch.model.batch_model`).
        welds: Free object body id -> its weld's equality id.
        num_envs: Number of worlds.

    Attributes:
        held: Root body id each world's cup holds (num_envs,), -1 where none.
    """

    def __init__(self, model: mujoco.MjModel, welds: Mapping[int, int], num_envs: int) -> None:
        self.model = model
        self.welds = dict(welds)
        self.num_envs = int(num_envs)
        self.cup_geom = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, CUP_GEOM)
        if self.cup_geom < 0:
            raise InvalidValueError(f"the model has no {CUP_GEOM!r} geom")
        self.cup_body = int(model.geom_bodyid[self.cup_geom])
        #: Geom -> the free object body (root) it belongs to, -1 for others.
        roots = model.body_rootid[model.geom_bodyid]
        self.geom_object = np.where(np.isin(roots, list(self.welds)), roots, -1)
        self.held = np.full(self.num_envs, -1, dtype=np.int64)

    def reset(self, worlds: np.ndarray) -> None:
        """Forget what ``worlds`` held (their ``eq_active`` is reset with their data)."""
        self.held[worlds] = -1

    def contacts(self, data: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The last physics step's contacts closer than ``TOUCH_DISTANCE``, all worlds:
        (world (k,), geom pairs (k, 2), distance (k,)).

        Args:
            data: The batch's ``mujoco_warp.Data``.
        """
        n = min(int(data.nacon.numpy()[0]), int(data.contact.dist.shape[0]))
        if n == 0:
            return np.zeros(0, dtype=int), np.zeros((0, 2), dtype=int), np.zeros(0)
        geom = data.contact.geom.numpy()[:n].reshape(n, 2)
        dist = data.contact.dist.numpy()[:n]
        world = data.contact.worldid.numpy()[:n]
        near = dist <= TOUCH_DISTANCE
        return world[near], geom[near], dist[near]

    def touched(self, data: Any) -> np.ndarray:
        """The closest free object each world's cup touches (num_envs,), -1 for none,
        from the contacts of the last physics step.

        Args:
            data: The batch's ``mujoco_warp.Data``.
        """
        out = np.full(self.num_envs, -1, dtype=np.int64)
        world, geom, dist = self.contacts(data)
        cup1, cup2 = geom[:, 0] == self.cup_geom, geom[:, 1] == self.cup_geom
        other = np.where(cup1, geom[:, 1], geom[:, 0])
        obj = np.where(cup1 | cup2, self.geom_object[other], -1)
        keep = obj >= 0
        best = np.full(self.num_envs, np.inf)
        for w, o, dd in zip(world[keep], obj[keep], dist[keep], strict=True):
            if dd < best[w]:
                best[w], out[w] = dd, o
        return out

    def cup_touching(self, data: Any) -> np.ndarray:
        """Worlds (num_envs,) whose cup geom touches anything (object, table, fixture)."""
        world, geom, _ = self.contacts(data)
        hit = (geom == self.cup_geom).any(axis=1)
        out = np.zeros(self.num_envs, dtype=bool)
        out[world[hit]] = True
        return out

    def held_touching(self, data: Any) -> np.ndarray:
        """Worlds (num_envs,) whose held object touches something besides the cup."""
        world, geom, _ = self.contacts(data)
        body = self.model.body_rootid[self.model.geom_bodyid[geom]]  # (k, 2)
        held = self.held[world][:, None]
        mine = (body == held) & (held >= 0)
        cup = geom == self.cup_geom
        hit = (mine[:, 0] & ~cup[:, 1] & (body[:, 1] != held[:, 0])) | \
              (mine[:, 1] & ~cup[:, 0] & (body[:, 0] != held[:, 0]))
        out = np.zeros(self.num_envs, dtype=bool)
        out[world[hit]] = True
        return out

    def grasp(self, wp_model: Any, data: Any, worlds: np.ndarray) -> np.ndarray:
        """Switch suction on in ``worlds``: weld the closest touching free object where
        it is (a world already holding something keeps it).

        Args:
            wp_model: The batch's ``mujoco_warp.Model`` (``eq_data`` batched per world).
            data: The batch's ``mujoco_warp.Data``.
            worlds: Boolean mask (num_envs,) of the worlds that switch suction on.

        Returns:
            Whether each world holds an object now (num_envs,).
        """
        want = np.asarray(worlds, dtype=bool) & (self.held < 0)
        touched = self.touched(data)
        grab = want & (touched >= 0)
        if grab.any():
            xpos = data.xpos.numpy()
            xquat = data.xquat.numpy()
            eq_data = wp_model.eq_data.numpy().copy()
            active = data.eq_active.numpy().copy()
            for w in np.flatnonzero(grab):
                obj = int(touched[w])
                inv = np.zeros(4)
                mujoco.mju_negQuat(inv, xquat[w, self.cup_body].astype(float))
                rel_pos, rel_quat = np.zeros(3), np.zeros(4)
                mujoco.mju_rotVecQuat(rel_pos, (xpos[w, obj] - xpos[w, self.cup_body])
                                      .astype(float), inv)
                mujoco.mju_mulQuat(rel_quat, inv, xquat[w, obj].astype(float))
                weld = self.welds[obj]
                eq_data[w, weld, :] = 0.0
                eq_data[w, weld, 3:6] = rel_pos
                eq_data[w, weld, 6:10] = rel_quat
                eq_data[w, weld, 10] = 1.0
                active[w, weld] = True
                self.held[w] = obj
            wp_model.eq_data.assign(eq_data)
            data.eq_active.assign(active)
        return self.held >= 0

    def release(self, data: Any, worlds: np.ndarray) -> None:
        """Switch suction off in ``worlds`` (their object welds go inactive).

        Args:
            data: The batch's ``mujoco_warp.Data``.
            worlds: Boolean mask (num_envs,).
        """
        off = np.asarray(worlds, dtype=bool) & (self.held >= 0)
        if not off.any():
            return
        active = data.eq_active.numpy().copy()
        for w in np.flatnonzero(off):
            active[w, self.welds[int(self.held[w])]] = False
            self.held[w] = -1
        data.eq_active.assign(active)


__all__ = ["WorldSuction"]
