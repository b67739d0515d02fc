"""``inside``: objects within a receptacle's inner walls, below its rim."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, ClassVar, Literal

from factask.relations.region import RegionRelation
from factask.vocabulary.names import Name


class Inside(RegionRelation):
    """Put the objects inside the receptacle ``container`` (a container, bowl or
    fixture): within its inner walls, below its rim."""

    anchor_fields: ClassVar[Mapping[str, tuple[str, ...]]] = {"container": ("receptacle",)}
    met_by_starting_in: ClassVar[str | None] = "container"
    region_field: ClassVar[str] = "container"
    between_floor_and_rim: ClassVar[bool] = True

    type: Literal["inside"] = "inside"
    container: Name

    @classmethod
    def example(cls) -> tuple[list[dict[str, Any]], Inside]:
        return ([{"name": "ball", "kind": "ball", "color": "red"},
                 {"name": "box", "kind": "container", "size": [0.15, 0.15, 0.06]}],
                cls(objects=["ball"], container="box"))
