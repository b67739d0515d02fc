"""The action encoding of datasets: every primitive of the env as one fixed-width vector.

:class:`~factask.sim.env.FactaskEnv` takes several action dicts (its
:data:`~factask.sim.env.ACTION_KINDS`): a pick-and-place ``{"pick", "place"}``, a low
carry (``+ "lift"``), a spatula push ``{"start", "end"}``, a drawer slide
``{"grasp", "slide_to"}``, a door swing ``{"grasp", "swing_to", "hinge"}`` and a switch
press ``{"press", "press_to"}``. A dataset stores each as :data:`ACTION_NAMES`:

* ``pick_x pick_y pick_z pick_yaw``: the primitive's first pose (pick, start, grasp, press);
* ``place_x place_y place_z place_yaw``: its second pose (place, end, slide_to, swing_to,
  press_to);
* ``lift``: a low carry's height (metres), else 0;
* ``hinge_x hinge_y``: a door swing's hinge, else 0;
* ``primitive``: the primitive's code (:attr:`~factask.sim.env.ActionKind.code`:
  0 pick_place, 1 low_carry, 2 push, 3 slide, 4 swing, 5 press).

The first eight columns are the layout of :data:`ACTION_ENCODING` 1 (pick and place
only), so a pick-and-place reads the same in both. :func:`encode_action` and
:func:`decode_action` are exact inverses on the numbers the env reads (float64), so a
replay from the encoded actions is bit-identical.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from factask.sim.env import ACTION_KINDS, ActionKind, action_kind
from factask.vocabulary.errors import FactaskError

#: Version of the action layout (1: the 8 pick-and-place columns; 2: :data:`ACTION_NAMES`).
ACTION_ENCODING = 2
#: Names of the two poses' columns (the layout of encoding 1).
POSE_NAMES = ["pick_x", "pick_y", "pick_z", "pick_yaw",
              "place_x", "place_y", "place_z", "place_yaw"]


def _extra_columns() -> dict[str, list[str]]:
    out: dict[str, list[str]] = {}
    for kind in sorted(ACTION_KINDS, key=lambda k: k.code):
        for key, width in kind.extras:
            out.setdefault(key, [key] if width == 1 else [f"{key}_{c}" for c in "xyz"[:width]])
    return out


#: The extra keys' columns, in order: key -> its column names (one per number).
EXTRA_COLUMNS = _extra_columns()
#: Names of a dataset's ``action`` (decision frames) and ``action.primitive``.
ACTION_NAMES = [*POSE_NAMES, *(c for cols in EXTRA_COLUMNS.values() for c in cols),
                "primitive"]
#: Width of an encoded action.
ACTION_WIDTH = len(ACTION_NAMES)
#: Primitive code -> kind.
KINDS_BY_CODE: dict[int, ActionKind] = {k.code: k for k in ACTION_KINDS}
#: The plain pick-and-place (what encoding 1 held).
PICK_PLACE = next(k for k in ACTION_KINDS if k.name == "pick_place")


class ActionEncodingError(FactaskError, ValueError):
    """An action dict of no known primitive, or a vector that encodes none."""


def _slot(key: str) -> slice:
    start = len(POSE_NAMES)
    for k, cols in EXTRA_COLUMNS.items():
        if k == key:
            return slice(start, start + len(cols))
        start += len(cols)
    raise ActionEncodingError(f"no action columns for {key!r}")  # every extra key has some


def encode_action(action: Mapping[str, Any]) -> np.ndarray:
    """An env action dict as a (:data:`ACTION_WIDTH`,) float64 vector.

    Raises:
        ActionEncodingError: the dict holds no primitive's keys (the message names its
            keys and the accepted sets), or a value of the wrong size.
    """
    try:
        kind = action_kind(dict(action) if isinstance(action, Mapping) else action)
    except FactaskError as exc:
        raise ActionEncodingError(f"cannot record this action: {exc}") from exc
    vec = np.zeros(ACTION_WIDTH, np.float64)
    for i, key in enumerate(kind.poses):
        vec[4 * i:4 * i + 4] = _numbers(action[key], key, 4, exact=True)
    for key, width in kind.extras:
        vec[_slot(key)] = _numbers(action[key], key, width)
    vec[-1] = kind.code
    return vec


def _numbers(value: Any, key: str, width: int, exact: bool = False) -> np.ndarray:
    """The first ``width`` numbers of ``value``, the ones the env reads (a hinge's third
    is ignored; a pose, ``exact``, must be ``width`` numbers)."""
    try:
        arr = np.asarray(value, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError) as exc:
        raise ActionEncodingError(f"action[{key!r}] must be numbers, got {value!r}") from exc
    if arr.size < width or (exact and arr.size != width):
        raise ActionEncodingError(f"action[{key!r}] must hold {width} numbers, got {value!r}")
    return arr[:width]


def decode_action(vec: Any) -> dict[str, np.ndarray]:
    """The env action dict of an encoded vector (:func:`encode_action`'s inverse).

    A vector of 8 numbers (:data:`ACTION_ENCODING` 1) is a pick-and-place.

    Raises:
        ActionEncodingError: not 8 or :data:`ACTION_WIDTH` numbers, or an unknown code.
    """
    arr = np.asarray(vec, dtype=np.float64).reshape(-1)
    if arr.shape == (len(POSE_NAMES),):
        arr = upgrade_actions(arr[None])[0]
    if arr.shape != (ACTION_WIDTH,):
        raise ActionEncodingError(f"an encoded action has {ACTION_WIDTH} numbers "
                                  f"({', '.join(ACTION_NAMES)}), got {arr.shape}")
    code = arr[-1]
    kind = KINDS_BY_CODE.get(int(code)) if float(code).is_integer() else None
    if kind is None:
        raise ActionEncodingError(f"unknown primitive code {code} (known: "
                                  f"{ {k.code: k.name for k in ACTION_KINDS} })")
    out = {key: arr[4 * i:4 * i + 4].copy() for i, key in enumerate(kind.poses)}
    for key, _ in kind.extras:
        out[key] = arr[_slot(key)].copy()
    return out


def upgrade_actions(actions: np.ndarray) -> np.ndarray:
    """Actions of encoding 1 ((T, 8) pick and place) as (T, :data:`ACTION_WIDTH`)."""
    arr = np.asarray(actions, dtype=np.float64)
    out = np.zeros((len(arr), ACTION_WIDTH), np.float64)
    out[:, :len(POSE_NAMES)] = arr.reshape(len(arr), len(POSE_NAMES))
    out[:, -1] = PICK_PLACE.code
    return out


def primitive_name(vec: Any) -> str:
    """The primitive an encoded vector holds ("pick_place", "push", ...)."""
    return action_kind(decode_action(vec)).name
