"""Subtask factors: one checkable goal each, over a scope of variables."""

from __future__ import annotations

from typing import Annotated

from pydantic import BaseModel, ConfigDict, Field, model_validator

from factask.relations import Relation
from factask.vocabulary.limits import MAX_REFERENCES, Text
from factask.vocabulary.names import Name


class SubtaskFactor(BaseModel):
    """One subtask: a goal relation over a scope of variables.

    Attributes:
        name: snake_case identifier, unique in the graph.
        description: The language goal ("put the red block in the green zone").
        goal: The goal relation (discriminated on its ``type``).
        scope: Variables the factor touches; defaults to those its goal names.
        weight: Share of the task's reward; a graph's weights sum to 1.
        after: Factors that must be done before this one (explicit order).
        milestone: False (default): the goal must hold at the end of the episode and
            is re-checked every step. True: the goal counts once achieved, in order
            (when every factor before it has been reached), and keeps its progress
            even if a later factor moves its objects again (see
            :mod:`factask.graph.order`).
        initial_setup: What must already hold before the subtask runs (language).
        template: Name of the subtask template it came from, if any (provenance).
    """

    model_config = ConfigDict(extra="forbid")

    name: Name
    description: Text = ""
    goal: Relation
    scope: Annotated[list[Name], Field(max_length=MAX_REFERENCES)] | None = None
    weight: Annotated[float, Field(gt=0, le=1, allow_inf_nan=False)] = 1.0
    after: list[Name] = Field(default_factory=list, max_length=MAX_REFERENCES)
    milestone: bool = False
    initial_setup: Text = ""
    template: Name | None = None

    @model_validator(mode="after")
    def _default_scope(self) -> SubtaskFactor:
        if self.scope is None:
            self.scope = self.goal.variable_names()
        return self

    @property
    def scope_names(self) -> list[str]:
        """The scope (never None after validation)."""
        return list(self.scope or [])

    def moved(self) -> list[str]:
        """Variables this factor moves."""
        return list(self.goal.objects)

    def anchors(self) -> list[str]:
        """Variables this factor's goal is relative to."""
        return self.goal.anchors()
