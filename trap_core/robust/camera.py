"""Camera motion from the images or the patterns, and each pattern's motion relative to the scene.

Beyond the paper (TRAP_SPEC section 10, "object versus background"): the background moves with
the camera, so most of the frame moves together. Per pair of consecutive frames, the step is
the one read from the images where the graph stage read one (:mod:`trap_core.robust.image_steps`),
and otherwise a similarity transform (rotation, scale, translation) fitted to the displacements
of the patterns seen in both frames. Patterns are not votes: an object with many structures
(windows, wheels) over a plain background holds most of them, and a fit robust to half of the patterns moving on their
own then follows the object. So each cell of a ``GRID`` x ``GRID`` grid over the frame votes
once (the median displacement of its patterns); the transform most cells agree on (RANSAC,
within ``AGREE_PX``) is refined by least median of squares on the patterns it fits. Chaining
the transforms maps every frame into the first frame's coordinates ("world"). In the world,
background patterns stand still and objects move.

Over a plain scene (sky, sea, asphalt, a smooth photograph) one region, the backdrop, covers
most of the frame, and most faces hold it. Its barycentre stays near the middle of the view
wherever the camera goes, so positions that average it in move less than the scene does:
:func:`camera_paths` is given positions without it (:func:`~trap_core.robust.backdrop.without_backdrop`). Over such a
scene the background also forms few frequent patterns (its specks and streaks are islands in
the backdrop), and the objects' patterns then outvote it: :func:`camera_paths` adds every
region that can be matched to one in the next frame as a two-frame path of its own.
"""
from __future__ import annotations

import cv2
import numpy as np

from trap_core.clustering import ClusterSummary, ObservedPaths, Track, box_centres
from trap_core.robust._kernels import region_steps, world_speeds, world_step_sums
from trap_core.rag import StackedGraphs

GRID = 12  # cells per side of the frame, one vote each for the camera's motion
AGREE_PX = 1.0  # a cell (a pattern) agrees with a camera motion that puts it within this
MAX_ZOOM_STEP = 1.5  # no camera zooms by half between two frames: a fit that does is degenerate
MATCH_AREA_RATIO = 1.5  # a region matched in the next frame has at most this ratio of areas to its match
HOP_SHARE = 0.5  # a pattern with this share of its world path in hops, a cluster with more of its occurrences on such
# patterns, moves in hops (world_steps; which occurrences count: trap_core.robust.hops)


def camera_paths(graphs: StackedGraphs, observed: ObservedPaths, reach: float) -> ObservedPaths:
    """The paths :func:`camera_transforms` is fitted to: the patterns' ``observed`` paths, which
    the caller places without the backdrop (:func:`~trap_core.clustering.observed_paths` of
    :func:`~trap_core.robust.backdrop.without_backdrop`),
    and the regions matched from frame to frame in the video's stacked ``graphs`` (at most
    ``reach`` px apart) as two-frame paths of their own: of the regions that are not the backdrop
    and do not reach the image's edge (their barycentres move with the crop), two of one colour
    label whose areas differ by at most ``MATCH_AREA_RATIO``, each the other's nearest such.

    Unlike frequent patterns, every region of the background votes, however plain the scene;
    regions matched wrongly, and those of the objects, are outliers to the fit.

    Over four photographs with a backdrop, the camera's motion read from positions with it was
    0.36-0.96 px a frame off the true pan (median over 12-frame windows), and 0.00 without it.
    Over a cat's face, which segments into a backdrop and a few dozen streaks, the objects
    held most patterns and the motion read from them was 1.74 px a frame off; with the
    regions, 0.47 (``benchmarks/camera_motion.py``).
    """
    first_id = int(observed.pattern.max()) + 1 if observed.pattern.size else 0
    first, second, frames = region_steps(graphs.node_offsets, graphs.bbox, graphs.centroid, graphs.area, graphs.label,
                                         graphs.backdrop, graphs.by_place, float(reach), MATCH_AREA_RATIO)
    return ObservedPaths(np.concatenate([observed.pattern, np.repeat(first_id + np.arange(first.size), 2)]),
                         np.concatenate([observed.frame, np.column_stack([frames, frames + 1]).reshape(-1)]),
                         np.concatenate([observed.position,
                                         np.stack([graphs.centroid[first], graphs.centroid[second]],
                                                  axis=1).reshape(-1, 2)]))


