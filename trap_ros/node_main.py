"""What every standalone node executable shares: init, one-line errors, exit codes, shutdown."""
from __future__ import annotations

import sys
from collections.abc import Callable

import rclpy
from rclpy.executors import ExternalShutdownException

from trap_core.bagio import BagError
from trap_core.pipeline import ParameterError
from trap_ros.memory import limit_malloc_arenas


def run_node(name: str, body: Callable[[], int], args: list[str] | None) -> None:
    """``rclpy.init``, run ``body`` (its return value is the exit code), then shut down.

    Bad input ends with ``name: error: ...`` on stderr and exit code 1; Ctrl-C with 130.
    """
    limit_malloc_arenas()
    rclpy.init(args=args)
    code = 0
    try:
        code = body()
    except (BagError, ParameterError) as error:
        print(f"{name}: error: {error}", file=sys.stderr)
        code = 1
    except (KeyboardInterrupt, ExternalShutdownException):
        code = 130
    finally:
        if rclpy.ok():
            rclpy.shutdown()
    sys.exit(code)
