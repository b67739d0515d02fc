"""Run independent jobs in this process, in it and a spawn-started process pool, or on Ray.

Collection shards and policy-evaluation tasks share this: each job is a top-level
function and its arguments (picklable), results come back in job order, and a
callback sees each job as it completes.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from multiprocessing import get_context
from typing import Any

from factask.vocabulary.errors import FactaskError


class ParallelError(FactaskError, ValueError):
    """Parallel execution asked for wrongly (Ray missing)."""


def run_jobs(fn: Callable[..., Any], jobs: Sequence[tuple[Any, ...]], workers: int = 1,
             ray_address: str | None = None,
             on_done: Callable[[int, Any], None] | None = None) -> list[Any]:
    """``[fn(*job) for job in jobs]``, in parallel.

    Args:
        fn: A top-level function (workers import it by name).
        jobs: Argument tuples.
        workers: Processes, this one included; 1 (or a single job) runs here, in order.
        ray_address: Run on Ray instead: "auto" (a running cluster, or the instance
            this process already started), "local" (start one here) or an address.
        on_done: Called here with (job index, result) as each job completes.

    Returns:
        The results in job order.

    Raises:
        ParallelError: ``ray_address`` given but Ray is not installed.
    """
    results: list[Any] = [None] * len(jobs)

    def done(i: int, value: Any) -> None:
        results[i] = value
        if on_done is not None:
            on_done(i, value)

    if ray_address:
        _run_ray(fn, jobs, ray_address, done)
    elif workers <= 1 or len(jobs) <= 1:
        for i, job in enumerate(jobs):
            done(i, fn(*job))
    else:
        _run_pool(fn, jobs, workers, done)
    return results


def _run_pool(fn: Callable[..., Any], jobs: Sequence[tuple[Any, ...]], workers: int,
              done: Callable[[int, Any], None]) -> None:
    """This process and ``workers - 1`` spawned children share the jobs.

    A spawned child pays seconds of start-up (it imports MuJoCo and factask) before
    its first job; this process is warm, so it works from the start instead of
    waiting. Each child keeps one job queued behind the running one so that it never
    idles while this process is busy with a job of its own.
    """
    pending = deque(range(len(jobs)))
    in_flight: dict[Future[Any], int] = {}
    depth = 2 * (workers - 1)
    # spawn: a forked child would inherit the parent's GL and MuJoCo state.
    with ProcessPoolExecutor(max_workers=workers - 1, mp_context=get_context("spawn")) as pool:
        while pending or in_flight:
            while pending and len(in_flight) < depth:
                i = pending.popleft()
                in_flight[pool.submit(fn, *jobs[i])] = i
            finished = [f for f in in_flight if f.done()]
            if not finished and pending:
                i = pending.pop()  # from the back: the children keep the front
                done(i, fn(*jobs[i]))
                continue
            if not finished:
                finished = list(wait(in_flight, return_when=FIRST_COMPLETED).done)
            for fut in finished:
                done(in_flight.pop(fut), fut.result())


def _run_ray(fn: Callable[..., Any], jobs: Sequence[tuple[Any, ...]], address: str,
             done: Callable[[int, Any], None]) -> None:
    try:
        import ray
    except ImportError as exc:
        raise ParallelError("--ray needs Ray (fix: pip install 'factask[ray]')") from exc
    started = not ray.is_initialized()
    if started:
        ray.init(address=None if address == "local" else address, include_dashboard=False,
                 log_to_driver=False)
    try:
        remote = ray.remote(fn)
        pending = {remote.remote(*job): i for i, job in enumerate(jobs)}
        while pending:
            ready, _ = ray.wait(list(pending), num_returns=1)
            done(pending.pop(ready[0]), ray.get(ready[0]))
    finally:
        if started:
            ray.shutdown()
