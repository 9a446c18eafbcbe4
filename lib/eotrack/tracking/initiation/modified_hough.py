"""Modified Hough track initiation of Xu & Wang (Acta Astronomica Sinica 57(2):211, 2016).

Over a short arc a space object moves on a straight line at constant speed on the image, so its
detections lie on one line of the (t, x, y) space. The method votes in a four-parameter space
``(ρ, θ, v, s)``:

* ``ρ = x cos θ + y sin θ`` (eq. 1) — the image line, θ ∈ [0°, 180°);
* ``v`` — the apparent speed (pixels per second), ``s`` ∈ {−, +} the direction along the line
  (``+`` = along ``u(θ) = (sin θ, −cos θ)``, i.e. increasing image x; for θ = 0, decreasing y).

At frame ``k`` every candidate of ``O_k`` is paired with every candidate of the two previous
frames ``j = k−1`` and ``i = k−2`` (previous in the sequence — frames need not be consecutive
nor evenly spaced: the speed uses the real time difference). Pairs inside the velocity gate
``v_min ≤ v ≤ v_max`` give a cell ``(ρ_n, θ_n, v_n, s)`` of sizes ``δρ, δθ, δv``; the cells form
the set ``S_k = S_kj ∪ S_ki`` and the pairs are recorded in the point-set matrix ``Q``.

Votes (reading adopted here, see the notebook's errata): ``P(t)`` is the number of distinct
frames of the last ``m`` whose detections are in ``Q(t)``. A frame therefore adds at most one
vote per cell however many of its points fall in it (the paper's set-based ``P(t) += 1``), and
the first pair of a cell counts both its frames. A track is confirmed by the ``(m−1)/m`` rule:
``P(t) ≥ m − 1``, or, for a cell of ``S_k`` that falls short, together with a 6-neighbour ``t′``
(±1 cell in ρ, θ or v, same s) that the least-squares line through ``Q(t)`` is close to (within
1.5 cells of its centre in ρ and θ), when the two cells together hold ``m − 1`` frames. Cells are examined in
decreasing ``P``; a confirmed track clears its cells and is handed to tracking (its detections
leave every other cell and later frames' candidate sets). Votes older than ``m`` frames expire.

Implementation: the vote matrix is a dense ``uint32`` array holding, per cell, a bit mask of the
frames that voted (frame index mod 32), so ``P(t)`` is a popcount of the mask restricted to the
window; the pairs of the last ``m`` frames are kept in arrays for ``Q``. All per-pair work is
vectorised.
"""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy.stats import chi2 as _chi2_dist

from eotrack.validation import as_finite_array, check_int, check_positive

from .base import Frame, Track, validate_frames
from .gating import TrackHandOff, canonical_order, check_velocity_gate
from .pairs import PointGrid, cv_fit_batch, greedy_disjoint, occupancy_image

__all__ = ["ModifiedHoughInitiator", "ModifiedHoughRun", "line_through_points", "pair_parameters"]

_BITS = 32
_MAX_M = 16


@functools.lru_cache(maxsize=256)
def _chi2_ppf(q: float, dof: int) -> float:
    """``scipy.stats.chi2.ppf`` (cached: it costs milliseconds per call)."""
    return float(_chi2_dist.ppf(q, dof))


def line_through_points(xy: np.ndarray) -> tuple[float, float]:
    """Total-least-squares line ``ρ = x cos θ + y sin θ`` through points, θ in [0, π).

    Parameters
    ----------
    xy
        ``(k, 2)`` points, ``k ≥ 2`` and not all equal.

    Returns
    -------
    rho, theta : float
        Line parameters (pixels, radians).
    """
    p = np.asarray(xy, float)
    if p.ndim != 2 or p.shape[1] != 2 or len(p) < 2:
        raise ValueError(f"xy must have shape (k, 2) with k >= 2, got {p.shape}")
    c = p.mean(axis=0)
    cov = np.cov((p - c).T, bias=True)
    w, vec = np.linalg.eigh(cov)
    if w[-1] <= 0:
        raise ValueError("xy points all coincide: no line through them")
    normal = vec[:, 0]
    theta = math.atan2(normal[1], normal[0]) % math.pi
    rho = c[0] * math.cos(theta) + c[1] * math.sin(theta)
    return float(rho), float(theta)


@dataclass
class ModifiedHoughRun:
    """Result of :meth:`ModifiedHoughInitiator.run`: the tracks and a per-frame log.

    ``log`` has one dict per frame with ``frame``, ``time_s``, ``candidates`` (detections left
    for initiation after hand-off), ``pairs`` (velocity-gated pairs), ``rejected`` (pairs
    removed by the velocity gate), ``created`` (cells that
    received their first vote), ``destroyed`` (cells whose votes all expired or were purged,
    without being confirmed), ``confirmed`` (tracks confirmed) and ``tentative`` (cells holding
    votes after the frame).
    """

    tracks: list[Track]
    log: list[dict] = field(default_factory=list)


