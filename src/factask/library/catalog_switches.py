"""Library tasks with switchable fixtures: stoves (and a lamp) switched on and off.

A stove stands fixed on the table; its switch is a variable of its own, a push
button that starts ``mounted_on`` it, off (up) or on (pressed down)
(:mod:`factask.scene.switch`). The robot switches it on by pressing the button
down with the cup and off by holding it and pulling it back up
(:mod:`factask.sim.robots.switch_press`). The button stands on the stove's control
strip, which ``on`` keeps clear (:func:`~factask.scene.objects.placement_area`), so
it stays reachable whether a pot is put on the stove before or after.
"""

from __future__ import annotations

from factask.graph import MountedOn, StateVariable, TaskGraph
from factask.library.builders import assemble, register, start_on, use, var
from factask.library.conventions import BLOCK, BOWL

#: A zone wide enough for a pot (a 12 cm bowl) set down within the oracle's aim.
WIDE_ZONE = (0.18, 0.18, 0.001)


def stove(name: str = "stove", on: bool = False, color: str = "gray",
          kind: str = "stove") -> tuple[StateVariable, StateVariable]:
    """A switchable fixture variable and its switch (``<name>_switch``).

    Args:
        name: The fixture's variable name.
        on: Whether its switch starts on (pressed down).
        color: The fixture's colour (the button is red).
        kind: A switchable kind (``stove``, ``lamp``).

    Returns:
        The fixture and its switch.
    """
    host = var(name, kind, color, description=f"the {name.replace('_', ' ')}")
    switch = var(f"{name}_switch", "switch", "red",
                 description=f"the switch of the {name.replace('_', ' ')}",
                 initial=MountedOn(host=name, on=on))
    return host, switch


@register("turn-on-stove")
def turn_on_stove() -> TaskGraph:
    host, switch = stove()
    return assemble("turn-on-stove", "Turn on the stove.",
                    use("switch_on", switch=switch), extra=[host])


@register("turn-off-stove")
def turn_off_stove() -> TaskGraph:
    host, switch = stove(on=True)
    return assemble("turn-off-stove", "Turn off the stove.",
                    use("switch_off", switch=switch), extra=[host])


@register("turn-on-stove-and-put-pot-on-it")
def turn_on_stove_and_put_pot_on_it() -> TaskGraph:
    host, switch = stove()
    pot = var("blue_pot", "bowl", "blue", BOWL, fixed=False, description="the blue pot")
    on = use("switch_on", switch=switch)
    return assemble("turn-on-stove-and-put-pot-on-it",
                    "Turn on the stove and then put the blue pot on it.",
                    on, use("place_on_top", objects=pot, support=host, after=[on]))


@register("put-block-on-stove-and-turn-it-on")
def put_block_on_stove_and_turn_it_on() -> TaskGraph:
    host, switch = stove()
    block = var("red_block", "block", "red", BLOCK)
    put = use("place_on_top", objects=block, support=host)
    return assemble("put-block-on-stove-and-turn-it-on",
                    "Put the red block on the stove, then turn the stove on.",
                    put, use("switch_on", switch=switch, after=[put]))


@register("turn-off-stove-and-move-pot-to-zone")
def turn_off_stove_and_move_pot_to_zone() -> TaskGraph:
    host, switch = stove("black_stove", on=True, color="black")
    pot = var("blue_pot", "bowl", "blue", BOWL, fixed=False, description="the blue pot",
              initial=start_on(host))
    zone = var("green_zone", "zone", "green", WIDE_ZONE)
    off = use("switch_off", switch=switch)
    return assemble("turn-off-stove-and-move-pot-to-zone",
                    "Turn off the black stove, then move the blue pot from it to the green "
                    "zone.",
                    off, use("place_in_zone", objects=pot, zone=zone, after=[off]),
                    extra=[host])


@register("turn-on-two-stoves")
def turn_on_two_stoves() -> TaskGraph:
    left, left_switch = stove("left_stove")
    right, right_switch = stove("right_stove", color="white")
    return assemble("turn-on-two-stoves", "Turn on both stoves.",
                    use("switch_on", prefix="left", switch=left_switch),
                    use("switch_on", prefix="right", switch=right_switch),
                    extra=[left, right])


@register("turn-on-lamp")
def turn_on_lamp() -> TaskGraph:
    host, switch = stove("lamp", kind="lamp", color="yellow")
    return assemble("turn-on-lamp", "Turn on the lamp.",
                    use("switch_on", switch=switch), extra=[host])


@register("put-pot-on-stove-and-turn-it-on")
def put_pot_on_stove_and_turn_it_on() -> TaskGraph:
    # The other order of turn-on-stove-and-put-pot-on-it: a 12 cm pot on the stove
    # first, then the press; the button on the control strip stays clear of the pot.
    host, switch = stove("white_stove", color="white")
    pot = var("red_pot", "bowl", "red", BOWL, fixed=False, description="the red pot")
    put = use("place_on_top", objects=pot, support=host)
    return assemble("put-pot-on-stove-and-turn-it-on",
                    "Put the red pot on the white stove, then turn the stove on.",
                    put, use("switch_on", switch=switch, after=[put]))
