"""Read LIBERO's BDDL task files into :class:`~factask.compat.libero.model.BddlProblem`.

LIBERO (Liu et al., 2023) writes each task as a BDDL problem: the regions things
start in, the fixtures and objects, the initial conditions and the goal, and an
instruction. This is the first step of taking those tasks in as factor graphs: the
file read faithfully into typed values, with no opinion yet about what a ``wooden
cabinet`` or ``In`` is in factask. LIBERO itself reads them with the ``bddl``
package; this reader has no dependency and is built for files from outside: every
problem is a :class:`BddlError` naming the file, line and column, and the work is
bounded whatever the text (see :mod:`factask.compat.libero.sexpr`).

The grammar, and what is decided here where LIBERO's reader is silent:

* ``(define (problem NAME) SECTION...)``; section heads, ``define``, ``problem``
  and predicate names are case-insensitive (kept lower-cased); names, types and
  words are kept as written (LIBERO's reader lower-cases everything).
* ``(:objects ...)`` and ``(:goal ...)`` are required, as is ``(problem NAME)``;
  any other section may be absent. A section given twice is an error.
* Sections the reader does not interpret (``:requirements``, ``:scene_properties``)
  are kept as raw text in ``BddlProblem.extra``, never an error.
* ``:fixtures`` and ``:objects`` are PDDL typed lists (``a b - type``); names
  after the last type get ``fixture`` / ``object``, as in LIBERO. A name declared
  twice (in either list) is an error.
* A region is ``(NAME (:target T) (:ranges ((x0 y0 x1 y1)...)) (:yaw_rotation
  ((lo hi)...)) ...)``; ``:target`` is required, other attributes are kept raw.
  Numbers must be finite; a yaw may also be written with ``pi`` (``-pi/2``), which
  LIBERO's ``eval`` allows. Two regions with the same full name are an error.
* The goal is one condition; a top-level ``(And ...)`` is flattened into
  ``BddlProblem.goal`` (nested ``And`` within it too). ``Or`` and ``Not`` (and an
  ``And`` under them) are kept as a :class:`Predicate` of that name whose
  arguments are predicates; any other predicate's arguments must be names.
  Quantifiers (``forall``, ``exists``) are errors. An empty goal is an error.
"""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import cast

from factask.compat.libero.model import (
    CONNECTIVES,
    BddlProblem,
    Predicate,
    Range,
    Region,
    YawRange,
)
from factask.compat.libero.sexpr import (
    MAX_TEXT_CHARS,
    Atom,
    BddlError,
    Document,
    Node,
    SList,
    describe,
    read_sexpr,
    to_text,
)
from factask.vocabulary.errors import quote

#: Sections this reader interprets (lower-cased heads).
SECTIONS = frozenset({"problem", ":domain", ":language", ":regions", ":fixtures",
                      ":objects", ":obj_of_interest", ":init", ":goal"})
#: Sections a file must have.
REQUIRED = ("problem", ":objects", ":goal")
#: Predicates that bind variables: outside what LIBERO's tasks use, refused.
QUANTIFIERS = frozenset({"forall", "exists"})

