"""The task library: templates, tasks, and the `list` / `show` commands."""

from __future__ import annotations

import difflib
import json
from itertools import pairwise
from pathlib import Path

import pytest
from helpers import GENSIM_TASKS as GENSIM
from typer.testing import CliRunner

from factask.cli.app import app
from factask.graph import (
    CompositionError,
    On,
    StartInside,
    StartOn,
    TaskGraph,
    compose,
    kind_spec,
    parse_graph,
)
from factask.library import (
    TASKS,
    TEMPLATES,
    UnknownTaskError,
    get_task,
    get_template,
    list_tasks,
    match_pairs,
    task_names,
)
from factask.library.builders import var
from factask.library.tags import matches_tags, reuse_stats, task_tags
from factask.vocabulary.world import WORKSPACE_X, WORKSPACE_Y

REQUIRED = [
    "place-red-in-green", "stack-block-pyramid", "stack-block-pyramid-seq", "towers-of-hanoi",
    "align-box-corner", "block-insertion", "palletizing-boxes", "packing-boxes",
    "put-block-in-bowl", "build-bridge", "build-car", "build-house",
    "stack-blocks-in-container", "color-coordinated-cylinder-tower",
    "color-sorted-container-stack", "multi-level-block-construction",
    "sort-and-assemble-block-castle", "align-pair-colored-blocks-along-line",
    "insertion-in-color-sequenced-zones", "stack-boxes-column", "place-box-in-pallet",
]

runner = CliRunner()


@pytest.fixture(scope="module")
def graphs() -> dict[str, TaskGraph]:
    return {name: get_task(name) for name in task_names()}


@pytest.fixture(scope="module")
def gensim_names() -> set[str]:
    if not GENSIM.exists():
        pytest.skip("gensim_tasks.json not available")
    return {t["name"] for t in json.loads(GENSIM.read_text())}


# --------------------------------------------------------------------- registry
def test_at_least_30_tasks_and_the_required_ones() -> None:
    assert len(TASKS) >= 30
    missing = [n for n in REQUIRED if n not in TASKS]
    assert not missing


def test_task_names_sorted_and_match_registry() -> None:
    # sorted as a reader sorts: the capital of Four-corner-pyramid-challenge does not
    # put it first (issue 37, item 15)
    assert task_names() == sorted(TASKS, key=lambda n: (n.casefold(), n))


def test_required_names_are_spelled_as_in_gensim(gensim_names: set[str]) -> None:
    # Every required name except the library's own stack-boxes-column is a GenSim task.
    assert [n for n in REQUIRED if n not in gensim_names] == ["stack-boxes-column"]


def test_no_task_name_is_a_misspelled_gensim_name(gensim_names: set[str]) -> None:
    for name in TASKS:
        if name in gensim_names:
            continue
        near = difflib.get_close_matches(name, gensim_names, n=1, cutoff=0.9)
        assert not near, f"{name!r} looks like GenSim's {near[0]!r}; spell it exactly"


def test_unknown_task_suggests_close_names() -> None:
    with pytest.raises(UnknownTaskError) as info:
        get_task("tower-of-hanoi")
    assert "towers-of-hanoi" in info.value.suggestions
    assert "towers-of-hanoi" in str(info.value)


def test_list_tasks_summaries(graphs: dict[str, TaskGraph]) -> None:
    infos = {i.name: i for i in list_tasks()}
    assert set(infos) == set(TASKS)
    g = graphs["build-house"]
    info = infos["build-house"]
    assert (info.n_variables, info.n_factors) == (len(g.variables), len(g.factors))
    assert info.templates == ("build_row", "layer_on_row", "place_on_top")
    assert info.to_dict()["templates"] == list(info.templates)


# ------------------------------------------------------------------------ tasks
def test_every_task_validates_and_round_trips(graphs: dict[str, TaskGraph]) -> None:
    for name, g in graphs.items():
        assert g.name == name
        assert g.problems() == []
        again = parse_graph(g.to_json())
        assert again == g, name
        assert again.to_json() == g.to_json()


def test_descriptions_are_filled_in(graphs: dict[str, TaskGraph]) -> None:
    for name, g in graphs.items():
        assert g.description.strip(), name
        for f in g.factors:
            assert f.description.strip(), (name, f.name)
            assert "{" not in f.description and "{" not in f.initial_setup, (name, f.name)
        for v in g.variables:
            assert v.description.strip(), (name, v.name)


