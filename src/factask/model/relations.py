"""Goal relations: what must hold in the scene for a subtask factor to be satisfied.

A relation names the variables it *moves* (``objects``) and the variables it is
*anchored* to (a support, a zone, a reference). The library turns every relation
into concrete target poses at reset (relation solving), so nobody — least of all
an LLM — computes target coordinates by hand. Each relation type's docstring is
shown to LLMs verbatim in the prompts: keep it exact and short.
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field

from factask.model.names import Name
from factask.model.tolerances import Tolerances

#: Target coordinates are bounded (metres): far beyond any table, never overflowing.
COORDINATE_LIMIT = 10.0
Coordinate = Annotated[float, Field(ge=-COORDINATE_LIMIT, le=COORDINATE_LIMIT,
                                    allow_inf_nan=False)]
#: Yaw in degrees (any finite turn up to two full turns either way).
Angle = Annotated[float, Field(ge=-720.0, le=720.0, allow_inf_nan=False)]


class _Relation(BaseModel):
    model_config = ConfigDict(extra="forbid")

    objects: list[Name] = Field(
        min_length=1, description="Variables this goal moves (all instances of each)."
    )
    tolerances: Tolerances = Field(default_factory=Tolerances)

    def anchors(self) -> list[str]:
        """Variables the goal is relative to (never moved by this goal)."""
        return []

    def variable_names(self) -> list[str]:
        """Every variable the relation mentions: objects first, then anchors."""
        seen: dict[str, None] = dict.fromkeys(self.objects)
        seen.update(dict.fromkeys(self.anchors()))
        return list(seen)


class TargetPose(BaseModel):
    """A target pose on the table: position (metres) and yaw (degrees).

    ``z`` is the height of the object's centre; leave it out to mean "resting on
    whatever is below" (the table or a support).
    """

    model_config = ConfigDict(extra="forbid")

    x: Coordinate
    y: Coordinate
    z: Coordinate | None = None
    yaw_deg: Angle = 0.0


class AtPose(_Relation):
    """Put the objects at explicit target poses. ``poses`` are in world coordinates,
    or in the frame of variable ``frame`` if given. ``matches[i][j] = 1`` lets object
    instance i go to pose j (default: any object to any pose); each object needs its
    own pose. ``check_yaw`` false ignores rotation."""

    type: Literal["at_pose"] = "at_pose"
    poses: list[TargetPose] = Field(min_length=1)
    matches: list[list[Annotated[int, Field(ge=0, le=1)]]] | None = None
    frame: Name | None = None
    check_yaw: bool = True

    def anchors(self) -> list[str]:
        return [self.frame] if self.frame else []


class InZone(_Relation):
    """Put every object inside the footprint of the region variable ``zone``
    (a zone, pallet, kit, stand, line, bowl, container or fixture)."""

    type: Literal["in_zone"] = "in_zone"
    zone: Name

    def anchors(self) -> list[str]:
        return [self.zone]


class On(_Relation):
    """Put the objects resting on top of ``support`` (side by side if several).
    If ``support`` has several instances the objects rest centred on the group,
    aligned with it (e.g. a bar bridging two pillars)."""

    type: Literal["on"] = "on"
    support: Name

    def anchors(self) -> list[str]:
        return [self.support]


class Inside(_Relation):
    """Put the objects inside the receptacle ``container`` (a container, bowl or
    fixture): within its inner walls, below its rim."""

    type: Literal["inside"] = "inside"
    container: Name

    def anchors(self) -> list[str]:
        return [self.container]


class Stack(_Relation):
    """Stack the objects into one column, first object at the bottom. The column
    stands on ``base`` if given, else on a free spot of the table. With ``ordered``
    false any order of the objects counts."""

    type: Literal["stack"] = "stack"
    base: Name | None = None
    ordered: bool = True

    def anchors(self) -> list[str]:
        return [self.base] if self.base else []


class Row(_Relation):
    """Place the objects side by side in a straight row, centre-to-centre
    ``spacing`` metres apart (default: widest object + 1 cm). ``along``: lie on
    that line/zone variable. ``on``: rest on top of the row of variable ``on``
    (same count: one on each; one fewer: each bridging two neighbours, as in a
    pyramid)."""

    type: Literal["row"] = "row"
    spacing: Annotated[float, Field(gt=0, le=0.5, allow_inf_nan=False)] | None = None
    along: Name | None = None
    on: Name | None = None
    ordered: bool = True

    def anchors(self) -> list[str]:
        return [n for n in (self.along, self.on) if n]


class Circle(_Relation):
    """Arrange the objects evenly on a circle of ``radius`` metres (default: just
    wide enough), around variable ``center`` if given, else around a free spot."""

    type: Literal["circle"] = "circle"
    radius: Annotated[float, Field(gt=0, le=0.4, allow_inf_nan=False)] | None = None
    center: Name | None = None

    def anchors(self) -> list[str]:
        return [self.center] if self.center else []


class Aligned(_Relation):
    """Align each object with the ``reference`` variable: ``center`` puts it at the
    reference's position and yaw (an ell into its fixture, a block onto a marker);
    ``corner`` puts the object's corner into the reference corner marker."""

    type: Literal["aligned"] = "aligned"
    reference: Name
    mode: Literal["center", "corner"] = "center"

    def anchors(self) -> list[str]:
        return [self.reference]


Relation = Annotated[
    AtPose | InZone | On | Inside | Stack | Row | Circle | Aligned,
    Field(discriminator="type"),
]

#: Relation type name -> class.
RELATION_TYPES: dict[str, type[_Relation]] = {
    cls.model_fields["type"].default: cls
    for cls in (AtPose, InZone, On, Inside, Stack, Row, Circle, Aligned)
}

#: Which anchor field of each relation must have which capability of its kind
#: (see :class:`factask.model.kinds.KindSpec`): used by validation and prompts.
ANCHOR_CAPABILITY: dict[tuple[str, str], tuple[str, ...]] = {
    ("in_zone", "zone"): ("region",),
    ("on", "support"): ("support", "receptacle"),
    ("inside", "container"): ("receptacle",),
    ("stack", "base"): ("support", "region"),
    ("row", "along"): ("region",),
    ("row", "on"): ("support",),
    ("circle", "center"): ("region", "support", "receptacle"),
}
