"""The data: every object and fixture type LIBERO registers, and every scene
(problem class), with their factask stand-ins.

Facts read from LIBERO's source (MIT licence): the types are the keys of LIBERO's
object registry (``libero/libero/envs/objects/``: the HOPE groceries, the Google
scanned dishes, the TurboSquid furniture and the articulated fixtures; a class
``Chefmate8Frypan`` is the type ``chefmate_8_frypan``), the regions are the sites
of each asset's XML (``contain_region``, ``top_side``, ``heating_region``, the
shelf levels, the caddy's compartments), the scenes are the problem classes of
``libero/libero/envs/problems/`` with their table sizes. Sizes are real-ish sizes of
the real things (full extents, metres), read off the asset's sites where they say
it (the cabinets' top boards, the caddy's compartments, the
microwave's top), else a typical size of the grocery or dish.
"""

from __future__ import annotations

from dataclasses import dataclass

from factask.compat.libero.spec import (
    LiberoKind,
    bowl,
    box,
    cabinet,
    can,
    container,
    fixed_box,
    scene_table,
    shelf,
)

TYPES: dict[str, LiberoKind] = {
    # ---- the scenes' tables and the floor: factask's table -------------------------
    "table": scene_table("the main table (tabletop and kitchen scenes)"),
    "kitchen_table": scene_table("the kitchen scene's table"),
    "living_room_table": scene_table("the living room scene's table"),
    "study_table": scene_table("the study scene's table"),
    "coffee_table": scene_table("the coffee table scene's table"),
    "floor": scene_table("the floor scene's ground: the table"),
    "target_zone": LiberoKind("zone", (0.10, 0.10, 0.001), "gray", fixed=True,
                              note="LIBERO's flat target zone marker", category="zone"),
    # ---- articulated fixtures --------------------------------------------------------
    "flat_stove": LiberoKind("stove", (0.23, 0.20, 0.03), "silver", fixed=True, fixture=True,
                             note="flat stove: factask's stove, its cook region the top "
                                  "behind the control strip; its knob is the stove's "
                                  "push-button switch (Turnon / Turnoff: switched_on / "
                                  "switched_off)",
                             regions=(("cook_region", "top"), ("top_side", "top")),
                             category="fixture"),
    "wooden_cabinet": cabinet((0.22, 0.24, 0.27), "brown",
                              "wooden cabinet: a cabinet of three drawers (its bottom, "
                              "middle and top regions) whose top side things can stand on"),
    "white_cabinet": cabinet((0.22, 0.24, 0.27), "white",
                             "white cabinet (the wooden cabinet's model in white): three "
                             "drawers, its top side a support"),
    "short_cabinet": cabinet((0.20, 0.22, 0.24), "tan",
                             "short cabinet: a low cabinet of three drawers (its bottom, "
                             "middle and top regions)"),
    "microwave": LiberoKind("microwave", (0.20, 0.24, 0.15), "silver", fixed=True,
                            fixture=True,
                            note="microwave: factask's microwave (open at its door side "
                                 "and, for top-down cups, at the top; its heating region "
                                 "is its inside) and its hinged door (Open / Close)",
                            regions=(("heating_region", "inside"), ("top_side", "open_top")),
                            category="fixture",
                            plain=fixed_box((0.20, 0.26, 0.21), "silver",
                                            "microwave (its door unused by the file): a "
                                            "fixed box, its top side a support",
                                            regions=(("top_side", "top"),))),
    "short_fridge": fixed_box((0.26, 0.26, 0.30), "white",
                              "short fridge: a fixed box; its shelves are behind a "
                              "hinged door",
                              regions=(("top_side", "top"), ("upper_region", "door"),
                                       ("middle_region", "door"), ("lower_region", "door")),
                              articulation="hinged door (factask's door hangs only on "
                                           "a microwave, one chamber; the fridge's three "
                                           "shelves behind it are not modelled)"),
    "slide_cabinet": fixed_box((0.20, 0.26, 0.24), "tan",
                               "slide cabinet: a fixed box (its sliding door is not "
                               "modelled)",
                               articulation="sliding door (factask has drawers and "
                                            "hinged doors, no sliding door)"),
    "window": fixed_box((0.04, 0.20, 0.20), "gray", "window: a fixed panel",
                        regions=(), articulation="sliding sash (no factask kind slides "
                                                 "a panel sideways)"),
    "faucet": fixed_box((0.06, 0.06, 0.15), "silver", "faucet: a fixed post",
                        regions=(), articulation="handle turned on and off (factask's "
                                                 "switches are push buttons on a stove "
                                                 "or a lamp; no faucet kind)"),
    "basin_faucet": fixed_box((0.06, 0.10, 0.12), "silver", "basin faucet: a fixed post",
                              regions=(), articulation="handle turned on and off (factask's "
                                                 "switches are push buttons on a stove "
                                                 "or a lamp; no faucet kind)"),
    # ---- furniture (TurboSquid) ----------------------------------------------------
    "wine_rack": fixed_box((0.12, 0.20, 0.09), "tan",
                           "wine rack: a fixed low box (no slots); 9 cm high, so that the "
                           "cabinet's middle drawer slides out over it (the 0.75 map "
                           "puts the rack 4 cm in front of the cabinet)",
                           regions=(("top_region", "top"), ("top_side", "top"))),
    "wooden_shelf": shelf((0.44, 0.25, 0.20), "brown",
                          "wooden shelf: LIBERO's three stacked levels (19 cm deep) as "
                          "factask's stepped shelf of three levels rising away from the "
                          "robot, 44 cm deep so that each step (14.3 cm) holds a bowl; its top "
                          "board (top_side) is the top level",
                          levels=(("bottom_region", 0), ("middle_region", 1),
                                  ("top_region", 2), ("top_side", 2))),
    "wooden_two_layer_shelf": shelf((0.44, 0.35, 0.20), "brown",
                                    "wooden two-layer shelf: its two layers and its top "
                                    "board as factask's stepped shelf of three levels "
                                    "rising away from the robot (bottom layer, top layer, "
                                    "top board), 44 cm deep so that each step (14.3 cm) holds a "
                                    "bowl",
                                    levels=(("bottom_region", 0), ("top_region", 1),
                                            ("top_side", 2))),
    "rack": fixed_box((0.20, 0.14, 0.04), "silver", "simple dish rack: a fixed low box",
                      regions=(("top_side", "top"), ("top_region", "top"))),
    "dining_set_group": LiberoKind("kit", (0.20, 0.20, 0.02), "white", fixed=True,
                                   note="dining set group: a flat support; its centre "
                                        "region is its top",
                                   regions=(("center_region", "top"),), category="plate"),
    "desk_caddy": container((0.14, 0.40, 0.10), "brown",
                            "desk caddy: one open container 14 x 40 cm (LIBERO's four "
                            "compartments, left, right, front and back, are one inside)",
                            inside=("left_contain_region", "right_contain_region",
                                    "front_contain_region", "back_contain_region",
                                    "contain_region")),
    "bowl_drainer": container((0.14, 0.24, 0.08), "silver",
                              "bowl drainer: one open container (its left and right "
                              "regions are one inside)",
                              inside=("left_region", "right_region", "contain_region")),
    "wooden_tray": container((0.18, 0.28, 0.04), "brown", "wooden tray: a shallow open "
                             "container"),
    "white_storage_box": LiberoKind("box", (0.135, 0.12, 0.14), "white", fixed=True,
                                    note="white storage box: a fixed box, its top side a "
                                         "support",
                                    regions=(("top_side", "top"), ("bottom_side", "side"),
                                             ("left_side", "side"), ("right_side", "side")),
                                    category="box"),
    # ---- dishes (Google scanned) ---------------------------------------------------
    "akita_black_bowl": bowl((0.12, 0.12, 0.05), "black", "black bowl, 12 cm across"),
    "white_bowl": bowl((0.13, 0.13, 0.05), "white", "white bowl, 13 cm across"),
    "red_bowl": bowl((0.12, 0.12, 0.05), "red", "red bowl, 12 cm across"),
    "glazed_rim_porcelain_ramekin": bowl((0.09, 0.09, 0.045), "white",
                                         "ramekin: a small bowl"),
    "chefmate_8_frypan": bowl((0.18, 0.18, 0.045), "black",
                              "8-inch frying pan: a wide shallow bowl (no handle)"),
    "plate": LiberoKind("kit", (0.16, 0.16, 0.01), "white", fixed=True,
                        note="plate: factask's flat plate (kit), square, fixed",
                        category="plate"),
    "basket": container((0.24, 0.17, 0.08), "brown", "basket: an open fixed container"),
    # ---- mugs and pots (TurboSquid) ------------------------------------------------
    "red_coffee_mug": can(0.08, 0.09, "red", "red coffee mug (no handle)", "mug"),
    "porcelain_mug": can(0.08, 0.09, "white", "porcelain mug (no handle)", "mug"),
    "white_yellow_mug": can(0.08, 0.09, "yellow", "white and yellow mug (no handle)", "mug"),
    "moka_pot": can(0.08, 0.13, "silver", "moka pot (no handle)", "pot"),
    # ---- books ---------------------------------------------------------------------
    "black_book": box((0.10, 0.15, 0.03), "black", "black book, lying flat, its long side "
                    "across (y: it fits a shelf's step and the caddy so)", "book"),
    "yellow_book": box((0.10, 0.15, 0.03), "yellow", "yellow book, lying flat, its long side "
                    "across (y: it fits a shelf's step and the caddy so)", "book"),
    # ---- food boxes and packs (HOPE) -----------------------------------------------
    "cookies": box((0.14, 0.08, 0.05), "orange", "cookie box, lying flat"),
    "cream_cheese": box((0.075, 0.045, 0.03), "silver", "cream cheese pack"),
    "butter": box((0.10, 0.05, 0.04), "yellow", "butter pack"),
    "chocolate_pudding": box((0.09, 0.06, 0.03), "brown", "chocolate pudding mix box"),
    "popcorn": box((0.12, 0.09, 0.04), "red", "popcorn box, lying flat"),
    "macaroni_and_cheese": box((0.12, 0.08, 0.035), "blue",
                               "macaroni and cheese box, lying flat"),
    # ---- cans, bottles, jars, cartons: upright cylinders (HOPE, TurboSquid) --------
    "alphabet_soup": can(0.066, 0.10, "red", "alphabet soup can"),
    "tomato_sauce": can(0.066, 0.085, "maroon", "tomato sauce can"),
    "cherries": can(0.066, 0.085, "red", "can of cherries"),
    "corn": can(0.066, 0.085, "yellow", "can of corn"),
    "ketchup": can(0.055, 0.15, "pink", "ketchup bottle", "bottle"),
    "bbq_sauce": can(0.055, 0.15, "brown", "barbecue sauce bottle", "bottle"),
    "salad_dressing": can(0.05, 0.16, "green", "salad dressing bottle", "bottle"),
    "new_salad_dressing": can(0.05, 0.16, "lime", "salad dressing bottle (new label)",
                              "bottle"),
    "mayo": can(0.065, 0.11, "white", "mayonnaise jar", "jar"),
    "milk": can(0.065, 0.15, "white", "milk carton, as an upright cylinder", "carton"),
    "orange_juice": can(0.065, 0.15, "orange", "orange juice carton, as an upright "
                        "cylinder", "carton"),
    "wine_bottle": can(0.075, 0.30, "olive", "wine bottle", "bottle"),
}


