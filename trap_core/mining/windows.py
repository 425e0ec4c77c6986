"""Windowed mining: a long video mined window by window, its spatio-temporal patterns stitched.

TRAP_SPEC section 3 mines the whole video at once, which holds every frame's face sets in
memory. Here the graphs arrive one by one; every ``window`` frames the buffered window is
mined (frequencies counted inside it) and only ``overlap`` frames are kept for the next one.
Consecutive windows share ``overlap >= tau`` frames, so every link of the occurrence graph
(frames at most ``tau`` apart) lies inside one window; a component cut by a window border is
kept open, and continues in the next window through the occurrences the two windows share
(same frame, pattern and faces). Each shared frame is then owned by one window (the border
is the middle of the overlap), so ``freq_st`` sums exactly over windows.

With the paper's linking (``"graph"``) the components are those of mining the whole video,
for every pattern frequent in the windows it occurs in; a pattern frequent in one window but
not the next loses fewer than ``freq_min`` frames at that border. With ``"assignment"`` a path
of one window continues the path of the previous window it shares most occurrences with,
and only when that choice is mutual, so one object still makes one path.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from trap_core.mining.errors import MiningError
from trap_core.mining.miner import mine
from trap_core.mining.params import MiningParams
from trap_core.mining.result import MiningResult
from trap_core.rag import PlaneGraph


@dataclass
class _Piece:
    """The kept occurrences of one window (global frame numbers) and their global component."""

    frame: np.ndarray
    pattern_hash: np.ndarray
    faces: np.ndarray
    position: np.ndarray
    box: np.ndarray
    node_box: np.ndarray
    component: np.ndarray

    def take(self, rows: np.ndarray) -> _Piece:
        return _Piece(*(getattr(self, name)[rows] for name in self.__dataclass_fields__))

    def keys(self, rows: np.ndarray) -> np.ndarray:
        """(len(rows), 2 + max_faces) identity of each occurrence: frame, pattern, faces."""
        return np.column_stack([self.frame[rows], self.pattern_hash[rows], self.faces[rows].astype(np.int64)])


class WindowedMiner:
    """Mine plane graphs as they arrive, in windows of ``window`` frames overlapping by ``overlap``.

    Parameters
    ----------
    params : MiningParams
        As for :func:`trap_core.mining.mine`; frequencies are counted per window.
    window : int
        Frames per window; memory holds one window's graphs and face sets.
    overlap : int, optional
        Frames shared by consecutive windows, at least ``params.tau`` (the default).
    choose_params : callable, optional
        Called with the first window's graphs; returns the parameters for every window
        (how the automatic frequency is chosen once, on the first window).
    """

    def __init__(self, params: MiningParams, window: int, overlap: int | None = None,
                 choose_params: Callable[[list[PlaneGraph]], MiningParams] | None = None) -> None:
        overlap = params.tau if overlap is None else overlap
        if overlap < params.tau:
            raise MiningError(f"window overlap ({overlap} frames) must be at least tau ({params.tau} frames)")
        if window <= 2 * overlap:
            raise MiningError(f"window ({window} frames) must be longer than twice the overlap ({overlap} frames)")
        self.params = params
        self.window = window
        self.overlap = overlap
        self._choose_params = choose_params
        self._graphs: list[PlaneGraph] = []
        self._start = 0                       # global frame of self._graphs[0]
        self._pieces: list[_Piece] = []       # windows whose frames are all owned
        self._last: _Piece | None = None      # the newest window, its end not owned yet
        self._parent: list[int] = []          # union-find over global components
        self._owned_frames = np.zeros(0, dtype=np.int64)  # distinct owned frames of each component
        self._pattern_faces: dict[int, int] = {}
        self._pattern_frequency: dict[int, int] = {}
        self.windows_mined = 0

    @property
    def frames(self) -> int:
        """Frames added so far."""
        return self._start + len(self._graphs)

    def add(self, graph: PlaneGraph) -> None:
        """Add the next frame's graph; mines a window when one is complete."""
        self._graphs.append(graph)
        if len(self._graphs) == self.window:
            self._mine(final=False)
            drop = self.window - self.overlap
            self._graphs = self._graphs[drop:]
            self._start += drop

    def finish(self) -> MiningResult:
        """Mine what is left and return the stitched spatio-temporal patterns of all frames."""
        if self._last is None:  # the whole stream fits in one window: nothing to stitch
            self._choose()
            self.windows_mined = 1
            return mine(self._graphs, self.params)
        if len(self._graphs) > self.overlap:  # frames added since the last window was mined
            self._mine(final=True)
        self._settle(self._last)
        self._pieces.append(self._last)
        self._last = None
        return self._result()

    def _choose(self) -> None:
        if self._choose_params is not None:
            self.params = self._choose_params(self._graphs)
            self._choose_params = None

    def _mine(self, final: bool) -> None:
        self._choose()
        head = self.overlap if self._last is not None else 0
        mined = mine(self._graphs, self.params, first_frame=self._start,
                     open_ends=(head, 0 if final else self.overlap))
        self.windows_mined += 1
        for hash_, faces, frequency in zip(mined.pattern_hash.tolist(), mined.pattern_faces.tolist(),
                                           mined.pattern_frequency.tolist()):
            self._pattern_faces[hash_] = faces
            self._pattern_frequency[hash_] = max(frequency, self._pattern_frequency.get(hash_, 0))
        local = np.empty(mined.occ_frame.size, dtype=np.int64)
        local[mined.st_rows] = np.repeat(np.arange(mined.n_st), mined.st_occurrences)
        first_id = len(self._parent)
        self._parent.extend(range(first_id, first_id + mined.n_st))
        self._owned_frames = np.r_[self._owned_frames, np.zeros(mined.n_st, dtype=np.int64)]
        piece = _Piece(mined.occ_frame, mined.pattern_hash[mined.occ_pattern], mined.occ_faces, mined.occ_position,
                       mined.occ_box, mined.occ_node_box, local + first_id)
        if self._last is not None:
            piece = self._stitch(self._last, piece)
        self._last = piece

    def _stitch(self, previous: _Piece, piece: _Piece) -> _Piece:
        """Join components through shared occurrences. A shared occurrence is owned by the
        previous window before the middle of the overlap and by the new one from there on; an
        occurrence only one window holds (its pattern is rare in the other) stays with it."""
        rows_before = np.flatnonzero(previous.frame >= self._start)
        rows_after = np.flatnonzero(piece.frame < self._start + self.overlap)
        same_before, same_after = _identical(previous.keys(rows_before), piece.keys(rows_after))
        same_before, same_after = rows_before[same_before], rows_after[same_after]
        pairs, counts = np.unique(np.column_stack([previous.component[same_before], piece.component[same_after]]),
                                  axis=0, return_counts=True)
        if self.params.linking == "assignment":
            pairs = _mutual_best(pairs, counts)
        for a, b in pairs.tolist():
            self._union(a, b)
        border = self._start + self.overlap // 2
        keep_before = np.ones(previous.frame.size, dtype=bool)
        keep_before[same_before[previous.frame[same_before] >= border]] = False
        keep_after = np.ones(piece.frame.size, dtype=bool)
        keep_after[same_after[piece.frame[same_after] < border]] = False
        owned = previous.take(keep_before)
        self._settle(owned)
        self._pieces.append(owned)
        return piece.take(keep_after)

    def _settle(self, piece: _Piece) -> None:
        """Count the distinct frames each component owns in ``piece`` (whose frames it owns)."""
        stride = int(piece.frame.max(initial=0)) + 1
        owned = np.unique(piece.component * stride + piece.frame) // stride
        self._owned_frames += np.bincount(owned, minlength=len(self._parent))

    def _find(self, node: int) -> int:
        parent = self._parent
        while parent[node] != node:
            parent[node] = parent[parent[node]]
            node = parent[node]
        return node

    def _union(self, a: int, b: int) -> None:
        ra, rb = self._find(a), self._find(b)
        if ra != rb:
            self._parent[max(ra, rb)] = min(ra, rb)

    def _result(self) -> MiningResult:
        parent = np.array(self._parent, dtype=np.int64)
        while True:  # pointer jumping to every component's root
            grand = parent[parent]
            if np.array_equal(grand, parent):
                break
            parent = grand
        frames_of_root = np.bincount(parent, weights=self._owned_frames, minlength=parent.size)
        first = np.full(parent.size, np.iinfo(np.int64).max)
        last = np.full(parent.size, -1)
        for piece in self._pieces:
            np.minimum.at(first, parent[piece.component], piece.frame)
            np.maximum.at(last, parent[piece.component], piece.frame)
        enough = self.params.frequent_enough(frames_of_root, first, last, self.frames)
        kept = [enough[parent[piece.component]] for piece in self._pieces]
        root = np.concatenate([parent[piece.component[k]] for piece, k in zip(self._pieces, kept)])
        frame = np.concatenate([piece.frame[k] for piece, k in zip(self._pieces, kept)])
        order = np.lexsort((frame, root))  # the rows of each pattern, by frame: st_rows (no data moved)
        root = root[order]
        fields = {}
        for name in ("frame", "pattern_hash", "faces", "position", "box", "node_box"):
            # one field at a time, each window's copy freed as soon as it is gathered
            fields[name] = np.concatenate([getattr(piece, name)[k] for piece, k in zip(self._pieces, kept)])
            for piece in self._pieces:
                setattr(piece, name, None)
        self._pieces = []
        starts = np.flatnonzero(np.r_[True, root[1:] != root[:-1]]) if root.size else np.empty(0, np.int64)
        pattern_hash = np.array(sorted(self._pattern_faces), dtype=np.int64)
        occ_pattern = np.searchsorted(pattern_hash, fields["pattern_hash"]).astype(np.int32)
        return MiningResult(pattern_hash, np.array([self._pattern_frequency[h] for h in pattern_hash.tolist()],
                                                   dtype=np.int64),
                            np.array([self._pattern_faces[h] for h in pattern_hash.tolist()], dtype=np.int64),
                            fields["frame"], occ_pattern, fields["position"], fields["box"], fields["node_box"],
                            fields["faces"], occ_pattern[order[starts]].astype(np.int64),
                            np.r_[starts, root.size].astype(np.int64), order.astype(np.int32))


