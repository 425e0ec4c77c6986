"""Long bags tracked chunk by chunk (ours): memory bounded by a chunk, results while the bag plays.

TRAP tracks a whole video at once: every frame's graph and every frequent pattern's occurrences
are held until the end (about a quarter of a megabyte a frame: an hour at 25 Hz would not fit in
memory), and its selection is relative to the video (a track covers a share of it). With
``chunk > 0``, a bag longer than ``chunk + overlap`` frames is tracked in chunks of that many
frames, one starting every ``chunk`` frames, so consecutive chunks share ``overlap`` frames
(``4 tau``). A track of a chunk continues the previous chunk's track whose boxes match its own
(IoU at least 0.5) in the most shared frames, at least ``tau`` of them, one to one, and keeps
its id. An object out of view across a chunk border has no shared frames: as fragments are
rejoined within a chunk (:func:`trap_core.robust.rejoin_fragments`), a new track that enters
the view (or appears inside it) takes the id of a previous chunk's track that ended before it
started, left the view the same way (or vanished inside it), and is made of the same
structures: for one of the two, the share of its occurrences whose plane patterns the other
also has is at least ``rejoin_similarity``; most similar first, one to one. Each chunk gives the
boxes of its frames up to the middle of the overlap with the next one (ids decided by then); they
are final as soon as the chunk is tracked, while later frames are still read.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from trap_core.clustering import Track, box_iou, in_rows
from trap_core.pipeline.params import TrapParams
from trap_core.pipeline.pattern_miner import PatternMiner
from trap_core.pipeline.tracking import TrackingResult, track
from trap_core.rag import PlaneGraph
from trap_core.robust import reaches_border

MIN_IOU = 0.5  # boxes that hold the same object
MOST_SHARED = 0.75  # a track seen in fewer than tau shared frames continues one it matches in this share of them


@dataclass(frozen=True)
class ChunkSummary:
    """What one chunk's tracking found (its own mining result is not kept: memory)."""

    first_frame: int
    frames: int
    plane_patterns: int
    spatio_temporal_patterns: int
    clusters_at_cut: int
    tracks: int
    seconds: dict[str, float]


@dataclass
class ChunkedRun:
    """Tracks over the whole bag (global frames and ids) and one summary per chunk tracked."""

    tracks: list[Track] = field(default_factory=list)
    chunks: list[ChunkSummary] = field(default_factory=list)

    @property
    def seconds(self) -> dict[str, float]:
        """Per stage, summed over the chunks."""
        total: dict[str, float] = {}
        for chunk in self.chunks:
            for stage, value in chunk.seconds.items():
                total[stage] = total.get(stage, 0.0) + value
        return total

    def seconds_while_reading(self) -> float:
        """Tracking done while frames were still read (windows mined, chunks before the last), so
        the reading stage can be reported without it."""
        return sum(c.seconds.get("mining", 0.0) for c in self.chunks) + sum(
            s for c in self.chunks[:-1] for stage, s in c.seconds.items() if stage != "mining")


