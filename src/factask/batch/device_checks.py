"""The slot relations' batched check on the device (Warp kernels), for every world at once.

``at_pose``, ``stack``, ``row``, ``circle`` and ``aligned`` — the relations most library
tasks use — share one check (:func:`~factask.batch.checks.check_slots_batch`): which
object fits which allowed slot, one object per slot, progress = the share placed.
Here the same numbers come from three kernels over the poses on the device:

1. ``slot_fits`` — one thread per (world, object, slot): XY distance, Z band, tilt
   from upright (none for spheres), yaw modulo the object's symmetry, not held;
2. ``assign_simple`` — one thread per world: where each object fits at most one slot
   and each slot at most one object (nearly always) the assignment is that slot; a
   chain (a stack) counts slots only from the bottom up without gaps;
3. ``progress`` — one thread per world: placed share and satisfied.

A world whose fits are not one-to-one needs an assignment solver; those worlds (the
kernel flags them) are solved on the host with the NumPy check's solver and written
back, so the result equals :func:`~factask.batch.checks.check_slots_batch` in every
world. Computed in float64 (Warp's ``float64`` runs on CPUs and GPUs), so a fit
decides as NumPy's does up to the last bit of ``atan2``/``acos``.

Quaternions must be unit (MuJoCo keeps free joints' normalised; :class:`BatchScene`
normalises). Other relation kinds stay host-side (:mod:`factask.batch.checks`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import warp as wp

from factask.batch.checks import BatchFactorStatus, assign_slots
from factask.batch.geometry import yaws
from factask.batch.targets import BatchTargets
from factask.relations.base import RelationBase
from factask.relations.status import MAX_TILT_DEG
from factask.scene.objects import SPHERE_KINDS, SceneObject
from factask.vocabulary.errors import InvalidValueError

#: Relation kinds this module checks on the device.
DEVICE_SLOT_KINDS = ("at_pose", "stack", "row", "circle", "aligned")
#: Degrees per radian (a Warp constant: kernels read only those of module globals).
_DEG = wp.constant(wp.float64(180.0 / math.pi))


#: How an object's tilt is measured (:func:`~factask.relations.status.upright_tilt_deg`):
#: its z axis from world z; not at all (a sphere); its x axis's slope (a log, which may
#: have rolled about it).
_TILT_Z, _TILT_NONE, _TILT_AXIS = wp.constant(0), wp.constant(1), wp.constant(2)


def _tilt_rule(obj: SceneObject) -> int:
    if obj.kind in SPHERE_KINDS:
        return 1
    return 2 if obj.kind == "log" else 0


@wp.kernel
def slot_fits(poses: wp.array3d(dtype=wp.float64), held: wp.array2d(dtype=wp.int32),
              cols: wp.array(dtype=wp.int32), tilt_rule: wp.array(dtype=wp.int32),
              symmetry: wp.array(dtype=wp.float64), target: wp.array4d(dtype=wp.float64),
              matches: wp.array3d(dtype=wp.int32), slot_yaw: wp.array2d(dtype=wp.float64),
              tol: wp.vec4d, check_yaw: wp.int32,
              fits: wp.array3d(dtype=wp.int32)):  # pragma: no cover - device code
    """fits[w, i, j]: object i fits slot j in world w (``tol``: xy, z, yaw, tilt)."""
    w, i, j = wp.tid()
    c = cols[i]
    ok = matches[w, i, j] != 0 and held[w, c] == 0
    dx = poses[w, c, 0] - target[w, i, j, 0]
    dy = poses[w, c, 1] - target[w, i, j, 1]
    dz = poses[w, c, 2] - target[w, i, j, 2]
    ok = ok and wp.sqrt(dx * dx + dy * dy) <= tol[0] and wp.abs(dz) <= tol[1]
    qw = poses[w, c, 3]
    qx = poses[w, c, 4]
    qy = poses[w, c, 5]
    qz = poses[w, c, 6]
    if tilt_rule[i] == _TILT_Z:
        zz = qw * qw - qx * qx - qy * qy + qz * qz
        zz = wp.clamp(zz, wp.float64(-1.0), wp.float64(1.0))
        ok = ok and wp.acos(zz) * _DEG <= tol[3]
    elif tilt_rule[i] == _TILT_AXIS:
        xz = wp.float64(2.0) * (qx * qz - qw * qy)
        xz = wp.clamp(wp.abs(xz), wp.float64(0.0), wp.float64(1.0))
        ok = ok and wp.asin(xz) * _DEG <= tol[3]
    if check_yaw != 0 and symmetry[i] > wp.float64(0.0):
        yaw = wp.atan2(wp.float64(2.0) * (qw * qz + qx * qy),
                       wp.float64(1.0) - wp.float64(2.0) * (qy * qy + qz * qz))
        s = symmetry[i]
        # NumPy's mod: C's fmod, then the divisor's sign (fmod keeps the dividend's).
        d = wp.mod((yaw - slot_yaw[w, j]) * _DEG, s)
        if d < wp.float64(0.0):
            d = d + s
        ok = ok and wp.min(d, s - d) <= tol[2]
    fits[w, i, j] = wp.where(ok, 1, 0)


@wp.kernel
def assign_simple(fits: wp.array3d(dtype=wp.int32), chain: wp.int32,
                  slot: wp.array2d(dtype=wp.int32),
                  simple: wp.array(dtype=wp.int32)):  # pragma: no cover - device code
    """World w's slot per object where fits are one-to-one (else ``simple[w] = 0``)."""
    w = wp.tid()
    n = fits.shape[1]
    m = fits.shape[2]
    one_to_one = wp.int32(1)
    for i in range(n):
        count = wp.int32(0)
        slot[w, i] = -1
        for j in range(m):
            if fits[w, i, j] != 0:
                if count == 0:
                    slot[w, i] = j
                count += 1
        if count > 1:
            one_to_one = 0
    for j in range(m):
        count = wp.int32(0)
        for i in range(n):
            count += fits[w, i, j]
        if count > 1:
            one_to_one = 0
    simple[w] = one_to_one
    if chain != 0 and one_to_one != 0:
        upto = wp.int32(0)  # slots 0 .. upto - 1 are all filled
        stop = wp.int32(0)
        for j in range(m):
            filled = wp.int32(0)
            for i in range(n):
                if slot[w, i] == j:
                    filled = 1
            if filled == 0:
                stop = 1
            if stop == 0:
                upto = j + 1
        for i in range(n):
            if slot[w, i] >= upto:
                slot[w, i] = -1


