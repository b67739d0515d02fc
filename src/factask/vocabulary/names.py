"""Identifier rules for variables, factors, templates and tasks."""

from __future__ import annotations

import re
from typing import Annotated

from pydantic import AfterValidator, StringConstraints

from factask.vocabulary.errors import InvalidValueError

#: Separator between a variable's name and an instance index (``blocks__2``).
INSTANCE_SEPARATOR = "__"

#: Pattern of variable, factor, slot and template names: snake_case identifiers.
#: A double underscore is reserved (it separates a variable from an instance index).
NAME_PATTERN = r"^[a-z][a-z0-9_]{0,63}$"
#: Pattern of task names: kebab-case as in GenSim's task list (snake_case accepted;
#: capitals too: the list spells one ``Four-corner-pyramid-challenge``).
TASK_NAME_PATTERN = r"^[A-Za-z0-9][A-Za-z0-9_-]{0,99}$"


def _no_double_underscore(value: str) -> str:
    if INSTANCE_SEPARATOR in value:
        raise InvalidValueError(f"name {value!r} contains '__', which is reserved for "
                                "instance names (blocks__2); use single underscores")
    return value


Name = Annotated[
    str, StringConstraints(pattern=NAME_PATTERN), AfterValidator(_no_double_underscore)
]
TaskName = Annotated[str, StringConstraints(pattern=TASK_NAME_PATTERN)]


def instance_names(variable: str, count: int) -> list[str]:
    """Names of the objects a variable stands for: itself, or ``name__i`` if count > 1."""
    if count == 1:
        return [variable]
    return [f"{variable}{INSTANCE_SEPARATOR}{i}" for i in range(count)]


def unique_name(name: str, taken: set[str], max_length: int = 64) -> str:
    """``name``, or the first of ``name_2``, ``name_3``, ... not in ``taken`` (cut to
    ``max_length`` before the suffix); the result is added to ``taken``.

    Args:
        name: The wanted name.
        taken: Names in use; updated.
        max_length: Longest name allowed.

    Returns:
        A name not in ``taken`` before the call.
    """
    out, k = name, 2
    while out in taken:
        suffix = f"_{k}"
        out = f"{name[:max_length - len(suffix)].rstrip('_')}{suffix}"
        k += 1
    taken.add(out)
    return out


def slugify(text: str, separator: str, max_length: int, fallback: str,
            max_words: int | None = None, letter_first: bool = True) -> str:
    """An identifier from free text: its lower-case words of letters and digits joined
    by ``separator`` ("Stack the blocks!" -> "stack-the-blocks" or "stack_the_blocks").

    Args:
        text: Any text.
        separator: ``"-"`` for task names, ``"_"`` for variable and factor names.
        max_length: Longest result; longer names are cut at a word boundary where
            possible.
        fallback: The name when the text has no word, and the prefix of a name that
            must start with a letter but does not.
        max_words: Keep at most this many words.
        letter_first: The name must start with a letter (variable and factor names).
    """
    words = re.findall(r"[a-z0-9]+", text.lower())
    name = separator.join(words[:max_words] if max_words is not None else words)
    if len(name) > max_length:
        cut = name[:max_length]
        name = cut.rsplit(separator, 1)[0] if separator in cut else cut
    if not name:
        return fallback
    if letter_first and not name[0].isalpha():
        name = f"{fallback}{separator}{name}"[:max_length].rstrip(separator)
    return name
