"""``in_zone``: objects inside the footprint of a region variable."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, ClassVar, Literal

from factask.model.names import Name
from factask.relations.region import RegionRelation


class InZone(RegionRelation):
    """Put every object inside the footprint of the region variable ``zone``
    (a zone, pallet, kit, stand, line, bowl, container or fixture)."""

    anchor_fields: ClassVar[Mapping[str, tuple[str, ...]]] = {"zone": ("region",)}
    region_field: ClassVar[str] = "zone"

    type: Literal["in_zone"] = "in_zone"
    zone: Name

    @classmethod
    def example(cls) -> tuple[list[dict[str, Any]], InZone]:
        return ([{"name": "blocks", "kind": "block", "count": 2},
                 {"name": "green_zone", "kind": "zone", "color": "green"}],
                cls(objects=["blocks"], zone="green_zone"))
