"""LIBERO's shipped BDDL files as factask task graphs (issue 38, part 4)."""

from __future__ import annotations

import pytest

from factask.compat.libero import (
    LIBERO_KINDS,
    LiberoUnsupported,
    UnknownLiberoType,
    import_libero,
    load_bddl,
    parse_bddl,
    shipped_bddl_files,
)
from factask.compat.libero.importer import to_factask_xy
from factask.vocabulary.errors import FactaskError
from factask.vocabulary.world import WORKSPACE_X, WORKSPACE_Y

#: Every shipped file that LiberoUnsupported refuses → words its message must hold.
UNSUPPORTED = {
    "pick_up_the_black_bowl_on_the_ramekin_and_place_it_on_the_plate":
        ("glazed_rim_porcelain_ramekin_1", "not modelled"),
}
#: Files that import but whose layout the reset cannot sample → words of its failure.
RESET_FAILS = {
    # The 16 cm plate (made movable: the goal moves it) has no room in its start
    # region beside the cabinet and clear of the 19 cm goal zone (docs/libero.md).
    "push_the_plate_to_the_front_of_the_stove": "no free spot",
}
#: Files the arm completes in fewer than 3 of 4 episodes (docs/libero.md) → why.
#: (None now: the bowl next to the cookie box, 2 of 4 while the arm's wrist came down
#: on the cabinet beside it, is 4 of 4 since the arm leans out of furniture.)
ARM_BELOW_BAR: dict[str, str] = {}
FILES = {p.stem: p for p in shipped_bddl_files()}


def test_the_table_names_shipped_files():
    assert set(UNSUPPORTED) <= set(FILES)
    assert len(FILES) == 30


def test_kinds_table_covers_every_shipped_type():
    for path in FILES.values():
        problem = load_bddl(path)
        for type_name in (*problem.objects.values(), *problem.fixtures.values()):
            assert type_name in LIBERO_KINDS, (path.name, type_name)


@pytest.mark.parametrize("stem", sorted(FILES))
def test_every_shipped_file_imports_or_is_refused(stem):
    if stem in UNSUPPORTED:
        with pytest.raises(LiberoUnsupported) as info:
            import_libero(FILES[stem])
        for word in UNSUPPORTED[stem]:
            assert word in str(info.value)
        return
    result = import_libero(FILES[stem])
    graph = result.graph.ensure_valid()
    problem = result.problem
    assert graph.description == problem.language
    assert graph.name == stem.replace("_", "-")
    assert set(result.names) == {n for n, t in {**problem.objects, **problem.fixtures}.items()
                                 if LIBERO_KINDS[t].kind is not None}
    # One factor per goal predicate, and an 'open' milestone before a put into a
    # drawer that starts shut.
    assert len([f for f in graph.factors if not f.milestone]) == len(problem.goal)


def test_object_suite_goal_is_inside_the_basket():
    for path in shipped_bddl_files("libero_object"):
        graph = import_libero(path).graph
        (factor,) = graph.factors
        assert factor.goal.type == "inside" and factor.goal.container == "basket_1"


def test_coordinate_map_puts_every_region_centre_in_the_workspace():
    for path in FILES.values():
        for region in load_bddl(path).regions:
            for x0, y0, x1, y1 in region.ranges:
                x, y = to_factask_xy((x0 + x1) / 2, (y0 + y1) / 2)
                assert WORKSPACE_X[0] <= x <= WORKSPACE_X[1], (path.name, region.full_name)
                assert WORKSPACE_Y[0] <= y <= WORKSPACE_Y[1], (path.name, region.full_name)


def test_unknown_type_is_a_typed_error():
    text = FILES["put_the_bowl_on_the_plate"].read_text().replace(
        "cream_cheese_1 - cream_cheese", "cream_cheese_1 - space_heater")
    with pytest.raises(UnknownLiberoType, match="space_heater"):
        import_libero(parse_bddl(text))
    assert issubclass(UnknownLiberoType, FactaskError)


IMPORTED = sorted(set(FILES) - set(UNSUPPORTED) - set(RESET_FAILS))


def _wins(stem: str, robot: str) -> tuple[int, list[str | None]]:
    from factask.sim.episode import run_episode

    graph = import_libero(FILES[stem]).graph
    results = [run_episode(graph, seed, robot=robot) for seed in range(4)]
    return sum(r.success for r in results), [r.failure for r in results if not r.success]


@pytest.mark.parametrize("stem", IMPORTED)
def test_the_floating_oracle_completes_every_imported_file(stem):
    wins, failures = _wins(stem, "floating")
    assert wins >= 3, failures


@pytest.mark.parametrize("stem", [pytest.param(s, marks=pytest.mark.xfail(
    reason=ARM_BELOW_BAR[s], strict=False)) if s in ARM_BELOW_BAR else s for s in IMPORTED])
def test_the_arm_oracle_completes_every_imported_file(stem):
    wins, failures = _wins(stem, "arm")
    assert wins >= 3, failures


@pytest.mark.parametrize("stem", sorted(RESET_FAILS))
def test_a_file_whose_layout_cannot_be_sampled_says_why(stem):
    from factask.sim.episode import run_episode

    result = run_episode(import_libero(FILES[stem]).graph, 0)
    assert not result.success and RESET_FAILS[stem] in (result.failure or "")


