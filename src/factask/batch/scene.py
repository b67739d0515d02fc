"""What a batched check looks at: every object's pose in every world, what is held.

The batched twin of :class:`~factask.relations.status.CheckScene`: poses are arrays
over worlds (``W``) and objects (``N``, in a fixed order of instance names).
Quaternions are normalised here as :class:`~factask.geometry.Pose` does, so a
batched check and a scalar check see the same numbers.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from factask.batch.geometry import normalize_quat
from factask.geometry import Pose
from factask.relations.status import CheckError
from factask.scene.objects import SceneObject
from factask.vocabulary.errors import InvalidValueError


@dataclass(frozen=True)
class BatchScene:
    """Poses of every object instance in ``W`` worlds.

    Attributes:
        objects: Scene objects by instance name.
        names: Instance names, the column order of the arrays.
        pos: Positions (W, N, 3).
        quat: Unit quaternions (W, N, 4) (normalised on construction).
        held: Which instance the robot holds, per world (W, N) bool (None: nothing).

    Raises:
        InvalidValueError: the arrays' shapes do not fit ``names``.
    """

    objects: Mapping[str, SceneObject]
    names: tuple[str, ...]
    pos: np.ndarray
    quat: np.ndarray
    held: np.ndarray | None = None
    _index: dict[str, int] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        pos = np.asarray(self.pos, dtype=float)
        quat = np.asarray(self.quat, dtype=float)
        n = len(self.names)
        if pos.ndim != 3 or pos.shape[1:] != (n, 3) or quat.shape != (*pos.shape[:2], 4):
            raise InvalidValueError(f"BatchScene needs pos (W, {n}, 3) and quat (W, {n}, 4), "
                                    f"got {pos.shape} and {quat.shape}")
        held = np.zeros(pos.shape[:2], dtype=bool) if self.held is None else \
            np.asarray(self.held, dtype=bool)
        if held.shape != pos.shape[:2]:
            raise InvalidValueError(f"held must be (W, {n}) booleans, got {held.shape}")
        object.__setattr__(self, "pos", pos)
        object.__setattr__(self, "quat", normalize_quat(quat))
        object.__setattr__(self, "held", held)
        object.__setattr__(self, "_index", {name: k for k, name in enumerate(self.names)})

    @classmethod
    def from_poses(cls, objects: Mapping[str, SceneObject],
                   poses: Sequence[Mapping[str, Pose]],
                   held: Sequence[Sequence[str]] | None = None) -> BatchScene:
        """A batch scene from one pose mapping per world (tests, CPU states).

        Args:
            objects: Scene objects by instance name (their order is the column order).
            poses: Per world, the pose of every instance.
            held: Per world, the instances the robot holds (default: none).

        Returns:
            The scene.

        Raises:
            CheckError: a world lacks the pose of an instance.
        """
        names = tuple(objects)
        try:
            pos = np.array([[p[n].pos for n in names] for p in poses], dtype=float)
            quat = np.array([[p[n].quat for n in names] for p in poses], dtype=float)
        except KeyError as exc:
            raise CheckError(f"no pose for object {exc.args[0]!r}; pass the pose of every "
                             "instance (fixed ones too)") from None
        w = len(poses)
        mask = np.zeros((w, len(names)), dtype=bool)
        for k, hs in enumerate(held or [()] * w):
            for h in hs:
                mask[k, names.index(h)] = True
        return cls(objects, names, pos.reshape(w, len(names), 3),
                   quat.reshape(w, len(names), 4), mask)

    @property
    def num_worlds(self) -> int:
        """Number of worlds ``W``."""
        return int(self.pos.shape[0])

    def columns(self, names: Sequence[str]) -> np.ndarray:
        """Column indices of ``names``.

        Raises:
            CheckError: an instance this scene does not have.
        """
        try:
            return np.array([self._index[n] for n in names], dtype=int)
        except KeyError as exc:
            raise CheckError(f"no pose for object {exc.args[0]!r} in the batch scene") from None

    def finite(self) -> np.ndarray:
        """Worlds (W,) whose every pose is finite (elsewhere the simulation failed)."""
        return np.isfinite(self.pos).all(axis=(1, 2)) & np.isfinite(self.quat).all(axis=(1, 2))


__all__ = ["BatchScene"]