@wp.kernel
def progress(slot: wp.array2d(dtype=wp.int32), share: wp.array(dtype=wp.float64),
             satisfied: wp.array(dtype=wp.int32)):  # pragma: no cover - device code
    """Placed share and satisfied of world w."""
    w = wp.tid()
    n = slot.shape[1]
    placed = wp.int32(0)
    for i in range(n):
        if slot[w, i] >= 0:
            placed += 1
    share[w] = wp.where(n > 0, wp.float64(placed) / wp.float64(n), wp.float64(1.0))
    satisfied[w] = wp.where(placed == n, 1, 0)


@dataclass(frozen=True)
class DeviceFactorStatus:
    """One slot factor's status in every world, as Warp arrays on the device.

    Attributes:
        progress: (W,) float64.
        satisfied: (W,) int32 (1: satisfied).
        slot: (W, n) int32: the slot each object is placed in, -1 where none.
        solved_on_host: Worlds whose assignment the host solved (not one-to-one).
    """

    progress: Any
    satisfied: Any
    slot: Any
    solved_on_host: np.ndarray

    def to_host(self) -> BatchFactorStatus:
        """The same numbers as NumPy arrays (a device-to-host copy)."""
        return BatchFactorStatus(self.progress.numpy(), self.satisfied.numpy() != 0,
                                 self.slot.numpy() >= 0)


