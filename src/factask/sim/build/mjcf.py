"""MJCF export of every asset kind and of the table (``dm_control.mjcf``).

The compile path builds scenes through ``mujoco.MjSpec`` (:mod:`factask.sim.build.mjspec`);
this module writes the same bodies as MJCF elements, for the files of
``mjcf_assets/`` (``scripts/export_assets.py``) and for anyone who wants a scene
as an MJCF tree. Both read one description, :func:`factask.sim.build.parts.plan_object`,
and a test compiles a graph both ways and compares the models.

The geometry and the constants live in :mod:`factask.sim.build.parts`; they are
re-exported here so ``from factask.sim.build.mjcf import kind_parts`` keeps working.
"""

from __future__ import annotations

from typing import Any

from dm_control import mjcf

from factask.sim.build.parts import (
    BALL_FRICTION,
    BOWL_SEGMENTS,
    FIXTURE_CLEARANCE,
    GEOM_SEPARATOR,
    MARKER_GROUP,
    OBJECT_CONDIM,
    OBJECT_FRICTION,
    OBJECT_GROUP,
    OBJECT_SOLIMP,
    OBJECT_SOLREF,
    ROLLING_CONDIM,
    AssetError,
    HollowShape,
    Part,
    PartType,
    fixture_fits,
    fixture_hollow,
    fixture_size_for,
    fmt,
    kind_parts,
    parts_aabb,
    plan_object,
)
from factask.sim.build.stage import (
    CAMERA_FOVY,
    FLOOR_POS,
    FLOOR_RGBA,
    FLOOR_SIZE,
    FRONT_CAMERA,
    FRONT_CAMERA_POS,
    HEADLIGHT_AMBIENT,
    HEADLIGHT_DIFFUSE,
    HEADLIGHT_SPECULAR,
    LIGHTS,
    OFFSCREEN_SIZE,
    SHADOW_SIZE,
    TABLE_HEIGHT,
    TABLE_RGBA,
    TABLE_THICKNESS,
    TOP_CAMERA,
    TOP_CAMERA_HEIGHT,
    TOP_CAMERA_POS,
    TOP_CAMERA_XYAXES,
    WORKSPACE_CENTER,
    look_at_xyaxes,
    table_top,
)
from factask.vocabulary.kinds import UnknownKindError
from factask.vocabulary.kinds import kind_spec as _kind_spec

__all__ = [
    "BOWL_SEGMENTS", "CAMERA_FOVY", "FIXTURE_CLEARANCE", "FLOOR_RGBA", "FRONT_CAMERA",
    "FRONT_CAMERA_POS", "GEOM_SEPARATOR", "MARKER_GROUP", "OBJECT_CLASS", "OBJECT_CONDIM",
    "OBJECT_FRICTION", "OBJECT_GROUP", "OBJECT_SOLIMP", "OBJECT_SOLREF", "OFFSCREEN_SIZE",
    "SHADOW_SIZE", "TABLE_HEIGHT", "TABLE_RGBA", "TABLE_THICKNESS", "TOP_CAMERA",
    "TOP_CAMERA_HEIGHT", "VISUAL_CLASS", "WORKSPACE_CENTER", "XML_PRECISION", "AssetError",
    "HollowShape", "Part", "PartType", "asset_xml", "build_object", "build_object_like",
    "build_table", "configure_visual", "ensure_default_classes", "fixture_fits",
    "fixture_hollow", "fixture_size_for", "kind_parts", "new_root", "parts_aabb", "table_xml",
]

#: MJCF default classes of colliding object geoms and of visual-only geoms.
OBJECT_CLASS = "object"
VISUAL_CLASS = "visual"
#: Significant digits of numbers in MJCF text.
XML_PRECISION = 10


def build_object(parent: Any, name: str, kind: str, size: tuple[float, float, float],
                 color: str = "gray", mass: float | None = None, fixed: bool | None = None,
                 **options: Any) -> Any:
    """Add one object body to ``parent`` (an MJCF element).

    Args:
        parent: The worldbody (or, for free objects only, any body) to add to.
        name: Instance name (body ``name``, geoms ``name:<part>``).
        kind: Asset kind.
        size: Full extents in metres.
        color: Palette colour name.
        mass: Mass in kg (default: the kind's density).
        fixed: Mocap body instead of a free joint (default: the kind's).
        **options: ``hollow``, ``pos``, ``quat``, ``visual_only``, ``alpha``,
            ``group`` of :func:`factask.sim.build.parts.plan_object`.

    Returns:
        The new body element.

    Raises:
        AssetError: bad kind, size, colour or mass, or a fixed body whose parent is
            not the worldbody.
    """
    plan = plan_object(name, kind, size, color, mass, fixed, **options)
    if plan.mocap and parent.tag != "worldbody":
        raise AssetError(name, "a fixed object (mocap body) must be a child of the worldbody",
                         "pass root.worldbody as the parent")
    ensure_default_classes(parent.root)
    body_kwargs: dict[str, Any] = {"name": name, "pos": list(plan.pos)}
    if plan.quat is not None:
        body_kwargs["quat"] = list(plan.quat)
    if plan.mocap:
        body_kwargs["mocap"] = "true"
    body = parent.add("body", **body_kwargs)
    if not plan.mocap:
        body.add("freejoint", name=plan.joint_name)
    for g in plan.geoms:
        geom: dict[str, Any] = {"name": g.name, "type": g.type, "size": list(g.size),
                                "pos": list(g.pos), "rgba": list(g.rgba), "group": g.group}
        if g.quat is not None:
            geom["quat"] = list(g.quat)
        geom["dclass"] = OBJECT_CLASS if plan.collides else VISUAL_CLASS
        if plan.collides and g.rolls:
            geom["condim"] = ROLLING_CONDIM
            geom["friction"] = list(BALL_FRICTION)
        if g.mass is not None:
            geom["mass"] = g.mass
        body.add("geom", **geom)
    return body


