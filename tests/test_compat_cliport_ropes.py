"""CLIPort's bead-chain ropes: createMultiBody + createConstraint chains become ropes."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from factask.compat.cliport import Unsupported, import_cliport
from factask.compat.cliport.scoring import scored_episode
from factask.relations import RopeAlong

ORIGINALS = Path(__file__).parents[1] / "src" / "factask" / "data" / "cliport_tasks"
ROPES = Path(__file__).parent / "cliport_ropes"
BAD = Path(__file__).parent / "cliport_tasks" / "bad"


def _rope_goal(result) -> RopeAlong:
    (factor,) = result.graph.factors
    assert isinstance(factor.goal, RopeAlong)
    return factor.goal


@pytest.mark.parametrize("name", ["align_rope.py", "manipulating_rope.py"])
def test_ravens_bead_chain_becomes_one_rope_on_the_beads_targets(name: str) -> None:
    result = import_cliport(ORIGINALS / name, seed=0)
    (rope,) = [v for v in result.graph.variables if v.kind == "rope"]
    assert rope.count == 20 and rope.color == "red"  # 18 red beads, 2 white ends
    pitch = 2 * 0.005 * np.sqrt(2)  # Ravens: the square's side over 20 beads
    np.testing.assert_allclose(rope.size, (pitch, 0.01, 0.01), atol=1e-6)
    goal = _rope_goal(result)
    assert goal.either_end and goal.tolerances.xy == pytest.approx(0.02)
    ravens = result.goals[0]
    assert ravens.objects == rope.instances  # Ravens scores the same segments
    pts = np.array([(p.x, p.y) for p in goal.points])
    np.testing.assert_allclose(pts, np.array(ravens.targets)[:, :2], atol=1e-5)
    np.testing.assert_allclose(np.linalg.norm(np.diff(pts, axis=0), axis=1), pitch, atol=1e-5)
    assert not any("createMultiBody" in w or "Unsupported" in w for w in result.warnings)


def test_gensim_make_ropes_is_the_same_bead_chain() -> None:
    result = import_cliport(ROPES / "gensim_rope_on_line.py", seed=1)
    (rope,) = [v for v in result.graph.variables if v.kind == "rope"]
    assert rope.count == 20 and rope.color == "blue"
    assert rope.size[0] == pytest.approx(0.015, abs=1e-6)  # 30 cm line / 20 beads
    goal = _rope_goal(result)
    line = result.graph.variable("line_green_0")
    pts = np.array([(p.x, p.y) for p in goal.points])
    # The targets run along the line, through its centre.
    assert np.linalg.norm(pts.mean(axis=0) - np.array([line.initial.x, line.initial.y])) < 1e-3


def test_a_hand_written_chain_is_recognised_by_its_links_not_its_code() -> None:
    """Sphere beads, link points on both sides, the goal listing the last bead first,
    an L of targets and identity matches: still one rope, slots in chain order,
    one direction only."""
    result = import_cliport(ROPES / "bead_chain_l_shape.py", seed=0)
    (rope,) = [v for v in result.graph.variables if v.kind == "rope"]
    assert rope.count == 16 and rope.color == "yellow"
    np.testing.assert_allclose(rope.size, (0.015, 0.012, 0.012), atol=1e-6)
    goal = _rope_goal(result)
    assert not goal.either_end  # matches = identity: Ravens accepts one direction only
    ravens = result.goals[0]
    # The goal lists bead 15 first; the slots follow the chain from bead 0.
    first = ravens.objects.index(rope.instances[0])
    assert (goal.points[0].x, goal.points[0].y) == pytest.approx(ravens.targets[first][:2])


def test_a_ring_of_beads_is_unsupported() -> None:
    with pytest.raises(Unsupported, match="ring or a tree"):
        import_cliport(BAD / "rope_task.py")


def test_a_goal_over_some_beads_only_is_unsupported(tmp_path: Path) -> None:
    src = (ROPES / "gensim_rope_on_line.py").read_text()
    src = src.replace("objs=objects, matches=matches, targ_poses=targets",
                      "objs=objects[:5], matches=matches[:5, :5], targ_poses=targets[:5]")
    path = tmp_path / "half_rope.py"
    path.write_text(src)
    with pytest.raises(Unsupported, match="5 of the 20 beads"):
        import_cliport(path, seed=0)


@pytest.mark.slow
@pytest.mark.parametrize(("path", "seeds"), [
    (ORIGINALS / "align_rope.py", (0, 1)),
    (ROPES / "bead_chain_l_shape.py", (0,)),
])
def test_the_oracle_completes_bead_chain_tasks_under_ravens_scoring(path: Path,
                                                                    seeds: tuple) -> None:
    for seed in seeds:
        result = import_cliport(path, seed=seed)
        episode, ravens = scored_episode(result, seed)
        assert episode.success, episode.failure
        assert ravens.success, ravens.rewards


def test_objects_added_with_add_object_and_linked_are_a_rope_too() -> None:
    result = import_cliport(ROPES / "ball_chain_add_object.py", seed=0)
    (rope,) = result.graph.variables
    assert rope.kind == "rope" and rope.count == 12 and rope.color == "blue"
    assert rope.size[0] == pytest.approx(0.015)
    assert _rope_goal(result).either_end
