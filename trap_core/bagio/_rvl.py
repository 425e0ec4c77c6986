"""RVL, the lossless code of ``compressedDepth rvl`` images (compiled, numba ``nogil``).

Values go out as groups of 3 bits, lowest first, one nibble each with its top bit set while more
follow; nibbles fill 32-bit words from the top. Pixels go out as runs: the length of a run of
zeros, the length of the run of non-zeros after it, then each non-zero as the zigzag-coded
difference from the non-zero before it. :mod:`trap_core.bagio.compressed_depth` reads the
message around it.
"""
from __future__ import annotations

import numba as nb
import numpy as np

_WORD = 0xFFFFFFFF
_LONGEST = 30  # bits of value the decoder accepts (a run or a difference is far shorter)


@nb.njit(cache=True, nogil=True)
def _read(words, state):
    """The next value; ``state`` is (next word, current word's unread nibbles, their count).
    -1 when the words end, or a value runs on past ``_LONGEST`` bits (corrupt data)."""
    value = 0
    shift = 0
    while shift <= _LONGEST:
        if state[2] == 0:
            if state[0] >= words.size:
                return -1
            state[1] = np.int64(words[state[0]])
            state[0] += 1
            state[2] = 8
        nibble = (state[1] >> 28) & 0xF
        state[1] = (state[1] << 4) & _WORD
        state[2] -= 1
        value |= (nibble & 0x7) << shift
        shift += 3
        if nibble & 0x8 == 0:
            return value
    return -1


@nb.njit(cache=True, nogil=True)
def rvl_decode(words, n_pixels):
    """``(samples, complete)``: ``n_pixels`` uint16 samples decoded from ``words`` (uint32), and
    False if the words end before them or a run reaches past them (the rest stays 0)."""
    out = np.zeros(n_pixels, dtype=np.uint16)
    state = np.zeros(3, dtype=np.int64)
    done = 0
    previous = 0
    while done < n_pixels:
        zeros = _read(words, state)
        if zeros < 0 or done + zeros > n_pixels:
            return out, False
        done += zeros
        nonzeros = _read(words, state)
        if nonzeros < 0 or done + nonzeros > n_pixels:
            return out, False
        for _ in range(nonzeros):
            positive = _read(words, state)
            if positive < 0:
                return out, False
            previous = (previous + ((positive >> 1) ^ -(positive & 1))) & 0xFFFF
            out[done] = previous
            done += 1
    return out, True


@nb.njit(cache=True, nogil=True)
def _write(words, state, value):
    """Append ``value``; ``state`` is (next word, word being filled, its nibbles)."""
    while True:
        nibble = value & 0x7
        value >>= 3
        if value:
            nibble |= 0x8
        state[1] = ((state[1] << 4) | nibble) & _WORD
        state[2] += 1
        if state[2] == 8:
            words[state[0]] = state[1]
            state[0] += 1
            state[1] = 0
            state[2] = 0
        if value == 0:
            return


@nb.njit(cache=True, nogil=True)
def rvl_encode(samples):
    """``samples`` (uint16, 1-D) as RVL words (uint32)."""
    n = samples.size
    words = np.zeros(n + 2, dtype=np.uint32)  # a pixel takes at most 6 nibbles, with its runs' lengths 8
    state = np.zeros(3, dtype=np.int64)
    done = 0
    previous = 0
    while done < n:
        zeros = 0
        while done + zeros < n and samples[done + zeros] == 0:
            zeros += 1
        _write(words, state, zeros)
        done += zeros
        nonzeros = 0
        while done + nonzeros < n and samples[done + nonzeros] != 0:
            nonzeros += 1
        _write(words, state, nonzeros)
        for _ in range(nonzeros):
            current = np.int64(samples[done])
            delta = current - previous
            _write(words, state, ((delta << 1) ^ (delta >> 63)) & _WORD)
            previous = current
            done += 1
    if state[2]:
        words[state[0]] = (state[1] << (4 * (8 - state[2]))) & _WORD
        state[0] += 1
    return words[: state[0]]
