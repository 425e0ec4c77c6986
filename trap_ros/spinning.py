"""Spin several nodes at once and stop them so that they can be destroyed cleanly.

rclpy Jazzy's ``MultiThreadedExecutor`` hands callbacks to a thread pool, and its ``shutdown()``
returns without waiting for them (it skips its own wait once the shutdown flag is set) and destroys
the guard condition those queued callbacks trigger when they start. A callback still queued at
the end of a run then fails with "cannot use Destroyable because destruction was requested",
which rclpy prints as "The following exception was never retrieved" when the task is collected.
Each node here has its own single-threaded executor in its own thread instead: callbacks run in
the spinning thread itself, so once the thread has been joined, none runs or waits.
"""
from __future__ import annotations

import threading
from collections.abc import Sequence

from rclpy.context import Context
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node

WAKE_SECONDS = 0.1
"""How long a spinning thread waits for work before it looks at the stop flag again."""


class NodeSpinners:
    """One spinning thread per node; nodes run their callbacks in parallel with each other (each
    node's callbacks one at a time, as its default mutually exclusive callback group wants).

    Parameters
    ----------
    nodes
        The nodes to spin; they are destroyed by their owner, after :meth:`stop`.
    context
        The context the nodes belong to (rclpy's default context when ``None``).
    """

    def __init__(self, nodes: Sequence[Node], context: Context | None = None) -> None:
        self._stopping = threading.Event()
        self._executors = []
        for node in nodes:
            executor = SingleThreadedExecutor(context=context)
            executor.add_node(node)
            self._executors.append(executor)
        self._threads = [threading.Thread(target=self._spin, args=(executor,), name=f"trap-spin-{node.get_name()}",
                                          daemon=True)
                         for executor, node in zip(self._executors, nodes)]

    def _spin(self, executor: SingleThreadedExecutor) -> None:
        while not self._stopping.is_set() and executor.context.ok():
            executor.spin_once(timeout_sec=WAKE_SECONDS)

    def start(self) -> None:
        """Start spinning every node."""
        for thread in self._threads:
            thread.start()

    def stop(self) -> None:
        """Return once no callback of any node runs or waits to run (the callback running when
        asked finishes first); the nodes can then be destroyed."""
        self._stopping.set()
        for thread in self._threads:
            thread.join()
        for executor in self._executors:
            executor.shutdown()
