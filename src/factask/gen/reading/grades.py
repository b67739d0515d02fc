"""Sizes that tell alike objects apart: "the small ball in the small bowl, the large
ball in the large bowl".

Read as one group, "the small ball" and "the large ball" are one ball, and every goal
the words give the two lands on it. Where the words give one kind (of one colour, or
of none) two or more contrasting **grades** -- small / large, short / tall, short /
long -- the group becomes one object per grade (:func:`grade_members`), each of the
kind's default size scaled by its grade (:data:`SCALES`: small three quarters, large
one and a half, tall twice as high, short half as high, long twice as long), so the
scene has the sizes the words contrast and the goals can tell the objects apart.

A grade word that contrasts with nothing ("the long bar across the two cylinders")
splits nothing: the kind's default is one size, and the accounting judges the word.
A grade may stand for its object alone: "two grey boxes, a small one and a large
one" (:func:`factask.gen.reading.words.resolve_ones` reads "one" after a grade as
the kind last named). "The other box", after "the small box" in the same sentence,
is the graded one not named before it (:func:`pick_graded`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from typing import Protocol

from factask.gen.reading.selectors import Mention as SelectorMention
from factask.gen.reading.words import GRADE_WORDS, kind_of, plural_of, resolve_ones, words_of
from factask.vocabulary.kinds import kind_spec
from factask.vocabulary.palette import COLOR_NAMES

#: Grade -> the scale of the kind's default size (x, y, z). "short" against "long" is
#: along x, not z: see :func:`_scale`.
SCALES: dict[str, tuple[float, float, float]] = {
    "small": (0.75, 0.75, 0.75), "large": (1.5, 1.5, 1.5), "tall": (1.0, 1.0, 2.0),
    "short": (1.0, 1.0, 0.5), "long": (2.0, 1.0, 1.0), "medium": (1.0, 1.0, 1.0)}
#: Superlatives that may stand for their object alone: "from the largest at the bottom
#: to the smallest on top".
SUPERLATIVES = frozenset({"smallest", "largest", "biggest", "tallest", "shortest",
                          "longest"})
#: The grades at the two ends of a series, by the grade of either end.
_ENDS = {"small": ("small", "large"), "large": ("small", "large"),
         "short": ("short", "tall"), "tall": ("short", "tall")}
#: Most graded members one group becomes.
MAX_GRADES = 3


class Mention(SelectorMention, Protocol):
    """What this module reads of a :class:`factask.gen.reading.mentions.Mention`."""

    @property
    def grade(self) -> str | None: ...


def grade_before(words: list[str], i: int) -> str | None:
    """The grade of the phrase whose kind word is ``words[i]``: a size word right
    before it or before its colours ("the big red cube", "a small one"); None: none."""
    j = i - 1
    while j >= 0 and i - j <= 4:
        if words[j] in GRADE_WORDS:
            return GRADE_WORDS[words[j]]
        if words[j] not in COLOR_NAMES and words[j] not in ("and", "or"):
            return None
        j -= 1
    return None


def _graded_phrases(words: list[str]) -> dict[tuple[str, str | None], list[str]]:
    """(kind, colour or None) -> the grades the words give it, first named first."""
    out: dict[tuple[str, str | None], list[str]] = {}
    for i, w in enumerate(words):
        kind = kind_of(w)[0]
        grade = grade_before(words, i) if kind is not None else None
        if kind is None or grade is None:
            continue
        colour = next((words[j] for j in range(i - 1, max(i - 4, -1), -1)
                       if words[j] in COLOR_NAMES), None)
        grades = out.setdefault((kind, colour), [])
        if grade not in grades:
            grades.append(grade)
    return out


def _scale(grade: str, grades: Sequence[str]) -> tuple[float, float, float]:
    if grade == "short" and "long" in grades:
        return (0.5, 1.0, 1.0)
    return SCALES[grade]


def grade_members(text: str, found: Sequence[Mention], most: int) -> list[Mention]:
    """``found`` with each group the words grade in contrasting sizes split by grade.

    Args:
        text: The proposal's description.
        found: Its mentions (frozen dataclasses with a ``grade`` field).
        most: The most mentions in all (a group is left whole past it).

    Returns:
        The mentions, a graded group replaced in place by one mention per grade (name
        ``small_ball``, ``grade`` set, ``size`` the kind's default scaled), its count
        shared evenly where the words count more than one of each, else one each.
    """
    words = _superlatives_spelled(resolve_ones(words_of(text))[0])
    phrases = _graded_phrases(words)
    out: list[Mention] = []
    for k, m in enumerate(found):
        grades = [g for (kind, colour), gs in phrases.items() for g in gs
                  if kind == m.kind and colour in (None, m.color)]
        grades = list(dict.fromkeys(grades))
        parts = _split(m, grades)
        if parts is None or len(out) + len(parts) + len(found) - k - 1 > most:
            out.append(m)
        else:
            out.extend(parts)
    return out


def _superlatives_spelled(words: list[str]) -> list[str]:
    """``words`` with a superlative that stands alone after "the" followed by the kind
    word named last ("three boxes from the largest ... to the smallest": "the largest
    box ... the smallest box")."""
    out: list[str] = []
    last: str | None = None
    for i, w in enumerate(words):
        out.append(w)
        kind, _plural, singular = kind_of(w)
        if kind is not None:
            last = singular
        elif w in SUPERLATIVES and last and i and words[i - 1] == "the" and not (
                i + 1 < len(words) and kind_of(words[i + 1])[0] is not None):
            out.append(last)
    return out


def _split(m: Mention, grades: list[str]) -> list[Mention] | None:
    if m.counted and m.count == 3 and len(grades) == 2 and set(grades) == set(
            _ENDS.get(grades[0], ())):
        grades = [grades[0], "medium", grades[1]]  # the two ends of three: one between
    if len(grades) < 2 or len(grades) > MAX_GRADES or m.group is not None or m.grade:
        return None
    if m.counted and m.count > len(grades) and m.count % len(grades):
        return None  # "five boxes, a small one and a large one": which is which is open
    # "a long log and a short log" (counted one by its article): one of each
    each = m.count // len(grades) if m.counted and m.count > len(grades) else 1
    stem = f"{m.color}_{m.kind}" if m.color else m.kind
    default = kind_spec(m.kind).default_size
    out = []
    for grade in grades:
        scale = _scale(grade, grades)
        size = tuple(round(d * s, 4) for d, s in zip(default, scale, strict=True))
        name = f"{grade}_{plural_of(stem) if each > 1 else stem}"
        out.append(replace(m, name=name, count=each, counted=True, grade=grade,  # type: ignore[type-var]
                           size=size))
    return out


def pick_graded(words: list[str], i: int, same: Sequence[Mention],
                other: bool) -> list[Mention] | None:
    """The graded objects the kind word ``words[i]`` names among ``same`` (alike
    objects, some graded): those of the grade before it; for "the other X", those whose
    grade no phrase before it named; None: the words pick none by grade."""
    if not any(m.grade for m in same):
        return None
    grade = grade_before(words, i)
    if grade is not None:
        return [m for m in same if m.grade == grade] or None
    if not other:
        return None
    named = {grade_before(words, j) for j in range(i) if kind_of(words[j])[0] is not None}
    rest = [m for m in same if m.grade and m.grade not in named]
    return rest if rest and len(rest) < len(same) else None


__all__ = ["GRADE_WORDS", "SCALES", "grade_before", "grade_members", "pick_graded"]
