"""The s-expression reader under the BDDL parser, and its one error type.

BDDL files are Lisp-style lists. This reader turns text into atoms and nested lists
that remember where they came from (an offset into the text), so every error the
parser raises later can name the file, line and column. It is written for text from
outside the project: its work is bounded before it starts (size, tokens, nesting),
it never recurses, and whatever it is given it either returns or raises
:class:`BddlError`, nothing else.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from factask.vocabulary.errors import FactaskError, clip, quote

#: Longest text read, in characters (a LIBERO file is about 4 KB).
MAX_TEXT_CHARS = 1_000_000
#: Deepest nesting of lists (a LIBERO file nests 6 deep, at a region's ranges).
MAX_DEPTH = 64
#: Most tokens (parentheses and atoms, comments not counted) in one text.
MAX_TOKENS = 100_000
#: Longest ``source`` (a file name) repeated in a message.
SOURCE_LIMIT = 200

#: A parenthesis, a comment to the end of its line, or an atom (anything else but space).
_TOKEN = re.compile(r"[()]|;[^\n]*|[^\s();]+")


class BddlError(FactaskError, ValueError):
    """A BDDL text could not be read: bad syntax, a missing or malformed section, a
    limit passed.

    The message reads ``"<source>:<line>:<column>: <what>; expected <expected>"``
    (the position where one is known). Also a ``ValueError``, as Python callers
    expect of bad input.

    Attributes:
        source: The file (or ``"<string>"``) the text came from.
        what: What was wrong.
        expected: What was expected instead ("" if nothing in particular).
        line: 1-based line of the problem, or None.
        column: 1-based column (in characters) of the problem, or None.
    """

    def __init__(self, source: str, what: str, expected: str = "",
                 line: int | None = None, column: int | None = None) -> None:
        self.source, self.what, self.expected = source, what, expected
        self.line, self.column = line, column
        where = clip(source, SOURCE_LIMIT)
        if line is not None:
            where += f":{line}:{column}"
        text = f"{where}: {what}"
        if expected:
            text += f"; expected {expected}"
        super().__init__(text)

    def __reduce__(self) -> tuple[type[BddlError], tuple[object, ...]]:
        """Pickles with every field (the default would pass the message alone)."""
        return (type(self), (self.source, self.what, self.expected, self.line, self.column))


@dataclass(frozen=True)
class Atom:
    """A word: anything between spaces, parentheses and comments.

    Attributes:
        text: The word as written.
        start: Offset of its first character in the text.
    """

    text: str
    start: int


@dataclass(frozen=True)
class SList:
    """A parenthesised list.

    Attributes:
        items: Its atoms and lists, in order.
        start: Offset of its ``(``.
        end: Offset just past its ``)``.
    """

    items: tuple[Atom | SList, ...]
    start: int
    end: int

    @property
    def head(self) -> str | None:
        """The first item lower-cased when it is an atom (a section's or predicate's
        name), else None."""
        if self.items and isinstance(self.items[0], Atom):
            return self.items[0].text.lower()
        return None


Node = Atom | SList


class Document:
    """A text being read, with its source name, for errors that say where.

    Args:
        text: The whole text.
        source: Where it came from (a path, or ``"<string>"``).
    """

    def __init__(self, text: str, source: str) -> None:
        self.text = text
        self.source = source

    def position(self, offset: int) -> tuple[int, int]:
        """The 1-based line and column of an offset into the text.

        Args:
            offset: Character offset.

        Returns:
            (line, column).
        """
        offset = max(0, min(offset, len(self.text)))
        line = self.text.count("\n", 0, offset) + 1
        column = offset - (self.text.rfind("\n", 0, offset) + 1) + 1
        return line, column

    def error(self, at: Node | int | None, what: str, expected: str = "") -> BddlError:
        """An error at a node or offset (or at no position in particular).

        Args:
            at: The node, the offset, or None.
            what: What is wrong.
            expected: What was expected instead.

        Returns:
            The error, to raise.
        """
        if at is None:
            return BddlError(self.source, what, expected)
        offset = at if isinstance(at, int) else at.start
        line, column = self.position(offset)
        return BddlError(self.source, what, expected, line, column)

    def raw(self, node: Node) -> str:
        """A node's text exactly as written (comments and layout included).

        Args:
            node: An atom or list of this document.

        Returns:
            The slice of the text it spans.
        """
        if isinstance(node, Atom):
            return node.text
        return self.text[node.start:node.end]


def read_sexpr(doc: Document) -> tuple[Node, ...]:
    """Every top-level atom and list of a document, without recursion.

    Args:
        doc: The text and its source.

    Returns:
        The top-level nodes, in order.

    Raises:
        BddlError: The text is longer than :data:`MAX_TEXT_CHARS`, has more than
            :data:`MAX_TOKENS` tokens, nests deeper than :data:`MAX_DEPTH`, or has a
            parenthesis without its partner.
    """
    text = doc.text
    if len(text) > MAX_TEXT_CHARS:
        raise doc.error(None, f"the text is {len(text):,} characters long",
                        f"at most {MAX_TEXT_CHARS:,}")
    top: list[Node] = []
    stack: list[tuple[int, list[Node]]] = []
    count = 0
    for match in _TOKEN.finditer(text):
        token = match.group()
        if token[0] == ";":
            continue
        count += 1
        if count > MAX_TOKENS:
            raise doc.error(match.start(), f"more than {MAX_TOKENS:,} tokens",
                            "a shorter text")
        if token == "(":
            if len(stack) >= MAX_DEPTH:
                raise doc.error(match.start(), f"lists nested deeper than {MAX_DEPTH}",
                                f"at most {MAX_DEPTH} levels of parentheses")
            stack.append((match.start(), []))
        elif token == ")":
            if not stack:
                raise doc.error(match.start(), "')' closes no list",
                                "every ')' to match an earlier '('")
            start, items = stack.pop()
            (stack[-1][1] if stack else top).append(SList(tuple(items), start, match.end()))
        else:
            (stack[-1][1] if stack else top).append(Atom(token, match.start()))
    if stack:
        raise doc.error(stack[-1][0], "'(' is never closed", "a matching ')'")
    return tuple(top)


def describe(node: Node) -> str:
    """A node as a message names it: an atom quoted, a list by its head.

    Args:
        node: The atom or list.

    Returns:
        Short text for a message.
    """
    if isinstance(node, Atom):
        return f"the word {quote(node.text, 40)}"
    first = node.items[0] if node.items else None
    if isinstance(first, Atom):
        return f"a list starting {quote(first.text, 40)}"
    return "an empty list" if first is None else "a list starting with a list"


def to_text(node: Node) -> str:
    """A node written back on one line, comments and layout dropped (recursion is
    bounded by :data:`MAX_DEPTH`).

    Args:
        node: The atom or list.

    Returns:
        Its words and parentheses separated by single spaces.
    """
    if isinstance(node, Atom):
        return node.text
    return f"({' '.join(to_text(item) for item in node.items)})"
