"""LIBERO's BDDL reader (factask.compat.libero, issue 38's first step): the 30 shipped
files read and say what they should, the grammar's decisions, errors that name the
file, line and column, and hostile text that only ever ends in a BddlError, quickly."""

from __future__ import annotations

import math
import pickle
import re
import time
from pathlib import Path, PurePosixPath

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from factask.compat.libero import (
    SHIPPED_SUITES,
    BddlError,
    BddlProblem,
    Predicate,
    Region,
    format_bddl,
    libero_data_dir,
    load_bddl,
    parse_bddl,
    shipped_bddl_files,
)
from factask.compat.libero.sexpr import MAX_DEPTH, MAX_TEXT_CHARS, MAX_TOKENS
from factask.vocabulary.errors import FactaskError

ROOT = Path(__file__).resolve().parents[1]
FILES = shipped_bddl_files()
TEXTS = [p.read_text() for p in FILES]
GOAL_PREDICATES = {"on", "in", "open", "close", "turnon", "turnoff"}
FAST = settings(deadline=2000, max_examples=150,
                suppress_health_check=[HealthCheck.too_slow])


def _file(rel: str) -> BddlProblem:
    return load_bddl(libero_data_dir() / rel)


def _minimal(**sections: str) -> str:
    """A small valid problem, with sections replaced (or removed, given "")."""
    parts = {"problem": "(problem p)", "objects": "(:objects a - box)",
             "goal": "(:goal (And (On a b)))"}
    parts.update(sections)
    return "(define " + " ".join(v for v in parts.values() if v) + ")"


# The shipped files ---------------------------------------------------------------------

def test_three_suites_of_ten_files_ship_and_no_other() -> None:
    assert len(FILES) == 30
    for suite in SHIPPED_SUITES:
        assert len(shipped_bddl_files(suite)) == 10
    folders = {p.name for p in libero_data_dir().iterdir() if p.is_dir()}
    assert folders == set(SHIPPED_SUITES)
    assert (libero_data_dir() / "LICENSE").read_text().startswith("MIT License")
    assert "8f1084e3132a39270c3a13ebe37270a43ece2a01" in (
        libero_data_dir() / "README.md").read_text()
    with pytest.raises(BddlError, match="not a shipped LIBERO suite"):
        shipped_bddl_files("libero_nope")


def test_the_package_data_patterns_install_every_shipped_file() -> None:
    tomllib = pytest.importorskip("tomllib")
    patterns = tomllib.loads((ROOT / "pyproject.toml").read_text())[
        "tool"]["setuptools"]["package-data"]["factask"]
    package = ROOT / "src" / "factask"
    shipped = [p for p in (package / "data" / "libero").rglob("*") if p.is_file()]
    assert len(shipped) == 32
    for path in shipped:
        rel = PurePosixPath(path.relative_to(package).as_posix())
        assert any(len(rel.parts) == len(PurePosixPath(pat).parts) and rel.match(pat)
                   for pat in patterns), f"{rel} is not in the package data"


@pytest.mark.parametrize("path", FILES, ids=[f"{p.parent.name}/{p.stem[:40]}" for p in FILES])
def test_every_shipped_file_reads_and_its_names_resolve(path: Path) -> None:
    problem = load_bddl(path)
    assert problem.source == str(path)
    assert problem.name in {"LIBERO_Tabletop_Manipulation", "LIBERO_Floor_Manipulation"}
    assert problem.domain == "robosuite" and problem.language and problem.extra == {}
    assert problem.goal and {p.name for p in problem.goal} <= GOAL_PREDICATES
    assert all(not p.is_connective for p in (*problem.init, *problem.goal))
    declared = set(problem.objects) | set(problem.fixtures) | {
        f"{r.target}_{r.name}" for r in problem.regions}
    used = [a for p in (*problem.init, *problem.goal) for a in p.args]
    assert all(isinstance(a, str) for a in used)
    assert set(used) | set(problem.objects_of_interest) <= declared
    assert problem.undeclared_names() == ()
    assert all(problem.kind_of(n) is not None for n in used)
    for region in problem.regions:
        assert problem.regions_by_full_name[region.full_name] is region
        # LIBERO's one loose end: every libero_goal file gives regions to a bowl drainer
        # it never declares (no condition mentions them).
        assert region.target in declared or (path.parent.name, region.target) == (
            "libero_goal", "bowl_drainer_1")
        assert all(math.isfinite(v) for row in (*region.ranges, *region.yaw_rotation)
                   for v in row)
    # LIBERO's own layout: printing the problem gives the file back byte for byte.
    assert format_bddl(problem) == path.read_text()


