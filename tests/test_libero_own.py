"""LIBERO import made general (issue 38): every type LIBERO registers, the region
rule, the six scenes, and a held-out-style corpus of our own BDDL files
(``tests/data/libero_own``: objects, fixtures, regions and scenes the 30
development files do not use)."""

from __future__ import annotations

from pathlib import Path

import pytest

from factask.compat.libero import (
    LIBERO_KINDS,
    BddlProblem,
    LiberoUnsupported,
    Predicate,
    Region,
    UnknownLiberoType,
    import_libero,
    load_bddl,
    shipped_bddl_files,
)
from factask.compat.libero.kinds import (
    LIBERO_SCENES,
    UnknownLiberoRegion,
    category_kind,
    libero_kind,
    region_role,
)
from factask.vocabulary.kinds import kind_spec, shape_problem
from factask.vocabulary.world import WORKSPACE_X

OWN = {p.stem: p for p in sorted((Path(__file__).parent / "data" / "libero_own")
                                 .glob("*.bddl"))}

#: Every object and fixture type LIBERO's registry holds (the keys of its
#: OBJECTS_DICT: libero/libero/envs/objects/), plus the scenes' table fixtures.
LIBERO_REGISTRY = (
    "microwave", "slide_cabinet", "window", "faucet", "basin_faucet", "short_cabinet",
    "short_fridge", "wooden_cabinet", "white_cabinet", "flat_stove",
    "rack", "white_bowl", "akita_black_bowl", "plate", "basket", "chefmate_8_frypan",
    "glazed_rim_porcelain_ramekin",
    "alphabet_soup", "bbq_sauce", "butter", "cherries", "chocolate_pudding", "cookies",
    "corn", "cream_cheese", "ketchup", "macaroni_and_cheese", "mayo", "milk",
    "orange_juice", "popcorn", "salad_dressing", "new_salad_dressing", "tomato_sauce",
    "wooden_tray", "white_storage_box", "wooden_shelf", "wooden_two_layer_shelf",
    "wine_rack", "wine_bottle", "dining_set_group", "bowl_drainer", "moka_pot",
    "black_book", "yellow_book", "red_coffee_mug", "desk_caddy", "porcelain_mug",
    "white_yellow_mug", "target_zone",
    "table", "kitchen_table", "living_room_table", "study_table", "coffee_table", "floor",
)

#: Own files the importer refuses → (error class, words its message must hold).
REFUSED = {
    "refused_put_the_mug_on_top_of_the_open_microwave": (
        LiberoUnsupported, ("microwave_1_top_side", "no roof")),
    "refused_turn_on_the_lit_stove": (LiberoUnsupported, ("Turnon flat_stove_1",
                                                          "starts switched on")),
    "refused_open_the_fridge": (LiberoUnsupported, ("short_fridge", "hinged door",
                                                    "hangs only on a microwave")),
    "refused_turn_on_the_faucet": (LiberoUnsupported, ("faucet", "push buttons",
                                                       "no faucet kind")),
    "refused_put_the_bowl_against_the_side_of_the_storage_box": (
        LiberoUnsupported, ("left_side", "side face")),
    "refused_put_the_pot_in_the_back_of_the_shelf": (UnknownLiberoRegion,
                                                     ("back_region", "wooden_shelf")),
    "refused_pick_up_the_mug": (LiberoUnsupported, ("Up red_coffee_mug_1", "no factask")),
    "refused_put_the_butter_in_the_plate_or_the_bowl": (LiberoUnsupported, ("Or",)),
    "refused_put_the_salt_in_the_basket": (UnknownLiberoType, ("salt_shaker",)),
    "refused_stack_the_white_bowl_on_the_black_bowl": (
        LiberoUnsupported, ("does not fit inside", "not modelled")),
}
IMPORTED = sorted(set(OWN) - set(REFUSED))
#: Own files the arm completes in fewer than 3 of 4 episodes → why.
ARM_BELOW_BAR = {
    "kitchen_put_the_bowl_in_the_bottom_drawer_of_the_white_cabinet":
        "the arm now opens the bottom drawer (it leans its tool out of the cabinet's "
        "face) and picks the bowl beside the cabinet, but the bowl, lowered into the "
        "drawer, catches on the handles of the drawers above (the floating cup's bowl "
        "scrapes past them) and tips over (2 of 6 episodes: 0 of 6 before the lean)",
}