def test_tasks_are_built_from_templates(graphs: dict[str, TaskGraph]) -> None:
    local: dict[str, set[str]] = {}  # a template one task uses lives in its catalog
    for name, g in graphs.items():
        assert g.factors, name
        for f in g.factors:
            assert f.template is not None, (name, f.name)
            if f.template not in TEMPLATES:
                local.setdefault(f.template, set()).add(name)
    assert all(len(users) == 1 for users in local.values()), local


def test_tasks_fit_the_workspace_and_the_oracle(graphs: dict[str, TaskGraph]) -> None:
    area = (WORKSPACE_X[1] - WORKSPACE_X[0]) * (WORKSPACE_Y[1] - WORKSPACE_Y[0])
    for name, g in graphs.items():
        # Piles and ropes are pushed or dragged as a whole, not carried one object per
        # action: the budget counts the objects a suction oracle carries (sixteen: GenSim's
        # largest rigid task stacks sixteen blocks; its reset took 0.2 s and an mj_step
        # 51 us at rest, against 41-49 us for twelve objects).
        carried = sum(v.count for v in g.variables
                      if not v.is_fixed and v.kind not in ("pile", "rope"))
        assert carried <= 16, name
        footprint = 0.0
        for v in g.variables:
            sx, sy, sz = v.extents
            assert sx <= 0.35 and sy <= 0.35 and sz <= 0.3, (name, v.name)
            if not v.is_fixed:
                assert max(sx, sy) <= 0.15, (name, v.name)  # a suction cup can carry it
            # A drawer lies inside its cabinet's footprint (in front of it when open,
            # where the layout keeps the table clear), a switch inside its host's, a
            # shelf's level inside its shelf's.
            if kind_spec(v.kind).collides and v.kind not in ("drawer", "switch",
                                                             "shelf_level"):
                footprint += sx * sy * v.count
        # Leave most of the table free so initial layouts can be sampled.
        assert footprint < 0.35 * area, (name, footprint)


def test_every_template_used_by_two_tasks_with_different_bindings(
    graphs: dict[str, TaskGraph],
) -> None:
    bindings: dict[str, dict[str, frozenset]] = {t: {} for t in TEMPLATES}
    for name, g in graphs.items():
        for f in g.factors:
            if f.template not in bindings:  # a task's own template, not a shared one
                continue
            sig = (tuple(f.scope_names), tuple(g.variable(v).kind for v in f.scope_names))
            bindings[f.template].setdefault(name, frozenset())
            bindings[f.template][name] |= {sig}
    for template, per_task in bindings.items():
        assert len(per_task) >= 2, f"template {template} used by {sorted(per_task)}"
        assert len(set(per_task.values())) >= 2, f"template {template}: same bindings"


def test_towers_of_hanoi_starts_stacked_and_restacks_in_order(
    graphs: dict[str, TaskGraph],
) -> None:
    g = graphs["towers-of-hanoi"]
    disks = sorted((v for v in g.variables if v.kind == "cylinder"),
                   key=lambda d: -d.extents[0])
    assert len(disks) == 3 and len({d.extents[0] for d in disks}) == 3
    assert all(0.015 <= d.extents[2] <= 0.02 for d in disks)
    # Largest on a stand, each smaller one on the previous.
    assert isinstance(disks[0].initial, StartOn)
    start = g.variable(disks[0].initial.support)
    assert start.kind == "stand"
    for lower, upper in pairwise(disks):
        assert isinstance(upper.initial, StartOn) and upper.initial.support == lower.name
    # Seven moves, one disk each, in a chain; the final ones rebuild the stack on
    # the goal stand (largest at the bottom); the moves a later move undoes are
    # milestones.
    assert len(g.factors) == 7 and g.factor_order() == g.factor_names()
    assert all(isinstance(f.goal, On) and len(f.goal.objects) == 1 for f in g.factors)
    final = {f.goal.objects[0]: f.goal.support for f in g.factors if not f.milestone}
    large, medium, small = (d.name for d in disks)
    assert final[medium] == large and final[small] == medium
    goal_stand = g.variable(final[large])
    assert goal_stand.kind == "stand" and goal_stand.name != start.name
    last_move = {f.goal.objects[0]: f.name for f in g.factors}
    assert [f.name for f in g.factors if not f.milestone] == sorted(
        last_move.values(), key=g.factor_names().index)


def test_pyramid_seq_has_explicit_order_the_plain_one_not(
    graphs: dict[str, TaskGraph],
) -> None:
    seq = graphs["stack-block-pyramid-seq"]
    assert [len(f.after) for f in seq.factors] == [0, 1, 1]
    assert all(not f.after for f in graphs["stack-block-pyramid"].factors)
    # Both pyramids are 3-2-1 rows resting on the layer below.
    for g in (seq, graphs["stack-block-pyramid"]):
        counts = [g.variable(f.goal.objects[0]).count for f in g.factors]
        assert counts == [3, 2, 1]
        assert [f.goal.type for f in g.factors] == ["row", "row", "row"]