def test_open_the_top_drawer_and_put_the_bowl_inside() -> None:
    p = _file("libero_goal/open_the_top_drawer_and_put_the_bowl_inside.bddl")
    assert p.language == "Open the top layer of the drawer and put the bowl inside"
    assert p.goal == (Predicate("in", ("akita_black_bowl_1", "wooden_cabinet_1_top_region")),)
    assert p.fixtures["wooden_cabinet_1"] == "wooden_cabinet"
    assert p.kind_of("wooden_cabinet_1") == "fixture"
    assert p.kind_of("akita_black_bowl_1") == "object"
    assert p.kind_of("wooden_cabinet_1_top_region") == "region"
    assert p.objects_of_interest == ("akita_black_bowl_1", "wooden_cabinet_1_top_region")
    # Two regions are called top_region: their full names tell them apart.
    tops = [r for r in p.regions if r.name == "top_region"]
    assert [r.full_name for r in tops] == ["wooden_cabinet_1_top_region", "wine_rack_1_top_region"]
    drawer = p.regions_by_full_name["wooden_cabinet_1_top_region"]
    assert drawer == Region("top_region", "wooden_cabinet_1")
    cabinet = p.regions_by_full_name["main_table_cabinet_region"]
    assert cabinet.ranges == ((0.02, -0.25, 0.04, -0.23),)
    assert cabinet.yaw_rotation == ((math.pi, math.pi),)
    assert p.init[4] == Predicate("on", ("wooden_cabinet_1", "main_table_cabinet_region"))


def test_a_spatial_file_declares_two_bowls_on_one_line() -> None:
    p = _file("libero_spatial/pick_up_the_black_bowl_between_the_plate_and_the_ramekin_and"
              "_place_it_on_the_plate.bddl")
    assert p.objects["akita_black_bowl_1"] == p.objects["akita_black_bowl_2"] == "akita_black_bowl"
    assert len(p.objects) == 5 and set(p.fixtures) == {"main_table", "wooden_cabinet_1",
                                                       "flat_stove_1"}
    assert p.goal == (Predicate("on", ("akita_black_bowl_1", "plate_1")),)
    yaw = p.regions_by_full_name["main_table_cabinet_region"].yaw_rotation
    assert yaw == ((2.6613777765410678, 2.7242096296128633),)


def test_an_object_file_is_on_the_floor_and_goals_name_the_basket() -> None:
    p = _file("libero_object/pick_up_the_ketchup_and_place_it_in_the_basket.bddl")
    assert p.name == "LIBERO_Floor_Manipulation" and p.fixtures == {"floor": "floor"}
    assert p.objects["basket_1"] == "basket"
    assert p.goal == (Predicate("in", ("ketchup_1", "basket_1_contain_region")),)
    assert p.regions_by_full_name["basket_1_contain_region"].ranges == ()


def test_open_and_turn_on_goals() -> None:
    assert _file("libero_goal/turn_on_the_stove.bddl").goal == (
        Predicate("turnon", ("flat_stove_1",)),)
    assert _file("libero_goal/open_the_middle_drawer_of_the_cabinet.bddl").goal == (
        Predicate("open", ("wooden_cabinet_1_middle_region",)),)


# The grammar's decisions ---------------------------------------------------------------

def test_nested_and_is_flattened_and_or_not_are_kept_nested() -> None:
    p = parse_bddl(_minimal(goal="(:goal (AND (On a b) (and (In a r) (Or (Not (Open d)) "
                                 "(And (Close d) (TurnOff s))))))"))
    assert p.goal == (
        Predicate("on", ("a", "b")), Predicate("in", ("a", "r")),
        Predicate("or", (Predicate("not", (Predicate("open", ("d",)),)),
                         Predicate("and", (Predicate("close", ("d",)),
                                           Predicate("turnoff", ("s",)))))))
    assert list(p.goal[2].names()) == ["d", "d", "s"]
    assert parse_bddl(format_bddl(p)) == p
    single = parse_bddl(_minimal(goal="(:goal (On a b))"))
    assert single.goal == (Predicate("on", ("a", "b")),)