def test_the_own_corpus_is_there_and_uses_new_types_and_scenes():
    assert len(OWN) >= 20 and len(IMPORTED) >= 20
    assert set(REFUSED) <= set(OWN) and set(ARM_BELOW_BAR) <= set(IMPORTED)
    dev = {t for p in shipped_bddl_files() for t in
           (*load_bddl(p).objects.values(), *load_bddl(p).fixtures.values())}
    own = {t for p in OWN.values() for t in
           (*load_bddl(p).objects.values(), *load_bddl(p).fixtures.values())}
    assert len(own - dev) >= 20
    scenes = {load_bddl(p).name.lower() for p in OWN.values()}
    assert scenes == set(LIBERO_SCENES)


def test_every_registered_type_has_a_valid_stand_in():
    assert set(LIBERO_REGISTRY) <= set(LIBERO_KINDS)
    specs = [*LIBERO_KINDS.items(), *((f"{t} (plain)", s.plain)
                                      for t, s in LIBERO_KINDS.items() if s.plain)]
    for type_name, spec in specs:
        if spec.kind is None:
            assert spec.fixture and spec.size is None, type_name
            continue
        assert spec.size is not None and spec.note, type_name
        assert shape_problem(spec.kind, spec.size) is None, (type_name, spec)
        for region, role in spec.regions:
            assert region_role(spec, region) == role
            if role == "inside":
                assert kind_spec(spec.kind).receptacle, type_name
            if role == "top":
                assert kind_spec(spec.kind).support, type_name


def test_the_category_rule_types_unregistered_names_and_only_those_it_knows():
    assert category_kind("red_soup_can").kind == "cylinder"
    assert category_kind("green_bowl").kind == "bowl"
    assert category_kind("green_bowl").color == "green"
    assert category_kind("blue_notebook").kind == "box"
    assert category_kind("plastic_tray").kind == "container"
    assert category_kind("space_heater") is None
    assert libero_kind("Akita_Black_Bowl") is LIBERO_KINDS["akita_black_bowl"]
    with pytest.raises(UnknownLiberoType, match="space_heater"):
        libero_kind("space_heater")


def test_region_roles_by_rule():
    assert region_role(LIBERO_KINDS["basket"], "contain_region") == "inside"
    assert region_role(LIBERO_KINDS["desk_caddy"], "back_contain_region") == "inside"
    # A shelf's level regions are levels of the stepped shelf, not roles.
    assert region_role(LIBERO_KINDS["wooden_shelf"], "middle_region") is None
    assert LIBERO_KINDS["wooden_shelf"].level_of("middle_region") == 1
    assert LIBERO_KINDS["wooden_shelf"].level_of("top_side") == 2
    assert LIBERO_KINDS["wooden_two_layer_shelf"].level_of("top_region") == 1
    assert LIBERO_KINDS["wooden_two_layer_shelf"].level_count == 3
    assert region_role(LIBERO_KINDS["microwave"], "heating_region") == "inside"
    assert region_role(LIBERO_KINDS["microwave"], "top_side") == "open_top"
    assert region_role(LIBERO_KINDS["microwave"].plain, "top_side") == "top"
    assert region_role(LIBERO_KINDS["short_fridge"], "upper_region") == "door"
    assert region_role(LIBERO_KINDS["flat_stove"], "cook_region") == "top"
    assert region_role(LIBERO_KINDS["white_cabinet"], "top_region") is None  # a drawer
    assert LIBERO_KINDS["white_cabinet"].drawers[-1] == "top_region"
    assert region_role(LIBERO_KINDS["wooden_shelf"], "back_region") is None