def test_goals_on_fixture_tops_and_table_regions_become_on_and_in_zone():
    graph = import_libero(FILES["put_the_bowl_on_the_stove"]).graph
    (factor,) = graph.factors
    assert factor.goal.type == "on" and factor.goal.support == "flat_stove_1"
    graph = import_libero(FILES["put_the_wine_bottle_on_the_rack"]).graph
    assert graph.factors[0].goal.support == "wine_rack_1"
    result = import_libero(FILES["push_the_plate_to_the_front_of_the_stove"])
    (factor,) = result.graph.factors
    assert factor.goal.type == "in_zone"
    zone = result.graph.variable(factor.goal.zone)
    plate = result.graph.variable("plate_1")
    assert zone.kind == "zone" and not plate.fixed
    # The zone is the region's centre, grown to take the whole plate.
    assert min(zone.size[:2]) >= max(plate.size[:2])
    assert any("goal zone" in w for w in result.warnings)


def test_a_cabinets_drawer_regions_are_drawers_and_open_close_read_as_relations():
    result = import_libero(FILES["open_the_middle_drawer_of_the_cabinet"])
    graph = result.graph
    drawers = {v.name: v for v in graph.variables if v.kind == "drawer"}
    assert sorted(drawers) == ["wooden_cabinet_1_bottom_drawer",
                               "wooden_cabinet_1_middle_drawer", "wooden_cabinet_1_top_drawer"]
    assert [drawers[n].initial.level for n in sorted(drawers)] == [0, 1, 2]
    assert all(d.initial.opening == 0.0 for d in drawers.values())
    (factor,) = graph.factors
    assert factor.goal.type == "open"
    assert factor.goal.objects == ["wooden_cabinet_1_middle_drawer"]
    # The cabinet faces the robot (its drawers slide towards -x) whatever LIBERO's yaw.
    assert graph.variable("wooden_cabinet_1").initial.yaw_deg == 0.0


def test_putting_into_a_shut_drawer_opens_it_first_as_a_milestone():
    result = import_libero(FILES["open_the_top_drawer_and_put_the_bowl_inside"])
    opened, put = result.graph.factors
    assert opened.goal.type == "open" and opened.milestone
    assert opened.goal.objects == ["wooden_cabinet_1_top_drawer"]
    assert put.goal.type == "inside" and put.goal.container == "wooden_cabinet_1_top_drawer"
    assert any("milestone" in w for w in result.warnings)


def test_a_drawer_open_in_init_starts_open_with_the_bowl_inside():
    graph = import_libero(FILES["pick_up_the_black_bowl_in_the_top_drawer_of_the_wooden_"
                                "cabinet_and_place_it_on_the_plate"]).graph
    drawer = graph.variable("wooden_cabinet_1_top_drawer")
    assert drawer.initial.opening == 1.0
    bowl = graph.variable("akita_black_bowl_1").initial
    assert bowl.type == "inside" and bowl.container == "wooden_cabinet_1_top_drawer"


def test_a_goal_that_moves_a_fixture_is_refused():
    text = FILES["put_the_bowl_on_the_plate"].read_text().replace(
        "(On akita_black_bowl_1 plate_1)", "(On flat_stove_1 plate_1)")
    with pytest.raises(LiberoUnsupported, match="fixture"):
        import_libero(parse_bddl(text))


def test_cli_import_libero_and_run_load(tmp_path):
    from typer.testing import CliRunner

    from factask.cli import app
    from factask.cli.run_cmds import load_task_source

    out = tmp_path / "g.json"
    ok = CliRunner().invoke(app, ["import-libero", str(FILES["put_the_bowl_on_the_plate"]),
                                  "--out", str(out)])
    assert ok.exit_code == 0 and out.is_file(), ok.output
    refused = CliRunner().invoke(app, ["import-libero", str(FILES[next(iter(UNSUPPORTED))])])
    assert refused.exit_code == 2
    graph, extra = load_task_source(str(FILES["put_the_bowl_on_the_plate"]))
    assert graph.name == "put-the-bowl-on-the-plate" and extra is None


def test_turn_on_the_stove_is_switched_on_of_the_stoves_switch():
    graph = import_libero(FILES["turn_on_the_stove"]).graph
    (factor,) = graph.factors
    assert factor.goal.type == "switched_on" and factor.goal.objects == ["flat_stove_1_switch"]
    stove, switch = graph.variable("flat_stove_1"), graph.variable("flat_stove_1_switch")
    assert stove.kind == "stove" and stove.fixed and switch.kind == "switch"
    assert switch.initial.type == "mounted_on" and switch.initial.host == "flat_stove_1"
    assert not switch.initial.on
    # Its control strip (-x) faces the robot whatever LIBERO's yaw.
    assert stove.initial.yaw_deg == 0.0
    # A bowl on the stove's cook region is on the stove (behind its control strip).
    graph = import_libero(FILES["put_the_bowl_on_the_stove"]).graph
    assert graph.factors[0].goal.support == "flat_stove_1"
