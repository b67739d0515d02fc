"""Seed splits of demonstration datasets, disjoint by construction (CLIPort's scheme).

==========  ===============================  =====================
split       seeds                            episodes at most
==========  ===============================  =====================
``train``   0, 2, 4, ... (even)              unbounded
``val``     1, 3, 5, ..., 9 999 (odd)        5 000
``test``    10 001, 10 003, ... (odd)        unbounded
==========  ===============================  =====================

Train seeds are even and the others odd, so train never meets val or test; val
stops below 10 000 where test starts, so val never meets test.
"""

from __future__ import annotations

from factask.vocabulary.errors import InvalidValueError

#: The splits.
SPLITS = ("train", "val", "test")
#: First test seed (CLIPort: odd seeds from 10 000).
TEST_START = 10_001
#: Most val episodes (val seeds stay below TEST_START).
MAX_VAL_EPISODES = (TEST_START - 1) // 2


def split_seed(split: str, k: int) -> int:
    """The seed of episode ``k`` (0-based) of ``split``.

    Raises:
        InvalidValueError: unknown split, negative ``k``, or val beyond its range.
    """
    if split not in SPLITS:
        raise InvalidValueError(f"split must be one of {SPLITS}, got {split!r}")
    if k < 0:
        raise InvalidValueError(f"episode index must be >= 0, got {k}")
    if split == "train":
        return 2 * k
    if split == "val":
        if k >= MAX_VAL_EPISODES:
            raise InvalidValueError(f"val has at most {MAX_VAL_EPISODES} episodes (its seeds "
                                    f"stay below the test seeds); got episode {k} "
                                    "(fix: use fewer val episodes)")
        return 2 * k + 1
    return TEST_START + 2 * k


def split_seeds(split: str, episodes: int, start: int = 0) -> list[int]:
    """Seeds of episodes ``start .. start + episodes - 1`` of ``split``."""
    return [split_seed(split, k) for k in range(start, start + episodes)]


def split_of_seed(seed: int) -> str:
    """The split a seed belongs to."""
    if seed % 2 == 0:
        return "train"
    return "val" if seed < TEST_START else "test"