def _identical(before: np.ndarray, after: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Index pairs (i, j) with ``before[i] == after[j]`` (rows; each side's rows are distinct)."""
    keys = np.concatenate([before, after])
    side = np.r_[np.zeros(len(before), np.int64), np.ones(len(after), np.int64)]
    index = np.r_[np.arange(len(before)), np.arange(len(after))]
    order = np.lexsort(keys.T[::-1])
    keys, side, index = keys[order], side[order], index[order]
    same = np.flatnonzero(np.all(keys[1:] == keys[:-1], axis=1) & (side[1:] != side[:-1]))
    first_before = side[same] == 0
    return (np.where(first_before, index[same], index[same + 1]),
            np.where(first_before, index[same + 1], index[same]))


def _mutual_best(pairs: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """The (before, after) pairs where each side shares more occurrences with the other than
    with anyone else."""
    if pairs.size == 0:
        return pairs
    order = np.lexsort((-counts, pairs[:, 0]))
    best_after = pairs[order][np.r_[True, np.diff(pairs[order][:, 0]) != 0]]
    order = np.lexsort((-counts, pairs[:, 1]))
    best_before = pairs[order][np.r_[True, np.diff(pairs[order][:, 1]) != 0]]
    both = {tuple(row) for row in best_before.tolist()}
    return np.array([row for row in best_after.tolist() if tuple(row) in both], dtype=np.int64).reshape(-1, 2)