@pytest.mark.parametrize("stem", sorted(REFUSED))
def test_an_own_file_is_refused_with_its_reason(stem):
    error, words = REFUSED[stem]
    with pytest.raises(error) as info:
        import_libero(OWN[stem])
    for word in words:
        assert word in str(info.value), str(info.value)


@pytest.mark.parametrize("stem", IMPORTED)
def test_an_own_file_imports(stem):
    result = import_libero(OWN[stem])
    graph = result.graph.ensure_valid()
    assert len([f for f in graph.factors if not f.milestone]) == len(result.problem.goal)


def test_compartments_fixtures_and_drawers_of_the_own_files():
    result = import_libero(OWN["study_put_both_books_in_the_caddy"])
    assert [f.goal.container for f in result.graph.factors] == ["desk_caddy_1"] * 2
    assert sum("compartment" in w for w in result.warnings) == 2
    graph = import_libero(OWN["kitchen_put_the_moka_pot_on_the_shelf"]).graph
    (factor,) = graph.factors
    assert factor.goal.type == "on" and factor.goal.support == "wooden_shelf_1_level_2"
    assert graph.variable("wooden_shelf_1").fixed
    result = import_libero(OWN["kitchen_put_the_bowl_in_the_bottom_drawer_of_the_white_cabinet"])
    opened, put = result.graph.factors
    assert opened.milestone and opened.goal.objects == ["white_cabinet_1_bottom_drawer"]
    assert put.goal.container == "white_cabinet_1_bottom_drawer"
    assert any("drawers pulled out stay on the workspace" in w for w in result.warnings)
    # A stove that starts turned on: its switch starts on (pressed down).
    result = import_libero(OWN["kitchen_put_the_moka_pot_on_the_lit_stove"])
    assert result.graph.factors[0].goal.support == "flat_stove_1"
    assert result.graph.variable("flat_stove_1_switch").initial.on


def test_the_shelves_are_stepped_shelves_and_their_levels():
    result = import_libero(OWN["study_put_the_book_on_the_bottom_layer_of_the_shelf"])
    graph = result.graph
    shelf = graph.variable("wooden_two_layer_shelf_1")
    assert shelf.kind == "shelf" and shelf.fixed and shelf.initial.yaw_deg == 0.0
    levels = [graph.variable(f"wooden_two_layer_shelf_1_level_{k}") for k in range(3)]
    assert [v.kind for v in levels] == ["shelf_level"] * 3
    assert [v.initial.level for v in levels] == [0, 1, 2]
    assert all(v.initial.cabinet == "wooden_two_layer_shelf_1" for v in levels)
    assert levels[0].size[2] < levels[1].size[2] < levels[2].size[2]
    assert levels[1].size[2] - levels[0].size[2] >= 0.05  # real levels, 5 cm apart
    (factor,) = graph.factors
    assert factor.goal.type == "on" and factor.goal.support == "wooden_two_layer_shelf_1_level_0"
    assert any("stepped shelf" in w for w in result.warnings)
    # The shelf's footprint stays on the workspace (moved back where needed).
    x = shelf.initial.x
    assert WORKSPACE_X[0] - 1e-9 <= x - shelf.size[0] / 2
    assert x + shelf.size[0] / 2 <= WORKSPACE_X[1] + 1e-9
    # A start on a level; a move between levels.
    graph = import_libero(
        OWN["study_move_the_book_from_the_bottom_to_the_top_layer_of_the_shelf"]).graph
    assert graph.variable("black_book_1").initial.support == "wooden_two_layer_shelf_1_level_0"
    assert graph.factors[0].goal.support == "wooden_two_layer_shelf_1_level_1"
    # top_region and top_side of the wooden shelf are both its top level.
    graph = import_libero(OWN["study_put_the_mug_on_the_top_level_of_the_shelf"]).graph
    assert graph.factors[0].goal.support == "wooden_shelf_1_level_2"
    assert len([v for v in graph.variables if v.kind == "shelf_level"]) == 3


