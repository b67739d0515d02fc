"""Observations and rewards as Warp arrays on the batch's device, for zero-copy sharing.

:meth:`DeviceObservations.observe` gathers every world's state-mode observation from
MuJoCo Warp's arrays with two kernels, on the device, into Warp arrays that stay
allocated (each call overwrites them): ``object_poses`` (W, n, 7), ``ee_pose`` (W, 7)
and ``suction`` (W, 1), float32, quaternions (w, x, y, z). Any DLPack consumer takes
them without a copy: ``wp.to_torch(a)``, ``jax.dlpack.from_dlpack(a)``,
``np.from_dlpack(a)`` (the CPU device; read-only there), ``cupy.from_dlpack(a)``.

:func:`status_arrays` puts a status's ``reward``, ``success`` and ``progress`` on the
device. The factor checks run on the host (NumPy, :mod:`factask.batch.checks`), so that
is one host-to-device copy per call, not zero-copy, until the checks run on the device.

A module of its own: Warp compiles a module's kernels together, and these kernels need
not invalidate the cached compilation of :mod:`factask.batch.kernels`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import warp as wp

if TYPE_CHECKING:
    from factask.batch.status import BatchStatus
    from factask.batch.worlds import LockstepWorlds


@wp.kernel
def gather_objects(qpos: wp.array2d(dtype=float), mocap_pos: wp.array2d(dtype=wp.vec3),
                   mocap_quat: wp.array2d(dtype=wp.quat), source: wp.array(dtype=int),
                   out: wp.array3d(dtype=float)):  # pragma: no cover - device code
    """Object k of world w: a free joint's qpos (source[k] >= 0, its address) or a
    mocap body's pose (source[k] = -1 - mocap id), as (x, y, z, qw, qx, qy, qz)."""
    w, k = wp.tid()
    s = source[k]
    if s >= 0:
        for i in range(7):
            out[w, k, i] = qpos[w, s + i]
    else:
        p = mocap_pos[w, -1 - s]
        q = mocap_quat[w, -1 - s]
        for i in range(3):
            out[w, k, i] = p[i]
        for i in range(4):
            out[w, k, 3 + i] = q[i]  # element 0 is w: MuJoCo's order in MuJoCo Warp


@wp.func
def mat_to_quat_wxyz(m: wp.mat33) -> wp.vec4:  # pragma: no cover - device code
    """MuJoCo's ``mju_mat2Quat`` (the largest component first, then normalised), so the
    device gives the host observation's sign as well as its rotation."""
    q = wp.vec4()
    if m[0, 0] + m[1, 1] + m[2, 2] > 0.0:
        q[0] = 0.5 * wp.sqrt(1.0 + m[0, 0] + m[1, 1] + m[2, 2])
        q[1] = 0.25 * (m[2, 1] - m[1, 2]) / q[0]
        q[2] = 0.25 * (m[0, 2] - m[2, 0]) / q[0]
        q[3] = 0.25 * (m[1, 0] - m[0, 1]) / q[0]
    elif m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        q[1] = 0.5 * wp.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2])
        q[0] = 0.25 * (m[2, 1] - m[1, 2]) / q[1]
        q[2] = 0.25 * (m[0, 1] + m[1, 0]) / q[1]
        q[3] = 0.25 * (m[0, 2] + m[2, 0]) / q[1]
    elif m[1, 1] > m[2, 2]:
        q[2] = 0.5 * wp.sqrt(1.0 - m[0, 0] + m[1, 1] - m[2, 2])
        q[0] = 0.25 * (m[0, 2] - m[2, 0]) / q[2]
        q[1] = 0.25 * (m[0, 1] + m[1, 0]) / q[2]
        q[3] = 0.25 * (m[1, 2] + m[2, 1]) / q[2]
    else:
        q[3] = 0.5 * wp.sqrt(1.0 - m[0, 0] - m[1, 1] + m[2, 2])
        q[0] = 0.25 * (m[1, 0] - m[0, 1]) / q[3]
        q[1] = 0.25 * (m[0, 2] + m[2, 0]) / q[3]
        q[2] = 0.25 * (m[1, 2] + m[2, 1]) / q[3]
    return wp.normalize(q)


@wp.kernel
def gather_tip(site_xpos: wp.array2d(dtype=wp.vec3), site_xmat: wp.array2d(dtype=wp.mat33),
               tip: int, held_tree: wp.array(dtype=int), ee_pose: wp.array2d(dtype=float),
               suction: wp.array2d(dtype=float)):  # pragma: no cover - device code
    """World w's suction tip pose (x, y, z, qw, qx, qy, qz) and whether it holds."""
    w = wp.tid()
    p = site_xpos[w, tip]
    q = mat_to_quat_wxyz(site_xmat[w, tip])
    for i in range(3):
        ee_pose[w, i] = p[i]
    for i in range(4):
        ee_pose[w, 3 + i] = q[i]
    suction[w, 0] = wp.where(held_tree[w] >= 0, 1.0, 0.0)


class DeviceObservations:
    """The state-mode observation of every world of ``batch``, gathered on its device.

    Args:
        batch: The batch (its Warp data, device, objects).
        free: (object index, qpos address) of each free object.
        fixed: (object index, mocap id) of each fixed (mocap) object.
        tip_site: The suction tip's site id.
        held_tree: (W,) Warp ints: each world's held object's sleep tree, -1 for none.
    """

    def __init__(self, batch: LockstepWorlds, free: list[tuple[int, int]],
                 fixed: list[tuple[int, int]], tip_site: int, held_tree: Any) -> None:
        self.batch, self.tip_site, self.held_tree = batch, int(tip_site), held_tree
        n, worlds = len(batch.object_names), batch.num_envs
        source = np.zeros(max(n, 1), dtype=np.int32)
        for k, adr in free:
            source[k] = adr
        for k, mocap in fixed:
            source[k] = -1 - mocap
        with wp.ScopedDevice(batch.device):
            self._source = wp.array(source, dtype=int)
            self.arrays: dict[str, Any] = {
                "object_poses": wp.zeros((worlds, n, 7), dtype=float),
                "ee_pose": wp.zeros((worlds, 7), dtype=float),
                "suction": wp.zeros((worlds, 1), dtype=float),
            }

    def observe(self) -> dict[str, Any]:
        """Gather every world's observation now (the arrays are reused: copy to keep).

        Returns:
            ``object_poses``, ``ee_pose``, ``suction``: Warp arrays on the device.
        """
        b, a = self.batch, self.arrays
        d = b.wp_data
        if len(b.object_names):
            wp.launch(gather_objects, dim=(b.num_envs, len(b.object_names)),
                      inputs=[d.qpos, d.mocap_pos, d.mocap_quat, self._source],
                      outputs=[a["object_poses"]], device=b.device)
        wp.launch(gather_tip, dim=b.num_envs,
                  inputs=[d.site_xpos, d.site_xmat, self.tip_site, self.held_tree],
                  outputs=[a["ee_pose"], a["suction"]], device=b.device)
        return dict(a)


def status_arrays(status: BatchStatus, device: str) -> dict[str, Any]:
    """A status's ``reward`` (W,), ``success`` (W,) and ``progress`` (W, F) as Warp
    arrays on ``device`` (float32, bool, float32): one host-to-device copy each."""
    with wp.ScopedDevice(device):
        return {"reward": wp.array(np.asarray(status.reward, np.float32), dtype=float),
                "success": wp.array(np.asarray(status.success, bool), dtype=bool),
                "progress": wp.array(np.asarray(status.progress, np.float32), dtype=float)}


__all__ = ["DeviceObservations", "gather_objects", "gather_tip", "status_arrays"]