def camera_transforms(paths: ObservedPaths, n_frames: int, image_steps: np.ndarray | None = None) -> np.ndarray:
    """(n_frames, 3, 3): ``M[t]`` maps world (frame 0) coordinates to frame t coordinates.

    Each step from a frame to the next is ``image_steps[t + 1]`` ((n_frames, 2, 3): the step into
    each frame read from the images, :mod:`trap_core.robust.image_steps`) where it was read, and
    otherwise fitted to the ``paths`` seen in both frames."""
    step = (paths.pattern[1:] == paths.pattern[:-1]) & (paths.frame[1:] == paths.frame[:-1] + 1)
    src_rows = np.flatnonzero(step)
    when = paths.frame[src_rows]
    order = np.argsort(when, kind="stable")
    src_rows, when = src_rows[order], when[order]
    bounds = np.searchsorted(when, np.arange(n_frames + 1))
    transforms = np.tile(np.eye(3), (n_frames, 1, 1))
    extent = paths.position.max(axis=0) + 1 if len(paths.frame) else np.ones(2)
    read = np.zeros(n_frames, dtype=bool) if image_steps is None else np.isfinite(image_steps).all(axis=(1, 2))
    for t in range(n_frames - 1):
        step_matrix = np.eye(3)
        rows = src_rows[bounds[t]:bounds[t + 1]]
        if read[t + 1]:
            step_matrix[:2] = image_steps[t + 1]
        elif rows.size:
            step_matrix[:2] = _paths_step(paths.position[rows], paths.position[rows + 1], extent)
        transforms[t + 1] = step_matrix @ transforms[t]
    return transforms


def _paths_step(src: np.ndarray, dst: np.ndarray, extent: np.ndarray) -> np.ndarray:
    """(2, 3) step taking paths' positions ``src`` in one frame to theirs ``dst`` in the next:
    :func:`similarity_step`, or where it finds none (or fewer than three paths), their median shift."""
    src, dst = src.astype(np.float32), dst.astype(np.float32)
    fitted = similarity_step(src, dst, extent) if len(src) >= 3 else None
    if fitted is not None:
        return fitted
    return np.column_stack([np.eye(2), np.median(dst - src, axis=0)])


def similarity_step(src: np.ndarray, dst: np.ndarray, extent: np.ndarray) -> np.ndarray | None:
    """(2, 3) similarity taking ``src`` to ``dst`` (positions of patterns, regions or image points
    in two frames whose (width, height) is at most ``extent``): the one most cells of the frame
    agree on, refined on the points it fits. None where no fit is found
    or the fit zooms by more than ``MAX_ZOOM_STEP`` (patterns bunched in one frame can give a
    scale of 0, which no chain of camera motions survives)."""
    cell = np.minimum((src / extent * GRID).astype(np.int64), GRID - 1) @ np.array([GRID, 1])
    cells, inverse = np.unique(cell, return_inverse=True)
    if cells.size >= 3:
        cell_src, cell_dst = _cell_medians(src, inverse, cells.size), _cell_medians(dst, inverse, cells.size)
        consensus, _ = cv2.estimateAffinePartial2D(cell_src, cell_dst, method=cv2.RANSAC,
                                                   ransacReprojThreshold=AGREE_PX)
        if consensus is not None:
            fits = np.linalg.norm(src @ consensus[:, :2].T + consensus[:, 2] - dst, axis=1) <= AGREE_PX
            if fits.sum() >= 3:
                src, dst = src[fits], dst[fits]
    fitted, _ = cv2.estimateAffinePartial2D(src, dst, method=cv2.LMEDS)
    if fitted is None:
        return None
    scale = np.sqrt(abs(np.linalg.det(fitted[:, :2])))
    return fitted if 1 / MAX_ZOOM_STEP <= scale <= MAX_ZOOM_STEP else None