def test_the_microwave_is_a_microwave_and_its_door():
    graph = import_libero(OWN["kitchen_open_the_microwave"]).graph
    microwave, door = graph.variable("microwave_1"), graph.variable("microwave_1_door")
    assert microwave.kind == "microwave" and microwave.fixed and door.kind == "door"
    assert door.initial.cabinet == "microwave_1" and door.initial.opening == 0.0
    assert microwave.initial.yaw_deg == 0.0  # its door side (-x) faces the robot
    (factor,) = graph.factors
    assert factor.goal.type == "open" and factor.goal.objects == ["microwave_1_door"]
    # (Open microwave_1) in :init: the door starts open; (Close ...) is 'closed'.
    graph = import_libero(OWN["kitchen_close_the_open_microwave"]).graph
    assert graph.variable("microwave_1_door").initial.opening == 1.0
    assert graph.factors[0].goal.type == "closed"
    # A put into the shut microwave: an 'open' milestone of the door first; a Close
    # goal comes after the put.
    result = import_libero(OWN["kitchen_put_the_mug_in_the_microwave_and_close_it"])
    opened, put, closed = result.graph.factors
    assert opened.milestone and opened.goal.type == "open"
    assert opened.goal.objects == ["microwave_1_door"]
    assert put.goal.type == "inside" and put.goal.container == "microwave_1"
    assert closed.goal.type == "closed" and put.name in closed.after
    # Already open at the start: no milestone.
    graph = import_libero(OWN["kitchen_put_the_bowl_in_the_open_microwave"]).graph
    assert [f.goal.type for f in graph.factors] == ["inside"]
    # A file that never names the door, Open / Close or the heating region keeps the
    # plain box, whose top is a support.
    graph = import_libero(OWN["kitchen_put_the_yellow_mug_on_top_of_the_microwave"]).graph
    assert graph.variable("microwave_1").kind == "box"
    assert not any(v.kind == "door" for v in graph.variables)


def test_a_kitchen_with_the_microwave_and_the_stove():
    graph = import_libero(OWN["kitchen_heat_the_mug_in_the_microwave_and_turn_on_the_stove"]
                          ).graph
    assert [f.goal.type for f in graph.factors] == ["open", "inside", "closed", "switched_on"]
    assert {v.kind for v in graph.variables} >= {"microwave", "door", "stove", "switch"}
    graph = import_libero(OWN["kitchen_turn_off_the_stove_and_put_the_moka_pot_on_the_plate"]
                          ).graph
    assert graph.variable("flat_stove_1_switch").initial.on
    assert graph.variable("moka_pot_1").initial.support == "flat_stove_1"


def _wins(stem: str, robot: str) -> tuple[int, list[str | None]]:
    from factask.sim.episode import run_episode

    graph = import_libero(OWN[stem]).graph
    results = [run_episode(graph, seed, robot=robot) for seed in range(4)]
    return sum(r.success for r in results), [r.failure for r in results if not r.success]


@pytest.mark.parametrize("stem", IMPORTED)
def test_the_floating_oracle_completes_every_own_file(stem):
    wins, failures = _wins(stem, "floating")
    assert wins >= 3, failures


@pytest.mark.parametrize("stem", [pytest.param(s, marks=pytest.mark.xfail(
    reason=ARM_BELOW_BAR[s], strict=False)) if s in ARM_BELOW_BAR else s for s in IMPORTED])
def test_the_arm_oracle_completes_every_own_file(stem):
    wins, failures = _wins(stem, "arm")
    assert wins >= 3, failures


