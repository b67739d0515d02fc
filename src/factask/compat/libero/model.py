"""What a LIBERO BDDL problem says, as typed immutable values, and the printer back.

The parser (:mod:`factask.compat.libero.bddl`) builds these; what comes after it
(mapping LIBERO's scenes and goals onto factask's kinds and relations) reads them
and never the text. :func:`format_bddl` writes a problem back in LIBERO's own layout,
so that a problem read, changed and written stays a file LIBERO reads.
"""

from __future__ import annotations

import functools
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Literal

#: Predicates whose arguments are conditions, not names (kept nested, never flattened
#: except a goal's top-level ``and``).
CONNECTIVES = frozenset({"and", "or", "not"})

#: A rectangle on a region's target, ``(x0, y0, x1, y1)`` as written.
Range = tuple[float, float, float, float]
#: A yaw interval in radians, ``(low, high)`` as written.
YawRange = tuple[float, float]
#: What a name in a problem stands for.
EntityKind = Literal["object", "fixture", "region"]


@dataclass(frozen=True)
class Predicate:
    """One condition: ``(On akita_black_bowl_1 plate_1)``.

    Attributes:
        name: The predicate's name, lower-cased (``on``, ``in``, ``open``, ``turnon``;
            ``and``/``or``/``not`` for a connective).
        args: Names for an atom; nested :class:`Predicate` for a connective.
    """

    name: str
    args: tuple[str | Predicate, ...] = ()

    @property
    def is_connective(self) -> bool:
        """True for ``and``, ``or`` and ``not``, whose arguments are conditions."""
        return self.name in CONNECTIVES

    def names(self) -> Iterator[str]:
        """Every name this condition mentions, nested conditions included.

        Returns:
            The names, in order of writing.
        """
        for arg in self.args:
            if isinstance(arg, Predicate):
                yield from arg.names()
            else:
                yield arg

    def __str__(self) -> str:
        words = [_predicate_word(self.name), *(str(a) for a in self.args)]
        return f"({' '.join(words)})"


@dataclass(frozen=True)
class Region:
    """A named region of a target (the table, the floor, a fixture or an object).

    LIBERO refers to a region by its full name, ``<target>_<name>``: region
    ``top_region`` of ``wooden_cabinet_1`` is ``wooden_cabinet_1_top_region``.

    Attributes:
        name: The region's own name as written (not unique in a file: two targets may
            each have a ``top_region``).
        target: What the region lies on or in.
        ranges: Rectangles ``(x0, y0, x1, y1)`` in the target's frame, as written;
            empty for a region the target's model defines (a drawer, a basket's inside).
        yaw_rotation: Yaw intervals ``(low, high)`` in radians; empty when not given.
        attributes: Any other attribute (``rgba``, ...) by name without its colon, as
            raw text of the whole attribute list.
    """

    name: str
    target: str
    ranges: tuple[Range, ...] = ()
    yaw_rotation: tuple[YawRange, ...] = ()
    attributes: dict[str, str] = field(default_factory=dict)

    @property
    def full_name(self) -> str:
        """The name ``:init``, ``:goal`` and ``:obj_of_interest`` use:
        ``<target>_<name>``."""
        return f"{self.target}_{self.name}"