@pytest.mark.parametrize(("goal", "message"), [
    ("(:goal (And))", "(and) has no condition"),
    ("(:goal (Not (On a b) (On b a)))", "(Not ...) has 2 conditions"),
    ("(:goal (forall (?x - box) (On ?x b)))", "quantifier 'forall'"),
    ("(:goal (On a (b)))", "where a name belongs"),
    ("(:goal (And a))", "where a condition belongs"),
    ("(:goal (On a b) (On b a))", "(:goal ...) has 2 items"),
])
def test_bad_goals_are_errors(goal: str, message: str) -> None:
    with pytest.raises(BddlError, match=re.escape(message)):
        parse_bddl(_minimal(goal=goal))


def test_typed_lists_unknown_sections_comments_and_case() -> None:
    text = """; a comment
    (DEFINE (PROBLEM p) ; another
      (:Requirements :strips)
      (:scene_properties (floor (:floor light)))
      (:fixtures table)
      (:objects a b - box c)
      (:Goal (and (on a b)))
    )"""
    p = parse_bddl(text)
    assert p.objects == {"a": "box", "b": "box", "c": "object"}
    assert p.fixtures == {"table": "fixture"}
    assert p.extra == {":requirements": "(:Requirements :strips)",
                       ":scene_properties": "(:scene_properties (floor (:floor light)))"}
    assert p.domain == "" and p.language == "" and p.regions == () and p.init == ()
    assert parse_bddl(format_bddl(p)) == p


def test_region_attributes_and_pi_yaws() -> None:
    regions = """(:regions (r (:target t) (:rgba (0 0 1 0)) (:ranges ((0 1 2 3) (4 5 6 7)))
                 (:yaw_rotation ((-pi/2 np.pi) (2*pi 1e-3)))))"""
    (region,) = parse_bddl(_minimal(regions=regions)).regions
    assert region.full_name == "t_r" and region.attributes == {"rgba": "(:rgba (0 0 1 0))"}
    assert region.ranges == ((0, 1, 2, 3), (4, 5, 6, 7))
    assert region.yaw_rotation == ((-math.pi / 2, math.pi), (2 * math.pi, 0.001))


@pytest.mark.parametrize(("regions", "message"), [
    ("(:regions (r (:ranges ((0 0 1 1)))))", "region 'r' has no (:target T)"),
    ("(:regions (r (:target t) (:ranges ((0 nan 1 1)))))",
     "region 'r' (target 't'): :ranges value 'nan' is not finite"),
    ("(:regions (r (:target t) (:ranges ((0 0 1e999 1)))))", "'1e999' is not finite"),
    ("(:regions (r (:target t) (:yaw_rotation ((-Infinity 0)))))", "'-Infinity' is not finite"),
    ("(:regions (r (:target t) (:ranges ((0 pi 1 1)))))", "the word 'pi' in :ranges"),
    ("(:regions (r (:target t) (:yaw_rotation ((pi/0 0)))))", "the word 'pi/0'"),
    ("(:regions (r (:target t) (:ranges ((0 0 1)))))", "rows of 4 numbers"),
    ("(:regions (r (:target t)) (r (:target t)))", "a second region named 't_r'"),
    ("(:regions (r (:target t) (:target u)))", "gives :target twice"),
    ("(:regions (r (target t)))", "attributes such as (:target T)"),
])
def test_bad_regions_are_errors_that_name_the_region(regions: str, message: str) -> None:
    with pytest.raises(BddlError, match=re.escape(message)):
        parse_bddl(_minimal(regions=regions))


