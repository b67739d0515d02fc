"""The one named colour palette of factask.

Colours are referred to by name everywhere (graphs, prompts, the CLIPort
compatibility layer). An unknown name is an error that lists the valid ones; it
never silently becomes red as in GenSim.
"""

from __future__ import annotations

from types import MappingProxyType

from factask.vocabulary.errors import FactaskError

# RGB in [0, 1]. The first eleven follow the Ravens/CLIPort palette (Tableau
# colours), so tasks ported from there look the same; the rest extend it for the
# colours GenSim's task list mentions.
_RGB: dict[str, tuple[float, float, float]] = {
    "blue": (78 / 255, 121 / 255, 167 / 255),
    "red": (255 / 255, 87 / 255, 89 / 255),
    "green": (89 / 255, 169 / 255, 79 / 255),
    "orange": (242 / 255, 142 / 255, 43 / 255),
    "yellow": (237 / 255, 201 / 255, 72 / 255),
    "purple": (176 / 255, 122 / 255, 161 / 255),
    "pink": (255 / 255, 157 / 255, 167 / 255),
    "cyan": (118 / 255, 183 / 255, 178 / 255),
    "brown": (156 / 255, 117 / 255, 95 / 255),
    "white": (255 / 255, 255 / 255, 255 / 255),
    "gray": (186 / 255, 176 / 255, 172 / 255),
    "black": (0.1, 0.1, 0.1),
    "silver": (0.75, 0.75, 0.75),
    "gold": (1.0, 0.84, 0.0),
    "indigo": (75 / 255, 0.0, 130 / 255),
    "violet": (238 / 255, 130 / 255, 238 / 255),
    "olive": (128 / 255, 128 / 255, 0.0),
    "navy": (0.0, 0.0, 128 / 255),
    "maroon": (128 / 255, 0.0, 0.0),
    "teal": (0.0, 128 / 255, 128 / 255),
    "magenta": (1.0, 0.0, 1.0),
    "lime": (0.5, 1.0, 0.0),
    "tan": (210 / 255, 180 / 255, 140 / 255),
    "beige": (245 / 255, 245 / 255, 220 / 255),
}

#: Name -> RGB (each channel in [0, 1]). Read-only.
COLORS = MappingProxyType(_RGB)

#: Valid colour names, in palette order.
COLOR_NAMES: tuple[str, ...] = tuple(_RGB)

#: Aliases accepted on input and normalised to a palette name.
COLOR_ALIASES = MappingProxyType({"grey": "gray", "violet_purple": "violet"})


class UnknownColorError(FactaskError, ValueError):
    """A colour name that is not in the palette."""


def normalize_color(name: str) -> str:
    """Return the palette name for ``name`` (case-insensitive, aliases resolved).

    Raises:
        UnknownColorError: ``name`` is not a palette colour; the message lists them.
    """
    key = str(name).strip().lower()
    key = COLOR_ALIASES.get(key, key)
    if key not in _RGB:
        raise UnknownColorError(
            f"unknown colour {name!r}; valid colours: {', '.join(COLOR_NAMES)}"
        )
    return key


def colour_of_word(word: str) -> str | None:
    """The palette colour a lower-case word of text names (``grey`` -> ``gray``), or
    None when the word is no colour."""
    key = COLOR_ALIASES.get(word, word)
    return key if key in _RGB else None


def rgba(name: str, alpha: float = 1.0) -> tuple[float, float, float, float]:
    """RGBA of a palette colour (raises :class:`UnknownColorError` if unknown)."""
    r, g, b = _RGB[normalize_color(name)]
    return (r, g, b, alpha)


def nearest_color(rgb: tuple[float, float, float] | list[float]) -> str:
    """Name of the palette colour closest (Euclidean, RGB) to ``rgb``.

    Used where outside code gives raw RGB tuples (the CLIPort layer).
    Channels above 1 are taken as 0-255.
    """
    vals = [float(c) for c in list(rgb)[:3]]
    if any(c > 1.0 for c in vals):
        vals = [c / 255.0 for c in vals]
    return min(_RGB, key=lambda n: sum((a - b) ** 2 for a, b in zip(_RGB[n], vals, strict=True)))
