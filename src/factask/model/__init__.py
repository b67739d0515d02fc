"""The graph model: variables, factors, relations, task graphs, templates.

Pure Python + pydantic + networkx; never imports MuJoCo or litellm.
"""

from factask.model.errors import (
    CompositionError,
    FactaskError,
    GraphValidationError,
    InvalidValueError,
    Problem,
    SubjectError,
)
from factask.model.factors import SubtaskFactor
from factask.model.graph import Limits, TaskGraph, graph_problems, parse_graph
from factask.model.kinds import (
    ASSET_KINDS,
    KIND_NAMES,
    AssetKind,
    KindSpec,
    UnknownKindError,
    kind_spec,
    yaw_symmetry_deg,
)
from factask.model.names import instance_names
from factask.model.palette import COLOR_NAMES, COLORS, UnknownColorError, normalize_color, rgba
from factask.model.templates import (
    SubtaskTemplate,
    TemplateSlot,
    compose,
    empty_graph,
    extract_fragment,
    extract_template,
    rename,
)
from factask.model.tolerances import Tolerances
from factask.model.variables import (
    AtFixedPose,
    InRegion,
    OnTable,
    Placement,
    StartInside,
    StartOn,
    StateVariable,
)
from factask.relations import (
    RELATION_TYPES,
    Aligned,
    AtPose,
    Circle,
    Inside,
    InZone,
    On,
    Relation,
    Row,
    Stack,
    TargetPose,
)

__all__ = [
    "ASSET_KINDS", "COLORS", "COLOR_NAMES", "KIND_NAMES", "RELATION_TYPES",
    "Aligned", "AssetKind", "AtFixedPose", "AtPose", "Circle", "CompositionError",
    "FactaskError", "GraphValidationError", "InRegion", "InZone", "Inside",
    "InvalidValueError", "KindSpec",
    "Limits", "On", "OnTable", "Placement", "Problem", "Relation", "Row", "Stack",
    "StartInside", "StartOn", "StateVariable", "SubjectError", "SubtaskFactor", "SubtaskTemplate",
    "TargetPose", "TaskGraph", "TemplateSlot", "Tolerances", "UnknownColorError",
    "UnknownKindError", "compose", "empty_graph", "extract_fragment", "extract_template",
    "graph_problems", "instance_names", "kind_spec", "normalize_color", "parse_graph",
    "rename", "rgba", "yaw_symmetry_deg",
]
