"""Policies given to factask eval-policy as module:callable in tests."""

from __future__ import annotations

from typing import Any


def stop_at_once(obs: dict[str, Any]) -> None:
    """A policy that ends every episode before acting."""
    return None


class Counting:
    """An object policy with reset(seed) and act(obs): acts nowhere useful, twice."""

    def reset(self, seed: int) -> None:
        self.left = 2

    def act(self, obs: dict[str, Any]) -> dict[str, Any] | None:
        if self.left == 0:
            return None
        self.left -= 1
        return {"pick": [0.5, 0.0, 0.0, 0.0], "place": [0.5, 0.1, 0.05, 0.0]}