@pytest.mark.parametrize(("sections", "message"), [
    ({"goal": ""}, "no (:goal ...) section"),
    ({"objects": ""}, "no (:objects ...) section"),
    ({"problem": ""}, "no (problem ...) section"),
    ({"goal": "(:goal (On a b)) (:goal (On a b))"}, "section ':goal' given twice"),
    ({"objects": "(:objects a - box) (:fixtures a - table)"}, "'a' is declared twice"),
    ({"objects": "(:objects a -)"}, "'-' at the end of the list"),
    ({"objects": "(:objects - box)"}, "'-' with no name before it"),
    ({"problem": "(problem p q)"}, "(problem ...) has 2 items"),
])
def test_bad_sections_are_errors(sections: dict[str, str], message: str) -> None:
    with pytest.raises(BddlError, match=re.escape(message)):
        parse_bddl(_minimal(**sections))


def test_errors_name_the_file_line_and_column_and_what_was_expected() -> None:
    text = TEXTS[0].replace("(:goal", "(:gaol")
    with pytest.raises(BddlError) as info:
        parse_bddl(text, "goal.bddl")
    err = info.value
    assert isinstance(err, FactaskError) and isinstance(err, ValueError)
    assert err.source == "goal.bddl" and err.line == 1 and err.column == 1
    assert str(err).startswith("goal.bddl:1:1: no (:goal ...) section; expected")
    lines = TEXTS[0].splitlines()
    row = next(i for i, line in enumerate(lines) if "0.04 -0.03" in line)
    bad = TEXTS[0].replace("0.04 -0.03", "0.04 nan", 1)
    with pytest.raises(BddlError, match="plate_region") as info:
        parse_bddl(bad, "nan.bddl")
    column = bad.splitlines()[row].index("nan") + 1
    assert (info.value.line, info.value.column) == (row + 1, column)
    with pytest.raises(BddlError, match=r"^<string>:3:5: '\(' is never closed"):
        parse_bddl("(define\n (problem p)\n    (:objects a\n")
    with pytest.raises(BddlError, match=rf"^<string>:1:{len(_minimal()) + 1}: '\)' closes"):
        parse_bddl(_minimal() + ")")
    with pytest.raises(BddlError, match="after the end of"):
        parse_bddl(_minimal() + " (define)")
    copy = pickle.loads(pickle.dumps(err))
    assert str(copy) == str(err) and copy.line == 1


def test_load_bddl_refuses_what_is_not_a_small_text_file(tmp_path: Path) -> None:
    with pytest.raises(BddlError, match="cannot read the file"):
        load_bddl(tmp_path / "missing.bddl")
    big = tmp_path / "big.bddl"
    big.write_text(" " * (MAX_TEXT_CHARS + 1))
    with pytest.raises(BddlError, match="larger than 1 MB"):
        load_bddl(big)
    binary = tmp_path / "binary.bddl"
    binary.write_bytes(b"(define \xff)")
    with pytest.raises(BddlError, match="not UTF-8"):
        load_bddl(binary)
    with pytest.raises(BddlError, match="a str"):
        parse_bddl(b"(define)")  # type: ignore[arg-type]


# Hostile text --------------------------------------------------------------------------

def _reads_or_refuses(text: str) -> None:
    try:
        parse_bddl(text, "fuzz")
    except BddlError as exc:
        assert str(exc).startswith("fuzz")


@pytest.mark.parametrize("text", [
    "(" * (MAX_DEPTH + 1) + ")" * (MAX_DEPTH + 1),
    "(define " + "(" * 200_000,
    ")" * 200_000,
    "a " * (MAX_TOKENS + 1),
    "x" * (MAX_TEXT_CHARS + 1),
    "(define (problem p) (:objects a) (:goal " + "(Not " * 62 + "(On a)" + ")" * 64,
    "", ";only a comment", "\x00\x01(\udcff)",
], ids=["depth", "open", "close", "tokens", "size", "deep-goal", "empty", "comment", "bytes"])
def test_limits_are_errors_and_quick(text: str) -> None:
    start = time.perf_counter()
    with pytest.raises(BddlError):
        parse_bddl(text)
    assert time.perf_counter() - start < 2.0


def test_nesting_up_to_the_limit_is_read() -> None:
    goal = "(:goal " + "(Not " * (MAX_DEPTH - 3) + "(On a)" + ")" * (MAX_DEPTH - 2)
    p = parse_bddl("(define (problem p) (:objects a) " + goal + ")")
    assert p.goal[0].name == "not" and list(p.goal[0].names()) == ["a"]


