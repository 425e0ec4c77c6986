"""Fewer malloc arenas: the memory a long bag's run needs, not what its threads fragment.

glibc gives each thread that allocates its own arena (up to 8 per core), and memory freed in
one arena is not reused by another. The spinning, reader, segmentation and mining threads all
allocate numpy arrays, so a 5600-frame ``process_bag`` run peaked at 2.75 GB RSS; with two
arenas it peaks at 1.9 GB at the same speed (measured with ``benchmarks/end_to_end.py``'s
RSS sampling). ``MALLOC_ARENA_MAX`` in the environment does the same but must be set before
the process starts, hence this call at the top of each executable.
"""
from __future__ import annotations

import ctypes
import ctypes.util

_M_ARENA_MAX = -8  # mallopt parameter number, from glibc's malloc.h


def limit_malloc_arenas(count: int = 2) -> bool:
    """Cap glibc's malloc arenas for the threads started from now on; False where not glibc."""
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")
        return bool(libc.mallopt(_M_ARENA_MAX, count))
    except (OSError, AttributeError):
        return False
