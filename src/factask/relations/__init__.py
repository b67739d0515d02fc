"""Goal relations: what must hold in the scene for a subtask factor to be satisfied.

A relation names the variables it *moves* (``objects``) and the variables it is
*anchored* to (a support, a zone, a reference). Each kind is one unit, one module
of this package (see :mod:`factask.relations.base`): its schema, how it is solved
into concrete target slots at reset (so nobody — least of all an LLM — computes
target coordinates by hand), and how it is checked.

To add a kind: write ``factask/relations/<kind>.py`` with one
:class:`~factask.relations.base.RelationBase` subclass, and add the class to
:data:`_UNITS` below. The graph model, validation, templates, the solver, the
checks, the oracle, the prompts and the JSON Schema all read :data:`RELATION_TYPES`.
"""

from __future__ import annotations

from typing import Annotated, Union

from pydantic import Field

from factask.relations.aligned import Aligned
from factask.relations.at_pose import AtPose, TargetPose
from factask.relations.base import RelationBase
from factask.relations.circle import Circle
from factask.relations.closed import Closed
from factask.relations.in_zone import InZone
from factask.relations.inside import Inside
from factask.relations.on import On
from factask.relations.open import Open
from factask.relations.pile_in_zone import PileInZone
from factask.relations.rope import RopeAlong
from factask.relations.row import Row
from factask.relations.stack import Stack
from factask.relations.switched_off import SwitchedOff
from factask.relations.switched_on import SwitchedOn

#: Every relation unit, in the order the schema and the prompts list them.
_UNITS: tuple[type[RelationBase], ...] = (AtPose, InZone, On, Inside, Stack, Row, Circle,
                                         Aligned, PileInZone, RopeAlong, Open, Closed,
                                         SwitchedOn, SwitchedOff)

#: The registry: relation kind (its ``type``) -> its class.
RELATION_TYPES: dict[str, type[RelationBase]] = {cls.kind(): cls for cls in _UNITS}

#: Any relation, discriminated on ``type`` (what a factor's ``goal`` holds).
Relation = Annotated[Union[_UNITS], Field(discriminator="type")]  # noqa: UP007

#: Which anchor field of each relation must have which capability of its kind
#: (see :class:`factask.vocabulary.kinds.KindSpec`), for the prompts.
ANCHOR_CAPABILITY: dict[tuple[str, str], tuple[str, ...]] = {
    (kind, field): caps for kind, cls in RELATION_TYPES.items()
    for field, caps in cls.anchor_fields.items() if caps
}

#: Every field, in any relation, that names a variable as an anchor (renaming and
#: templates rewrite these).
ANCHOR_FIELDS: tuple[str, ...] = tuple(dict.fromkeys(
    field for cls in _UNITS for field in cls.anchor_fields))

__all__ = ["ANCHOR_CAPABILITY", "ANCHOR_FIELDS", "RELATION_TYPES", "Aligned", "AtPose",
           "Circle", "Closed", "InZone", "Inside", "On", "Open", "PileInZone", "Relation",
           "RelationBase", "RopeAlong", "Row", "Stack", "SwitchedOff", "SwitchedOn",
           "TargetPose"]
