"""Stand-in for ``pybullet`` while a task file is loaded.

Pure pose maths (``getQuaternionFromEuler``, ``multiplyTransforms``,
``getQuaternionFromAxisAngle``, ``getAxisAngleFromQuaternion``,
``getDifferenceQuaternion``, ``getQuaternionSlerp``, ``rotateVector``, ...) is
computed; calls about recorded objects (``getBasePositionAndOrientation``,
``resetBasePositionAndOrientation``, ``changeVisualShape``) read or update the
recording; bodies built from shapes and the constraints between them
(``createCollisionShape``, ``createVisualShape``, ``createMultiBody``,
``createConstraint``, ``changeConstraint``, ``removeConstraint``) are recorded
(:mod:`factask.compat.cliport.bodies`: a chain of them becomes a rope);
``stepSimulation`` does nothing (nothing moves during a reset); calls that tune
PyBullet's physics or debug drawing (:data:`IGNORED_CALLS`: ``changeDynamics``,
``setGravity``, ...) are accepted with a warning. Anything else raises
:class:`~factask.compat.cliport.errors.Unsupported` naming the call.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from factask.compat.cliport import bodies, transforms
from factask.compat.cliport.errors import PoseError, Unsupported
from factask.compat.cliport.recorder import active_session, color_name

# Constants task code passes around (values as in PyBullet).
GEOM_SPHERE, GEOM_BOX, GEOM_CYLINDER, GEOM_MESH, GEOM_PLANE, GEOM_CAPSULE = 2, 3, 4, 5, 6, 7
JOINT_REVOLUTE, JOINT_PRISMATIC, JOINT_SPHERICAL = 0, 1, 2
JOINT_PLANAR, JOINT_FIXED, JOINT_POINT2POINT, JOINT_GEAR = 3, 4, 5, 6
DIRECT, GUI = 2, 1


def _xyzw(rot: Rotation) -> tuple[float, ...]:
    return tuple(float(c) for c in rot.as_quat())


def getQuaternionFromEuler(euler: Any) -> tuple[float, ...]:
    """Quaternion xyzw of roll, pitch, yaw (PyBullet: fixed axes x, y, z)."""
    return _xyzw(Rotation.from_euler("xyz", list(euler)))


def getEulerFromQuaternion(quat: Any) -> tuple[float, ...]:
    """Roll, pitch, yaw of a quaternion xyzw."""
    return tuple(float(c) for c in transforms.rotation(quat).as_euler("xyz"))


def getMatrixFromQuaternion(quat: Any) -> tuple[float, ...]:
    """Row-major 3x3 rotation matrix, flat."""
    return transforms.matrix(quat)


def multiplyTransforms(pos0: Any, quat0: Any, pos1: Any, quat1: Any
                       ) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """(pos0, quat0) * (pos1, quat1)."""
    return transforms.multiply((pos0, quat0), (pos1, quat1))


def invertTransform(pos: Any, quat: Any) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """Inverse of (pos, quat)."""
    return transforms.invert((pos, quat))


def getQuaternionFromAxisAngle(axis: Any, angle: float) -> tuple[float, ...]:
    """Quaternion xyzw of a turn by ``angle`` (radians) about ``axis``.

    Raises:
        PoseError: a zero axis (no direction to turn about; a ValueError).
    """
    a = np.asarray(axis, dtype=float).reshape(3)
    norm = float(np.linalg.norm(a))
    if norm == 0.0:
        raise PoseError("getQuaternionFromAxisAngle: the axis is zero")
    return _xyzw(Rotation.from_rotvec(a / norm * float(angle)))


def getAxisAngleFromQuaternion(quat: Any) -> tuple[tuple[float, ...], float]:
    """(unit axis, angle in [0, pi]) of a quaternion xyzw; axis (1, 0, 0) for no turn."""
    rotvec = transforms.rotation(quat).as_rotvec()
    angle = float(np.linalg.norm(rotvec))
    axis = rotvec / angle if angle > 1e-12 else np.array([1.0, 0.0, 0.0])
    return tuple(float(c) for c in axis), angle


def getDifferenceQuaternion(quat_start: Any, quat_end: Any) -> tuple[float, ...]:
    """The turn that takes ``quat_start`` to ``quat_end`` (end * start^-1, world frame)."""
    return _xyzw(transforms.rotation(quat_end) * transforms.rotation(quat_start).inv())


def getQuaternionSlerp(quat_start: Any, quat_end: Any, fraction: float) -> tuple[float, ...]:
    """Spherical interpolation from ``quat_start`` (0) to ``quat_end`` (1)."""
    start = transforms.rotation(quat_start)
    delta = (transforms.rotation(quat_end) * start.inv()).as_rotvec()  # the shorter way
    return _xyzw(Rotation.from_rotvec(delta * float(fraction)) * start)


def rotateVector(quat: Any, vector: Any) -> tuple[float, ...]:
    """``vector`` turned by the quaternion xyzw."""
    out = transforms.rotation(quat).apply(np.asarray(vector, dtype=float).reshape(3))
    return tuple(float(c) for c in out)


def getBasePositionAndOrientation(obj_id: int, *args: Any, **kwargs: Any
                                  ) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """The recorded pose of an object (nothing has moved during a reset)."""
    o = active_session().obj(obj_id)
    return tuple(map(float, o.pos)), tuple(map(float, o.quat))


def resetBasePositionAndOrientation(obj_id: int, pos: Any, quat: Any,
                                    *args: Any, **kwargs: Any) -> None:
    """Move a recorded object (its start pose becomes this one)."""
    o = active_session().obj(obj_id)
    o.pos, o.quat = transforms.split_pose((pos, quat))


def changeVisualShape(obj_id: int, link: int = -1, *args: Any,
                      rgbaColor: Any = None, **kwargs: Any) -> None:
    """Recolour a recorded object (other visual changes are ignored)."""
    s = active_session()
    o = s.obj(obj_id)
    if rgbaColor is not None:
        o.color = color_name(rgbaColor, s)
    if kwargs.get("textureUniqueId") is not None:
        s.warn("p.changeVisualShape(textureUniqueId=...) ignored: factask has no textures")


def getVisualShapeData(obj_id: int, *args: Any, **kwargs: Any
                       ) -> list[tuple[Any, ...]]:
    """One visual-shape entry of the recorded object: (id, link, geom, dimensions, ...)."""
    o = active_session().obj(obj_id)
    rgba = (0.5, 0.5, 0.5, 1.0)
    return [(o.obj_id, -1, GEOM_BOX, tuple(o.size), b"", (0.0, 0.0, 0.0),
             (0.0, 0.0, 0.0, 1.0), rgba)]


def getAABB(obj_id: int, *args: Any, **kwargs: Any
            ) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """World axis-aligned box around the recorded object's box, rotated by its pose.

    The box's half extents are turned by the object's orientation (|R| times the
    half extents: the box around its eight rotated corners), so a 0.1 x 0.02 bar
    yawed 90 degrees spans 0.02 along x.
    """
    o = active_session().obj(obj_id)
    rot = np.abs(transforms.rotation(o.quat).as_matrix())
    half = rot @ (np.asarray(o.size, dtype=float) / 2)
    return tuple(map(float, o.pos - half)), tuple(map(float, o.pos + half))


def createCollisionShape(shapeType: int, radius: float = bodies.DEFAULT_RADIUS,
                         halfExtents: Any = bodies.DEFAULT_HALF_EXTENTS,
                         height: float = bodies.DEFAULT_HEIGHT, *args: Any,
                         **kwargs: Any) -> int:
    """Record a collision shape (box, sphere, cylinder, capsule); returns its id."""
    return bodies.add_shape(active_session(), shapeType, radius, halfExtents, height)


def createVisualShape(shapeType: int, radius: float = bodies.DEFAULT_RADIUS,
                      halfExtents: Any = bodies.DEFAULT_HALF_EXTENTS,
                      length: float = bodies.DEFAULT_HEIGHT, *args: Any,
                      rgbaColor: Any = None, **kwargs: Any) -> int:
    """Record a visual shape (its colour colours the body); returns its id."""
    return bodies.add_shape(active_session(), shapeType, radius, halfExtents, length,
                            rgbaColor)


def createMultiBody(baseMass: float = 0.0, baseCollisionShapeIndex: int = -1,
                    baseVisualShapeIndex: int = -1, basePosition: Any = (0.0, 0.0, 0.0),
                    baseOrientation: Any = (0.0, 0.0, 0.0, 1.0), *args: Any,
                    **kwargs: Any) -> int:
    """Record a one-link body made of recorded shapes; returns its object id.

    Raises:
        Unsupported: a body with links (``linkMasses`` ...) or batch positions.
    """
    if kwargs.get("linkMasses") or kwargs.get("batchPositions") or len(args) > 2:
        raise Unsupported("pybullet.createMultiBody with links or batch positions: only "
                          "single bodies made of one shape are supported")
    return bodies.add_multibody(active_session(), baseMass, baseCollisionShapeIndex,
                                baseVisualShapeIndex, basePosition, baseOrientation)


def createConstraint(parentBodyUniqueId: int, parentLinkIndex: int = -1,
                     childBodyUniqueId: int = -1, childLinkIndex: int = -1,
                     jointType: int = JOINT_FIXED, jointAxis: Any = (0.0, 0.0, 0.0),
                     parentFramePosition: Any = (0.0, 0.0, 0.0),
                     childFramePosition: Any = (0.0, 0.0, 0.0), *args: Any,
                     **kwargs: Any) -> int:
    """Record a constraint between two bodies; returns its id."""
    return bodies.add_constraint(active_session(), parentBodyUniqueId, parentLinkIndex,
                                 childBodyUniqueId, childLinkIndex, jointType,
                                 parentFramePosition, childFramePosition)


def changeConstraint(constraint_id: int, *args: Any, **kwargs: Any) -> None:
    """Accepted and ignored (a rope's links in factask have their own strength)."""
    if int(constraint_id) not in active_session().constraints:
        raise Unsupported(f"pybullet.changeConstraint: no constraint {constraint_id!r}")


def removeConstraint(constraint_id: int, *args: Any, **kwargs: Any) -> None:
    """Forget a recorded constraint."""
    active_session().constraints.pop(int(constraint_id), None)


def stepSimulation(*args: Any, **kwargs: Any) -> None:
    """No-op: nothing is simulated while recording."""


#: Calls that tune PyBullet's own physics or debug drawing: factask has its own
#: (each kind's mass and friction, standard gravity, a fixed timestep), so they
#: are accepted with a warning naming what takes their place.
IGNORED_CALLS: dict[str, str] = {
    "changeDynamics": "factask gives each kind its own mass and friction",
    "setGravity": "factask's world has standard gravity",
    "setTimeStep": "factask's physics has its own fixed timestep",
    "setRealTimeSimulation": "factask's physics has its own fixed timestep",
    "setPhysicsEngineParameter": "factask's physics has its own solver settings",
    "configureDebugVisualizer": "nothing is drawn while a task is recorded",
    "resetDebugVisualizerCamera": "nothing is drawn while a task is recorded",
    "addUserDebugLine": "nothing is drawn while a task is recorded",
    "addUserDebugText": "nothing is drawn while a task is recorded",
    "removeUserDebugItem": "nothing is drawn while a task is recorded",
    "removeAllUserDebugItems": "nothing is drawn while a task is recorded",
}


def _ignored(name: str) -> Any:
    def call(*args: Any, **kwargs: Any) -> int:
        active_session().warn(f"p.{name}(...) ignored: {IGNORED_CALLS[name]}")
        return 0  # what PyBullet returns for a debug item id; other calls return None
    call.__name__ = name
    return call


def getNumBodies(*args: Any, **kwargs: Any) -> int:
    """How many objects the task has added so far."""
    return len(active_session().objects)


def getNumJoints(obj_id: int, *args: Any, **kwargs: Any) -> int:
    """0: every recorded object is a single rigid body."""
    active_session().obj(obj_id)
    return 0


def __getattr__(name: str) -> Any:
    if name.startswith("__"):
        raise AttributeError(name)
    if name in IGNORED_CALLS:
        return _ignored(name)
    raise Unsupported(f"pybullet.{name} is not supported by factask's CLIPort layer "
                      "(only pose maths and recorded-object poses/colours are)")
