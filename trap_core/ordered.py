"""Work on a thread pool, results in order: what the graph stage, the miner, the pattern
distances and the clusters' tracks share.

The compiled kernels release the GIL, so a pool of ``threads`` works on that many frames (or
bands of a matrix, or tracks) at once. The graph stage and the miner need the frames' results
in frame order (progress, stitching, publishing), and must not have every frame's work
submitted at once (its inputs and outputs would all be held): :func:`in_order`. Work whose
items are few and known at once takes :func:`each_on_threads`.
"""
from __future__ import annotations

from collections import deque
from collections.abc import Callable, Iterable, Iterator, Sequence
from concurrent.futures import Future, ThreadPoolExecutor
from typing import TypeVar

Item = TypeVar("Item")
Result = TypeVar("Result")


def in_order(pool: ThreadPoolExecutor, work: Callable, arguments: Iterable[tuple], threads: int) -> Iterator:
    """``work(*a)`` for each ``a`` of ``arguments``, in their order, run on ``pool``. At most
    ``2 * threads`` calls are in flight or done ahead of the caller; ``arguments`` is read one
    call at a time, as room is made. An error in a call is raised when its result is reached."""
    pending: deque[Future] = deque()
    for args in arguments:
        pending.append(pool.submit(work, *args))
        if len(pending) >= 2 * threads:
            yield pending.popleft().result()
    while pending:
        yield pending.popleft().result()


def each_on_threads(work: Callable[[Item], Result], items: Sequence[Item], threads: int) -> list[Result]:
    """``work(item)`` for each of ``items``, in their order, up to ``threads`` at once (on the
    caller's thread alone where one thread or one item is all there is). ``work`` must release
    the GIL for most of its time (compiled kernels) to gain anything, and must not write what
    another call reads. An error in a call is raised once every call has ended."""
    if threads <= 1 or len(items) <= 1:
        return [work(item) for item in items]
    with ThreadPoolExecutor(min(threads, len(items)), thread_name_prefix="trap-work") as pool:
        return list(pool.map(work, items))
