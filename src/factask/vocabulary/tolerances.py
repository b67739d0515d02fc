"""Named goal-check tolerances and their defaults (one definition, used everywhere)."""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict, Field

#: Default XY position tolerance, metres (Ravens: 1 cm).
XY_TOLERANCE = 0.01
#: Default height tolerance, metres: an object "rests" where expected within this.
Z_TOLERANCE = 0.015
#: Default yaw tolerance, degrees, applied modulo the object's symmetry (Ravens: 15).
YAW_TOLERANCE_DEG = 15.0
#: Fraction of an object's footprint that must lie inside a zone/container.
REGION_FRACTION = 1.0
#: A drawer is ``open`` from this fraction of its travel out (its joint's range) ...
DRAWER_OPEN_FRACTION = 0.9
#: ... and ``closed`` up to this fraction (a 5 % gap reads as shut).
DRAWER_CLOSED_FRACTION = 0.05
#: A switch is ``switched_on`` from this fraction of its button's travel pressed
#: down (its joint's range) ...
SWITCH_ON_FRACTION = 0.8
#: ... and ``switched_off`` up to this fraction (a button nudged 2 mm reads as up).
SWITCH_OFF_FRACTION = 0.2
#: Reward above which an episode counts as a success (the research's definition).
SUCCESS_REWARD = 0.99
#: Fraction of episodes that must succeed for a task to count as completed.
COMPLETION_FRACTION = 0.5


class Tolerances(BaseModel):
    """Tolerances of one goal check.

    Attributes:
        xy: XY distance to the target, metres.
        z: Height difference to the target, metres (support/rest check).
        yaw_deg: Yaw difference modulo the object's symmetry, degrees.
        region_fraction: For zone/container checks, the fraction of the object's
            footprint that must be inside the region.
    """

    model_config = ConfigDict(extra="forbid", frozen=True)

    xy: float = Field(XY_TOLERANCE, gt=0, le=0.5, allow_inf_nan=False)
    z: float = Field(Z_TOLERANCE, gt=0, le=0.5, allow_inf_nan=False)
    yaw_deg: float = Field(YAW_TOLERANCE_DEG, gt=0, le=180, allow_inf_nan=False)
    region_fraction: float = Field(REGION_FRACTION, gt=0, le=1, allow_inf_nan=False)
