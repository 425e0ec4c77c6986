"""All parameters of a TRAP run, flat names as used in ROS parameter files (config/trap.yaml)."""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any

from trap_core.clustering import LINKAGES, MAX_TRACKS
from trap_core.mining import MiningParams
from trap_core.segmentation import COLOUR_SPACES, THRESHOLD_MODES

SEGMENTATIONS = ("felzenszwalb", "colour")
METHODS = ("paper", "robust")
# Which node needs which parameters (the segmentation node: stages 1-2; the mining node: 3-7).
GRAPH_STAGE = ("segmentation", "k", "max_regions", "sigma", "min_size", "threshold", "connectivity", "mean_gap",
               "colour_space", "chroma_weight", "max_side", "colour_bins", "contact_tolerance", "threads")
# What the segmentation node also reads: whether tracking will take the camera's steps from the
# images (:attr:`TrapParams.reads_image_steps`); the graph stage reads them only then.
IMAGE_STEP_STAGE = ("method", "image_motion", "min_speed", "grow", "still_regions")


class ParameterError(ValueError):
    """A parameter is unknown or out of range; the message is one line for the user."""


def _p(default: Any, doc: str) -> Any:
    return field(default=default, metadata={"doc": doc})


@dataclass(frozen=True)
class TrapParams:
    """Defaults are the paper's (TRAP_SPEC), marked (ours) where the paper is silent."""

    segmentation: str = _p("felzenszwalb", "felzenszwalb, or colour: exact-colour regions (synthetic videos)")
    k: float = _p(7.0, "segmentation threshold constant (constant mode: colour-distance units)")
    max_regions: int = _p(480, "Felzenszwalb: k is raised (for the whole video, from its first frame) until a frame "
                                "has at most this many regions at the working size: textured footage cut into "
                                "thousands of flickering regions is slow and noisy (ours; 480 = twice the paper's "
                                "videos); 0 = k as given")
    sigma: float = _p(0.8, "Gaussian smoothing before segmentation")
    min_size: int = _p(20, "regions smaller than this (pixels) are merged")
    threshold: str = _p("constant", "constant (paper: tau = k) or size (original: tau = k/|C|)")
    connectivity: int = _p(4, "pixel connectivity of the segmentation: 4 or 8")
    mean_gap: float = _p(0.0, "Felzenszwalb, constant threshold: regions of min_size pixels or more merge only if "
                              "their mean colours are at most this times k apart, so a region does not climb the "
                              "colour ramps that JPEG or video compression leave along edges into a differently "
                              "coloured neighbour (ours; 5 for compressed footage over textured ground: README, "
                              "compressed frames); 0 = off (paper)")
    colour_space: str = _p("rgb", "Felzenszwalb: colour distances in rgb (paper) or lab (CIELAB, scaled so that steps "
                                  "between greys weigh as in rgb: a hue change at one brightness is not outweighed "
                                  "by the brightness steps of texture; ours)")
    chroma_weight: float = _p(0.0, "Felzenszwalb: weight of the chroma axes against brightness in colour distances "
                                   "(ours): 0 fits it on the first frame, for the whole video, to the ratio of "
                                   "brightness to chroma spread between neighbouring pixels, within 1..2 "
                                   "(compressed footage and textured ground vary little in chroma, noise of each "
                                   "channel as much as in brightness); 1 keeps the colour space's (paper)")
    max_side: int = _p(640, "px: frames are segmented with their longer side scaled to this (down, or up for smaller "
                            "frames), so objects get as many regions as at the size the defaults were made for; "
                            "results stay in the frame's pixels (ours); 0 = each frame at its own size")
    colour_bins: int = _p(4, "levels per colour channel of the node labels; grey regions get its square (ours)")
    contact_tolerance: float = _p(0.0, "drop contacts shorter than this x sqrt(smaller region area) px, so faces do "
                                       "not flicker with pixel rounding (ours); 0 = keep all (paper)")
    eps: float = _p(40.0, "px: occurrences closer than this in frames at most tau apart are linked")
    tau: int = _p(25, "frames: temporal threshold of occurrence linking")
    freq_st_min: float = _p(36.0, "minimum frames of a spatio-temporal pattern: >= 1 frames (36 = 1.4 s at 25 Hz), "
                                  "< 1 share of the video")
    freq_st_cut: int = _p(8, "robust: frames enough for a spatio-temporal pattern seen within tau frames of the "
                             "video's (chunk's) first or last frame: the video cut it, and an object that enters "
                             "the view in its last freq_st_min frames (leaves in its first) is seen no longer "
                             "(8 = tau/3 at 25 Hz). Such a pattern is clustered only if it moves steadily and no "
                             "longer one goes along with it, apart from the others, and joins them only by "
                             "rejoining; 0 = freq_st_min (paper)")
    auto_frequency: bool = _p(False, "choose freq = freq_st (from freq_st_min on) so 600..2000 patterns are found "
                                     "(the paper's rule of thumb)")
    freq_min: float = _p(0.0, "minimum frames holding a pattern: 0 = freq_st_min (paper), < 1 share, >= 1 frames")
    max_faces: int = _p(3, "largest pattern, in faces")
    mining_window: int = _p(1500, "frames mined at once: longer videos are mined in windows overlapping by tau "
                                  "frames and stitched, memory bounded (ours); shares in freq_st_min/freq_min are "
                                  "of the window; 0 = the whole video at once (paper)")
    chunk: int = _p(9000, "frames: a longer bag is tracked in chunks starting every this many frames, sharing 4 tau "
                          "frames with the next (tracks continue across with their ids); memory is bounded by a "
                          "chunk and results are final while the bag plays; shares of the video are of a chunk "
                          "(ours); 0 = the whole bag at once")
    method: str = _p("robust", "paper (TRAP as published) or robust (ours: README 'Method')")
    one_path: bool = _p(True, "robust: link each pattern's occurrences one to one (one object, one path)")
    link_reach: float = _p(0.8, "robust: a pattern's path takes no step longer than this times the larger side of its "
                                "last occurrence (x sqrt of the frames waited): such a step is onto another object; "
                                "0 = eps only")
    label_memory: bool = _p(True, "robust: a region that continues one of the previous frame (near, similar area "
                                  "and colour) keeps its label, and one that appears is labelled under the first "
                                  "frame's light (gain measured on continuing regions), so light changes do not "
                                  "flip labels")
    min_speed: float = _p(0.0012, "robust: image widths per frame, relative to the camera and read over tau/2 "
                                  "frames, below which patterns (and, over tau frames, clusters) are background "
                                  "(0.0012 = 0.77 px/frame at 640 px; per frame, as the barycentres' jitter it "
                                  "stands above, at any frame rate); 0 = off")
    image_motion: bool = _p(True, "robust: the camera's motion from one frame to the next is read from the images "
                                  "(optical flow at grid points, the motion most of the frame agrees on), where they "
                                  "show enough of the scene, and from the patterns and regions elsewhere; false: "
                                  "from the patterns and regions only")
    steady_steps: float = _p(0.5, "robust: a pattern whose steps from one frame to the next (in the world) are not "
                                  "steady, the median under this share of its speed over tau/2 frames (still between "
                                  "hops) or the mean over its inverse times it (back and forth), with half its path "
                                  "or more in steps of eps/4, moves in hops between look-alikes of the background "
                                  "(bricks, tiles); a cluster mostly (in occurrences) of such patterns, but where "
                                  "steady ones of it are seen, or with none steady, half in hops on average, is "
                                  "background; unsupervised, a track whose cluster has no steady pattern is not "
                                  "counted unless its own boxes step steadily; 0 = off")
    own_region: bool = _p(True, "robust: a cluster selected as a track whose own region (the one most of its "
                                "occurrences hold) is found again, tau/5 frames before and after, where the camera's "
                                "motion puts it more often than where the cluster's motion does stays with the scene "
                                "(a chain of noise-born structures): it is background, and the next cluster is taken; "
                                "a selected cluster's pattern whose own region, along its own path, stays with the "
                                "scene so is left out of its track")
    one_object: bool = _p(True, "robust: a cluster of the cut whose patterns lie on two objects at once (further "
                                "apart than half their sizes on average, or in tau frames) is split down the "
                                "hierarchy; a selected cluster's pattern that shares its regions mostly with "
                                "another selected cluster's, while its own is elsewhere too, goes to that cluster")
    rejoin: bool = _p(True, "robust: rejoin fragments of one object across occlusions and exits; with one_track, "
                            "a track that left the view is continued by the track, or spare cluster, bringing its "
                            "object back")
    rejoin_similarity: float = _p(0.3, "robust: share of a fragment (counted in occurrences) whose structures the "
                                       "other also has, needed to rejoin them")
    rejoin_colour_reach: float = _p(20.0, "robust: fragments across an exit or a gap of more than tau frames are "
                                          "rejoined only if their regions' colours agree within this RGB distance, "
                                          "at one brightness ratio (ours); 0 = colours not compared")
    core_share: float = _p(0.8, "robust: track box from regions in at least this share of the occurrences, each "
                                "counted by its pattern's lifetime; 0 = all")
    still_regions: bool = _p(True, "robust: a core region found again, tau/5 frames before and after, at most half as "
                                   "far from where the camera's motion puts it as from where the track's does is "
                                   "background the object crosses: it leaves the box (the region most occurrences "
                                   "hold stays)")
    edge_lines: bool = _p(True, "robust: the lines of blended pixels that smoothing before segmentation makes "
                                "along a sharp edge (regions thinner than 1.5 px of the working size), where nearer "
                                "in colour to the ground outside the box than to what it holds, do not widen a track "
                                "box by their width")
    size_jump: float = _p(1.5, "robust: a track box this many times wider or taller than its usual size (running "
                               "median over 4 tau frames each side where it is alone) holds more than the object, "
                               "one this many times narrower or shorter (away from the border) a part of it: it is "
                               "given the usual size, which is the larger boxes' where a quarter of a piece's boxes "
                               "are that much larger and of one size (the whole object); 0 = off")
    grow: bool = _p(True, "robust: track boxes grow over nearby regions that move with the track, tau/5 frames before "
                          "or after (objects the segmentation splits into parts)")
    fill_gaps: bool = _p(True, "robust: a track's box is interpolated through its gaps of at most tau frames "
                               "(patterns missed for a few frames), not where its motion takes it out of view in the gap")
    one_track: bool = _p(True, "robust: tracks whose boxes match (IoU >= 0.5, or the smaller 90 % inside the other) "
                               "in 80 % of the (at least tau) frames they share hold one object: they are merged, and "
                               "so are two that lie close and move as one there (parts of one object); "
                               "boxes more than half the usual size off the track's path (tau/3 frames each side) "
                               "are dropped; a stretch of tau or more frames where a track repeats another's boxes "
                               "is dropped from it if it turns where the stretch begins or ends (with the boxes "
                               "inferred up to it and any piece of under tau frames it leaves on its own), and a "
                               "track so cut short is continued by a spare cluster that goes on where it ended (or "
                               "held its object up to there, or comes out of the track that hid it), or by a track "
                               "that takes its object over there; "
                               "look-alike tracks that traded objects where they met exchange their continuations back")
    own_frames: bool = _p(True, "robust, n_objects = 0: clusters are ranked by the frames no kept cluster is near "
                                "(not all their frames), must be seen (occurrences whose regions do not reach the "
                                "view's edge) in min_track_length of the video, and a cluster left out as near one "
                                "kept cluster lends its track the frames it lacks (same object, usual size, no other "
                                "track's box, none while the object is out of the view)")
    to_border: bool = _p(True, "robust: a track that ends (starts) at the image border is continued while its object, "
                               "moving as over its last (first) tau/2 frames fully in view, is partly visible")
    groups: bool = _p(True, "robust: where tracks' boxes merge, each gets its usual size at its side of the pair, "
                            "and a track that vanishes inside another's box continues there while it holds two "
                            "objects (and not where it does in under three quarters of those frames: it flickers); "
                            "once the track rules have run, a box so placed in a meeting of up to 2 tau "
                            "frames follows the straight path of its track across it, inside the pair's box")
    follow_ends: bool = _p(True, "robust: once the track rules have run, a track is followed back from its first box, "
                                 "on from its last and into the gaps fill_gaps leaves, by the regions inside the box, "
                                 "each found again where the box's motion puts it with about its area and colour, for "
                                 "as long as half of their area agrees on one shift and the box stays clear of the "
                                 "border and of other tracks' boxes; not from a box off the track's usual size")
    steady_edges: bool = _p(True, "robust: once the track rules have run, a box edge further than a fifth of the "
                                  "track's box size from both lines of that edge, over the tau/2 frames before and "
                                  "the tau/2 after, is put between them (a region merged in or a part lost for a few "
                                  "frames)")
    linkage: str = _p("average", "hierarchical clustering linkage: average, single, complete, weighted (ours)")
    ignore_top: float = _p(0.1, "share of the top levels of the hierarchy the lifetime cut ignores")
    n_objects: int = _p(0, "objects to track; 0 = found without supervision (ours)")
    length_tolerance: float = _p(0.1, "share of the video: clusters this close to the longest compete")
    min_track_length: float = _p(0.25, "share of the video a track must cover when n_objects = 0, at most "
                                       "min_track_frames frames (ours)")
    min_track_frames: int = _p(200, "frames: a track of a long video need not cover more than this, whatever "
                                    "min_track_length asks (ours; 200 = 8 s at 25 Hz, more than the share asks of "
                                    "a video of up to 800 frames): objects that pass through the view are in it "
                                    "for seconds, not for a share of the video; 0 = min_track_length alone")
    min_pass_frames: int = _p(100, "robust, one_track, n_objects = 0: frames: a track that enters the view through "
                                   "its border and leaves through it (or is in view when the video starts or ends) "
                                   "need only cover this many, if fewer than min_track_length and min_track_frames "
                                   "ask (ours: an object that crosses the view in seconds is seen whole); 0 = off")
    separation: float = _p(40.0, "px (of the working size, max_side): a cluster this close to kept tracks in most "
                                 "of its frames is not a new object (ours)")
    size_separation: float = _p(0.5, "robust, n_objects = 0: where this share of the largest track's usual size "
                                      "(the median of its boxes' larger side) is more than separation, clusters are "
                                      "selected again with it as separation (ours: the parts of objects large in the "
                                      "view stand further apart than separation); 0 = off")
    threads: int = _p(2, "frames segmented, or enumerated (mining), at once, and so bands of the pattern "
                         "distances and the clusters' tracks a rule asks for together")

    def __post_init__(self) -> None:
        checks = [
            (self.segmentation in SEGMENTATIONS, f"segmentation must be one of {SEGMENTATIONS}"),
            (self.threshold in THRESHOLD_MODES, f"threshold must be one of {THRESHOLD_MODES}"),
            (self.colour_space in COLOUR_SPACES, f"colour_space must be one of {COLOUR_SPACES}"),
            (self.method in METHODS, f"method must be one of {METHODS}"),
            (self.linkage in LINKAGES, f"linkage must be one of {LINKAGES}"),
            (self.k >= 0 and self.sigma >= 0 and self.min_size >= 0 and self.mean_gap >= 0 and self.chroma_weight >= 0,
             "k, sigma, min_size, mean_gap and chroma_weight must be >= 0"),
            (self.max_regions == 0 or self.max_regions >= 16, "max_regions must be 0 (off) or at least 16"),
            (self.connectivity in (4, 8), "connectivity must be 4 or 8"),
            (1 <= self.colour_bins <= 256, "colour_bins must be within 1..256"),
            (self.max_side == 0 or self.max_side >= 32, "max_side must be 0 (full size) or at least 32"),
            (self.contact_tolerance >= 0, "contact_tolerance must be >= 0"),
            (self.eps > 0 and self.tau >= 1, "eps must be > 0 and tau >= 1"),
            (self.freq_st_min > 0 and self.freq_min >= 0, "freq_st_min must be > 0 and freq_min >= 0"),
            (1 <= self.max_faces <= 8, "max_faces must be within 1..8"),
            (self.freq_st_cut >= 0, "freq_st_cut must be >= 0"),
            (self.mining_window == 0 or self.mining_window > 2 * self.tau,
             "mining_window must be 0 (whole video) or more than 2 x tau"),
            (self.chunk == 0 or self.chunk >= 4 * self.tau, "chunk must be 0 (whole bag) or at least 4 x tau frames"),
            (0 <= self.ignore_top < 1 and 0 <= self.length_tolerance <= 1,
             "ignore_top must be within [0, 1) and length_tolerance within [0, 1]"),
            (self.n_objects >= 0 and 0 <= self.min_track_length <= 1, "n_objects >= 0, min_track_length within [0, 1]"),
            (self.min_track_frames >= 0 and self.min_pass_frames >= 0,
             "min_track_frames and min_pass_frames must be >= 0"),
            (self.separation >= 0 and self.size_separation >= 0 and 1 <= self.threads <= 64,
             "separation and size_separation >= 0, threads within 1..64"),
            (self.size_jump == 0 or self.size_jump > 1, "size_jump must be 0 (off) or more than 1"),
            (self.link_reach >= 0, "link_reach must be >= 0"),
            (self.min_speed >= 0 and 0 <= self.rejoin_similarity <= 1 and 0 <= self.core_share <= 1
             and 0 <= self.steady_steps <= 1,
             "min_speed >= 0, rejoin_similarity, core_share and steady_steps within [0, 1]"),
        ]
        for ok, message in checks:
            if not ok:
                raise ParameterError(message)

    def in_frame_pixels(self, width: float, height: float) -> TrapParams:
        """These parameters for frames of ``width`` x ``height``: ``separation`` is in pixels of
        the working size, so it grows and shrinks with the frames segmented scaled (``max_side``),
        as the objects do. ``eps`` stays in frame pixels: it only bounds a link whose step is already
        bounded by the pattern's own size (``link_reach``), and scaling it too was measured worse
        (more links across look-alikes)."""
        pixel = self.working_pixel(width, height)
        return self if pixel == 1.0 else dataclasses.replace(self, separation=self.separation * pixel)

    def working_pixel(self, width: float, height: float) -> float:
        """Frame pixels per pixel of the size frames of ``width`` x ``height`` are segmented at."""
        working = self.working_side(width, height)
        return 1.0 if working is None else max(width, height) / working

    def working_side(self, width: float, height: float) -> int | None:
        """The longer side frames of ``width`` x ``height`` are segmented at when it is not
        their own (``max_side``), else None."""
        return None if not self.max_side or max(width, height) == self.max_side else self.max_side

    @property
    def reads_camera(self) -> bool:
        """Whether tracking reads the camera's motion: the robust method, where a rule needs it
        (``min_speed``, ``grow``, ``still_regions``)."""
        return self.method == "robust" and bool(self.min_speed > 0 or self.grow or self.still_regions)

    @property
    def reads_image_steps(self) -> bool:
        """Whether tracking reads the camera's steps between frames from the images: where it
        reads the camera at all (:attr:`reads_camera`), with ``image_motion``. The graph stage
        reads each step with the frame (2.5 ms a frame, README "Camera motion from the images")
        only then: the paper's method never looks at it."""
        return self.reads_camera and self.image_motion

    def track_length(self, n_frames: int) -> float:
        """Share of a video of ``n_frames`` a track must cover when the number of objects is not
        given: ``min_track_length``, but never more than ``min_track_frames`` frames. A share
        alone asks an object of a long video (a chunk is 9000 frames) to stay in view for
        minutes; one that passes through it never would."""
        if not self.min_track_frames or n_frames <= 0:
            return self.min_track_length
        return min(self.min_track_length, self.min_track_frames / n_frames)

    def track_frames(self, n_frames: int) -> int:
        """:meth:`track_length` in whole frames: ``min_track_length`` of the video rounded down,
        and never more than ``min_track_frames`` (the share times the frames can fall a hair
        under it in floating point)."""
        frames = int(self.min_track_length * n_frames)
        return min(frames, self.min_track_frames) if self.min_track_frames else frames

    def pass_frames(self, n_frames: int) -> int:
        """Frames a track that passes through the view (in through its border, out through it)
        must hold: ``min_pass_frames``, but never more than :meth:`track_frames`. Without the
        rules that tell a passing track from a piece (the paper's method, or no ``one_track``),
        :meth:`track_frames` itself."""
        passing = self.method == "robust" and self.one_track and self.min_pass_frames > 0
        return min(self.track_frames(n_frames), self.min_pass_frames) if passing else self.track_frames(n_frames)

    def selection_length(self, n_frames: int) -> float:
        """Share of a video of ``n_frames`` a cluster must cover to be selected when the number of
        objects is not given: :meth:`track_length`, or :meth:`pass_frames` where that is fewer.
        Tracks shorter than a track must be are kept once the track rules have run only if they
        pass through the view (README, tracks that pass through)."""
        if n_frames <= 0:
            return self.track_length(n_frames)
        return min(self.track_length(n_frames), self.pass_frames(n_frames) / n_frames)

    def max_tracks(self, n_frames: int) -> int:
        """At most how many tracks a video of ``n_frames`` gets when the number of objects is not
        given: ``MAX_TRACKS`` (a bound for videos whose tracks cover ``min_track_length`` of them)
        as many times over as :meth:`selection_length` asks less than that share. Where a track need
        cover only a tenth as many frames, ten times as many objects can pass through the video
        one after another (a chunk of traffic: 11 times, 220 tracks)."""
        share = self.selection_length(n_frames)
        return MAX_TRACKS * max(1, round(self.min_track_length / share)) if share > 0 else MAX_TRACKS

    def as_dict(self) -> dict[str, Any]:
        return dataclasses.asdict(self)

    def mining(self, n_frames: int) -> MiningParams:
        """Mining parameters for a video of ``n_frames`` (shares of the video become frame counts)."""
        def frames(value: float) -> int:
            return max(1, round(value * n_frames)) if value < 1 else int(value)
        return MiningParams(eps=self.eps, tau=self.tau, freq_st_min=frames(self.freq_st_min),
                            freq_min=frames(self.freq_min) if self.freq_min else None, max_faces=self.max_faces,
                            linking="assignment" if self.method == "robust" and self.one_path else "graph",
                            reach=self.link_reach,
                            freq_st_cut=self.freq_st_cut if self.method == "robust" and self.freq_st_cut else None,
                            threads=self.threads)

    @classmethod
    def descriptions(cls) -> dict[str, str]:
        """One-line meaning of each parameter (ROS parameter descriptors, README table)."""
        return {f.name: f.metadata["doc"] for f in dataclasses.fields(cls)}

    @classmethod
    def from_mapping(cls, values: dict[str, Any]) -> TrapParams:
        """Build from a flat mapping (ROS parameters); unknown names are an error."""
        fields = {f.name: f for f in dataclasses.fields(cls)}
        unknown = sorted(set(values) - set(fields))
        if unknown:
            raise ParameterError(f"unknown parameter(s): {', '.join(unknown)}")
        typed = {}
        for name, value in values.items():
            kind = type(fields[name].default)
            if kind is int and isinstance(value, float) and not value.is_integer():
                raise ParameterError(f"parameter {name} must be an integer, not {value!r}")
            if kind is bool and not isinstance(value, bool):
                raise ParameterError(f"parameter {name} must be true or false, not {value!r}")
            try:
                typed[name] = kind(value)
            except (TypeError, ValueError):
                raise ParameterError(f"parameter {name} must be a {kind.__name__}, not {value!r}") from None
        return cls(**typed)