def test_stack_boxes_column(graphs: dict[str, TaskGraph]) -> None:
    g = graphs["stack-boxes-column"]
    (f,) = g.factors
    assert f.goal.type == "stack" and f.goal.base is None
    assert sum(g.variable(o).count for o in f.goal.objects) == 3
    assert all(g.variable(o).extents == (0.07, 0.07, 0.07) for o in f.goal.objects)


def test_bridge_decks_rest_on_two_pillars(graphs: dict[str, TaskGraph]) -> None:
    for name in ("build-bridge", "construct-colorful-arch", "build-car"):
        g = graphs[name]
        deck = next(f for f in g.factors if f.name.startswith("deck_"))
        pillars = g.variable(deck.goal.support)
        assert pillars.count == 2
        # The deck must span the pillar gap with room to rest on both.
        span = deck.goal.objects[0]
        assert g.variable(span).extents[0] >= 0.12, name
        assert deck.name in g.factor_order()[1:]


def test_stacked_receptacles_start_nested_and_are_unstacked_before_sorting(
    graphs: dict[str, TaskGraph],
) -> None:
    for name in ("container-block-sorting", "color-coordinated-block-bowl-sorting"):
        g = graphs[name]
        hosts = [v for v in g.variables if v.kind in ("container", "bowl")]
        assert len(hosts) == 4 and not any(v.is_fixed for v in hosts), name
        nested = [v for v in hosts if isinstance(v.initial, StartInside)]
        assert len(nested) == 2, name
        for inner in nested:  # each fits inside its host with room for the cup's rim
            outer = g.variable(inner.initial.container)
            assert outer.extents[0] - inner.extents[0] >= 0.04, name
        unstack, *sort = g.factor_order()
        assert g.factor(unstack).goal.type == "row" and len(sort) == 4, name
        assert all(g.factor(f).goal.type == "inside" and unstack in g.factor(f).after
                   for f in sort), name
    assert "moves-receptacle" in task_tags("move-bowl-from-pallet-to-corner",
                                           graphs["move-bowl-from-pallet-to-corner"])


def test_sequenced_tasks_chain_their_factors(graphs: dict[str, TaskGraph]) -> None:
    for name in ("insertion-in-color-sequenced-zones", "color-coordinated-insertion"):
        g = graphs[name]
        for prev, f in pairwise(g.factors):
            assert f.after == [prev.name], name
        assert "red" in g.factor_order()[0]


def test_docs_list_every_task_and_template() -> None:
    doc = Path(__file__).resolve().parents[1] / "docs" / "library.md"
    text = doc.read_text()
    for name in [*TASKS, *TEMPLATES]:
        assert f"`{name}`" in text, name
    assert (doc.parent / "img" / "stack-block-pyramid-graph.png").exists()


# -------------------------------------------------------------------- templates
def test_at_least_12_templates_and_lookup() -> None:
    assert len(TEMPLATES) >= 12
    assert get_template("bridge") is TEMPLATES["bridge"]
    with pytest.raises(CompositionError) as info:
        get_template("brigde")
    assert "bridge" in str(info.value)


def test_template_descriptions_read_as_goals() -> None:
    red = var("red_block", "block", "red", (0.04, 0.04, 0.04))
    bowl = var("green_bowl", "bowl", "green", (0.12, 0.12, 0.05))
    frag = TEMPLATES["put_in_container"].instantiate(objects=red, container=bowl)
    assert frag.factors[0].description == "put the red block into the green bowl"
    with pytest.raises(CompositionError):  # a bowl cannot be moved into a block
        TEMPLATES["put_in_container"].instantiate(objects=bowl, container=red)


def test_match_pairs_sequential_chain_composes() -> None:
    blocks = [var(f"{c}_block", "block", c, (0.04, 0.04, 0.04)) for c in ("red", "blue")]
    zones = [var(f"{c}_zone", "zone", c, (0.12, 0.12, 0.001)) for c in ("red", "blue")]
    frags = match_pairs("place_in_zone", list(zip(blocks, zones, strict=True)),
                        sequential=True)
    g = compose(*frags, name="sort-two").ensure_valid()
    assert g.factor_order() == ["in_zone_red_block", "in_zone_blue_block"]
    assert g.factors[1].after == ["in_zone_red_block"]
    assert sum(f.weight for f in g.factors) == pytest.approx(1.0)


