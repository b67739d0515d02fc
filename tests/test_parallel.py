"""run_jobs: results in job order, a callback per job, work shared by this process and
its spawned children."""

from __future__ import annotations

import os
import time

import pytest

from factask.datasets.parallel import run_jobs


def pid_after(seconds: float, tag: int) -> tuple[int, int]:
    """The job's tag and the process that ran it (a top-level function: children
    import it by name)."""
    time.sleep(seconds)
    return tag, os.getpid()


def fail_on(tag: int, bad: int) -> int:
    if tag == bad:
        raise ValueError(f"job {tag} failed")
    return tag


@pytest.mark.parametrize("workers", [1, 3])
def test_results_come_back_in_job_order_with_one_callback_each(workers: int) -> None:
    seen: list[int] = []
    jobs = [(0.05, k) for k in range(8)]
    results = run_jobs(pid_after, jobs, workers=workers, on_done=lambda i, _r: seen.append(i))
    assert [tag for tag, _ in results] == list(range(8))
    assert sorted(seen) == list(range(8))


def test_this_process_works_while_children_start() -> None:
    """With two workers the (warm) parent runs jobs too, and so does the child."""
    jobs = [(0.3, k) for k in range(12)]
    pids = {pid for _, pid in run_jobs(pid_after, jobs, workers=2)}
    assert os.getpid() in pids
    assert len(pids) == 2


@pytest.mark.parametrize("bad", [0, 5])  # 0 runs in the child, 5 here
def test_a_failing_job_raises_its_error(bad: int) -> None:
    """Whether it failed here or in a child, the job's own error comes out."""
    with pytest.raises(ValueError, match=f"job {bad} failed"):
        run_jobs(fail_on, [(k, bad) for k in range(6)], workers=2)