@dataclass(frozen=True)
class BddlProblem:
    """One LIBERO task file, read.

    Attributes:
        name: The problem's name (``LIBERO_Tabletop_Manipulation``).
        domain: The domain (``robosuite``), "" when not given.
        language: The instruction, its words joined by single spaces.
        regions: Every region, in file order.
        fixtures: Fixture name → type (``wooden_cabinet_1`` → ``wooden_cabinet``).
        objects: Movable object name → type (``akita_black_bowl_1`` →
            ``akita_black_bowl``).
        objects_of_interest: The names listed in ``:obj_of_interest`` (objects,
            fixtures or region full names).
        init: The initial conditions, in file order.
        goal: The goal's conditions, its top-level ``and`` flattened.
        extra: Sections the parser does not interpret, by lower-cased head
            (``:requirements``), as raw text of the whole section.
        source: The file it was read from (not compared).
    """

    name: str
    domain: str
    language: str
    regions: tuple[Region, ...]
    fixtures: dict[str, str]
    objects: dict[str, str]
    objects_of_interest: tuple[str, ...]
    init: tuple[Predicate, ...]
    goal: tuple[Predicate, ...]
    extra: dict[str, str] = field(default_factory=dict)
    source: str = field(default="<string>", compare=False)

    @functools.cached_property
    def regions_by_full_name(self) -> dict[str, Region]:
        """Every region by its full name (``wooden_cabinet_1_top_region``)."""
        return {r.full_name: r for r in self.regions}

    def kind_of(self, name: str) -> EntityKind | None:
        """What a name in a condition stands for.

        Args:
            name: A name as ``:init`` or ``:goal`` writes it.

        Returns:
            ``"object"``, ``"fixture"``, ``"region"`` (a region's full name), or None
            when the problem declares no such name.
        """
        if name in self.objects:
            return "object"
        if name in self.fixtures:
            return "fixture"
        if name in self.regions_by_full_name:
            return "region"
        return None

    def undeclared_names(self) -> tuple[str, ...]:
        """Names used in ``:init``, ``:goal`` or ``:obj_of_interest`` that are no
        declared object, fixture or region full name (each once, first use first).

        Returns:
            The names; empty for a consistent file.
        """
        used = [n for p in (*self.init, *self.goal) for n in p.names()]
        used.extend(self.objects_of_interest)
        return tuple(n for n in dict.fromkeys(used) if self.kind_of(n) is None)


def _predicate_word(name: str) -> str:
    """A predicate's name as LIBERO writes it (``On``, ``Turnon``, ``And``)."""
    return name.capitalize() if name.isascii() else name


def _number(value: float) -> str:
    """A float as Python writes it, which the reader takes back exactly."""
    return repr(float(value))


def _region_lines(region: Region) -> list[str]:
    """A region's lines, indented as LIBERO's files indent them."""
    lines = [f"      ({region.name}", f"          (:target {region.target})"]
    for key, rows in (("ranges", region.ranges), ("yaw_rotation", region.yaw_rotation)):
        if rows:
            lines.append(f"          (:{key} (")
            lines.extend(f"              ({' '.join(_number(v) for v in row)})"
                         for row in rows)
            lines += ["            )", "          )"]
    lines.extend(f"          {raw}" for raw in region.attributes.values())
    lines.append("      )")
    return lines


def _typed_lines(names: dict[str, str]) -> list[str]:
    """``a b - type`` lines, one per run of names of one type (LIBERO's grouping)."""
    runs: list[tuple[list[str], str]] = []
    for name, kind in names.items():
        if runs and runs[-1][1] == kind:
            runs[-1][0].append(name)
        else:
            runs.append(([name], kind))
    return [f"    {' '.join(run)} - {kind}" for run, kind in runs]


def format_bddl(problem: BddlProblem) -> str:
    """A problem as BDDL text in LIBERO's layout; reading it back gives an equal
    problem.

    The names, words and raw sections are written as they are: a problem built by
    hand must use words BDDL can hold (no spaces, parentheses or ``;`` in a name).

    Args:
        problem: The problem to write.

    Returns:
        The text, ending with a newline.
    """
    out = [f"(define (problem {problem.name})"]
    if problem.domain:
        out.append(f"  (:domain {problem.domain})")
    out.append(f"  (:language {problem.language})")
    out.append("    (:regions")
    for region in problem.regions:
        out.extend(_region_lines(region))
    out += ["    )", "", "  (:fixtures", *_typed_lines(problem.fixtures), "  )", ""]
    out += ["  (:objects", *_typed_lines(problem.objects), "  )", ""]
    out += ["  (:obj_of_interest", *(f"    {n}" for n in problem.objects_of_interest), "  )", ""]
    out += ["  (:init", *(f"    {p}" for p in problem.init), "  )", ""]
    out += ["  (:goal", f"    ({' '.join(['And', *(str(p) for p in problem.goal)])})", "  )", ""]
    out.extend(f"  {raw}" for raw in problem.extra.values())
    out.append(")")
    return "\n".join(out) + "\n"