@dataclass(frozen=True)
class ModifiedHoughInitiator:
    """Xu & Wang's modified Hough initiator; defaults are the paper's settings.

    Parameters
    ----------
    d_rho
        Cell size δρ (pixels).
    d_theta_deg
        Cell size δθ (degrees).
    d_v
        Cell size δv (pixels per second).
    v_min, v_max
        Velocity gate (pixels per second).
    m
        Window of the ``(m−1)/m`` confirmation rule (``2 ≤ m ≤ 16``); ``m = 4`` is 3/4.
    handoff_gate_px
        Gate of the tracking hand-off that claims a confirmed track's later detections.
    neighbourhood
        Cells examined around a cell short of votes: 6 (±1 in one of ρ, θ, v — the paper's) or
        26 (±1 in any combination).
    origin_px
        Origin of ρ (the paper does not say; default the image corner ``(0, 0)``).
    max_cells
        Refuse parameter spaces larger than this (memory guard).
    literal
        ``True``: the paper's cell-counting procedure; ``False`` (default): the verified
        initiator (χ² test at ``sigma_px``, best fit first).
    sigma_px, alpha
        Centroid noise per axis and false-rejection probability of the verified χ² tests.
    accel_px_s2
        Verified initiator only: largest along- and cross-track acceleration (px/s²) of an
        object that must still be initiated. When > 0, every frame with a full window also
        searches **four-hit** tracks of constant acceleration: a seed pair ``(k−3, k−1)``, the
        hit of frame ``k`` in the χ² disc widened by the largest acceleration offset
        ``a√2/2·|(t_k − t_{k−3})(t_k − t_{k−1})|``, and the hit of ``k−2`` within the χ²
        (2 d.o.f.) disc of the quadratic through the other three. They compete with the
        3-hit triplets in one best-first selection (more hits first, then the fit's p-value),
        so a longer track is not lost to a chance triplet. ``0`` turns the search off.
    accel_gapped
        Verified initiator with ``accel_px_s2 > 0`` only: also search the three **gapped**
        four-hit windows of the last five frames (4 detections in 5 frames, the missed frame
        anywhere inside). Off by default: on the held-out family it raises recall but costs
        about 1.6× the time per frame (notebook 04, Beyond).
    accel_triplets
        Verified initiator with ``accel_px_s2 > 0`` only: the χ² test of a **three-hit**
        candidate adds the acceleration's variance (along and cross uniform in
        ``±accel_px_s2``: ``a²/3`` per axis) to the second difference of its positions, and
        three-hit candidates get four-hit constant-acceleration extensions (the χ² (2 d.o.f.)
        disc of the quadratic through the three hits) into the window's empty frames. The
        widening is density-aware (``chance_budget``). Off by default (the paper's scenes and
        the capstone keep the constant-velocity test).
    hold_triplets
        Verified initiator only: hold-and-confirm. A three-hit candidate whose last hit is in
        the current frame waits one frame (it is confirmed at the next frame if nothing longer
        took its detections; at the last frame of the sequence nothing waits), so that a
        four-hit track through the same detections is preferred to it. Confirmation windows
        then span ``m + 1`` frames. Off by default. A batch option: it needs to know the last
        frame, so a caller feeding a stream in chunks gets other tracks at the chunk ends than
        one ``initiate`` over the whole sequence.
    chance_budget
        With ``accel_triplets``: the acceleration widening of a triplet shape's third-point
        disc is cut so that the widened discs of one frame triple, **summed over all its
        velocity-gated seed pairs**, hold at most this many chance triplets in expectation
        (uniform clutter over the field); never below the constant-velocity disc. ``0`` lifts
        the cut.
    field_px
        With ``accel_triplets``: ``(width, height)`` of the field for ``chance_budget``
        (pixels). ``None`` (default): estimated at each frame from the detections of the
        window's frames up to it (their 1st–99th-percentile box: causal, robust to a stray
        detection).
    cv_check
        Literal procedure only: our constant-velocity check of a confirmed cell (one
        detection per frame whose consecutive pairs map to the cell or a 26-neighbour, all
        within δρ/2 of their constant-velocity fit). ``False`` runs the paper's bare procedure:
        the hits are the cell's points, one per frame (the one nearest the fit).
    grow
        Verified initiator with ``accel_px_s2 > 0`` (the default): **track growth** over the
        whole sequence (a batch decision; issue 27). Acceleration-widened 3-of-4 seeds are
        grown frame by frame with a least-squares constant-acceleration fit (irregular
        intervals and missed frames allowed), and one best-first selection over the whole
        sequence prefers longer tracks, so chance triplets (a clutter burst's too) cannot take
        the detections of a longer track; see ``_GrowEngine``. A track's ``confirmed_at`` is
        the first frame at which its hits meet the ``(m−1)/m`` rule. **Not causal**: when
        growth runs, the tracks confirmed at frame ``k`` depend on frames after ``k`` (appending
        a frame can change them), so it is an offline (batch) mode, not a real-time initiator
        as the paper's; see ``grow_min_accelerating`` for when it runs. ``False``: the causal
        frame-by-frame engine (the options ``hold_triplets``, ``accel_triplets``,
        ``accel_gapped`` act there only).
    seed_budget
        Growth: the acceleration widening of a seed shape's disc is cut so that it holds at
        most this many chance seeds per frame triple in expectation (``0``: no cut).
    grow_chance
        Growth: the growth disc of a frame is cut so that it holds at most this many chance
        detections in expectation (the frame's own detection count: a burst frame gets a
        smaller disc).
    triplet_budget
        Growth: a three-hit track failing the constant-velocity χ² test is still a candidate
        when its middle hit lies within the largest acceleration offset of its chord, that
        widening cut so such discs hold at most this many chance triplets per frame triple in
        expectation, and its constant-velocity fit crosses at most ``max_missed`` in-field
        frames without a hit. ``0``: three-hit tracks must pass the constant-velocity test.
    max_missed
        See ``triplet_budget``.
    miss_weight
        Growth: rank of a candidate = hits − ``miss_weight`` × in-field frames without a hit
        (then the fit's p-value).
    share_missed
        Growth: a three-hit candidate lost in the selection that shares exactly one detection
        with selected three-hit tracks (none with longer ones) and misses at most this many
        in-field frames is also reported (ambiguous triplets both kept); ``−1``: never.
    grow_min_accelerating
        Growth runs only when the data call for it: the causal engine runs first, and its
        result is kept unless (a) a frame is a clutter burst (``grow_burst``), or (b) at least
        this many of its tracks of ≥ ``m + 1`` hits pass the constant-acceleration χ² and fail
        the constant-velocity one (both at ``alpha``), or (c) the growth engine's own result
        holds at least this many such tracks (the causal engine can lose every accelerating
        object to chance triplets, so (b) alone misses the scenes that need growth most).
        Tracks of ``m`` hits are not evidence: in clutter, chance four-hit tracks pass the
        constant-acceleration test and fail the constant-velocity one too often. So scenes of
        constant-velocity objects without bursts (the paper's) keep the causal engine's
        tracks. ``0``: always grow.
    grow_burst
        Growth runs (unless the frames are crowded) when one frame holds more than this many
        times the median frame's detections and at least 50 more (a clutter burst); ``0``:
        bursts do not trigger growth.
    grow_max_seeds
        Growth is skipped (the causal engine runs) when, in the median frame, the unwidened
        χ² discs alone would hold more than this many chance seeds per frame triple (crowded
        frames: from ≈ 120 uniform detections per 512² frame at 1 s intervals; the held-out
        family's frames hold ≈ 1–10).
    """

    d_rho: float = 5.0
    d_theta_deg: float = 5.0
    d_v: float = 3.0
    v_min: float = 10.0
    v_max: float = 240.0
    m: int = 4
    handoff_gate_px: float = 5.0
    neighbourhood: int = 6
    origin_px: tuple[float, float] = (0.0, 0.0)
    max_cells: int = 50_000_000
    literal: bool = False
    sigma_px: float = 0.3
    alpha: float = 1e-3
    accel_px_s2: float = 3.0
    accel_gapped: bool = False
    accel_triplets: bool = False
    hold_triplets: bool = False
    chance_budget: float = 2.0
    field_px: tuple[float, float] | None = None
    cv_check: bool = True
    grow: bool = True
    seed_budget: float = 100.0
    grow_chance: float = 0.01
    triplet_budget: float = 10.0
    max_missed: int = 2
    miss_weight: float = 0.25
    share_missed: int = 1
    grow_max_seeds: float = 100.0
    grow_min_accelerating: int = 1
    grow_burst: float = 3.0

    def __post_init__(self) -> None:
        check_positive(self.d_rho, "d_rho")
        check_positive(self.d_theta_deg, "d_theta_deg")
        if self.d_theta_deg > 180:
            raise ValueError(f"d_theta_deg must be <= 180, got {self.d_theta_deg}")
        check_positive(self.d_v, "d_v")
        check_velocity_gate(self.v_min, self.v_max)
        check_int(self.m, "m", min_value=2, max_value=_MAX_M)
        check_positive(self.handoff_gate_px, "handoff_gate_px")
        check_int(self.max_cells, "max_cells", min_value=1)
        if not isinstance(self.literal, (bool, np.bool_)):
            raise TypeError(f"literal must be True or False, got {self.literal!r}")
        check_positive(self.sigma_px, "sigma_px")
        a = check_positive(self.alpha, "alpha")
        if not a < 1:
            raise ValueError(f"alpha must lie in (0, 1), got {self.alpha}")
        check_positive(self.accel_px_s2, "accel_px_s2", allow_zero=True)
        check_positive(self.chance_budget, "chance_budget", allow_zero=True)
        if self.field_px is not None:
            f = np.asarray(self.field_px, dtype=float)
            if f.shape != (2,) or not np.all(np.isfinite(f)) or np.any(f <= 0):
                raise ValueError(f"field_px must be two positive numbers (width, height in "
                                 f"pixels) or None, got {self.field_px!r}")
        for name in ("accel_gapped", "accel_triplets", "hold_triplets", "cv_check"):
            if not isinstance(getattr(self, name), (bool, np.bool_)):
                raise TypeError(f"{name} must be True or False, got {getattr(self, name)!r}")
        # options that would otherwise be silently ignored
        if self.literal and (self.hold_triplets or self.accel_triplets):
            raise ValueError("hold_triplets and accel_triplets act on the verified initiator "
                             "only (literal=False)")
        if not self.literal and not self.cv_check:
            raise ValueError("cv_check=False is the paper's bare procedure: literal=True only")
        if (self.accel_triplets or self.accel_gapped) and self.accel_px_s2 == 0:
            raise ValueError("accel_triplets / accel_gapped need accel_px_s2 > 0")
        if not self.accel_triplets and (self.field_px is not None or self.chance_budget != 2.0):
            raise ValueError("chance_budget and field_px act with accel_triplets=True only")
        if not self.literal and self.m < 4:
            raise ValueError(f"the verified initiator (literal=False) needs m >= 4 (a triplet "
                             f"plus the window), got m={self.m}; use literal=True for m < 4")
        if not isinstance(self.grow, (bool, np.bool_)):
            raise TypeError(f"grow must be True or False, got {self.grow!r}")
        for name in ("seed_budget", "grow_chance", "triplet_budget", "miss_weight",
                     "grow_max_seeds", "grow_burst"):
            check_positive(getattr(self, name), name, allow_zero=True)
        check_positive(self.grow_chance, "grow_chance")
        check_int(self.max_missed, "max_missed", min_value=0)
        check_int(self.share_missed, "share_missed", min_value=-1)
        check_int(self.grow_min_accelerating, "grow_min_accelerating", min_value=0)
        if self.grow and not self.literal and self.accel_px_s2 > 0 and (
                self.hold_triplets or self.accel_triplets or self.accel_gapped):
            raise ValueError("hold_triplets, accel_triplets and accel_gapped act on the causal "
                             "engine only: pass grow=False with them")
        if self.neighbourhood not in (6, 26):
            raise ValueError(f"neighbourhood must be 6 (the paper's) or 26, got "
                             f"{self.neighbourhood!r}")
        o = np.asarray(self.origin_px, dtype=float)
        if o.shape != (2,) or not np.all(np.isfinite(o)):
            raise ValueError(f"origin_px must be two finite numbers, got {self.origin_px!r}")

    # ------------------------------------------------------------------ public
    def initiate(self, frames: Sequence) -> list[Track]:
        """Confirmed tracks from ``frames`` (a sequence of ``(time_s, xy)``)."""
        return self.run(frames).tracks

    def run(self, frames: Sequence, *, log: bool = False) -> ModifiedHoughRun:
        """Process the frames in order; optionally log per-frame counts (Table 2 of the paper).

        Parameters
        ----------
        frames
            Sequence of ``(time_s, xy)`` in increasing time order.
        log
            Also record the per-frame log (costs a scan of the vote matrix per frame).
        """
        fr = validate_frames(frames)
        perms = [canonical_order(f.xy) for f in fr]
        times = np.array([f.time_s for f in fr])
        if not self.literal:
            xys = [f.xy[p] for f, p in zip(fr, perms)]
            work = [Frame(float(t), x) for t, x in zip(times, xys)]
            causal = _VerifiedEngine(self, xys, times, work, perms, log).run()
            if not (self.grow and self.accel_px_s2 > 0) \
                    or _crowded(self, times, xys) > self.grow_max_seeds:
                return causal
            k = self.grow_min_accelerating
            if _burst(xys, self.grow_burst) or _accelerating(
                    causal.tracks, fr, times, self, min_hits=self.m + 1) >= k:
                return _GrowEngine(self, xys, times, work, perms, log).run()
            # the causal engine can lose the very accelerating objects that would show the
            # need for growth (chance triplets take their detections): the growth engine's own
            # tracks are evidence too
            grown = _GrowEngine(self, xys, times, work, perms, log).run()
            return grown if _accelerating(grown.tracks, fr, times, self,
                                          min_hits=self.m + 1) >= k else causal
        o = np.asarray(self.origin_px, dtype=float)
        xys = [f.xy[p] - o for f, p in zip(fr, perms)]
        return _Engine(self, xys, times, fr, perms, log).run()

    def cell_of(self, xy_a: np.ndarray, t_a: float, xy_b: np.ndarray,
                t_b: float) -> tuple[float, float, float, int]:
        """``(ρ, θ_deg, v, s)`` of the motion from ``xy_a`` at ``t_a`` to ``xy_b`` at ``t_b``."""
        o = np.asarray(self.origin_px, dtype=float)
        a = np.asarray(xy_a, float).reshape(1, 2) - o
        b = np.asarray(xy_b, float).reshape(1, 2) - o
        if not float(t_b) > float(t_a):
            raise ValueError(f"t_b must be later than t_a, got {t_a} and {t_b}")
        rho, theta, v, s = _pair_params(a, b, float(t_b) - float(t_a))
        return float(rho[0]), float(np.degrees(theta[0])), float(v[0]), int(s[0])