def ensure_default_classes(root: Any) -> None:
    """Add the geom default classes objects use (contact parameters; no collision
    for visual-only geoms) to ``root`` unless it has them.

    Args:
        root: The MJCF root element.
    """
    if root.find("default", OBJECT_CLASS) is not None:
        return
    obj = root.default.add("default", dclass=OBJECT_CLASS)
    obj.geom.set_attributes(friction=list(OBJECT_FRICTION), condim=OBJECT_CONDIM,
                            solref=list(OBJECT_SOLREF), solimp=list(OBJECT_SOLIMP))
    vis = root.default.add("default", dclass=VISUAL_CLASS)
    vis.geom.set_attributes(contype=0, conaffinity=0)


def build_object_like(parent: Any, obj: Any, **kwargs: Any) -> Any:
    """:func:`build_object` from any object with ``name, kind, size, color, mass``
    (and optionally ``fixed``) attributes, such as a scene-object record.

    Args:
        parent: See :func:`build_object`.
        obj: The object description.
        **kwargs: Passed on to :func:`build_object`.

    Returns:
        The new body element.
    """
    return build_object(
        parent, obj.name, obj.kind, tuple(obj.size), obj.color, getattr(obj, "mass", None),
        getattr(obj, "fixed", None), **kwargs,
    )


def configure_visual(root: Any, shadow_size: int = SHADOW_SIZE) -> None:
    """Set the scene's rendering options (shadow map size, offscreen buffer).

    Args:
        root: The MJCF root element.
        shadow_size: Shadow map size in pixels (smaller renders faster in software).
    """
    root.visual.quality.shadowsize = shadow_size
    root.visual.get_children("global").offwidth = OFFSCREEN_SIZE[0]
    root.visual.get_children("global").offheight = OFFSCREEN_SIZE[1]
    root.visual.headlight.ambient = list(HEADLIGHT_AMBIENT)
    root.visual.headlight.diffuse = list(HEADLIGHT_DIFFUSE)
    root.visual.headlight.specular = list(HEADLIGHT_SPECULAR)


def build_table(worldbody: Any) -> Any:
    """Add the table (top face at z = 0), the floor, lights and cameras.

    Cameras: ``top`` looks straight down at the workspace centre (image up =
    world +x, away from the robot); ``front`` looks at it obliquely from beyond
    the far edge of the table.

    Args:
        worldbody: The MJCF worldbody.

    Returns:
        The table top geom.
    """
    ensure_default_classes(worldbody.root)
    size, pos = table_top()
    table = worldbody.add("geom", name="table", type="box", dclass=OBJECT_CLASS,
                          size=list(size), pos=list(pos), rgba=list(TABLE_RGBA))
    worldbody.add("geom", name="floor", type="plane", size=list(FLOOR_SIZE),
                  pos=list(FLOOR_POS), rgba=list(FLOOR_RGBA))
    for name, shadow, lpos, ldir, diffuse, specular in LIGHTS:
        worldbody.add("light", name=name, directional="true",
                      castshadow="true" if shadow else "false", pos=list(lpos), dir=list(ldir),
                      diffuse=list(diffuse), specular=list(specular))
    worldbody.add("camera", name=TOP_CAMERA, pos=list(fmt(TOP_CAMERA_POS)),
                  xyaxes=[int(v) for v in TOP_CAMERA_XYAXES], fovy=CAMERA_FOVY)
    worldbody.add("camera", name=FRONT_CAMERA, pos=list(fmt(FRONT_CAMERA_POS)),
                  xyaxes=list(look_at_xyaxes(FRONT_CAMERA_POS, WORKSPACE_CENTER)),
                  fovy=CAMERA_FOVY)
    return table


def new_root(model: str) -> Any:
    """An empty MJCF root with factask's rendering options.

    Args:
        model: The model's name.

    Returns:
        A ``dm_control.mjcf.RootElement``.
    """
    root = mjcf.RootElement(model=model)
    configure_visual(root)
    return root


def asset_xml(kind: str, color: str = "gray") -> str:
    """MJCF text of one asset of ``kind`` at its default size, alone (no table).

    Args:
        kind: Asset kind.
        color: Palette colour.

    Returns:
        Deterministic XML text (what ``mjcf_assets/<kind>.xml`` holds).

    Raises:
        AssetError: unknown kind or colour.
    """
    try:
        spec = _kind_spec(kind)
    except UnknownKindError as exc:
        raise AssetError(kind, str(exc), "use one of the listed kinds") from None
    root = new_root(f"asset_{kind}")
    build_object(root.worldbody, kind, kind, spec.default_size, color)
    return str(root.to_xml_string(precision=XML_PRECISION))


def table_xml() -> str:
    """MJCF text of the table, floor, lights and cameras (``mjcf_assets/table.xml``)."""
    root = new_root("table")
    build_table(root.worldbody)
    return str(root.to_xml_string(precision=XML_PRECISION))
