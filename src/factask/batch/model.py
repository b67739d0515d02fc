"""The batch's host model: the scene's spec with two edits, compiled once.

1. **One inactive cup-to-object weld per free object** (the grasp per world,
   :mod:`factask.batch.suction`): MuJoCo Warp gives ``eq_data`` and ``eq_active`` a
   value per world, not ``eq_obj2id``.
2. **The table top is a plane** at its top face. MuJoCo Warp 3.17 collides a box
   with a cylinder by GJK/EPA and multi-contact; for a 2 cm cylinder resting on the
   1.5 m table box it returned, in one state, two contacts 58 cm deep (MuJoCo's C
   collider: four contacts 0.02 mm deep), and the cylinder was thrown off the table
   (docs/batch.md, "the two-world cylinder fault"). Against a plane every primitive
   (box, cylinder, sphere, capsule) has an analytic collider. What changes: the
   plane has no edge, so in a batch nothing falls off the table (the floor 0.7 m
   below is never reached); on the table the contacts are the same.

Bodies, joints, geoms and their ids stay the scene model's (checked).
"""

from __future__ import annotations

import mujoco

from factask.sim.build.compile import CompiledScene
from factask.sim.build.stage import TABLE_THICKNESS
from factask.sim.robots.suction import SUCTION_WELD
from factask.vocabulary.errors import InvalidValueError

#: Name prefix of the per-object welds (``suction__<instance>``).
WELD_PREFIX = "suction__"
#: The table top's geom (factask.sim.build.mjspec).
TABLE_GEOM = "table"


def _add_object_welds(spec: mujoco.MjSpec, scene: CompiledScene) -> dict[int, str]:
    """One inactive weld, cup body to object, per free object; body id -> weld name."""
    base = next((e for e in spec.equalities if e.name == SUCTION_WELD), None)
    if base is None:
        raise InvalidValueError("the scene has no suction weld: compile it with a robot")
    names = {}
    for inst, handle in scene.objects.items():
        if handle.mocap_id is not None or handle.qpos_adr is None:
            continue
        body = scene.model.body(handle.body_id).name
        spec.add_equality(name=f"{WELD_PREFIX}{inst}", type=mujoco.mjtEq.mjEQ_WELD,
                          objtype=mujoco.mjtObj.mjOBJ_BODY, name1=base.name1, name2=body,
                          active=False, solref=list(base.solref), solimp=list(base.solimp))
        names[handle.body_id] = f"{WELD_PREFIX}{inst}"
    return names


def _table_top_as_plane(spec: mujoco.MjSpec) -> None:
    """The table box becomes a plane through its top face (same extents drawn)."""
    table = next((g for g in spec.geoms if g.name == TABLE_GEOM), None)
    if table is None or table.type != mujoco.mjtGeom.mjGEOM_BOX:
        return
    table.type = mujoco.mjtGeom.mjGEOM_PLANE
    table.pos = [table.pos[0], table.pos[1], table.pos[2] + TABLE_THICKNESS / 2]
    table.size = [table.size[0], table.size[1], TABLE_THICKNESS]


def batch_model(scene: CompiledScene) -> tuple[mujoco.MjModel, dict[int, int]]:
    """The batch's host model (see the module's two edits).

    Args:
        scene: The compiled scene (its spec is copied, not changed).

    Returns:
        (the model, free object body id -> its weld's equality id). Bodies, joints,
        geoms and their ids are the scene model's.

    Raises:
        InvalidValueError: the scene has no ``suction`` weld (no robot).
    """
    spec = scene.spec.copy()
    names = _add_object_welds(spec, scene)
    _table_top_as_plane(spec)
    model = spec.compile()
    if (model.nbody, model.nq, model.ngeom) != (scene.model.nbody, scene.model.nq,
                                                 scene.model.ngeom):
        raise InvalidValueError("the batch's edits changed the scene's bodies or geoms")
    welds = {body: mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_EQUALITY, name)
             for body, name in names.items()}
    return model, welds


__all__ = ["TABLE_GEOM", "WELD_PREFIX", "batch_model"]
