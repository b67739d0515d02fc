"""Where the suction cup takes an object, and where it is then let go.

A solid object is taken at the centre of its top face. A receptacle (a bowl, a
container, a free fixture) has no top face there -- its centre is air over the
floor or over what lies inside -- so it is taken on its rim: a point on the
middle of its wall, which the cup (3 cm wide) reaches from above. Of the rim
points, the oracle takes one whose cup disk keeps clear of everything that
stands as high as the rim nearby (a nested receptacle, a block inside whose top
is level with the rim): the cup's guarded descent stops at the first contact,
and the suction holds whatever it touched first. Among the clear ones it takes
the one nearest the robot's base (the arm's reach).

The cup carries the object turned by the tool's rotation, so the place point is
the target centre plus the pick offset turned by that rotation: the object ends
with its centre on the target whatever point it was held by.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from factask.geometry import Pose, wrap_angle
from factask.scene.objects import SceneObject, top_z, yaw_rotation_2d
from factask.sim.robots.suction import CUP_RADIUS
from factask.vocabulary.kinds import WALL_THICKNESS
from factask.vocabulary.world import ROBOT_BASE

#: Rim points tried around a round receptacle.
ROUND_RIM_POINTS = 16
#: Rim points tried along each wall of a rectangular one (corners included).
WALL_RIM_POINTS = 5
#: What stands within this much (m) below the rim still counts as level with it: a
#: block resting inside whose top is at the rim, a nested receptacle's rim.
LEVEL_MARGIN = 0.005
#: Gap (m) wanted between the cup's edge and anything level with the rim.
CUP_GAP = 0.003


def takes_by_rim(obj: SceneObject) -> bool:
    """Whether the cup takes ``obj`` by its rim (a free receptacle) rather than at
    its top centre."""
    return obj.spec.receptacle and not obj.fixed


def rim_points(obj: SceneObject) -> np.ndarray:
    """Candidate grasp points (k, 2) on the middle of a receptacle's walls, in its own
    frame."""
    mid = obj.half_xy - WALL_THICKNESS / 2
    if obj.spec.round:
        ang = np.linspace(0.0, 2 * math.pi, ROUND_RIM_POINTS, endpoint=False)
        return mid[0] * np.stack([np.cos(ang), np.sin(ang)], axis=1)
    t = np.linspace(-1.0, 1.0, WALL_RIM_POINTS)
    walls = [np.stack([np.full_like(t, sx * mid[0]), t * mid[1]], axis=1) for sx in (-1, 1)]
    walls += [np.stack([t * mid[0], np.full_like(t, sy * mid[1])], axis=1) for sy in (-1, 1)]
    return np.concatenate(walls)


def _distance_to_footprint(point: np.ndarray, obj: SceneObject, pose: Pose) -> float:
    """Horizontal distance (m) from ``point`` to the footprint of ``obj`` at ``pose``
    (0 inside it)."""
    local = yaw_rotation_2d(pose.yaw).T @ (point - pose.pos[:2])
    if obj.spec.round:
        return max(0.0, float(np.linalg.norm(local)) - obj.half_xy[0])
    return float(np.linalg.norm(np.maximum(np.abs(local) - obj.half_xy, 0.0)))


def grasp_offset(obj: SceneObject, pose: Pose, objects: Mapping[str, SceneObject],
                 poses: Mapping[str, Pose]) -> np.ndarray:
    """World XY offset (2,) from the object's centre to where the cup takes it: zero
    for a solid object, a rim point for a receptacle (see the module docstring)."""
    if not takes_by_rim(obj):
        return np.zeros(2)
    rim = top_z(obj, pose)
    level = [(o, poses[n]) for n, o in objects.items()
             if n != obj.name and o.collides and n in poses
             and top_z(o, poses[n]) > rim - LEVEL_MARGIN]
    centre = pose.pos[:2]
    offsets = rim_points(obj) @ yaw_rotation_2d(pose.yaw).T
    base = np.asarray(ROBOT_BASE[:2], dtype=float)

    def clearance(offset: np.ndarray) -> float:
        point = centre + offset
        return min((_distance_to_footprint(point, o, p) for o, p in level),
                   default=math.inf) - CUP_RADIUS

    gaps = np.array([clearance(d) for d in offsets])
    reach = np.linalg.norm(centre + offsets - base, axis=1)
    clear = gaps >= CUP_GAP
    if clear.any():
        return offsets[int(np.argmin(np.where(clear, reach, np.inf)))]
    return offsets[int(np.argmax(gaps))]


def pick_and_place_points(obj: SceneObject, current: Pose, target: Pose, pick_yaw: float,
                          place_yaw: float, objects: Mapping[str, SceneObject],
                          poses: Mapping[str, Pose]) -> tuple[np.ndarray, np.ndarray]:
    """The tool's pick and place (x, y, z, yaw) that move ``obj`` from ``current`` to
    ``target``: taken at its top (:func:`grasp_offset` from the centre), released
    with its top where the target puts it and the same point under the cup."""
    offset = grasp_offset(obj, current, objects, poses)
    turned = yaw_rotation_2d(wrap_angle(place_yaw - pick_yaw)) @ offset
    pick = np.array([current.pos[0] + offset[0], current.pos[1] + offset[1],
                     top_z(obj, current), pick_yaw])
    place = np.array([target.pos[0] + turned[0], target.pos[1] + turned[1],
                      target.pos[2] + obj.half[2], place_yaw])
    return pick, place