@dataclass(frozen=True)
class LiberoScene:
    """One LIBERO scene: a problem class and its table.

    Attributes:
        problem: The problem's name as a BDDL file writes it, lower-cased
            (``libero_kitchen_tabletop_manipulation``).
        table: The fixture type of its table (``kitchen_table``; ``floor``).
        table_size: LIBERO's table, (depth x, width y) in metres.
        note: What the scene is.
    """

    problem: str
    table: str
    table_size: tuple[float, float]
    note: str


#: Every scene LIBERO registers (``libero/libero/envs/problems/``), by problem name.
SCENES: dict[str, LiberoScene] = {s.problem: s for s in (
    LiberoScene("libero_tabletop_manipulation", "table", (1.0, 1.2),
                "the plain tabletop scene (main_table)"),
    LiberoScene("libero_kitchen_tabletop_manipulation", "kitchen_table", (1.0, 1.2),
                "the kitchen: its table, stoves, cabinets, microwave"),
    LiberoScene("libero_living_room_tabletop_manipulation", "living_room_table", (0.70, 1.6),
                "the living room: a low 0.70 x 1.6 m table"),
    LiberoScene("libero_study_tabletop_manipulation", "study_table", (1.0, 1.2),
                "the study: its table (centred 0.2 m nearer the robot), shelves, caddy"),
    LiberoScene("libero_coffee_table_manipulation", "coffee_table", (0.70, 1.6),
                "the coffee table scene: a low 0.70 x 1.6 m table"),
    LiberoScene("libero_floor_manipulation", "floor", (1.0, 1.2),
                "the floor scene: things on the ground, the robot on it"),
)}
