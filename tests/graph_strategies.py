"""Hypothesis strategies generating valid task graphs and templates.

Valid by construction: every factor moves objects no other factor moves, anchors
are fixed variables of a suitable kind or objects an *earlier* factor moves (so
the implied order is acyclic), ``after`` only names earlier factors, and weights
are normalised.
"""

from __future__ import annotations

import itertools

from hypothesis import strategies as st

from factask.graph import (
    Aligned,
    AtPose,
    Circle,
    Inside,
    InZone,
    On,
    Row,
    Stack,
    StateVariable,
    SubtaskFactor,
    TargetPose,
    TaskGraph,
)
from factask.vocabulary.palette import COLOR_NAMES

MOVABLE_KINDS = ["block", "box", "cylinder", "ball", "ell"]
SUPPORT_MOVABLE = ["block", "box", "cylinder"]
FIXED_KINDS = ["zone", "container", "bowl", "pallet", "stand", "line", "corner", "fixture", "kit"]

colors = st.sampled_from(COLOR_NAMES)
lengths = st.floats(0.02, 0.09, allow_nan=False).map(lambda x: round(x, 3))


@st.composite
def movable_variable(draw: st.DrawFn, name: str) -> StateVariable:
    kind = draw(st.sampled_from(MOVABLE_KINDS))
    size = draw(st.one_of(st.none(), st.tuples(lengths, lengths, lengths)))
    if size is not None:  # the shapes each kind can have (kinds.shape_problem)
        x, y, z = size
        if kind == "ball":
            size = (x, x, x)
        elif kind == "cylinder":
            size = (x, x, z)
        elif kind == "ell":
            size = (x, max(y, round(0.5 * x, 3)), z)
    return StateVariable(
        name=name,
        description=f"the {name.replace('_', ' ')}",
        kind=kind,
        size=size,
        color=draw(colors),
        count=draw(st.integers(1, 3)),
    )


@st.composite
def fixed_variable(draw: st.DrawFn, name: str) -> StateVariable:
    return StateVariable(
        name=name, description=f"the {name}", kind=draw(st.sampled_from(FIXED_KINDS)),
        color=draw(colors),
    )


def _kind_of(variables: list[StateVariable], name: str) -> str:
    return next(v.kind for v in variables if v.name == name)


@st.composite
def task_graphs(draw: st.DrawFn, prefix: str = "", max_factors: int = 5) -> TaskGraph:
    """A valid task graph whose every name starts with ``prefix``."""
    n_fixed = draw(st.integers(0, 3))
    n_mov = draw(st.integers(1, 6))
    fixed = [draw(fixed_variable(f"{prefix}fixed_{i}")) for i in range(n_fixed)]
    movable = [draw(movable_variable(f"{prefix}obj_{i}")) for i in range(n_mov)]
    variables = fixed + movable
    unmoved = [v.name for v in movable]
    moved_earlier: list[str] = []
    factors: list[SubtaskFactor] = []
    n_factors = draw(st.integers(0, min(max_factors, n_mov)))
    for k in range(n_factors):
        if not unmoved:
            break
        take = draw(st.integers(1, min(2, len(unmoved))))
        objs = unmoved[:take]
        del unmoved[:take]
        kinds = {f: [v.name for v in fixed if v.kind in ks] for f, ks in {
            "region": ["zone", "container", "bowl", "pallet", "stand", "line", "fixture", "kit"],
            "receptacle": ["container", "bowl", "fixture"],
            "support": ["pallet", "stand", "kit", "container", "bowl", "fixture"],
            "corner": ["corner"],
        }.items()}
        movable_supports = [n for n in moved_earlier if _kind_of(variables, n) in SUPPORT_MOVABLE]
        options = ["stack", "circle", "row", "at_pose"]
        if kinds["region"]:
            options.append("in_zone")
        if kinds["receptacle"]:
            options.append("inside")
        if kinds["support"] or movable_supports:
            options.append("on")
        n_inst = sum(v.count for v in movable if v.name in objs)
        # aligned gives each object an instance of the reference of its own.
        references = [v.name for v in fixed if v.count >= n_inst]
        if references:
            options.append("aligned")
        rtype = draw(st.sampled_from(options))
        if rtype == "in_zone":
            goal = InZone(objects=objs, zone=draw(st.sampled_from(kinds["region"])))
        elif rtype == "inside":
            goal = Inside(objects=objs, container=draw(st.sampled_from(kinds["receptacle"])))
        elif rtype == "on":
            goal = On(objects=objs,
                      support=draw(st.sampled_from(kinds["support"] + movable_supports)))
        elif rtype == "stack":
            base = draw(st.one_of(st.none(), st.sampled_from(movable_supports or [None])))
            # An ell carries only an ell no larger than itself: ells go on top,
            # the larger first.
            by_name = {v.name: v for v in variables}
            objs = sorted(objs, key=lambda n: (by_name[n].kind == "ell",
                                               -by_name[n].extents[0], -by_name[n].extents[1]))
            ells = [by_name[n].extents for n in objs if by_name[n].kind == "ell"]
            if all(hi[0] <= lo[0] and hi[1] <= lo[1] for lo, hi in itertools.pairwise(ells)):
                goal = Stack(objects=objs, base=base)
            else:  # two ells neither of which fits on the other
                goal = Row(objects=objs)
        elif rtype == "row":
            goal = Row(objects=objs, spacing=draw(st.one_of(st.none(), st.just(0.06))))
        elif rtype == "circle":
            goal = Circle(objects=objs, radius=draw(st.one_of(st.none(), st.just(0.1))))
        elif rtype == "aligned":
            goal = Aligned(objects=objs, reference=draw(st.sampled_from(references)))
        else:
            poses = [TargetPose(x=0.3 + 0.05 * i, y=0.1 * k - 0.2, yaw_deg=0.0)
                     for i in range(n_inst)]
            goal = AtPose(objects=objs, poses=poses,
                          matches=draw(st.one_of(st.none(), st.just([[1] * n_inst] * n_inst))))
        after = draw(st.lists(st.sampled_from([f.name for f in factors]), unique=True,
                              max_size=2)) if factors else []
        factors.append(SubtaskFactor(
            name=f"{prefix}goal_{k}", description=f"{rtype} goal {k}", goal=goal,
            weight=draw(st.floats(0.1, 1.0)), after=after,
        ))
        moved_earlier.extend(objs)
    total = sum(f.weight for f in factors)
    factors = [f.model_copy(update={"weight": f.weight / total}) for f in factors]
    name = draw(st.from_regex(r"[a-z][a-z0-9-]{0,12}", fullmatch=True))
    return TaskGraph(name=name, description="generated", variables=variables, factors=factors)