class DeviceSlotCheck:
    """A slot factor's targets on the device (uploaded once per reset), checkable on
    any poses of the same worlds.

    Args:
        goal: The factor's relation (one of :data:`DEVICE_SLOT_KINDS`).
        targets: Its solved targets in every world.
        objects: Scene objects by instance name.
        names: Instance names in the column order of the poses.
        device: The Warp device.

    Raises:
        InvalidValueError: another relation kind.
    """

    def __init__(self, goal: RelationBase, targets: BatchTargets,
                 objects: Mapping[str, SceneObject], names: Sequence[str], device: str) -> None:
        if goal.kind() not in DEVICE_SLOT_KINDS:
            raise InvalidValueError(f"relation {goal.kind()!r} has no device check (the "
                                    f"device checks: {', '.join(DEVICE_SLOT_KINDS)})")
        self.device, self.chain = device, bool(targets.chain)
        tol = goal.tolerances
        self.tol = wp.vec4d(tol.xy, tol.z, tol.yaw_deg, MAX_TILT_DEG)
        self.check_yaw = bool(targets.check_yaw)
        objs = [objects[o] for o in targets.objects]
        index = {n: k for k, n in enumerate(names)}
        self.shape = (targets.num_worlds, len(targets.objects), targets.matches.shape[2])
        with wp.ScopedDevice(device):
            self.cols = wp.array([index[o] for o in targets.objects], dtype=wp.int32)
            self.tilt_rule = wp.array([_tilt_rule(o) for o in objs], dtype=wp.int32)
            self.symmetry = wp.array([float(o.symmetry_deg) for o in objs], dtype=wp.float64)
            self.target = wp.array(targets.target_pos(objects), dtype=wp.float64)
            self.matches = wp.array(targets.matches.astype(np.int32), dtype=wp.int32)
            self.slot_yaw = wp.array(yaws(targets.slot_quat), dtype=wp.float64)

    def check(self, poses: Any, held: Any) -> DeviceFactorStatus:
        """The factor's status in every world.

        Args:
            poses: (W, N, 7) float64 Warp array: position, unit quaternion (w, x, y, z).
            held: (W, N) int32 Warp array: 1 where the robot holds that instance.

        Returns:
            The status on the device.
        """
        w, n, m = self.shape
        with wp.ScopedDevice(self.device):
            fits = wp.zeros((w, n, m), dtype=wp.int32)
            slot = wp.zeros((w, n), dtype=wp.int32)
            simple = wp.zeros(w, dtype=wp.int32)
            share = wp.zeros(w, dtype=wp.float64)
            satisfied = wp.zeros(w, dtype=wp.int32)
            if n and m:
                wp.launch(slot_fits, dim=(w, n, m),
                          inputs=[poses, held, self.cols, self.tilt_rule, self.symmetry,
                                  self.target, self.matches, self.slot_yaw, self.tol,
                                  int(self.check_yaw)], outputs=[fits])
            wp.launch(assign_simple, dim=w, inputs=[fits, int(self.chain)],
                      outputs=[slot, simple])
            hard = np.flatnonzero(simple.numpy() == 0)
            if len(hard):
                # Not one-to-one: the host's solver, as the NumPy check, for those worlds.
                host = slot.numpy()
                host[hard] = assign_slots(fits.numpy()[hard] != 0, self.chain)
                slot = wp.array(host, dtype=wp.int32)
            wp.launch(progress, dim=w, inputs=[slot], outputs=[share, satisfied])
        return DeviceFactorStatus(share, satisfied, slot, hard)


__all__ = ["DEVICE_SLOT_KINDS", "DeviceFactorStatus", "DeviceSlotCheck", "assign_simple",
           "progress", "slot_fits"]