def _cell_medians(points: np.ndarray, cell: np.ndarray, n_cells: int) -> np.ndarray:
    """(n_cells, 2) float32: per cell (0..n_cells-1, each holding points), the median of its points."""
    count = np.bincount(cell, minlength=n_cells)
    first = np.r_[0, np.cumsum(count)[:-1]]
    out = np.empty((n_cells, 2), dtype=np.float32)
    for axis in (0, 1):
        ordered = points[np.lexsort((points[:, axis], cell)), axis]
        out[:, axis] = 0.5 * (ordered[first + (count - 1) // 2] + ordered[first + count // 2])
    return out


def camera_moves(transforms: np.ndarray, frames: np.ndarray, lag: int) -> np.ndarray:
    """(len(frames), 2, 3, 3): the camera's motion from each of ``frames`` to the frame ``lag``
    before it and to the one ``lag`` after (clipped to the video), from ``transforms`` (frame 0
    to frame ``t``): where a region of the frame would be, had it stayed with the scene."""
    from_here = np.linalg.inv(transforms[frames])
    last = len(transforms) - 1
    return np.stack([transforms[np.clip(frames + shift, 0, last)] @ from_here for shift in (-lag, lag)], axis=1)


def map_points(homographies: np.ndarray, points: np.ndarray) -> np.ndarray:
    """(N, 2) ``points`` mapped by one (3, 3) homography or each by its own ((N, 3, 3))."""
    homographies = np.broadcast_to(homographies, (len(points), 3, 3))
    mapped = np.einsum("nij,nj->ni", homographies, np.column_stack([points, np.ones(len(points))]))
    return mapped[:, :2] / mapped[:, 2:]


def to_world(transforms: np.ndarray, frames: np.ndarray, points: np.ndarray) -> np.ndarray:
    """(N, 2) ``points`` seen in the view in ``frames`` (one frame each) mapped into world (frame 0)
    coordinates by the camera's ``transforms`` (frame 0 to frame ``t``), undone."""
    return map_points(np.linalg.inv(transforms[frames]), points)


def world_reach(track: Track, transforms: np.ndarray | None, share: float = 0.9) -> float:
    """The larger side of the box that holds the middle ``share`` of the track's box centres, per
    axis, in world coordinates (in the view's where ``transforms`` is None: the camera was not
    read). Jitter and a box that hops now and then widen it by little; an object that moves
    goes as far as it moves."""
    if not len(track):
        return 0.0
    centres = box_centres(track.boxes)
    if transforms is not None:
        centres = to_world(transforms, track.frames, centres)
    tail = 100 * (1 - share) / 2
    low, high = np.percentile(centres, [tail, 100 - tail], axis=0)
    return float(np.max(high - low))


def world_speed(paths: ObservedPaths, transforms: np.ndarray, n_patterns: int, lag: int = 1) -> np.ndarray:
    """(S,) speed of each pattern in world coordinates, pixels per frame (0 if seen once).

    The median over the pattern's observations of its displacement to the first observation
    at least ``lag`` frames later, divided by the frames between (first to last observation
    for a pattern seen for less than ``lag`` frames). Over a lag of many frames (the tracker
    takes ``tau``/2 for patterns and ``tau`` for clusters: half a second and a second at 25 Hz),
    jitter of the barycentres (regions changing shape with noise) does not add up while motion
    does.
    """
    return world_speeds(paths.pattern, paths.frame, paths.position, np.linalg.inv(transforms), lag, n_patterns)


def cluster_world_speed(summary: ClusterSummary, transforms: np.ndarray, lag: int) -> np.ndarray:
    """(C,) :func:`world_speed` of each cluster's mean path over the frames its patterns cover.

    Averaged over its patterns, a cluster's path jitters less than any one pattern's, so a chain
    of background patterns that each passed the speed threshold on noise is seen still here.
    """
    frames = [np.flatnonzero(covered) for covered in summary.covered]
    if not frames:  # nothing moved: no cluster
        return np.zeros(0)
    paths = summary.paths
    observed = ObservedPaths(np.repeat(np.arange(len(frames)), [f.size for f in frames]),
                             np.concatenate(frames),
                             np.concatenate([paths.at(c, f) for c, f in enumerate(frames)]))
    return world_speed(observed, transforms, len(frames), lag)


def world_steps(paths: ObservedPaths, transforms: np.ndarray, n_patterns: int, hop: float,
                max_gap: int = 2) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per pattern, from its world displacements between observations at most ``max_gap`` frames
    apart: (S,) the median per frame (NaN for a pattern never seen so close), (S,) the mean per
    frame (its path's length over the frames it spans), and (S,) the share of its path made in
    steps of at least ``hop`` px.

    Beside :func:`world_speed`: an object moves a little every frame, so its steps are about its
    speed over many frames (jitter adds a little). A chain of background occurrences that the
    linking took from one look-alike to the next (bricks, tiles, a fence) is made of hops the
    size of the texture's spacing: it stands still between them (its median step is that of
    standing still), or it hops back and forth (its path is many times what the hops add up to).
    (Where the camera's motion is misread, objects too stand still in the world between steps,
    but those steps are the few px of the error.)
    """
    median, path, frames, hopped = world_step_sums(paths.pattern, paths.frame, paths.position,
                                                   np.linalg.inv(transforms), hop, max_gap, n_patterns)
    return median, path / np.maximum(frames, 1), hopped / np.maximum(path, 1e-12)