def pair_parameters(xy_a: np.ndarray, xy_b: np.ndarray, dt: float | np.ndarray,
                    origin_px: tuple[float, float] = (0.0, 0.0),
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Hough parameters of the motions ``xy_a → xy_b`` (rows), eq. (1) of Xu & Wang.

    Parameters
    ----------
    xy_a, xy_b
        ``(n, 2)`` start and end positions (pixels); no row may have ``xy_a == xy_b``.
    dt
        Time from a to b (s, > 0), scalar or ``(n,)``.
    origin_px
        Origin of ρ.

    Returns
    -------
    rho, theta, v, s : numpy.ndarray
        ``ρ = x cos θ + y sin θ`` about the origin (pixels), θ ∈ [0, π) (radians), speed
        (pixels per second) and direction ``s = ±1`` along ``u(θ) = (sin θ, −cos θ)``.
    """
    a = as_finite_array(xy_a, "xy_a", shape=(None, 2))
    b = as_finite_array(xy_b, "xy_b", shape=(None, 2))
    if len(a) != len(b):
        raise ValueError(f"xy_a and xy_b must have the same length, got {len(a)} and {len(b)}")
    d = np.asarray(dt, dtype=float)
    if not np.all(np.isfinite(d)) or np.any(d <= 0):
        raise ValueError("dt must be finite and > 0")
    if np.any(np.all(a == b, axis=1)):
        raise ValueError("xy_a and xy_b coincide in some row: no line through them")
    o = np.asarray(origin_px, float)
    return _pair_params(a - o, b - o, d)


def _cv_residuals(t: np.ndarray, xy: np.ndarray) -> np.ndarray:
    """Squared residuals of a least-squares constant-velocity fit (no input checks; internal)."""
    tc = t - t.mean()
    den = float(tc @ tc)
    pm = xy.mean(axis=0)
    v = tc @ (xy - pm) / den if den > 0 else np.zeros(2)
    r = xy - pm - np.outer(tc, v)
    return r[:, 0] ** 2 + r[:, 1] ** 2


def _pair_params(a: np.ndarray, b: np.ndarray, dt: float | np.ndarray):
    """ρ, θ (rad, [0, π)), speed and direction s (±1) of pairs a → b."""
    return _pair_params_d(b[:, 0] - a[:, 0], b[:, 1] - a[:, 1], b, dt)


def _pair_params_d(dx: np.ndarray, dy: np.ndarray, b: np.ndarray, dt: float | np.ndarray):
    """:func:`_pair_params` from the displacements ``(dx, dy)`` and the end points ``b``."""
    length = np.hypot(dx, dy)
    # unit normal (cos θ, sin θ) = ±(−dy, dx)/|Δ|, flipped so that θ ∈ [0, π)
    flip = (dx < 0) | ((dx == 0) & (dy > 0))
    with np.errstate(invalid="ignore", divide="ignore"):
        c = np.where(flip, dy, -dy) / length
        s_ = np.where(flip, -dx, dx) / length
    theta = np.arctan2(s_, c)
    theta = np.where(theta >= np.pi, 0.0, theta)
    rho = b[:, 0] * c + b[:, 1] * s_
    along = dx * s_ - dy * c  # Δ · u(θ), u = (sin θ, −cos θ)
    sign = np.where(along >= 0, 1, -1)
    return rho, theta, length / dt, sign


class _Engine:
    """One run of the modified Hough over a frame sequence (internal)."""

    def __init__(self, cfg: ModifiedHoughInitiator, xys, times, frames, perms, log: bool):
        self.cfg = cfg
        self.xys = xys
        self.times = times
        self.frames = frames
        self.perms = perms
        self.log_on = log
        self.m = cfg.m
        self.need = cfg.m - 1
        self.d_theta = math.radians(cfg.d_theta_deg)
        self.n_theta = max(1, math.ceil(180.0 / cfg.d_theta_deg - 1e-9))
        self.v0 = math.floor(cfg.v_min / cfg.d_v)
        self.n_v = math.floor(cfg.v_max / cfg.d_v) - self.v0 + 1
        r_max = max((float(np.max(np.hypot(x[:, 0], x[:, 1]))) for x in xys if len(x)),
                    default=0.0)
        self.r_off = math.ceil(r_max / cfg.d_rho) + 2
        self.n_rho = 2 * self.r_off + 1
        n_cells = self.n_rho * self.n_theta * self.n_v * 2
        if n_cells > cfg.max_cells:
            raise ValueError(
                f"the (ρ, θ, v, s) space would have {n_cells} cells (> max_cells="
                f"{cfg.max_cells}); use larger cells d_rho/d_theta_deg/d_v or a narrower "
                f"velocity gate, or shift the detections closer to the origin")
        self.acc = np.zeros(n_cells, dtype=np.uint32)
        sizes = [len(x) for x in xys]
        self.off = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
        self.avail_flat = np.ones(int(self.off[-1]), dtype=bool)
        self.available = [self.avail_flat[self.off[f]:self.off[f + 1]] for f in range(len(xys))]
        self.xy_flat = np.concatenate([x for x in xys]) if sizes and self.off[-1] else \
            np.zeros((0, 2))
        self.fw = [Frame(float(t), x) for t, x in zip(times, xys)]
        self.flag = np.zeros(n_cells, dtype=bool)
        rng3 = (-1, 0, 1)
        self.offsets = [(a, b, c) for a in rng3 for b in rng3 for c in rng3
                        if (a, b, c) != (0, 0, 0)
                        and (cfg.neighbourhood == 26 or abs(a) + abs(b) + abs(c) == 1)]
        self.cleared: dict[int, int] = {}
        self.handoff = TrackHandOff(cfg.handoff_gate_px)
        # stored pairs of the last m current frames: dict frame -> dict of arrays
        self.pairs: dict[int, dict[str, np.ndarray]] = {}
        self.log: list[dict] = []
        self.tentative_prev = 0

    # -- cell indexing -------------------------------------------------------
    def _indices(self, rho, theta, v, s):
        cfg = self.cfg
        ir = np.floor(rho / cfg.d_rho).astype(np.int64) + self.r_off
        it = np.minimum((theta / self.d_theta).astype(np.int64), self.n_theta - 1)
        iv = np.floor(v / cfg.d_v).astype(np.int64) - self.v0
        iv = np.clip(iv, 0, self.n_v - 1)
        is_ = (s > 0).astype(np.int64)
        return ir, it, iv, is_

    def _key(self, ir, it, iv, is_):
        return ((ir * self.n_theta + it) * self.n_v + iv) * 2 + is_

    def _unkey(self, key):
        is_ = key % 2
        rest = key // 2
        iv = rest % self.n_v
        rest //= self.n_v
        it = rest % self.n_theta
        ir = rest // self.n_theta
        return ir, it, iv, is_

    def _centre(self, key):
        ir, it, iv, is_ = self._unkey(int(key))
        cfg = self.cfg
        rho = (ir - self.r_off + 0.5) * cfg.d_rho
        theta = min((it + 0.5) * self.d_theta, math.pi)
        v = (iv + self.v0 + 0.5) * cfg.d_v
        return rho, theta, v, (1 if is_ else -1)

    def _neighbours(self, ir, it, iv, is_):
        """Keys of the 6 (or 26) neighbours of cells (arrays, same s); invalid ones are -1."""
        out = []
        d_rho = self.cfg.d_rho
        for dr, dt, dv in self.offsets:
            r = ir + dr
            t = it + dt
            v = iv + dv
            # θ wrap-around: the line (ρ, θ) equals (−ρ, θ ± π) with s reversed
            wraps = (t < 0) | (t >= self.n_theta)
            rho_c = (r - self.r_off + 0.5) * d_rho
            r = np.where(wraps, np.floor(-rho_c / d_rho).astype(np.int64) + self.r_off, r)
            s = np.where(wraps, 1 - is_, is_)
            t = np.mod(t, self.n_theta)
            ok = (r >= 0) & (r < self.n_rho) & (v >= 0) & (v < self.n_v)
            key = self._key(np.clip(r, 0, self.n_rho - 1), t, np.clip(v, 0, self.n_v - 1), s)
            out.append(np.where(ok, key, -1))
        return out

    # -- main loop -------------------------------------------------------------
    def run(self) -> ModifiedHoughRun:
        n = len(self.xys)
        period = _BITS - self.m - 2
        for k in range(n):
            if k and k % period == 0:
                self.acc &= self._bits(k - self.m - 1, k)
            self._frame(k)
        return ModifiedHoughRun(self.handoff.tracks(self.perms), self.log)

    @staticmethod
    def _bits(first: int, last: int) -> np.uint32:
        mask = 0
        for f in range(max(first, 0), last + 1):
            mask |= 1 << (f % _BITS)
        return np.uint32(mask)

    def _frame(self, k: int) -> None:
        cfg = self.cfg
        xy_k = self.xys[k]
        avail_k = self.available[k]
        self.handoff.claim(k, self.times[k], xy_k, avail_k)
        for c in [c for c in self.pairs if c < k - self.m + 1]:
            del self.pairs[c]
        window = self._bits(k - self.m + 1, k)
        keys_all, fa_all, da_all, db_all = [], [], [], []
        idx_k = np.flatnonzero(avail_k)
        n_tried = 0
        for back in (1, 2):
            j = k - back
            if j < 0 or len(idx_k) == 0:
                continue
            idx_j = np.flatnonzero(self.available[j])
            n_tried += len(idx_j) * len(idx_k)
            if len(idx_j) == 0:
                continue
            a = self.xys[j][idx_j]
            b = xy_k[idx_k]
            dt = self.times[k] - self.times[j]
            dx = b[None, :, 0] - a[:, None, 0]
            dy = b[None, :, 1] - a[:, None, 1]
            d2 = dx * dx + dy * dy
            ia, ib = np.nonzero((d2 >= (cfg.v_min * dt) ** 2) & (d2 <= (cfg.v_max * dt) ** 2))
            if len(ia) == 0:
                continue
            rho, theta, v, s = _pair_params_d(dx[ia, ib], dy[ia, ib], b[ib], dt)
            key = self._key(*self._indices(rho, theta, v, s))
            keys_all.append(key)
            fa_all.append(np.full(len(ia), j, dtype=np.int64))
            da_all.append(idx_j[ia])
            db_all.append(idx_k[ib])
        if keys_all:
            keys = np.concatenate(keys_all)
            fa = np.concatenate(fa_all)
            da = np.concatenate(da_all)
            db = np.concatenate(db_all)
        else:
            keys = np.zeros(0, np.int64)
            fa = da = db = keys
        created = 0
        if self.log_on and len(keys):
            uk = np.unique(keys)
            created = int(np.count_nonzero((self.acc[uk] & window) == 0))
        bit_k = np.uint32(1 << (k % _BITS))
        for back in (1, 2):
            sel = fa == k - back
            if np.any(sel):
                self.acc[keys[sel]] |= bit_k | np.uint32(1 << ((k - back) % _BITS))
        self.pairs[k] = {"key": keys, "fa": fa, "da": da, "db": db}
        n_conf = self._extract(k, keys, window)
        if self.log_on:
            nxt = self._bits(k - self.m + 2, k)
            tentative = int(np.count_nonzero(self.acc & nxt))
            destroyed = self.tentative_prev + created - n_conf["cells"] - tentative
            self.log.append({"frame": k, "time_s": float(self.times[k]),
                             "candidates": len(idx_k), "pairs": len(keys),
                             "rejected": n_tried - len(keys),
                             "created": created, "destroyed": max(destroyed, 0),
                             "confirmed": n_conf["tracks"], "tentative": tentative})
            self.tentative_prev = tentative

    def _extract(self, k: int, keys: np.ndarray, window: np.uint32) -> dict:
        """Examine the cells of S_k in decreasing P and confirm tracks (see module docs)."""
        out = {"tracks": 0, "cells": 0}
        if len(keys) == 0:
            return out
        need = self.need
        pop = np.bitwise_count
        p_own = pop(self.acc[keys] & window)
        direct = p_own >= need
        cand_t = [keys[direct]]
        cand_t2 = [np.full(int(direct.sum()), -1, dtype=np.int64)]
        cand_p = [p_own[direct]]
        short = ~direct
        if np.any(short):
            ks = keys[short]
            own_s = self.acc[ks] & window
            p_s = p_own[short]
            for nb in self._neighbours(*self._unkey(ks)):
                m2 = self.acc[np.maximum(nb, 0)] & window
                hit = (nb >= 0) & (m2 != 0) & (pop(own_s | m2) >= need)
                if np.any(hit):
                    cand_t.append(ks[hit])
                    cand_t2.append(nb[hit])
                    cand_p.append(p_s[hit])
        t_all = np.concatenate(cand_t)
        if len(t_all) == 0:
            return out
        cands = np.unique(np.stack([-np.concatenate(cand_p).astype(np.int64), t_all,
                                    np.concatenate(cand_t2)], 1), axis=0)
        cells_all = np.unique(cands[:, 1:][cands[:, 1:] >= 0])
        sub = self._pairs_in(k, cells_all)
        lo = k - self.m + 1
        # vectorised pre-check: frames of still-available points per cell, union per candidate
        cm = self._cell_masks(sub, cells_all, lo)
        m1 = cm[np.searchsorted(cells_all, cands[:, 1])]
        m2 = np.where(cands[:, 2] >= 0,
                      cm[np.searchsorted(cells_all, np.maximum(cands[:, 2], 0))], 0)
        cands = cands[pop(m1 | m2) >= need]
        for _negp, t, t2 in cands:
            cells = [int(t)] if t2 < 0 else [int(t), int(t2)]
            if any(self.cleared.get(c, -1) == k for c in cells):
                continue
            pts = self._points_of(sub, cells, lo)
            if len(np.unique(pts[:, 0])) < need:
                continue
            hits = self._choose_hits(pts, int(t))
            if len(hits) < need:
                continue
            if t2 >= 0 and not self._line_close(sub, int(t), int(t2), lo):
                continue
            rho, theta, v, s = self._centre(int(t))
            self.handoff.confirm(hits, k, self.fw,
                                 info={"method": "modified_hough", "cells": cells,
                                       "rho_px": rho, "theta_deg": math.degrees(theta),
                                       "speed_px_s": v, "s": s})
            for c in cells:
                self.acc[c] = 0
                self.cleared[c] = k
            for f, d in hits:
                self.available[f][d] = False
            out["tracks"] += 1
            out["cells"] += len(cells)
        return out

    def _pairs_in(self, k: int, cells: np.ndarray) -> np.ndarray:
        """Live stored pairs falling in ``cells``, sorted by cell: rows ``(key, f_a, d_a, f_b, d_b)``.

        A pair is dead when its cell was cleared (by a confirmation) at or after its frame.
        """
        self.flag[cells] = True
        rows = []
        for cur, st in self.pairs.items():
            sel = self.flag[st["key"]]
            if np.any(sel):
                key = st["key"][sel]
                born = np.full(len(key), cur, dtype=np.int64)
                rows.append(np.stack([key, st["fa"][sel], st["da"][sel], born, st["db"][sel]], 1))
        self.flag[cells] = False
        if not rows:
            return np.zeros((0, 5), dtype=np.int64)
        sub = np.concatenate(rows)
        if self.cleared:
            ck = np.fromiter(self.cleared.keys(), dtype=np.int64)
            cv = np.fromiter(self.cleared.values(), dtype=np.int64)
            o = np.argsort(ck)
            ck, cv = ck[o], cv[o]
            pos = np.minimum(np.searchsorted(ck, sub[:, 0]), len(ck) - 1)
            dead = (ck[pos] == sub[:, 0]) & (cv[pos] >= sub[:, 3])
            sub = sub[~dead]
        return sub[np.argsort(sub[:, 0], kind="stable")]

    def _cell_masks(self, sub: np.ndarray, cells: np.ndarray, lo: int) -> np.ndarray:
        """Per cell of ``cells``, the bit mask of window frames with still-available points."""
        out = np.zeros(len(cells), dtype=np.uint32)
        if len(sub) == 0:
            return out
        pos = np.searchsorted(cells, sub[:, 0])
        for fc, dc in ((1, 2), (3, 4)):
            f = sub[:, fc]
            ok = (f >= lo) & self.avail_flat[self.off[f] + sub[:, dc]]
            np.bitwise_or.at(out, pos[ok], (np.uint32(1) << (f[ok] % _BITS)).astype(np.uint32))
        return out

    def _points_of(self, sub: np.ndarray, cells: list[int], lo: int) -> np.ndarray:
        """Distinct still-available ``(frame, detection)`` points of Q(cells) in the window."""
        parts = []
        for c in cells:
            i0, i1 = np.searchsorted(sub[:, 0], [c, c + 1])
            parts.append(sub[i0:i1])
        rows = np.concatenate(parts)
        f = np.concatenate([rows[:, 1], rows[:, 3]])
        d = np.concatenate([rows[:, 2], rows[:, 4]])
        g = np.unique(self.off[f] + d)  # global detection ids, unique
        g = g[self.avail_flat[g]]
        fr = np.searchsorted(self.off, g, side="right") - 1
        keep = fr >= lo
        return np.stack([fr[keep], g[keep] - self.off[fr[keep]]], 1)

    def _choose_hits(self, pts: np.ndarray, cell: int) -> list[tuple[int, int]]:
        """One detection per frame forming a constant-velocity track consistent with ``cell``.

        Every consecutive pair of the chosen hits must map to the cell or one of its 26
        neighbours (:meth:`_consistent`). Among the consistent choices (all combinations when
        there are at most 256, else the detection nearest a least-squares constant-velocity fit
        of all points in each frame) the one with the most frames, then the smallest residual
        of its own constant-velocity fit, wins. Returns ``[]`` when no consistent choice covers
        ``m − 1`` frames.
        """
        frames_u, counts = np.unique(pts[:, 0], return_counts=True)
        if np.all(counts == 1):
            return [(int(f), int(d)) for f, d in pts] if self._consistent(pts, cell) else []
        groups = [np.flatnonzero(pts[:, 0] == f) for f in frames_u]
        if np.prod(counts.astype(float)) > 256:
            res = _cv_residuals(self.times[pts[:, 0]], self.xy_flat[self.off[pts[:, 0]] + pts[:, 1]])
            groups = [g[np.argsort(res[g], kind="stable")[:2]] for g in groups]
        options = [groups]
        if len(groups) > self.need:
            options += [groups[:i] + groups[i + 1:] for i in range(len(groups))]
        best, best_cost = [], np.inf
        for gs in options:
            for combo in itertools.product(*gs):
                idx = np.array(combo)
                if not self._consistent(pts[idx], cell):
                    continue
                cost = self._cv_rss(pts[idx])
                if cost < best_cost:
                    best, best_cost = [(int(f), int(d)) for f, d in pts[idx]], cost
            if best:
                break
        return best

    def _cv_rss(self, hits: np.ndarray) -> float:
        """Residual sum of squares of a constant-velocity fit through ``hits``."""
        return float(np.sum(_cv_residuals(self.times[hits[:, 0]],
                                          self.xy_flat[self.off[hits[:, 0]] + hits[:, 1]])))

    def _consistent(self, hits: np.ndarray, cell: int) -> bool:
        """Hits (sorted by frame) form one constant-velocity track of ``cell``.

        Every consecutive pair maps to ``cell`` or a 26-neighbour of it, and every hit lies
        within half a ρ cell (δρ/2) of the least-squares constant-velocity fit through them.
        With ``cv_check=False`` (the bare procedure) every choice of one hit per frame passes.
        """
        if len(hits) < 2:
            return False
        if not self.cfg.cv_check:
            return True
        if len(hits) > 2:
            r2 = _cv_residuals(self.times[hits[:, 0]],
                               self.xy_flat[self.off[hits[:, 0]] + hits[:, 1]])
            if np.max(r2) > (0.5 * self.cfg.d_rho) ** 2:
                return False
        xy = self.xy_flat[self.off[hits[:, 0]] + hits[:, 1]]
        dt = np.diff(self.times[hits[:, 0]])
        rho, theta, v, s = _pair_params(xy[:-1], xy[1:], dt)
        if np.any(v < self.cfg.v_min) or np.any(v > self.cfg.v_max):
            return False
        ir, it, iv, is_ = self._indices(rho, theta, v, s)
        cr, ct, cv, cs = self._unkey(int(cell))
        dth = np.abs(it - ct)
        wrap = dth > self.n_theta // 2
        # across the θ wrap the same line has ρ → −ρ and s reversed
        ir_w = np.where(wrap, np.floor(-(ir - self.r_off + 0.5) * self.cfg.d_rho
                                       / self.cfg.d_rho).astype(np.int64) + self.r_off, ir)
        is_w = np.where(wrap, 1 - is_, is_)
        dth = np.where(wrap, self.n_theta - dth, dth)
        return bool(np.all((np.abs(ir_w - cr) <= 1) & (dth <= 1) & (np.abs(iv - cv) <= 1)
                           & (is_w == cs)))

    def _line_close(self, sub: np.ndarray, t: int, t2: int, lo: int) -> bool:
        """Is the least-squares line through Q(t) in t2 or a cell next to it (ρ, θ)?"""
        pts = self._points_of(sub, [t], lo)
        xy = self.xy_flat[self.off[pts[:, 0]] + pts[:, 1]]
        try:
            rho, theta = line_through_points(xy)
        except ValueError:
            return False
        rho_c, theta_c, _, _ = self._centre(t2)
        dth = abs(theta - theta_c)
        if dth > math.pi / 2:  # the same line across the θ wrap
            dth = math.pi - dth
            rho = -rho
        return abs(rho - rho_c) <= 1.5 * self.cfg.d_rho and dth <= 1.5 * self.d_theta



class _VerifiedEngine:
    """The improved initiator: triplets verified by a χ² test at the noise (internal).

    See :class:`ModifiedHoughInitiator` (``literal=False``). At frame ``k`` the three triplet
    shapes a 3-of-4 track can end with are searched: seeds ``(k−2, k)`` with the third
    detection in ``k−1`` or ``k−3``, and seeds ``(k−3, k−1)`` with the third in ``k``. For every
    seed pair at once (a broadcast over the two frames' detections, no pair list) the third
    detection's predicted position is looked up in a dilated occupancy image of the target frame;
    the few hits are checked exactly on a spatial grid inside the disc where the χ² test of the
    three-point constant-velocity fit passes (that disc *is* the test). Passing triplets are
    extended to the other frames of the window, ranked (more hits, then smaller χ²) and made
    disjoint best-first.
    """

    def __init__(self, cfg: ModifiedHoughInitiator, xys, times, frames, perms, log: bool):

        self.cfg = cfg
        self.xys = xys
        self.times = np.asarray(times, float)
        self.fw = frames
        self.perms = perms
        self.log_on = log
        self.m = cfg.m
        self.need = cfg.m - 1
        self.sigma = cfg.sigma_px
        self.hold = bool(cfg.hold_triplets)
        self.slots = cfg.m + 1 if self.hold else cfg.m
        self.thr = np.array([np.inf, np.inf, np.inf]
                            + [_chi2_ppf(1.0 - cfg.alpha, 2 * (n - 2))
                               for n in range(3, self.slots + 1)])
        # acceleration variance per image axis (along and cross uniform in ±a): a²/3
        self.q_acc = (cfg.accel_px_s2**2 / 3.0 if cfg.accel_triplets else 0.0)
        self.held = np.zeros((0, 3), dtype=np.int64)
        self.last = len(xys) - 1
        self.chance_budget = float(cfg.chance_budget)
        self._thr2 = _chi2_ppf(1.0 - cfg.alpha, 2)
        sizes = [len(x) for x in xys]
        self.off = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
        self.avail_flat = np.ones(int(self.off[-1]), dtype=bool)
        self.available = [self.avail_flat[self.off[f]:self.off[f + 1]] for f in range(len(xys))]
        self.xy_flat = np.concatenate(xys) if self.off[-1] else np.zeros((0, 2))
        # the field of the density cap: the caller's, else estimated frame by frame (causal)
        self.field_fixed = (None if cfg.field_px is None
                            else float(cfg.field_px[0]) * float(cfg.field_px[1]))
        self.field_area = 1.0
        self.frame_of = np.repeat(np.arange(len(xys)), sizes)
        self.handoff = TrackHandOff(cfg.handoff_gate_px)
        self.log: list[dict] = []

    def run(self) -> ModifiedHoughRun:
        for k in range(len(self.xys)):
            self._frame(k)
        return ModifiedHoughRun(self.handoff.tracks(self.perms), self.log)

    # -- the third-point search ------------------------------------------------
    def _occupancy(self, f: int, r: float, cell: float = 1.0):
        """Occupancy image of frame ``f``'s available detections for radius ``r``."""
        return occupancy_image(self.xys[f][self.available[f]], r, cell_px=cell)

    def _triplets(self, fa: int, fb: int, ft: int, widen: float = 0.0) -> np.ndarray:
        """Triplets (seed in ``fa``, seed in ``fb``, third in ``ft``) passing the χ² disc test
        (its radius plus ``widen`` pixels) and the (noise-widened) velocity gate; rows of
        global ids in frame order."""
        cfg = self.cfg
        ia_all = np.flatnonzero(self.available[fa])
        ib_all = np.flatnonzero(self.available[fb])
        if len(ia_all) == 0 or len(ib_all) == 0 or not np.any(self.available[ft]):
            return np.zeros((0, 3), dtype=np.int64)
        ta, tb, tt = self.times[fa], self.times[fb], self.times[ft]
        dt = tb - ta
        tau = (tt - tb) / dt
        cfac = 1.0 + (1.0 + tau) ** 2 + tau**2  # var(x_t − prediction) / σ²
        var = self.sigma**2 * cfac
        if widen == 0.0 and self.q_acc > 0:
            # acceleration-aware: the quadratic leaves the line by a/2 (t_t − t_a)(t_t − t_b)
            q = self.q_acc
            if self.chance_budget > 0:  # 0: no cut
                # density-aware: the disc may not hold more than `chance_budget` chance triplets
                # in expectation (uniform clutter over the field, see _field)
                n_t = int(self.available[ft].sum())
                area = self.field_area
                n_pairs = len(ia_all) * len(ib_all) * min(
                    1.0, math.pi * (cfg.v_max * dt) ** 2 / area)
                r2_max = self.chance_budget * area / (math.pi * max(n_pairs * n_t, 1.0))
                q_max = max(r2_max / self.thr[3] - var, 0.0) / (0.5 * (tt - ta) * (tt - tb)) ** 2
                q = min(q, q_max)
            var += q * (0.5 * (tt - ta) * (tt - tb)) ** 2
        r = math.sqrt(self.thr[3] * var) + widen
        # cells of side ∝ r for wide discs (the acceleration search: r grows as Δt²), so the
        # image stays about (span / cell + 20)² cells whatever the frame intervals
        cell = max(1.0, r / 6.0)
        occ, x0, y0, w, h = self._occupancy(ft, r, cell)
        a = self.xys[fa][ia_all]
        b = self.xys[fb][ib_all]
        # prediction (1 + τ) b − τ a for every pair, as one outer sum per axis (float32), in
        # cell units
        f32 = np.float32
        ic = 1.0 / cell
        qx = (((1 + tau) * b[:, 0] - x0) * ic).astype(f32)[None, :] \
            + (-tau * ic * a[:, 0]).astype(f32)[:, None]
        qy = (((1 + tau) * b[:, 1] - y0) * ic).astype(f32)[None, :] \
            + (-tau * ic * a[:, 1]).astype(f32)[:, None]
        np.clip(qx, 0, w - 1, out=qx)
        np.clip(qy, 0, h - 1, out=qy)
        key = qy.astype(np.int32)
        key *= w
        key += qx.astype(np.int32)
        sa, sb = np.nonzero(occ[key])
        if len(sa) == 0:
            return np.zeros((0, 3), dtype=np.int64)
        d = b[sb] - a[sa]
        v2 = (d[:, 0] ** 2 + d[:, 1] ** 2) / dt**2
        slack = 4.0 * math.sqrt(2.0) * self.sigma / dt  # the gate is applied again to the fit
        ok = (v2 >= max(cfg.v_min - slack, 0.0) ** 2) & (v2 <= (cfg.v_max + slack) ** 2)
        sa, sb = sa[ok], sb[ok]
        pred = (1 + tau) * b[sb] - tau * a[sa]
        it_all = np.flatnonzero(self.available[ft])
        qi, pi, _ = PointGrid(self.xys[ft][it_all], r).query(pred, r, sort=False)
        ga = self.off[fa] + ia_all[sa[qi]]
        gb = self.off[fb] + ib_all[sb[qi]]
        gt = self.off[ft] + it_all[pi]
        return np.stack([ga, gb, gt], 1)

    def _field(self, k: int) -> float:
        """Area of the field for the density cap at frame ``k``: ``field_px`` if given, else
        the 1st–99th-percentile box of the detections of the window's frames up to ``k``
        (causal, and one stray detection cannot inflate it); at least 1 px²."""
        if self.field_fixed is not None:
            return self.field_fixed
        lo = max(0, k - self.slots + 1)
        pts = self.xy_flat[self.off[lo]:self.off[k + 1]]
        if len(pts) < 2:
            return 1.0
        q = np.percentile(pts, [1.0, 99.0], axis=0)
        return max(float(np.prod(q[1] - q[0] + 1.0)), 1.0)

    def _frame(self, k: int) -> None:
        xy_k = self.xys[k]
        avail_k = self.available[k]
        if self.q_acc > 0 and self.chance_budget > 0:
            self.field_area = self._field(k)
        self.handoff.claim(k, self.times[k], xy_k, avail_k)
        lo = max(0, k - self.m + 1)
        entry = {"frame": k, "time_s": float(self.times[k]), "candidates": int(avail_k.sum()),
                 "triplets": 0, "candidate tracks": 0, "conflicts": 0, "confirmed": 0}
        trip = []
        if k - 2 >= lo:
            trip.append(self._triplets(k - 2, k, k - 1))
        if k - 3 >= lo:
            trip.append(self._triplets(k - 2, k, k - 3))
            trip.append(self._triplets(k - 3, k - 1, k))
        rows = np.concatenate(trip) if trip else np.zeros((0, 3), dtype=np.int64)
        entry["triplets"] = len(rows)
        extra = self._accel_tracks(k) if (self.cfg.accel_px_s2 > 0 and self.m == 4
                                          and k >= 3) else None
        if extra is not None:
            entry["accelerating"] = len(extra[0])
        if self.hold and len(self.held):
            h = self.held
            self.held = np.zeros((0, 3), dtype=np.int64)
            h = h[np.all(self.avail_flat[h], axis=1)]
            rows = np.concatenate([rows, h])
            entry["held"] = len(h)
        if len(rows) or (extra is not None and len(extra[0])):
            self._confirm(k, rows, lo, entry, extra)
        if self.log_on:
            self.log.append(entry)

    # -- confirmation --------------------------------------------------------------
    def _fit(self, rows: np.ndarray, slot_t: np.ndarray):
        mask = rows >= 0
        g = np.maximum(rows, 0)
        tt = np.broadcast_to(slot_t, rows.shape)
        tm, pm, v, rss = cv_fit_batch(tt, self.xy_flat[g, 0], self.xy_flat[g, 1], mask)
        return mask, tm, pm, v, rss

    def _accel_tracks(self, k: int):
        """Four-hit constant-acceleration tracks of the window ``k−3 … k`` (see
        ``accel_px_s2``): rows of global ids in frame order, their
        χ² (2 d.o.f.), and the constant-velocity mean position and velocity (track info)."""
        cfg = self.cfg
        t = self.times
        out_rows, out_chi = [], []
        wins = [[k - 3, k - 2, k - 1, k]]
        if cfg.accel_gapped and k >= 4:  # 4 of 5 with one gap (the missed frame inside)
            wins += [[k - 4, k - 2, k - 1, k], [k - 4, k - 3, k - 1, k], [k - 4, k - 3, k - 2, k]]
        for fr in wins:
            f0, f1, f2, f3 = fr
            if not np.any(self.available[f1]):
                continue
            widen = cfg.accel_px_s2 * math.sqrt(2.0) / 2.0 * abs((t[f3] - t[f0]) * (t[f3] - t[f2]))
            trip = self._triplets(f0, f2, f3, widen=widen)
            if len(trip) == 0:
                continue
            ts = t[[f0, f2, f3]]
            tq = t[f1]
            lag = np.array([np.prod([(tq - ts[j]) / (ts[i] - ts[j]) for j in range(3) if j != i])
                            for i in range(3)])
            pred = np.einsum("i,nij->nj", lag, self.xy_flat[trip])
            var = 1.0 + float(lag @ lag)
            r4 = self.sigma * math.sqrt(self._thr2 * var)
            it_all = np.flatnonzero(self.available[f1])
            qi, pi, d2 = PointGrid(self.xys[f1][it_all], r4).query(pred, r4)
            if len(qi) == 0:
                continue
            rows = np.stack([trip[qi, 0], self.off[f1] + it_all[pi], trip[qi, 1],
                             trip[qi, 2]], 1)
            out_rows.append(rows)
            out_chi.append(d2 / (self.sigma**2 * var))
        if not out_rows:
            z = np.zeros((0, 2))
            return np.zeros((0, 4), dtype=np.int64), np.zeros(0), z, z
        rows, chi = np.concatenate(out_rows), np.concatenate(out_chi)
        tt = self.times[self.frame_of[rows]]
        _, pm, v, _ = cv_fit_batch(tt, self.xy_flat[rows, 0], self.xy_flat[rows, 1],
                                   np.ones(rows.shape, bool))
        speed = np.hypot(v[:, 0], v[:, 1])
        ok = (speed >= cfg.v_min) & (speed <= cfg.v_max)
        return rows[ok], chi[ok], pm[ok], v[ok]

    def _confirm(self, k: int, trip: np.ndarray, lo: int, entry: dict,
                 extra: tuple[np.ndarray, np.ndarray] | None = None) -> None:
        cfg = self.cfg
        m = self.slots
        first = k - m + 1
        lo = max(0, first)
        slot_t = self.times[np.clip(np.arange(first, k + 1), 0, None)]
        rows = np.full((len(trip), m), -1, dtype=np.int64)
        np.put_along_axis(rows, self.frame_of[trip] - first, trip, axis=1)
        rows = self._extend(rows, slot_t, lo, first)
        mask, _tm, pm, v, rss = self._fit(rows, slot_t)
        nh = mask.sum(axis=1)
        s2 = np.full(len(rows), self.sigma**2)
        if self.q_acc > 0 and len(rows):
            # three hits: χ² of the second difference with the acceleration's variance added,
            # rss / (σ² + q D² / (4 |c|²)), D = (t2−t1)(t3−t2)(t3−t1), c = (t3−t2, t1−t3, t2−t1)
            three = np.flatnonzero(nh == 3)
            tt = np.sort(np.where(mask[three], slot_t[None, :], np.inf), axis=1)[:, :3]
            t1, t2, t3 = tt[:, 0], tt[:, 1], tt[:, 2]
            c2 = (t3 - t2) ** 2 + (t3 - t1) ** 2 + (t2 - t1) ** 2
            dd = (t2 - t1) * (t3 - t2) * (t3 - t1)
            s2[three] += self.q_acc * dd**2 / (4.0 * c2)
        chi = rss / s2
        speed = np.hypot(v[:, 0], v[:, 1])
        ok = ((nh >= self.need) & (chi <= self.thr[nh]) & (speed >= cfg.v_min)
              & (speed <= cfg.v_max))
        rows, pm, v, chi, nh = rows[ok], pm[ok], v[ok], chi[ok], nh[ok]
        dof = 2 * (nh - 2)  # constant velocity: 2 coordinates × (hits − 2)
        if self.q_acc > 0 and np.any(nh == 3):
            q = self._extend_quadratic(rows[nh == 3], slot_t, lo, first)
            if len(q[0]):
                extra = q if extra is None or not len(extra[0]) else tuple(
                    np.concatenate([a, b]) for a, b in zip(_pad_rows(extra, m), q))
        if extra is not None and len(extra[0]):
            extra = _pad_rows(extra, m)
        if extra is not None and len(extra[0]):
            # accelerating four-hit tracks join the same best-first selection (more hits
            # first, then by the p-value of the fit: their χ² has 2 degrees of freedom, a
            # four-hit constant-velocity track's 4, so χ² values are not comparable)
            pm_a, v_a = extra[2], extra[3]
            if rows.shape[1] != extra[0].shape[1]:
                raise AssertionError("accelerating tracks need m = 4")  # pragma: no cover
            rows = np.concatenate([rows, extra[0]])
            pm = np.concatenate([pm, pm_a])
            v = np.concatenate([v, v_a])
            chi = np.concatenate([chi, extra[1]])
            nh = np.concatenate([nh, np.full(len(extra[0]), 4)])
            dof = np.concatenate([dof, np.full(len(extra[0]), 2)])
        entry["candidate tracks"] = len(rows)
        if len(rows) == 0:
            return
        # within a hit count, rank by the fit's p-value (for one d.o.f. the same as by χ²)
        order = np.lexsort((-_chi2_dist.logsf(chi, np.maximum(dof, 1)), -nh))
        pos = np.empty(len(rows), dtype=np.int64)
        pos[order] = np.arange(len(rows))
        defer = np.zeros(len(rows), bool)
        if self.hold and k < self.last:
            # hold-and-confirm: a three-hit candidate ending in this frame waits one frame, so a
            # longer track through its detections (next frame's search) is preferred to it
            defer = (nh == 3) & (rows[:, -1] >= 0)
        if np.any(defer):
            keep = np.flatnonzero(~defer)
            win = keep[greedy_disjoint(rows[keep], pos[keep], len(self.avail_flat))]
        else:
            win = greedy_disjoint(rows, pos, len(self.avail_flat))
        entry["conflicts"] = int(len(rows) - len(win) - defer.sum())
        entry["confirmed"] = len(win)
        if np.any(defer):
            used = np.zeros(len(self.avail_flat), bool)
            wr = rows[win]
            used[wr[wr >= 0]] = True
            d = rows[defer]
            d = d[~np.any(used[np.maximum(d, 0)] & (d >= 0), axis=1)]
            # the three hits of each deferred candidate, in frame order
            self.held = np.sort(np.where(d >= 0, d, np.iinfo(np.int64).max), axis=1)[:, :3]
            entry["deferred"] = len(self.held)
        if len(win) == 0:
            return
        rows, pm, v, chi, nh = rows[win], pm[win], v[win], chi[win], nh[win]
        ok = rows >= 0
        self.avail_flat[rows[ok]] = False
        infos = _track_infos(pm, v, cfg.origin_px)
        for info, c, n in zip(infos, chi.tolist(), nh.tolist()):
            info.update(method="modified_hough", chi2=c, n_hits=int(n))
        g = np.maximum(rows, 0)
        f = self.frame_of[g]
        self.handoff.confirm_batch(f, np.where(ok, g - self.off[f], -1), k, self.fw, info=infos)

    def _extend_quadratic(self, rows: np.ndarray, slot_t: np.ndarray, lo: int, first: int):
        """Four-hit constant-acceleration extensions of three-hit rows: for each empty slot,
        the nearest available detection inside the χ² (2 d.o.f.) disc of the quadratic through
        the three hits. Returns (rows, χ², mean position, velocity) as ``_accel_tracks``."""
        m = rows.shape[1]
        out, chis = [], []
        hit_slots = np.sort(np.where(rows >= 0, np.arange(m)[None, :], m), axis=1)[:, :3]
        g = np.take_along_axis(rows, hit_slots, 1)
        ts = slot_t[hit_slots]
        xy = self.xy_flat[g]  # (n, 3, 2)
        for s in range(m):
            f = first + s
            if f < lo or not np.any(self.available[f]):
                continue
            emp = np.flatnonzero(rows[:, s] < 0)
            if len(emp) == 0:
                continue
            tq = slot_t[s]
            t3 = ts[emp]
            lag = np.stack([np.prod([(tq - t3[:, j]) / (t3[:, i] - t3[:, j])
                                     for j in range(3) if j != i], axis=0)
                            for i in range(3)], 1)
            pred = np.einsum("ni,nij->nj", lag, xy[emp])
            var = 1.0 + (lag * lag).sum(axis=1)
            r = self.sigma * np.sqrt(self._thr2 * var)
            it_all = np.flatnonzero(self.available[f])
            qi, pi, d2 = PointGrid(self.xys[f][it_all], float(r.max())).query(pred, r)
            if len(qi) == 0:
                continue
            o = np.lexsort((d2, qi))
            qi, pi, d2 = qi[o], pi[o], d2[o]
            keep = np.r_[True, qi[1:] != qi[:-1]]
            qi, pi, d2 = qi[keep], pi[keep], d2[keep]
            ext = rows[emp[qi]].copy()
            ext[:, s] = self.off[f] + it_all[pi]
            out.append(ext)
            chis.append(d2 / (self.sigma**2 * var[qi]))
        if not out:
            z = np.zeros((0, 2))
            return np.zeros((0, m), dtype=np.int64), np.zeros(0), z, z
        rows4, chi = np.concatenate(out), np.concatenate(chis)
        _, _tm, pm, v, _ = self._fit(rows4, slot_t)
        speed = np.hypot(v[:, 0], v[:, 1])
        ok = (speed >= self.cfg.v_min) & (speed <= self.cfg.v_max)
        return rows4[ok], chi[ok], pm[ok], v[ok]

    def _extend(self, rows: np.ndarray, slot_t: np.ndarray, lo: int, first: int) -> np.ndarray:
        """Add, per row, the nearest available detection of each empty window slot inside the
        gate of the constant-velocity prediction (the full χ² test follows)."""
        m = rows.shape[1]
        for s in range(m):
            f = first + s
            if f < lo or not np.any(self.available[f]):
                continue
            emp = np.flatnonzero(rows[:, s] < 0)
            if len(emp) == 0:
                continue
            sub = rows[emp]
            mask, tm, pm, v, _ = self._fit(sub, slot_t)
            nh = mask.sum(axis=1)
            dtc = (slot_t[None, :] - tm[:, None]) * mask
            var = 1.0 + 1.0 / nh + (slot_t[s] - tm) ** 2 / (dtc * dtc).sum(axis=1)
            pred = pm + v * (slot_t[s] - tm)[:, None]
            r = self.sigma * np.sqrt(self.thr[min(self.m, 4)] * var)
            it_all = np.flatnonzero(self.available[f])
            qi, pi, d2 = PointGrid(self.xys[f][it_all], float(r.max())).query(pred, r)
            if len(qi) == 0:
                continue
            o = np.lexsort((d2, qi))
            qi, pi = qi[o], pi[o]
            keep = np.r_[True, qi[1:] != qi[:-1]]
            ext = sub[qi[keep]].copy()
            ext[:, s] = self.off[f] + it_all[pi[keep]]
            rows = np.concatenate([rows, ext])
        return rows


class _GrowEngine(_VerifiedEngine):
    """The verified initiator with track growth over the whole sequence (internal; ``grow``).

    1. **Seeds**: the three 3-of-4 triplet shapes of every frame ``k`` — the outer pair
       ``(k−2, k)`` with the third detection in ``k−1``, ``(k−3, k)`` with the third in ``k−2``
       or ``k−1`` — found with the χ² disc of the constant-velocity interpolation widened by
       the largest acceleration offset ``a√2/2·|(t − t_a)(t − t_b)|`` (``a = accel_px_s2``),
       cut per frame triple so that the widened discs hold at most ``seed_budget`` chance
       triplets in expectation (uniform clutter over the field).
    2. **Growth**: every seed takes, frame by frame (nearest in time first, inside frames
       before outside), the nearest detection inside the χ² (2 d.o.f.) disc of its
       least-squares **constant-acceleration** fit's prediction (prediction variance from the
       fit's leverage, so irregular intervals and gaps are handled), the disc cut per frame so
       that it holds at most ``grow_chance`` chance detections in expectation (a burst frame
       gets a smaller disc); a hit is kept if the fit's χ² (``2(n − 3)`` d.o.f.) still passes.
    3. **Candidates**: grown tracks of ≥ 4 hits (constant-acceleration χ²), and seeds that did
       not grow if they pass the strict constant-velocity χ² test (the paper-scene rule), all
       inside the velocity gate.
    4. **Conflicts**: one best-first selection over the whole sequence — more hits first, then
       the fit's p-value — so a chance triplet (through a burst frame or not) cannot take a
       detection from a longer track. A track's ``confirmed_at`` is the first frame at which
       its hits meet the ``(m−1)/m`` rule.
    """

    def __init__(self, cfg, xys, times, frames, perms, log):
        super().__init__(cfg, xys, times, frames, perms, log)

        n_f = len(xys)
        self.q_acc = 0.0
        self.chance_budget = 0.0
        # χ² thresholds of the constant-acceleration fit: 2 (n − 3) d.o.f. for n hits
        self.thr_ca = np.array([np.inf] * 4 + [_chi2_ppf(1.0 - cfg.alpha, 2 * (n - 3))
                                               for n in range(4, max(n_f, 4) + 1)])
        self.thr_cv3 = _chi2_ppf(1.0 - cfg.alpha, 2)
        self.area = _field_area(cfg, self.xy_flat)
        if len(self.xy_flat):
            self.box = (self.xy_flat.min(axis=0), self.xy_flat.max(axis=0))
        else:
            self.box = (np.zeros(2), np.zeros(2))
        self.n_det = np.array([len(x) for x in xys], dtype=float)

    def run(self) -> ModifiedHoughRun:
        n_f = len(self.xys)
        seeds = [self._seeds(k) for k in range(2, n_f)]
        self.n_seeds = [0, 0][:n_f] + [len(x) for x in seeds]
        seeds = [s for s in seeds if len(s)]
        if not seeds:
            return ModifiedHoughRun([], self._log([], []))
        trip = np.concatenate(seeds)
        # the frame triples of the shapes are distinct, so no seed is found twice
        trip = np.take_along_axis(trip, np.argsort(self.frame_of[trip], axis=1), 1)
        tri = self._tri_stats(trip)
        rows = np.full((len(trip), n_f), -1, dtype=np.int64)
        np.put_along_axis(rows, self.frame_of[trip], trip, axis=1)
        grown, rss_g = self._grow(rows, tri)
        nh = (grown >= 0).sum(axis=1)
        long_ = nh >= 4
        cands, chis, dofs, fits = [], [], [], []
        if np.any(long_):
            g4, first = np.unique(grown[long_], axis=0, return_index=True)
            _, tm4, pm4, v4, _ = self._fit(g4, self.times)
            cands.append(g4)
            chis.append(rss_g[long_][first] / self.sigma**2)
            dofs.append(2 * ((g4 >= 0).sum(axis=1) - 3))
            fits.append((tm4, pm4, v4, self._missed(g4 >= 0, pm4, v4, tm4)))
        # three-hit candidates: the seeds that did not grow, through the strict
        # constant-velocity test or as accelerating triplets (``triplet_budget``)
        s3 = np.flatnonzero(~long_)
        if len(s3):
            t3 = {k: val[s3] for k, val in tri.items()}
            chi = t3["chi_cv"]
            speed = np.hypot(t3["v"][:, 0], t3["v"][:, 1])
            ok = (chi <= self.thr_cv3) | (
                (self.cfg.triplet_budget > 0) & (t3["e2"] <= t3["r_acc"] ** 2))
            ok &= (speed >= self.cfg.v_min) & (speed <= self.cfg.v_max)
            s3 = s3[ok]
            t3 = {k: val[ok] for k, val in t3.items()}
            missed = self._missed(rows[s3] >= 0, t3["pm"], t3["v"], t3["tm"])
            keep = (t3["chi_cv"] <= self.thr_cv3) | (missed <= self.cfg.max_missed)
            s3 = s3[keep]
            cands.append(rows[s3])
            chis.append(t3["chi_cv"][keep])
            dofs.append(np.full(len(s3), 2))
            fits.append((t3["tm"][keep], t3["pm"][keep], t3["v"][keep], missed[keep]))
        rows = np.concatenate(cands)
        chi = np.concatenate(chis)
        dof = np.concatenate(dofs)
        if len(rows) == 0:
            return ModifiedHoughRun([], self._log([], []))
        _tm, pm, v, missed = (np.concatenate(x) for x in zip(*fits))
        speed = np.hypot(v[:, 0], v[:, 1])
        ok = (speed >= self.cfg.v_min) & (speed <= self.cfg.v_max)
        rows, chi, dof, pm, v, missed = rows[ok], chi[ok], dof[ok], pm[ok], v[ok], missed[ok]
        nh = (rows >= 0).sum(axis=1)
        key = nh - self.cfg.miss_weight * missed
        # log p-value of the fit (closed form for 2 d.o.f., the three-hit tracks)
        lp = -0.5 * chi
        big = dof != 2
        if np.any(big):
            lp[big] = _chi2_dist.logsf(chi[big], dof[big])
        order = np.lexsort((-lp, -key))
        pos = np.empty(len(rows), dtype=np.int64)
        pos[order] = np.arange(len(rows))
        win = greedy_disjoint(rows, pos, len(self.avail_flat))
        if self.cfg.share_missed >= 0:
            win = self._second_chance(rows, pos, nh, win, missed)
        self.cand_conf = self._confirmed_at(rows >= 0)
        rows, chi, nh, pm, v = rows[win], chi[win], nh[win], pm[win], v[win]
        conf = self.cand_conf[win]
        infos = _track_infos(pm, v, self.cfg.origin_px)
        tracks = []
        for r, c, n, k, info in zip(rows.tolist(), chi.tolist(), nh.tolist(), conf.tolist(),
                                    infos):
            info.update(method="modified_hough", chi2=c, n_hits=int(n), grown=True)
            hits = [(f, int(self.perms[f][g - self.off[f]])) for f, g in enumerate(r) if g >= 0]
            tracks.append(Track(hits=hits, confirmed_at=int(k), info=info))
        o = np.argsort(conf, kind="stable")
        tracks = [tracks[i] for i in o]
        return ModifiedHoughRun(tracks, self._log(rows, conf))

    def _second_chance(self, rows, pos, nh, win, missed) -> np.ndarray:
        """Three-hit candidates lost in the selection that share exactly one detection with
        selected three-hit tracks (none with longer ones) and have at most ``share_missed``
        in-field frames without a hit are added, disjoint among themselves (a detection is in
        at most two tracks)."""
        n = len(self.avail_flat)
        cnt = np.zeros(n, np.int64)
        long_used = np.zeros(n, bool)
        wr = rows[win]
        cnt[wr[wr >= 0]] += 1
        wl = wr[nh[win] >= 4]
        long_used[wl[wl >= 0]] = True
        lost = np.ones(len(rows), bool)
        lost[win] = False
        c = np.flatnonzero(lost & (nh == 3) & (missed <= self.cfg.share_missed))
        if len(c) == 0:
            return win
        r = rows[c]
        g = np.maximum(r, 0)
        shared = ((r >= 0) & (cnt[g] > 0)).sum(axis=1)
        ok = (shared == 1) & ~np.any((r >= 0) & long_used[g], axis=1)
        c = c[ok]
        if len(c) == 0:
            return win
        # disjoint among themselves (so a detection is in at most two tracks)
        add = c[greedy_disjoint(rows[c], pos[c], n)]
        return np.concatenate([win, add])

    def _tri_stats(self, trip: np.ndarray) -> dict:
        """Per seed (three global ids in frame order): times, the middle hit's squared
        deviation ``e2`` from the chord, the constant-velocity χ² (``e2 / (σ² c)``,
        ``c = 1 + λ² + (1 − λ)²``), the least-squares constant-velocity fit (mean time,
        position, velocity) and the acceptance radius ``r_acc`` of an accelerating triplet:
        the χ² disc widened by the largest acceleration offset ``a√2/2 (t2 − t1)(t3 − t2)``,
        cut so that such discs hold at most ``triplet_budget`` chance triplets per frame
        triple in expectation (never below the χ² disc)."""
        cfg = self.cfg
        f = self.frame_of[trip]
        t = self.times[f]
        p = self.xy_flat[trip]
        t1, t2, t3 = t[:, 0], t[:, 1], t[:, 2]
        lam = (t2 - t1) / (t3 - t1)
        e = p[:, 1] - p[:, 0] - lam[:, None] * (p[:, 2] - p[:, 0])
        e2 = e[:, 0] ** 2 + e[:, 1] ** 2
        cfac = 1.0 + lam**2 + (1.0 - lam) ** 2
        tm = t.mean(axis=1)
        tc = t - tm[:, None]
        pm = p.mean(axis=1)
        v = np.einsum("nk,nkc->nc", tc, p) / (tc * tc).sum(axis=1)[:, None]
        r0 = self.sigma * np.sqrt(self.thr_cv3 * cfac)
        widen = cfg.accel_px_s2 * math.sqrt(2.0) / 2.0 * (t2 - t1) * (t3 - t2)
        n1, n2, n3 = self.n_det[f[:, 0]], self.n_det[f[:, 1]], self.n_det[f[:, 2]]
        n_pairs = n1 * n3 * np.minimum(1.0, math.pi * (cfg.v_max * (t3 - t1)) ** 2 / self.area)
        r_b = np.sqrt(cfg.triplet_budget * self.area
                      / (math.pi * np.maximum(n_pairs * n2, 1.0)))
        r_acc = np.maximum(r0, np.minimum(r0 + widen, r_b))
        return {"t1": t1, "t2": t2, "t3": t3, "p": p, "e2": e2, "chi_cv": e2 / (self.sigma**2 * cfac),
                "tm": tm, "pm": pm, "v": v, "r_acc": r_acc}

    def _missed(self, hit, pm, v, tm) -> np.ndarray:
        """Frames in which a row's constant-velocity fit lies inside the field (the box of all
        detections) without a hit (``hit``: ``(n, frames)`` booleans)."""
        dt = self.times[None, :] - tm[:, None]
        x = pm[:, 0:1] + v[:, 0:1] * dt
        y = pm[:, 1:2] + v[:, 1:2] * dt
        (x0, y0), (x1, y1) = self.box
        inside = (x >= x0) & (x <= x1) & (y >= y0) & (y <= y1)
        return (inside & ~hit).sum(axis=1)

    def _log(self, rows, conf) -> list[dict]:
        if not self.log_on:
            return []
        conf = np.asarray(conf, dtype=np.int64)
        cand = getattr(self, "cand_conf", np.zeros(0, np.int64))
        seeds = getattr(self, "n_seeds", [0] * len(self.xys))
        out = []
        for k in range(len(self.xys)):
            n_c, n_w = int(np.sum(cand == k)), int(np.sum(conf == k))
            out.append({"frame": k, "time_s": float(self.times[k]),
                        "candidates": len(self.xys[k]), "triplets": int(seeds[k]),
                        "candidate tracks": n_c, "conflicts": max(n_c - n_w, 0),
                        "confirmed": n_w})
        return out

    def _confirmed_at(self, hit: np.ndarray) -> np.ndarray:
        """First frame at which the hits of each row meet the (m−1)/m rule."""
        m = self.m
        c = np.concatenate([np.zeros((len(hit), 1), np.int64), np.cumsum(hit, axis=1)], 1)
        n_f = hit.shape[1]
        lo = np.maximum(np.arange(n_f) - m + 1, 0)
        win = c[:, 1:] - c[:, lo]
        ok = win >= m - 1
        return np.where(ok.any(axis=1), np.argmax(ok, axis=1), n_f - 1)

    # -- seeds -------------------------------------------------------------------
    def _seeds(self, k: int) -> np.ndarray:
        shapes = [(k - 2, k, k - 1)]
        if k >= 3:
            shapes += [(k - 3, k, k - 2), (k - 3, k, k - 1)]
        out = [self._seed_shape(*s) for s in shapes]
        out = [o for o in out if len(o)]
        return np.concatenate(out) if out else np.zeros((0, 3), dtype=np.int64)

    def _seed_shape(self, fa: int, fb: int, ft: int) -> np.ndarray:
        cfg = self.cfg
        n_a, n_b, n_t = self.n_det[fa], self.n_det[fb], self.n_det[ft]
        if n_a == 0 or n_b == 0 or n_t == 0:
            return np.zeros((0, 3), dtype=np.int64)
        ta, tb, tt = self.times[fa], self.times[fb], self.times[ft]
        dt = tb - ta
        tau = (tt - tb) / dt
        r0 = self.sigma * math.sqrt(self.thr[3] * (1.0 + (1.0 + tau) ** 2 + tau**2))
        widen = cfg.accel_px_s2 * math.sqrt(2.0) / 2.0 * abs((tt - ta) * (tt - tb))
        if cfg.seed_budget > 0:
            n_pairs = n_a * n_b * min(1.0, math.pi * (cfg.v_max * dt) ** 2 / self.area)
            r_b = math.sqrt(cfg.seed_budget * self.area / (math.pi * max(n_pairs * n_t, 1.0)))
            widen = max(0.0, min(widen, r_b - r0))
        return self._triplets(fa, fb, ft, widen=widen)

    # -- growth --------------------------------------------------------------------
    def _grow(self, seed_rows: np.ndarray, tri: dict) -> tuple[np.ndarray, np.ndarray]:
        """Grow the seeds (rows of global ids per frame, −1 empty) with the least-squares
        constant-acceleration fit; returns the grown rows and their residual sums of squares."""
        t = self.times
        n_f = len(t)
        cfg = self.cfg
        rows = seed_rows.copy()
        cap = np.sqrt(cfg.grow_chance * self.area / (math.pi * np.maximum(self.n_det, 1.0)))
        grids = [PointGrid(self.xys[f], float(cap[f])) if len(self.xys[f]) else None
                 for f in range(n_f)]
        tried = rows >= 0
        thr2 = self._thr2
        n = len(rows)
        rss = np.zeros(n)  # the seeds' quadratics pass through their three hits
        nh = np.full(n, 3)
        lo, hi = tri["t1"].copy(), tri["t3"].copy()
        ts = np.stack([tri["t1"], tri["t2"], tri["t3"]], 1)
        for _ in range(n_f - 3):
            dist = np.maximum(np.maximum(lo[:, None] - t[None, :], t[None, :] - hi[:, None]),
                              0.0)
            dist[tried] = np.inf
            target = np.argmin(dist, axis=1)
            act = np.flatnonzero(np.isfinite(dist[np.arange(n), target]))
            if len(act) == 0:
                break
            tgt = target[act]
            tq = t[tgt]
            pred = np.empty((len(act), 2))
            lev = np.empty(len(act))
            three = nh[act] == 3
            i3 = act[three]
            if len(i3):
                # three hits: the quadratic through them (Lagrange), variance σ² Σ L_i²
                tt = ts[i3]
                q = tq[three][:, None]
                lag = np.stack([(q[:, 0] - tt[:, 1]) * (q[:, 0] - tt[:, 2])
                                / ((tt[:, 0] - tt[:, 1]) * (tt[:, 0] - tt[:, 2])),
                                (q[:, 0] - tt[:, 0]) * (q[:, 0] - tt[:, 2])
                                / ((tt[:, 1] - tt[:, 0]) * (tt[:, 1] - tt[:, 2])),
                                (q[:, 0] - tt[:, 0]) * (q[:, 0] - tt[:, 1])
                                / ((tt[:, 2] - tt[:, 0]) * (tt[:, 2] - tt[:, 1]))], 1)
                pred[three] = np.einsum("nk,nkc->nc", lag, tri["p"][i3])
                lev[three] = (lag * lag).sum(axis=1)
            if not np.all(three):
                pred[~three], lev[~three] = _ca_predict(t, self.xy_flat, rows[act[~three]],
                                                        tq[~three])
            r = np.minimum(self.sigma * np.sqrt(thr2 * (1.0 + lev)), cap[tgt])
            tried[act, tgt] = True
            new_r, new_f, new_g, new_d = [], [], [], []
            for f in np.unique(tgt).tolist():
                if grids[f] is None:
                    continue
                sel = np.flatnonzero(tgt == f)
                qi, pi, d2 = grids[f].query(pred[sel], r[sel], sort=False)
                if len(qi) == 0:
                    continue
                o = np.lexsort((d2, qi))
                qi, pi, d2 = qi[o], pi[o], d2[o]
                keep = np.r_[True, qi[1:] != qi[:-1]]
                new_r.append(sel[qi[keep]])
                new_f.append(np.full(int(keep.sum()), f))
                new_g.append(self.off[f] + pi[keep])
                new_d.append(d2[keep])
            if not new_r:
                continue
            j = np.concatenate(new_r)
            ri, fi, gi = act[j], np.concatenate(new_f), np.concatenate(new_g)
            # least squares: a new hit at distance d from the prediction adds d²/(1 + leverage)
            rss_new = rss[ri] + np.concatenate(new_d) / (1.0 + lev[j])
            ok = rss_new / self.sigma**2 <= self.thr_ca[nh[ri] + 1]
            ri, fi = ri[ok], fi[ok]
            rows[ri, fi] = gi[ok]
            rss[ri] = rss_new[ok]
            nh[ri] += 1
            lo[ri] = np.minimum(lo[ri], t[fi])
            hi[ri] = np.maximum(hi[ri], t[fi])
        return rows, rss

def _ca_fit(t: np.ndarray, xy: np.ndarray, rows: np.ndarray):
    """Least-squares constant-acceleration (quadratic) fits of rows of hits (global ids, −1
    empty; column = frame, times ``t``; at least three distinct times per row), in closed form:
    mean time ``t_m``, coefficients ``(n, 3, 2)`` of ``1, τ, τ²`` (``τ = t − t_m``), residual
    sum of squares and the inverse normal matrix ``(XᵀX)⁻¹`` as its six distinct entries
    ``(i00, i01, i02, i11, i12, i22)``."""
    w = (rows >= 0).astype(float)
    nw = w.sum(axis=1)
    tm = (w @ t) / nw
    tc = (t[None, :] - tm[:, None]) * w
    tc2 = tc * tc
    s0, s2, s3, s4 = nw, tc2.sum(axis=1), (tc2 * tc).sum(axis=1), (tc2 * tc2).sum(axis=1)
    p = xy[np.maximum(rows, 0)] * w[..., None]
    pm = p.sum(axis=1) / nw[:, None]
    pc = (p - pm[:, None, :]) * w[..., None]
    b0 = np.zeros_like(pm)  # Σ w (p − p_m) = 0
    b1 = np.einsum("nm,nmc->nc", tc, pc)
    b2 = np.einsum("nm,nmc->nc", tc2, pc)
    det = s0 * (s2 * s4 - s3 * s3) - s2**3
    i00, i01, i02 = (s2 * s4 - s3 * s3) / det, s2 * s3 / det, -s2 * s2 / det
    i11, i12, i22 = (s0 * s4 - s2 * s2) / det, -s0 * s3 / det, s0 * s2 / det
    c0 = i00[:, None] * b0 + i01[:, None] * b1 + i02[:, None] * b2
    c1 = i01[:, None] * b0 + i11[:, None] * b1 + i12[:, None] * b2
    c2 = i02[:, None] * b0 + i12[:, None] * b1 + i22[:, None] * b2
    rss = (pc * pc).sum(axis=(1, 2)) - (c1 * b1 + c2 * b2).sum(axis=1)
    coef = np.stack([c0 + pm, c1, c2], 1)
    return tm, coef, np.maximum(rss, 0.0), (i00, i01, i02, i11, i12, i22)


def _ca_predict(t: np.ndarray, xy: np.ndarray, rows: np.ndarray, tq: np.ndarray):
    """Prediction at ``tq`` of each row's constant-acceleration fit and its leverage
    ``xᵀ(XᵀX)⁻¹x`` (prediction variance ``σ² · (1 + leverage)`` for a new hit)."""
    tm, coef, _, (i00, i01, i02, i11, i12, i22) = _ca_fit(t, xy, rows)
    d = tq - tm
    d2 = d * d
    pred = coef[:, 0] + coef[:, 1] * d[:, None] + coef[:, 2] * d2[:, None]
    lev = i00 + 2 * i01 * d + (2 * i02 + i11) * d2 + 2 * i12 * d2 * d + i22 * d2 * d2
    return pred, lev

def _field_area(cfg: ModifiedHoughInitiator, xy: np.ndarray) -> float:
    """``field_px`` if given, else the 1st–99th-percentile box of the detections (≥ 1 px²)."""
    if cfg.field_px is not None:
        return float(cfg.field_px[0]) * float(cfg.field_px[1])
    if len(xy) < 2:
        return 1.0
    q = np.percentile(xy, [1.0, 99.0], axis=0)
    return max(float(np.prod(q[1] - q[0] + 1.0)), 1.0)


def _crowded(cfg: ModifiedHoughInitiator, times: np.ndarray, xys: list[np.ndarray]) -> float:
    """Median over frames ``k`` of the expected chance seeds of shape ``(k−2, k | k−1)`` inside
    the unwidened χ² disc (uniform clutter over the field): above ``grow_max_seeds`` the frames
    are too crowded for growth (the causal engine, with its depletion, runs)."""
    t = np.asarray(times, float)
    if len(t) < 3:
        return 0.0
    n = np.array([len(x) for x in xys], dtype=float)
    area = _field_area(cfg, np.concatenate(xys) if n.sum() else np.zeros((0, 2)))
    dt = t[2:] - t[:-2]
    lam = (t[1:-1] - t[:-2]) / dt
    r02 = cfg.sigma_px**2 * _chi2_ppf(1.0 - cfg.alpha, 2) * (1.0 + lam**2 + (1.0 - lam) ** 2)
    pairs = n[:-2] * n[2:] * np.minimum(1.0, math.pi * (cfg.v_max * dt) ** 2 / area)
    return float(np.median(pairs * n[1:-1] * math.pi * r02 / area))


def _burst(xys: list[np.ndarray], factor: float) -> bool:
    """Whether one frame holds more than ``factor`` times the median frame's detections and
    at least 50 more (a clutter burst: chance triplets through it compete for the other
    frames' detections); ``factor`` 0: never."""
    if factor <= 0 or len(xys) < 3:
        return False
    n = np.array([len(x) for x in xys], dtype=float)
    med = float(np.median(n))
    return bool(np.any((n > factor * med) & (n >= med + 50.0)))


def _accelerating(tracks: list[Track], frames: list[Frame], times: np.ndarray,
                  cfg: ModifiedHoughInitiator, min_hits: int | None = None) -> int:
    """How many tracks of at least ``m`` hits the constant-acceleration χ² accepts and the
    constant-velocity χ² rejects (both at ``alpha``, noise ``sigma_px``): the evidence that the
    scene holds accelerating objects (``grow_min_accelerating``)."""
    long_ = [tr for tr in tracks if len(tr.hits) >= (cfg.m if min_hits is None else min_hits)]
    if not long_:
        return 0
    n_f = len(frames)
    pts, rows = [], np.full((len(long_), n_f), -1, dtype=np.int64)
    k = 0
    for i, tr in enumerate(long_):  # a handful of long tracks per scene
        for f, d in tr.hits:
            pts.append(frames[f].xy[d])
            rows[i, f] = k
            k += 1
    xy = np.asarray(pts, float)
    _, _, rss_ca, _ = _ca_fit(times, xy, rows)
    mask = rows >= 0
    g = np.maximum(rows, 0)
    _, _, _, rss_cv = cv_fit_batch(np.broadcast_to(times, rows.shape), xy[g, 0], xy[g, 1], mask)
    nh = mask.sum(axis=1)
    s2 = cfg.sigma_px**2
    ca_ok = rss_ca / s2 <= np.array([_chi2_ppf(1.0 - cfg.alpha, 2 * (n - 3)) for n in nh])
    cv_bad = rss_cv / s2 > np.array([_chi2_ppf(1.0 - cfg.alpha, 2 * (n - 2)) for n in nh])
    return int(np.sum(ca_ok & cv_bad))


def _pad_rows(extra: tuple, m: int) -> tuple:
    """``extra`` (rows, χ², mean position, velocity) with its rows padded on the left to ``m``
    columns (empty slots ``−1``)."""
    rows = extra[0]
    if rows.shape[1] >= m:
        return extra
    pad = np.full((len(rows), m - rows.shape[1]), -1, dtype=np.int64)
    return (np.concatenate([pad, rows], 1), *extra[1:])


def _track_infos(p_mean: np.ndarray, v: np.ndarray, origin) -> list[dict]:
    """ρ, θ (about ``origin``), speed and direction of fitted constant-velocity tracks."""
    b = np.asarray(p_mean, float) - np.asarray(origin, float)
    rho, theta, speed, s = _pair_params(b - v, b, 1.0)
    theta = np.degrees(theta)
    pm = np.asarray(p_mean, float)
    return [{"rho_px": float(rho[i]), "theta_deg": float(theta[i]),
             "speed_px_s": float(speed[i]), "s": int(s[i]),
             "xy_mean_px": (float(pm[i, 0]), float(pm[i, 1])),
             "velocity_px_s": (float(v[i, 0]), float(v[i, 1]))} for i in range(len(pm))]
