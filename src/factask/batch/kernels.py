"""Warp kernels of the batched env: each world's low-level command, held objects awake,
the peak contact and constraint counts, the deepest contact.

Imported only once the backend is known to be installed
(:func:`factask.batch.device.load_backend`): it imports Warp at module import.
Quaternions in MuJoCo Warp's arrays keep MuJoCo's order (w, x, y, z).
"""

from __future__ import annotations

import warp as wp


@wp.kernel
def set_mocap_xyzyaw(cmd: wp.array2d(dtype=float), mocap: int,
                     mocap_pos: wp.array2d(dtype=wp.vec3),
                     mocap_quat: wp.array2d(dtype=wp.quat)):  # pragma: no cover - device code
    """World w's mocap body ``mocap`` to (x, y, z) = cmd[w, 0:3], yawed by cmd[w, 3]."""
    w = wp.tid()
    half = cmd[w, 3] * 0.5
    mocap_pos[w, mocap] = wp.vec3(cmd[w, 0], cmd[w, 1], cmd[w, 2])
    # Element 0 is w (MuJoCo's order), whatever Warp's own quaternion convention.
    mocap_quat[w, mocap] = wp.quat(wp.cos(half), 0.0, 0.0, wp.sin(half))


@wp.kernel
def set_ctrl(cmd: wp.array2d(dtype=float),
             ctrl: wp.array2d(dtype=float)):  # pragma: no cover - device code
    """World w's actuator controls to cmd[w, :]."""
    w, k = wp.tid()
    ctrl[w, k] = cmd[w, k]


@wp.kernel
def track_peaks(nacon: wp.array(dtype=int), nefc: wp.array(dtype=int),
                peak_nacon: wp.array(dtype=int),
                peak_nefc: wp.array(dtype=int)):  # pragma: no cover - device code
    """Keep the most contacts (all worlds) and constraint rows (per world) any step had:
    MuJoCo Warp counts past its capacities (and drops the excess), and a step in the
    middle of a move can overflow where the state after it does not."""
    w = wp.tid()
    wp.atomic_max(peak_nefc, w, nefc[w])
    if w == 0:
        wp.atomic_max(peak_nacon, 0, nacon[0])


@wp.kernel
def track_deepest(nacon: wp.array(dtype=int), dist: wp.array(dtype=float),
                  worldid: wp.array(dtype=int), geom: wp.array(dtype=wp.vec2i),
                  robot_geom: wp.array(dtype=int),
                  deepest: wp.array(dtype=float)):  # pragma: no cover - device code
    """Keep, per world, the deepest contact (most negative distance) any step had
    between two geoms not of the robot (``robot_geom[g]`` 1): a narrowphase that
    answers a penetration of decimetres is a physics failure, even where the
    positions stay finite. The robot's contacts are left out: the cup is moved
    kinematically and its weld is compliant, so its cup and stem press centimetres
    into a bowl held by the rim, by design."""
    i = wp.tid()
    if i < nacon[0]:
        g = geom[i]
        if robot_geom[g[0]] == 0 and robot_geom[g[1]] == 0:
            wp.atomic_min(deepest, worldid[i], dist[i])


@wp.kernel
def wake_trees(tree: wp.array(dtype=int), ntree: int, awake: int,
               tree_asleep: wp.array2d(dtype=int)):  # pragma: no cover - device code
    """Keep world w's tree ``tree[w]`` awake (none where it is -1): a sleeping tree is
    woken with its whole sleep cycle; an awake one gets its full awake count back.

    A held object is welded to the cup, a static mocap body: MuJoCo's sleep rules do
    not wake a tree for an equality with a static body, nor keep it awake."""
    w = wp.tid()
    t = tree[w]
    if t < 0:
        return
    if tree_asleep[w, t] < 0:
        tree_asleep[w, t] = awake
        return
    cur = t
    for _ in range(ntree + 1):
        nxt = tree_asleep[w, cur]
        if nxt < 0 or nxt >= ntree:
            break
        tree_asleep[w, cur] = awake
        cur = nxt
        if cur == t:
            break


__all__ = ["set_ctrl", "set_mocap_xyzyaw", "track_deepest", "track_peaks", "wake_trees"]
