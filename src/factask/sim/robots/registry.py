"""The robot registry: every robot a scene can carry, in one table (pure data).

Compile, the env, the CLI (``--robot``), the docs and the tests all read
:data:`ROBOTS`. Each entry is named after what it models; ``"arm"`` is the
documented default arm (an alias of ``"ur10e"``) and ``"arm_ur5e"`` an alias of
``"ur5e"``, kept so existing code and commands keep working.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from factask.vocabulary.errors import FactaskError


class RobotError(FactaskError):
    """A robot cannot be built or bound (unknown kind, missing element in a model)."""


@dataclass(frozen=True)
class DHArm:
    """Standard DH parameters of a 6-DoF UR-type arm (metres, radians).

    Attributes:
        name: Label used in docs and reports.
        d: Link offsets d1..d6.
        a: Link lengths a1..a6.
        alpha: Link twists alpha1..alpha6.
        radii: Capsule radius of each of the 6 links.
        max_speed: Joint speed limits (rad/s), base to wrist: the datasheet's.
        max_accel: Joint acceleration limits (rad/s^2) of planned motions.
    """

    name: str
    d: tuple[float, ...]
    a: tuple[float, ...]
    alpha: tuple[float, ...]
    radii: tuple[float, ...]
    max_speed: tuple[float, ...] = (math.pi,) * 6
    max_accel: tuple[float, ...] = (12.0,) * 6


_HALF_PI = math.pi / 2
#: Datasheet joint speeds: 180 deg/s; the UR10e's base and shoulder 120 deg/s.
_DEG180 = math.pi
_DEG120 = 2 * math.pi / 3

#: UR5e, from Universal Robots' published DH table.
UR5E = DHArm(
    name="ur5e",
    d=(0.1625, 0.0, 0.0, 0.1333, 0.0997, 0.0996),
    a=(0.0, -0.425, -0.3922, 0.0, 0.0, 0.0),
    alpha=(_HALF_PI, 0.0, 0.0, _HALF_PI, -_HALF_PI, 0.0),
    radii=(0.06, 0.054, 0.045, 0.04, 0.04, 0.035),
)

#: UR10e, from Universal Robots' published DH table (the arm that reaches the whole
#: Ravens workspace top-down from the origin; see docs/robot.md).
UR10E = DHArm(
    name="ur10e",
    d=(0.1807, 0.0, 0.0, 0.17415, 0.11985, 0.11655),
    a=(0.0, -0.6127, -0.57155, 0.0, 0.0, 0.0),
    alpha=(_HALF_PI, 0.0, 0.0, _HALF_PI, -_HALF_PI, 0.0),
    radii=(0.075, 0.065, 0.055, 0.045, 0.045, 0.04),
    max_speed=(_DEG120, _DEG120, _DEG180, _DEG180, _DEG180, _DEG180),
)


@dataclass(frozen=True)
class RobotEntry:
    """One registered robot.

    Attributes:
        name: Registry name (``--robot`` value).
        models: What it models, in words.
        arm: DH parameters of the arm it builds, or None for the floating cup.
    """

    name: str
    models: str
    arm: DHArm | None = None


#: Every robot, by name.
ROBOTS: dict[str, RobotEntry] = {
    entry.name: entry for entry in (
        RobotEntry("floating", "a mocap-driven floating suction cup, no arm (the fast mode)"),
        RobotEntry("ur10e", "a 6-DoF arm with UR10e kinematics and a suction cup", UR10E),
        RobotEntry("ur5e", "a 6-DoF arm with UR5e kinematics and a suction cup", UR5E),
    )
}
#: Other accepted names: alias -> registry name.
ALIASES: dict[str, str] = {"arm": "ur10e", "arm_ur5e": "ur5e"}
#: The arm the ``"arm"`` alias builds.
DEFAULT_ARM: DHArm = UR10E
#: Every name a ``robot=`` argument accepts.
ROBOT_NAMES: tuple[str, ...] = (*ROBOTS, *ALIASES)


def robot_entry(name: str) -> RobotEntry:
    """The registry entry of ``name`` (a registry name or an alias).

    Raises:
        RobotError: no robot of that name (lists the names there are).
    """
    entry = ROBOTS.get(ALIASES.get(name, name))
    if entry is None:
        raise RobotError(f"unknown robot {name!r} (fix: use one of {', '.join(ROBOT_NAMES)})")
    return entry


def describe_robots() -> str:
    """One line per accepted name, for help texts."""
    lines = [f"{e.name}: {e.models}" for e in ROBOTS.values()]
    lines += [f"{alias}: same as {target}" for alias, target in ALIASES.items()]
    return "; ".join(lines)