@FAST
@given(st.text(max_size=3000))
def test_random_text_reads_or_is_a_bddl_error(text: str) -> None:
    _reads_or_refuses(text)


SOUP = ["(", ")", "(", ")", "define", "problem", ":domain", ":language", ":regions",
        ":target", ":ranges", ":yaw_rotation", ":fixtures", ":objects", ":obj_of_interest",
        ":init", ":goal", "And", "Or", "Not", "forall", "On", "In", "-", "a", "b", "t",
        "0.5", "-1e3", "nan", "inf", "pi", "-pi/2", "pi/0", ";", "\n"]


@FAST
@given(st.lists(st.sampled_from(SOUP), max_size=400))
def test_token_soup_reads_or_is_a_bddl_error(tokens: list[str]) -> None:
    _reads_or_refuses(" ".join(tokens))


@FAST
@given(st.sampled_from(TEXTS), st.data())
def test_truncated_and_mutated_real_files_read_or_are_bddl_errors(text: str,
                                                                    data: st.DataObject) -> None:
    cut = data.draw(st.integers(0, len(text)))
    _reads_or_refuses(text[:cut])
    at = data.draw(st.integers(0, len(text)))
    width = data.draw(st.integers(0, 40))
    _reads_or_refuses(text[:at] + data.draw(st.sampled_from(SOUP)) + text[at + width:])


# Round trip ----------------------------------------------------------------------------

NAMES = st.builds(str.__add__, st.sampled_from("abcdefghijklmnopqrstuvwxyz"),
                  st.text("abcxyz019_", max_size=8))
FLOATS = st.floats(allow_nan=False, allow_infinity=False)
ATOMS = st.builds(Predicate, st.sampled_from(sorted(GOAL_PREDICATES)),
                  st.lists(NAMES, max_size=3).map(tuple))
CONDITIONS = st.recursive(ATOMS, lambda inner: st.one_of(
    st.builds(lambda c: Predicate("not", (c,)), inner),
    st.builds(lambda cs: Predicate("or", tuple(cs)), st.lists(inner, min_size=1, max_size=3)),
    st.builds(lambda cs: Predicate("and", tuple(cs)), st.lists(inner, min_size=1, max_size=3)),
), max_leaves=8)
REGIONS = st.builds(
    Region, NAMES, NAMES,
    st.lists(st.tuples(FLOATS, FLOATS, FLOATS, FLOATS), max_size=2).map(tuple),
    st.lists(st.tuples(FLOATS, FLOATS), max_size=2).map(tuple),
    st.dictionaries(st.sampled_from(["rgba", "color", "z"]), NAMES, max_size=2).map(
        lambda d: {k: f"(:{k} {v})" for k, v in d.items()}))


@st.composite
def problems(draw: st.DrawFn) -> BddlProblem:
    names = draw(st.lists(NAMES, unique=True, max_size=8))
    split = draw(st.integers(0, len(names)))
    declared = {n: draw(NAMES) for n in names}
    return BddlProblem(
        name=draw(NAMES), domain=draw(st.one_of(st.just(""), NAMES)),
        language=" ".join(draw(st.lists(st.text("Abcxyz,.'", min_size=1, max_size=6),
                                        max_size=6))),
        regions=tuple(draw(st.lists(REGIONS, max_size=4, unique_by=lambda r: r.full_name))),
        fixtures=dict(list(declared.items())[:split]),
        objects=dict(list(declared.items())[split:]),
        objects_of_interest=tuple(draw(st.lists(NAMES, max_size=3))),
        init=tuple(draw(st.lists(CONDITIONS, max_size=4))),
        goal=tuple(draw(st.lists(CONDITIONS.filter(lambda c: c.name != "and"),
                                 min_size=1, max_size=4))),
        extra={f":x_{k}": f"(:x_{k} {v})" for k, v in draw(st.dictionaries(NAMES, NAMES,
                                                                           max_size=2)).items()},
    )


@FAST
@given(problems())
def test_a_printed_problem_reads_back_equal(problem: BddlProblem) -> None:
    text = format_bddl(problem)
    assert parse_bddl(text) == problem
    assert format_bddl(parse_bddl(text)) == text