# ------------------------------------------------------------------ tags, reuse
def test_tags_are_read_off_the_graph(graphs: dict[str, TaskGraph]) -> None:
    hanoi = task_tags("towers-of-hanoi", graphs["towers-of-hanoi"])
    assert hanoi[0] == "family:stacking"
    assert {"objects:3", "relation:on", "sequenced", "milestones", "starts-stacked",
            "origin:ravens"} <= set(hanoi)
    assert "needs-arm-reach" not in hanoi  # three thin disks stay low
    tower = set(task_tags("rainbow-stack", graphs["rainbow-stack"]))
    assert {"relation:stack", "needs-arm-reach", "origin:gensim"} <= tower
    assert "origin:factask" in task_tags("stack-boxes-column", graphs["stack-boxes-column"])
    put = set(task_tags("put-block-in-bowl", graphs["put-block-in-bowl"]))
    assert "distractors" in put and "sequenced" not in put
    for name, g in graphs.items():
        tags = task_tags(name, g)
        assert len(tags) == len(set(tags)), name
        for f in g.factors:
            assert f"relation:{f.goal.type}" in tags, (name, f.name)


def test_matches_tags_bare_values_and_all_of() -> None:
    tags = ("family:stacking", "objects:3", "sequenced")
    assert matches_tags(tags, [])
    assert matches_tags(tags, ["stacking", "objects:3"])
    assert not matches_tags(tags, ["stacking", "milestones"])
    assert not matches_tags(tags, ["family:placing"])


def test_reuse_figure_counts_factors_of_shared_templates(
    graphs: dict[str, TaskGraph],
) -> None:
    stats = reuse_stats(graphs)
    assert stats.tasks == len(graphs)
    assert stats.factors == sum(len(g.factors) for g in graphs.values())
    assert stats.reuse >= 0.8
    # A template used by one task only does not count as shared.
    one = {"towers-of-hanoi": graphs["towers-of-hanoi"]}
    assert reuse_stats(one).shared == 0 and reuse_stats(one).factors == 7


def test_cli_list_tag_filters_and_stats_prints_reuse() -> None:
    result = runner.invoke(app, ["list", "--json", "--tag", "family:stacking,sequenced"])
    assert result.exit_code == 0, result.output
    names = [d["name"] for d in json.loads(result.stdout)]
    assert "towers-of-hanoi" in names and "put-block-in-bowl" not in names
    assert all({"family:stacking", "sequenced"} <= set(d["tags"]) for d in
               json.loads(result.stdout))
    stats = runner.invoke(app, ["list", "--stats", "--tag", "insertion"],
                          env={"COLUMNS": "200"})
    assert stats.exit_code == 0, stats.output
    assert "subtask reuse" in stats.stdout and "block-insertion" in stats.stdout
    figure = reuse_stats({n: get_task(n) for n in task_names()}).reuse
    assert f"{100 * figure:.1f} %" in stats.stdout


# -------------------------------------------------------------------------- CLI
def test_cli_list_json() -> None:
    result = runner.invoke(app, ["list", "--json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert [d["name"] for d in data] == task_names()
    assert all(d["n_factors"] >= 1 and d["templates"] for d in data)


def test_cli_list_table() -> None:
    result = runner.invoke(app, ["list"], env={"COLUMNS": "200"})
    assert result.exit_code == 0, result.output
    assert "towers-of-hanoi" in result.stdout and "stack_on_base" in result.stdout


def test_cli_show_json_is_accepted_by_validate() -> None:
    shown = runner.invoke(app, ["show", "build-bridge", "--json"])
    assert shown.exit_code == 0, shown.output
    assert shown.stdout.strip() == get_task("build-bridge").to_json()
    checked = runner.invoke(app, ["validate", "-"], input=shown.stdout)
    assert checked.exit_code == 0, checked.output
    assert "valid" in checked.stdout


def test_cli_show_pretty_lists_goals_in_order() -> None:
    result = runner.invoke(app, ["show", "build-house"], env={"COLUMNS": "200"})
    assert result.exit_code == 0, result.output
    out = result.stdout
    assert "put the green chimney on top of the yellow roof" in out
    assert out.index("row_red_base_blocks") < out.index("on_top_green_chimney")


def test_cli_show_png(tmp_path: Path) -> None:
    png = tmp_path / "g.png"
    result = runner.invoke(app, ["show", "towers-of-hanoi", "--png", str(png)])
    assert result.exit_code == 0, result.output
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_cli_show_unknown_task_exits_2_with_suggestions() -> None:
    result = runner.invoke(app, ["show", "build-brige"])
    assert result.exit_code == 2
    assert "build-bridge" in result.output
