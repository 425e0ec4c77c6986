"""Work on a thread pool, results in order: what the graph stage and the miner share.

The compiled kernels release the GIL, so a pool of ``threads`` works on that many frames at
once. Each caller needs the frames' results in frame order (progress, stitching, publishing),
and must not have every frame's work submitted at once (its inputs and outputs would all be
held).
"""
from __future__ import annotations

from collections import deque
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import Future, ThreadPoolExecutor


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