def _one_type_task(type_name: str) -> BddlProblem | None:
    """A small kitchen task about one registered type: a fixture with a top gets the
    butter on its top (one with only an inside, the microwave: inside it); a
    receptacle gets the butter inside (a bowl: the can of cherries); anything else (a
    ramekin too) goes into the basket (onto the plate when larger than 15 cm).
    None for the tables, zones and plates (nothing to do with them alone)."""
    spec = LIBERO_KINDS[type_name]
    if spec.kind in (None, "zone", "kit"):
        return None
    name, table = f"{type_name}_1", "kitchen_table"
    movable = "cherries" if spec.kind == "bowl" else "butter"
    if spec.fixture or (spec.fixed and not kind_spec(spec.kind).receptacle):
        tops = [r for r, role in spec.regions if role == "top"] + [r for r, _ in spec.levels]
        insides = [r for r, role in spec.regions if role == "inside"]
        if not tops and not insides:
            return None
        fixtures, objects = {name: type_name}, {"butter_1": "butter"}
        sub = (tops or insides)[0]  # a microwave: its heating region, behind its door
        goal = Predicate("on" if tops else "in", ("butter_1", f"{name}_{sub}"))
    elif kind_spec(spec.kind).receptacle and max(spec.size or (0.0,)) >= 0.10:
        inside = next(r for r, role in spec.regions if role == "inside")
        fixtures, objects = {}, {name: type_name, f"{movable}_1": movable}
        goal, sub = Predicate("in", (f"{movable}_1", f"{name}_{inside}")), inside
    else:
        host = "plate_1" if max(spec.size or (0.0,)) > 0.15 else "basket_1"
        fixtures, objects = {}, {name: type_name, host: host[:-2]}
        sub = "contain_region"
        goal = (Predicate("on", (name, host)) if host == "plate_1" else
                Predicate("in", (name, "basket_1_contain_region")))
    places = dict(zip(objects if not fixtures else [*fixtures, *objects],
                      ((-0.1, -0.2), (0.1, 0.2)), strict=False))
    regions = [Region(f"{n}_init", table, ((x - 0.01, y - 0.01, x + 0.01, y + 0.01),))
               for n, (x, y) in places.items()]
    target = name if goal.args[1].startswith(name) else "basket_1"
    regions.append(Region(sub, target))
    return BddlProblem(
        "LIBERO_Kitchen_Tabletop_Manipulation", "robosuite", f"{goal}", tuple(regions),
        {table: table, **fixtures}, objects, (),
        tuple(Predicate("on", (n, f"{table}_{n}_init")) for n in places), (goal,))


@pytest.mark.parametrize("type_name", sorted(t for t in LIBERO_KINDS if _one_type_task(t)))
def test_every_registered_type_imports_and_the_floating_cup_completes_a_task_with_it(
        type_name):
    from factask.sim.episode import run_episode

    problem = _one_type_task(type_name)
    graph = import_libero(problem, name=type_name.replace("_", "-")).graph
    results = [run_episode(graph, seed, robot="floating") for seed in range(2)]
    assert all(r.success for r in results), [r.failure for r in results]


def test_the_low_tables_of_the_living_room_and_coffee_table_map_nearer_the_robot():
    from factask.compat.libero.importer import LOW_TABLE_OFFSET_X, OFFSET_X, to_factask_xy
    from factask.vocabulary.world import WORKSPACE_X

    assert to_factask_xy(0.0, 0.0, LOW_TABLE_OFFSET_X)[0] < to_factask_xy(0.0, 0.0)[0]
    # The 0.70 m deep table's whole depth lands on (about) the workspace.
    near, far = (to_factask_xy(x, 0.0, LOW_TABLE_OFFSET_X)[0] for x in (-0.35, 0.35))
    assert near >= WORKSPACE_X[0] - 0.02 and far <= WORKSPACE_X[1] + 0.02
    assert OFFSET_X == 0.58
    graph = import_libero(OWN["living_room_put_the_far_tomato_sauce_in_the_near_basket"]).graph
    start = graph.variable("tomato_sauce_1").initial
    assert start.x[1] <= WORKSPACE_X[1] and start.x[0] > 0.6