_NUMBER = re.compile(r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?")
_NOT_FINITE = re.compile(r"[+-]?(?:nan|inf|infinity)", re.IGNORECASE)
_PI = re.compile(r"(?:np\.)?pi")


def load_bddl(path: str | Path) -> BddlProblem:
    """Read a BDDL file.

    Args:
        path: The file (UTF-8).

    Returns:
        The problem, with ``source`` the path.

    Raises:
        BddlError: The file cannot be read, is larger than 1 MB or not UTF-8, or
            :func:`parse_bddl` rejects its text.
    """
    source = str(path)
    try:
        with open(path, "rb") as f:
            data = f.read(MAX_TEXT_CHARS + 1)
    except OSError as exc:
        raise BddlError(source, f"cannot read the file ({exc.strerror or exc})",
                        "a readable BDDL file") from exc
    if len(data) > MAX_TEXT_CHARS:
        raise BddlError(source, "the file is larger than 1 MB", "a LIBERO task file")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise BddlError(source, f"not UTF-8 text (byte {exc.start})", "a text file") from exc
    return parse_bddl(text, source)


def parse_bddl(text: str, source: str = "<string>") -> BddlProblem:
    """Read one BDDL problem from text.

    Args:
        text: The whole file's text.
        source: Where it came from, for messages.

    Returns:
        The problem.

    Raises:
        BddlError: The text is not one well-formed problem (see the module
            docstring for the grammar), or passes a limit of
            :mod:`factask.compat.libero.sexpr`.
    """
    if not isinstance(source, str):
        source = repr(source)
    if not isinstance(text, str):
        raise BddlError(source, f"the text is a {type(text).__name__}", "a str")
    doc = Document(text, source)
    top = read_sexpr(doc)
    if not top:
        raise doc.error(None, "no BDDL in the text", "(define (problem NAME) ...)")
    define = top[0]
    if not isinstance(define, SList) or define.head != "define":
        raise doc.error(define, f"the text starts with {describe(define)}",
                        "(define (problem NAME) ...)")
    if len(top) > 1:
        raise doc.error(top[1], f"{describe(top[1])} after the end of (define ...)",
                        "nothing after the problem's closing ')'")
    sections: dict[str, SList] = {}
    extra: dict[str, str] = {}
    for item in define.items[1:]:
        if not isinstance(item, SList) or item.head is None:
            raise doc.error(item, f"{describe(item)} among the sections",
                            "a section such as (:objects ...)")
        if item.head in sections or item.head in extra:
            raise doc.error(item, f"section {quote(item.head)} given twice", "each once")
        if item.head in SECTIONS:
            sections[item.head] = item
        else:
            extra[item.head] = doc.raw(item)
    for head in REQUIRED:
        if head not in sections:
            form = "(problem NAME)" if head == "problem" else f"a ({head} ...) section"
            raise doc.error(define, f"no ({head} ...) section", form)
    return _Reader(doc).problem(sections, extra)


class _Reader:
    """The sections of one document turned into values.

    Every method raises :class:`BddlError` (through ``self.doc.error``) at the node
    that is wrong; their docstrings say what they read.

    Args:
        doc: The document the nodes come from.
    """

    def __init__(self, doc: Document) -> None:
        self.doc = doc

    def problem(self, sections: dict[str, SList], extra: dict[str, str]) -> BddlProblem:
        """The whole problem.

        Args:
            sections: The interpreted sections by lower-cased head (the required ones
                present).
            extra: The other sections' raw text by lower-cased head.

        Returns:
            The problem.
        """

        def get(head: str) -> tuple[Node, ...]:
            return sections[head].items[1:] if head in sections else ()

        fixtures = self.typed(sections.get(":fixtures"), "fixture", {})
        objects = self.typed(sections[":objects"], "object", fixtures)
        regions = tuple(self.region(r) for r in get(":regions"))
        seen: dict[str, Region] = {}
        for node, region in zip(get(":regions"), regions, strict=True):
            if region.full_name in seen:
                raise self.doc.error(node, f"a second region named {quote(region.full_name)}",
                                     "region full names (<target>_<name>) to be unique")
            seen[region.full_name] = region
        domain = self.single(sections[":domain"]) if ":domain" in sections else ""
        return BddlProblem(
            name=self.single(sections["problem"]), domain=domain,
            language=" ".join(self.word(w) for w in get(":language")),
            regions=regions, fixtures=fixtures, objects=objects,
            objects_of_interest=tuple(self.name(n, "a name") for n in get(":obj_of_interest")),
            init=tuple(self.predicate(p) for p in get(":init")),
            goal=self.goal(sections[":goal"]), extra=extra, source=self.doc.source)

    def name(self, node: Node, what: str) -> str:
        """A name: an atom other than ``-``; ``what`` says what was expected."""
        if not isinstance(node, Atom) or node.text == "-":
            raise self.doc.error(node, f"{describe(node)} where a name belongs", what)
        return node.text

    def single(self, section: SList) -> str:
        """The one name of ``(problem NAME)`` or ``(:domain NAME)``."""
        if len(section.items) != 2:
            raise self.doc.error(section, f"({section.head} ...) has "
                                 f"{len(section.items) - 1} items", "exactly one name")
        return self.name(section.items[1], f"({section.head} NAME)")

    def word(self, node: Node) -> str:
        """A word of the instruction (a list in it is kept as written)."""
        return node.text if isinstance(node, Atom) else to_text(node)

    def typed(self, section: SList | None, default: str,
              taken: dict[str, str]) -> dict[str, str]:
        """A PDDL typed list ``a b - type c - type2 d``.

        Args:
            section: The ``(:fixtures ...)`` or ``(:objects ...)`` list, or None.
            default: The type of names after the last ``- type``.
            taken: Names declared already (by the other list).

        Returns:
            Name → type, in order of writing.
        """
        if section is None:
            return {}
        out: dict[str, str] = {}
        pending: list[Atom] = []
        items = section.items[1:]
        i = 0
        while i < len(items):
            node = items[i]
            if isinstance(node, Atom) and node.text == "-":
                if not pending:
                    raise self.doc.error(node, "'-' with no name before it",
                                         "names, then '- type'")
                if i + 1 >= len(items):
                    raise self.doc.error(node, "'-' at the end of the list", "a type after '-'")
                kind = self.name(items[i + 1], "a type after '-'")
                self.declare(pending, kind, out, taken)
                pending, i = [], i + 2
                continue
            if not isinstance(node, Atom):
                raise self.doc.error(node, f"{describe(node)} in ({section.head} ...)",
                                     "names, then '- type'")
            pending.append(node)
            i += 1
        self.declare(pending, default, out, taken)
        return out

    def declare(self, names: list[Atom], kind: str, out: dict[str, str],
                taken: dict[str, str]) -> None:
        """Adds ``names`` of type ``kind`` to ``out``; a name met before is an error."""
        for atom in names:
            if atom.text in out or atom.text in taken:
                raise self.doc.error(atom, f"{quote(atom.text)} is declared twice",
                                     "each fixture and object name once")
            out[atom.text] = kind

    def region(self, node: Node) -> Region:
        """One region, ``(NAME (:target T) (:ranges ...) (:yaw_rotation ...) ...)``."""
        if not isinstance(node, SList) or not node.items or not isinstance(node.items[0], Atom):
            raise self.doc.error(node, f"{describe(node)} among the regions",
                                 "(NAME (:target T) (:ranges (...)) ...)")
        name = self.name(node.items[0], "a region name")
        attrs: dict[str, SList] = {}
        for attr in node.items[1:]:
            if not isinstance(attr, SList) or not (attr.head or "").startswith(":"):
                raise self.doc.error(attr, f"{describe(attr)} in region {quote(name)}",
                                     "attributes such as (:target T)")
            head = attr.head or ""
            if head in attrs:
                raise self.doc.error(attr, f"region {quote(name)} gives {head} twice",
                                     "each attribute once")
            attrs[head] = attr
        target_attr = attrs.pop(":target", None)
        if target_attr is None:
            raise self.doc.error(node, f"region {quote(name)} has no (:target T)",
                                 "the fixture, object or floor it lies on")
        if len(target_attr.items) != 2:
            raise self.doc.error(target_attr, f"region {quote(name)}: (:target ...) has "
                                 f"{len(target_attr.items) - 1} items", "exactly one name")
        target = self.name(target_attr.items[1], "(:target NAME)")
        where = f"region {quote(name)} (target {quote(target)})"
        ranges = cast("tuple[Range, ...]", self.rows(attrs.pop(":ranges", None), 4, where))
        yaws = cast("tuple[YawRange, ...]",
                    self.rows(attrs.pop(":yaw_rotation", None), 2, where))
        return Region(name=name, target=target, ranges=ranges, yaw_rotation=yaws,
                      attributes={h[1:]: self.doc.raw(a) for h, a in attrs.items()})

    def rows(self, attr: SList | None, width: int, where: str) -> tuple[tuple[float, ...], ...]:
        """``(:ranges ((x0 y0 x1 y1) ...))`` or ``(:yaw_rotation ((lo hi) ...))``.

        Args:
            attr: The attribute's list, or None when the region has none.
            width: Numbers per row (4 for ranges, 2 for yaws, which may use ``pi``).
            where: The region, as messages name it.

        Returns:
            The rows, each ``width`` finite numbers.
        """
        if attr is None:
            return ()
        form = "((x0 y0 x1 y1) ...)" if width == 4 else "((low high) ...)"
        if len(attr.items) != 2 or not isinstance(attr.items[1], SList):
            raise self.doc.error(attr, f"{where}: {attr.head} is not one list of rows",
                                 f"({attr.head} {form})")
        rows = []
        for row in attr.items[1].items:
            if not isinstance(row, SList) or len(row.items) != width:
                raise self.doc.error(row, f"{where}: {describe(row)} in {attr.head}",
                                     f"rows of {width} numbers, {form}")
            rows.append(tuple(self.number(v, where, attr.head or "", width == 2)
                              for v in row.items))
        return tuple(rows)

    def number(self, node: Node, where: str, key: str, yaw: bool) -> float:
        """A finite number (``yaw``: or an expression of ``pi``) of attribute ``key``."""
        text = node.text if isinstance(node, Atom) else ""
        value: float | None = None
        if _NUMBER.fullmatch(text) or _NOT_FINITE.fullmatch(text):
            value = float(text)
        elif yaw:
            value = _pi_expression(text)
        if value is None:
            expected = "a number or an expression of pi (-pi/2)" if yaw else "a number"
            raise self.doc.error(node, f"{where}: {describe(node)} in {key}", expected)
        if not math.isfinite(value):
            raise self.doc.error(node, f"{where}: {key} value {quote(text, 40)} is not "
                                 "finite", "a finite number")
        return value

    def goal(self, section: SList) -> tuple[Predicate, ...]:
        """The goal's one condition, its top-level ``and`` (and any ``and`` directly
        in it) flattened, in order of writing."""
        if len(section.items) != 2:
            raise self.doc.error(section, f"(:goal ...) has {len(section.items) - 1} items",
                                 "one condition, usually (And (Pred args...) ...)")
        out: list[Predicate] = []
        todo = [self.predicate(section.items[1])]
        while todo:  # depth first; an And has at least one argument, all conditions
            cond = todo.pop()
            if cond.name == "and":
                todo.extend(cast("tuple[Predicate, ...]", cond.args)[::-1])
            else:
                out.append(cond)
        return tuple(out)

    def predicate(self, node: Node) -> Predicate:
        """A condition ``(Pred names...)``, or ``(And|Or|Not conditions...)`` kept nested
        (recursion bounded by the reader's nesting limit)."""
        if not isinstance(node, SList) or node.head is None:
            raise self.doc.error(node, f"{describe(node)} where a condition belongs",
                                 "(Pred args...)")
        name, args = node.head, node.items[1:]
        if name in QUANTIFIERS:
            raise self.doc.error(node, f"quantifier {quote(name)} is not supported",
                                 "conditions over named objects")
        if name in CONNECTIVES:
            if name == "not" and len(args) != 1:
                raise self.doc.error(node, f"(Not ...) has {len(args)} conditions",
                                     "exactly one")
            if not args:
                raise self.doc.error(node, f"({name}) has no condition", "at least one")
            return Predicate(name, tuple(self.predicate(a) for a in args))
        return Predicate(name, tuple(self.name(a, f"names as arguments of {name!r} (only "
                                                  "And, Or and Not take conditions)")
                                     for a in args))


def _pi_expression(text: str) -> float | None:
    """``[+-]factor([*/]factor)*`` with factors numbers, ``pi`` or ``np.pi``; None when
    the text is not one (or divides by zero)."""
    sign = -1.0 if text.startswith("-") else 1.0
    body = text[1:] if text[:1] in "+-" else text
    parts = re.split(r"([*/])", body)
    value = 0.0
    for i in range(0, len(parts), 2):
        part = parts[i]
        if _PI.fullmatch(part):
            factor = math.pi
        elif re.fullmatch(r"(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?", part):
            factor = float(part)
        else:
            return None
        if i == 0:
            value = factor
        elif parts[i - 1] == "*":
            value *= factor
        elif factor == 0:
            return None
        else:
            value /= factor
    return sign * value