class ChunkedTracker:
    """Give it every frame's graph with :meth:`add`; :meth:`finish` returns the tracks.

    Parameters
    ----------
    params : TrapParams
        ``params.chunk`` frames per chunk step (0: the whole stream is one chunk).
    n_frames : int, optional
        Length of the stream when known (shares of the video in the parameters are then
        shares of each chunk's actual length).
    """

    def __init__(self, params: TrapParams, n_frames: int | None = None) -> None:
        self.params = params
        self.overlap = 4 * params.tau
        self.length = params.chunk + self.overlap if params.chunk else 0
        self.n_frames = n_frames
        self.run = ChunkedRun()
        self._graphs: list[PlaneGraph] = []
        self._start = 0                              # global frame of self._graphs[0]
        self._miner = PatternMiner(params, self._span(0))
        self._next_miner: PatternMiner | None = None  # fed the overlap, for the next chunk
        self._pending: list[Track] | None = None      # the last chunk's tracks, global ids, not all final yet
        self._structures: dict[int, dict[int, float]] = {}  # last chunk's tracks: plane pattern -> occurrences
        self._pieces: dict[int, list[Track]] = {}
        self._fresh: list[Track] = []
        self.final_frames = 0                        # boxes of every frame before this one are final
        self._next_id = 1

    @property
    def frames(self) -> int:
        """Frames added so far."""
        return self._start + len(self._graphs)

    def add(self, graph: PlaneGraph) -> None:
        """The next frame's graph; tracks a chunk when one is complete."""
        self._graphs.append(graph)
        self._miner.add(graph)
        if self.length and len(self._graphs) > self.params.chunk:
            if self._next_miner is None:
                self._next_miner = PatternMiner(self.params, self._span(self._start + self.params.chunk))
            self._next_miner.add(graph)
            if len(self._graphs) == self.length:
                self._track_chunk(final=False)
                self._start += self.params.chunk
                self._graphs = self._graphs[self.params.chunk:]
                self._miner, self._next_miner = self._next_miner, None

    def finish(self) -> ChunkedRun:
        """Track what is left and return every track over the whole stream."""
        covered = self._pending is not None and len(self._graphs) <= self.overlap  # no frame after the last chunk
        if covered:
            self._emit(self.frames)
        elif len(self._graphs) >= 2:
            self._track_chunk(final=True)
        self.run.tracks = [_joined(track_id, pieces) for track_id, pieces in sorted(self._pieces.items())]
        return self.run

    def take_final(self) -> list[Track]:
        """Boxes made final since the last call (pieces of tracks, global frames and ids): all of
        frames before :attr:`final_frames`."""
        fresh, self._fresh = self._fresh, []
        return fresh

    def _span(self, first_frame: int) -> int | None:
        """Frames of the chunk starting at ``first_frame``, when known."""
        if self.n_frames is None:
            return self.length or None
        rest = max(self.n_frames - first_frame, 1)
        return min(rest, self.length) if self.length else rest

    def _track_chunk(self, final: bool) -> None:
        """Track the current chunk; its boxes are final up to the middle of the overlap with the
        next chunk (to the end of the stream if ``final``)."""
        result = track(self._graphs, self.params, self._miner)
        tracks = [dataclasses.replace(t, frames=t.frames + self._start) for t in result.tracks]
        structures = [_structures(result, t.cluster) for t in result.tracks]
        continued = {}
        if self._pending is not None:
            continued = self._continued(self._pending, tracks)
            continued.update(self._returned(self._pending, tracks, structures, continued))
        self._pending = self._numbered(tracks, continued)
        self._structures = {t.track_id: s for t, s in zip(self._pending, structures)}
        self._emit(self.frames if final else self._start + self.params.chunk + self.overlap // 2)
        self.run.chunks.append(ChunkSummary(self._start, len(self._graphs), result.mining.n_patterns,
                                            result.mining.n_st, result.hierarchy.cut_level, len(tracks),
                                            result.seconds))

    def _continued(self, previous: list[Track], current: list[Track]) -> dict[int, int]:
        """{index in ``current``: id of the previous chunk's track it continues}: boxes that match
        in ``tau`` shared frames, or, where the two tracks share fewer (one starts late in the
        overlap, or the other ends early), in ``MOST_SHARED`` of at least ``tau``/2 of them."""
        shared = np.arange(self._start, self._start + self.overlap)
        tau = self.params.tau
        matches = []
        for i, new in enumerate(current):
            for old in previous:
                frames, in_new, in_old = np.intersect1d(new.frames, old.frames, return_indices=True)
                inside = np.isin(frames, shared)
                both = int(inside.sum())
                same = int((box_iou(new.boxes[in_new[inside]], old.boxes[in_old[inside]]) >= MIN_IOU).sum())
                if same >= tau or (2 * both >= tau and same >= MOST_SHARED * both):
                    matches.append((same, i, old.track_id))
        taken_new: dict[int, int] = {}
        taken_old: set[int] = set()
        for _, i, old_id in sorted(matches, key=lambda m: -m[0]):
            if i not in taken_new and old_id not in taken_old:
                taken_new[i] = old_id
                taken_old.add(old_id)
        return taken_new

    def _returned(self, previous: list[Track], current: list[Track], structures: list[dict[int, float]],
                  continued: dict[int, int]) -> dict[int, int]:
        """{index in ``current``: id of the previous chunk's track whose object it is, come back}."""
        width, height = self._graphs[0].frame_size
        taken = set(continued.values())
        ended = [t for t in previous if t.track_id not in taken]
        matches = []
        for i, new in enumerate(current):
            if i in continued:
                continue
            enters = bool(reaches_border(new.boxes[:1], width, height)[0])
            for old in ended:
                leaves = bool(reaches_border(old.boxes[-1:], width, height)[0])
                if old.frames[-1] < new.frames[0] and leaves == enters:
                    similarity = _similarity(self._structures[old.track_id], structures[i])
                    if similarity >= self.params.rejoin_similarity:
                        matches.append((similarity, i, old.track_id))
        found: dict[int, int] = {}
        for _, i, old_id in sorted(matches, key=lambda m: -m[0]):
            if i not in found and old_id not in taken:
                found[i] = old_id
                taken.add(old_id)
        return found

    def _numbered(self, tracks: list[Track], continued: dict[int, int]) -> list[Track]:
        out = []
        for i, t in enumerate(tracks):
            if i not in continued:
                continued[i] = self._next_id
                self._next_id += 1
            out.append(dataclasses.replace(t, track_id=continued[i]))
        return out

    def _emit(self, stop: int) -> None:
        """The last chunk's boxes from the first frame not final yet up to ``stop`` are final."""
        for t in self._pending or []:
            keep = (t.frames >= self.final_frames) & (t.frames < stop)
            if keep.any():
                piece = in_rows(t, keep)
                self._pieces.setdefault(t.track_id, []).append(piece)
                self._fresh.append(piece)
        self.final_frames = stop


def _structures(result: TrackingResult, cluster: int) -> dict[int, float]:
    """Occurrences of each plane pattern (by its hash: the same in every chunk) in a track's cluster."""
    mined = result.mining
    patterns = np.flatnonzero(result.labels == cluster)
    hashes = mined.pattern_hash[mined.st_pattern[patterns]]
    counts = mined.st_occurrences[patterns].astype(float)
    out: dict[int, float] = {}
    for key, count in zip(hashes.tolist(), counts.tolist()):
        out[key] = out.get(key, 0.0) + count
    return out


def _similarity(a: dict[int, float], b: dict[int, float]) -> float:
    """For one of the two, the share of its occurrences whose plane patterns the other also has,
    the larger (a short fragment may show only some of an object's structures)."""
    def share(x: dict[int, float], y: dict[int, float]) -> float:
        total = sum(x.values())
        return sum(v for k, v in x.items() if k in y) / total if total else 0.0
    return max(share(a, b), share(b, a))


def _joined(track_id: int, pieces: list[Track]) -> Track:
    first = pieces[0]
    points = None if any(p.points is None for p in pieces) else np.vstack([p.points for p in pieces])
    return Track(track_id, np.concatenate([p.frames for p in pieces]), np.vstack([p.boxes for p in pieces]),
                 np.concatenate([p.score for p in pieces]), first.cluster, points)
