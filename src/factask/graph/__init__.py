"""The task graph: factors over variables, their order, validation, templates.

The layer above :mod:`factask.relations` (each factor's goal is one of them), which
sits above :mod:`factask.vocabulary`. This package re-exports the whole graph model
(vocabulary, relation schemas, graph) for :mod:`factask`. Pure Python + pydantic +
networkx; never imports MuJoCo or litellm.
"""

from factask.graph.factors import SubtaskFactor
from factask.graph.taskgraph import Limits, TaskGraph, graph_problems, parse_graph
from factask.graph.templates import (
    SubtaskTemplate,
    TemplateSlot,
    compose,
    empty_graph,
    extract_fragment,
    extract_template,
    rename,
)
from factask.relations import (
    RELATION_TYPES,
    Aligned,
    AtPose,
    Circle,
    Closed,
    Inside,
    InZone,
    On,
    Open,
    Relation,
    Row,
    Stack,
    SwitchedOff,
    SwitchedOn,
    TargetPose,
)
from factask.vocabulary.errors import (
    CompositionError,
    FactaskError,
    GraphValidationError,
    InvalidValueError,
    Problem,
    SubjectError,
)
from factask.vocabulary.kinds import (
    ASSET_KINDS,
    KIND_NAMES,
    AssetKind,
    KindSpec,
    UnknownKindError,
    kind_spec,
    yaw_symmetry_deg,
)
from factask.vocabulary.names import instance_names
from factask.vocabulary.palette import COLOR_NAMES, COLORS, UnknownColorError, normalize_color, rgba
from factask.vocabulary.tolerances import Tolerances
from factask.vocabulary.variables import (
    AtFixedPose,
    InCabinet,
    InRegion,
    MountedOn,
    OnTable,
    Placement,
    StartInside,
    StartOn,
    StateVariable,
)

__all__ = [
    "ASSET_KINDS",
    "COLORS",
    "COLOR_NAMES",
    "KIND_NAMES",
    "RELATION_TYPES",
    "Aligned",
    "AssetKind",
    "AtFixedPose",
    "AtPose",
    "Circle",
    "Closed",
    "CompositionError",
    "FactaskError",
    "GraphValidationError",
    "InCabinet",
    "InRegion",
    "InZone",
    "Inside",
    "InvalidValueError",
    "KindSpec",
    "Limits",
    "MountedOn",
    "On",
    "OnTable",
    "Open",
    "Placement",
    "Problem",
    "Relation",
    "Row",
    "Stack",
    "StartInside",
    "StartOn",
    "StateVariable",
    "SubjectError",
    "SubtaskFactor",
    "SubtaskTemplate",
    "SwitchedOff",
    "SwitchedOn",
    "TargetPose",
    "TaskGraph",
    "TemplateSlot",
    "Tolerances",
    "UnknownColorError",
    "UnknownKindError",
    "compose",
    "empty_graph",
    "extract_fragment",
    "extract_template",
    "graph_problems",
    "instance_names",
    "kind_spec",
    "normalize_color",
    "parse_graph",
    "rename",
    "rgba",
    "yaw_symmetry_deg",
]
