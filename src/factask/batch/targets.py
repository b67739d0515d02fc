"""One factor's solved targets in every world, stacked into arrays.

Each world of a batch has its own initial layout and so its own
:class:`~factask.relations.solving.SolvedFactor`; the vectorised checks
(:mod:`factask.batch.checks`) read them as arrays over worlds. What a relation
fixes for every layout — which objects, which anchors, whether slots form a
chain, whether yaw counts — must agree across the worlds; the numbers (slot poses,
surfaces, matches) may differ.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from factask.relations.solving import SolvedFactor
from factask.scene.objects import SceneObject
from factask.vocabulary.errors import InvalidValueError


@dataclass(frozen=True)
class BatchTargets:
    """A factor's solved targets over ``W`` worlds.

    Attributes:
        factor: Factor name.
        relation: Relation type.
        objects: Instances the factor moves (``n``), in relation order.
        slot_pos: Slot positions (W, m, 3).
        slot_quat: Slot orientations (W, m, 4).
        surfaces: Surface height per slot (W, m); NaN where the slot's height is
            given explicitly (then the slot position is the target).
        matches: Which object may take which slot (W, n, m).
        regions: Region instances (``in_zone``, ``inside``, ``pile_in_zone``).
        support_group: Support instances (``on``).
        check_yaw: Whether yaw is checked.
        chain: Slots form a column (slot k counts only if k - 1 does).
        supports: Per slot, what the object there rests on or slides in (an instance
            name or ``table``): a drawer's cabinet for ``open`` / ``closed``, a
            switch's host for ``switched_on`` / ``switched_off``.
    """

    factor: str
    relation: str
    objects: tuple[str, ...]
    slot_pos: np.ndarray
    slot_quat: np.ndarray
    surfaces: np.ndarray
    matches: np.ndarray
    regions: tuple[str, ...]
    support_group: tuple[str, ...]
    check_yaw: bool
    chain: bool
    supports: tuple[str, ...] = ()

    @property
    def num_worlds(self) -> int:
        """Number of worlds ``W``."""
        return int(self.slot_pos.shape[0])

    @classmethod
    def stack(cls, solved: Sequence[SolvedFactor]) -> BatchTargets:
        """Stack one factor's solved targets of every world.

        Args:
            solved: The factor's :class:`SolvedFactor` per world (at least one).

        Returns:
            The stacked targets.

        Raises:
            InvalidValueError: no worlds, or the worlds disagree on what the relation
                fixes (factor, relation, objects, anchors, slot count, chain, yaw).
        """
        if not solved:
            raise InvalidValueError("BatchTargets.stack needs the solved factor of at "
                                    "least one world")
        first = solved[0]
        for s in solved[1:]:
            same = (s.factor == first.factor and s.relation == first.relation
                    and s.objects == first.objects and len(s.slots) == len(first.slots)
                    and s.regions == first.regions and s.support_group == first.support_group
                    and s.chain == first.chain and s.check_yaw == first.check_yaw
                    and s.supports == first.supports)
            if not same:
                raise InvalidValueError(
                    f"factor {first.factor!r}: the worlds' solved targets differ in what the "
                    "relation fixes (objects, anchors, slot count, chain, yaw check or "
                    "supports)")
        m = len(first.slots)
        pos = np.array([[p.pos for p in s.slots] for s in solved], dtype=float).reshape(-1, m, 3)
        quat = np.array([[p.quat for p in s.slots] for s in solved],
                        dtype=float).reshape(-1, m, 4)
        surf = np.array([[np.nan if (not s.surfaces or s.surfaces[j] is None)
                          else float(s.surfaces[j]) for j in range(m)] for s in solved],
                        dtype=float).reshape(-1, m)
        matches = np.array([np.asarray(s.matches, dtype=bool) for s in solved])
        return cls(first.factor, first.relation, tuple(first.objects), pos, quat, surf,
                   matches, tuple(first.regions), tuple(first.support_group),
                   bool(first.check_yaw), bool(first.chain), tuple(first.supports))

    def target_pos(self, objects: Mapping[str, SceneObject]) -> np.ndarray:
        """Target centre (W, n, m, 3) of object i when it takes slot j (see
        :meth:`SolvedFactor.target_pose`: on a surface, its half height above it)."""
        half_z = np.array([objects[o].half[2] for o in self.objects])  # (n,)
        pos = np.broadcast_to(self.slot_pos[:, None, :, :],
                              (self.num_worlds, len(self.objects), *self.slot_pos.shape[1:]))
        pos = pos.copy()
        surf = self.surfaces[:, None, :]  # (W, 1, m)
        on_surface = np.isfinite(surf)
        z = np.where(on_surface, surf + half_z[None, :, None], pos[..., 2])
        pos[..., 2] = z
        return pos

    def select(self, worlds: np.ndarray) -> BatchTargets:
        """The targets of some worlds (an index array or a boolean mask over worlds)."""
        return BatchTargets(self.factor, self.relation, self.objects, self.slot_pos[worlds],
                            self.slot_quat[worlds], self.surfaces[worlds],
                            self.matches[worlds], self.regions, self.support_group,
                            self.check_yaw, self.chain, self.supports)


__all__ = ["BatchTargets"]
