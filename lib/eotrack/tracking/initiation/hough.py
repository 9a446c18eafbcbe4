"""Classic Hough-transform track initiation over a batch of scans.

Every detection of the last ``m`` frames is mapped to its curve ``ρ = x cos θ + y sin θ``,
θ ∈ [0, π), and the curves are accumulated in cells ``Δρ × Δθ`` (Yang J.Y., 2019, after
Carlson et al. 1994). Peaks are tracks: the highest cell is taken, its detections (one per frame:
the one closest to the cell's line) form a track when they come from at least ``n`` distinct
frames; their votes are removed and the next peak is examined, until no cell holds ``n`` votes.
The classic transform knows nothing of time or speed: collinear detections in the wrong order or
at an inconsistent speed are accepted — the weakness the modified Hough removes.

:func:`hough_accumulator` is the plain accumulator (the same quantity as
``skimage.transform.hough_line`` on a rasterised image or ``cv2.HoughLinesPointSet`` on the
points), used by the benchmark.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from eotrack.validation import as_points, check_int, check_positive

from .base import Frame, Track, validate_frames
from .gating import TrackHandOff, canonical_order

__all__ = ["HoughAccumulator", "HoughInitiator", "hough_accumulator"]


@dataclass(frozen=True)
class HoughAccumulator:
    """A ρ–θ vote matrix.

    Attributes
    ----------
    votes
        ``(n_rho, n_theta)`` integer counts (``int32``; a transposed view of a θ-major array).
    rho_edges
        ``n_rho + 1`` bin edges (pixels).
    theta
        ``n_theta`` bin centres (radians, in [0, π)).
    bins
        ``(n_points, n_theta)`` ρ-bin of every point at every θ (for vote removal).
    """

    votes: np.ndarray
    rho_edges: np.ndarray
    theta: np.ndarray
    bins: np.ndarray

    def peak(self) -> tuple[float, float, int]:
        """``(ρ centre, θ, votes)`` of the highest cell (ties: lowest ρ, then θ index)."""
        i = int(np.argmax(self.votes))
        r, t = divmod(i, self.votes.shape[1])
        return (0.5 * (self.rho_edges[r] + self.rho_edges[r + 1]), float(self.theta[t]),
                int(self.votes[r, t]))


def hough_accumulator(xy: np.ndarray, d_rho: float = 1.0, d_theta_deg: float = 1.0,
                      rho_max: float | None = None) -> HoughAccumulator:
    """Accumulate the Hough curves of points: one vote per point per θ column.

    Parameters
    ----------
    xy
        Points ``(n, 2)`` (pixels; x = column, y = row).
    d_rho
        ρ bin width (pixels).
    d_theta_deg
        θ step (degrees); θ centres are ``(i + ½) Δθ``, ``i = 0 … ⌈180/Δθ⌉ − 1``.
    rho_max
        The ρ range is ``[−rho_max, rho_max]``; default: the largest ``|xy|`` (rounded up).

    Returns
    -------
    HoughAccumulator
    """
    p = as_points(xy, "xy")
    dr = check_positive(d_rho, "d_rho")
    dth = check_positive(d_theta_deg, "d_theta_deg")
    if dth > 180:
        raise ValueError(f"d_theta_deg must be <= 180, got {dth}")
    r_need = float(np.max(np.hypot(p[:, 0], p[:, 1]))) if len(p) else 0.0
    if rho_max is None:
        rmax = max(dr, math.ceil(r_need / dr) * dr)
    else:
        rmax = check_positive(rho_max, "rho_max")
        if rmax < r_need:
            raise ValueError(f"rho_max={rmax} is smaller than the largest |xy| = {r_need:.3f}")
    n_theta = max(1, math.ceil(180.0 / dth - 1e-9))
    theta = (np.arange(n_theta) + 0.5) * math.radians(dth)
    theta = np.minimum(theta, math.pi - 1e-12)
    n_rho = math.ceil(2 * rmax / dr) + 1
    edges = -rmax + dr * np.arange(n_rho + 1)
    # ρ + rmax ≥ 0, so truncation is the floor. Worked in blocks of θ columns, so that every
    # temporary is small (a few 100 kB): large fresh arrays cost more in page faults than the
    # arithmetic. One small matrix product per block.
    cs = np.stack([np.cos(theta), np.sin(theta)]) / dr
    off = rmax / dr
    n_pts = len(p)
    bins = np.empty((n_pts, n_theta), dtype=np.int32)
    votes_t = np.empty((n_theta, n_rho), dtype=np.int32)
    step = max(1, min(n_theta, 36_000 // max(n_pts, 1)))
    for j0 in range(0, n_theta, step):
        j1 = min(j0 + step, n_theta)
        rho = p @ cs[:, j0:j1]
        rho += off
        b = rho.astype(np.int32)
        np.minimum(b, n_rho - 1, out=b)
        bins[:, j0:j1] = b
        b += np.arange(j1 - j0, dtype=np.int32) * n_rho
        votes_t[j0:j1] = np.bincount(b.ravel(), minlength=(j1 - j0) * n_rho).reshape(
            j1 - j0, n_rho)
    votes = votes_t.T
    return HoughAccumulator(votes=votes, rho_edges=edges, theta=theta, bins=bins)


@dataclass(frozen=True)
class HoughInitiator:
    """Classic Hough initiator over a sliding batch of the last ``m`` frames.

    Parameters
    ----------
    d_rho
        ρ cell (pixels).
    d_theta_deg
        θ cell (degrees).
    n, m
        A peak is a track when its detections come from ≥ ``n`` distinct frames of the last
        ``m`` (the batch); ``2 ≤ n ≤ m``.
    handoff_gate_px
        Gate of the tracking hand-off after confirmation (pixels).
    """

    d_rho: float = 5.0
    d_theta_deg: float = 1.0
    n: int = 3
    m: int = 4
    handoff_gate_px: float = 5.0

    def __post_init__(self) -> None:
        check_positive(self.d_rho, "d_rho")
        check_positive(self.d_theta_deg, "d_theta_deg")
        if self.d_theta_deg > 180:
            raise ValueError(f"d_theta_deg must be <= 180, got {self.d_theta_deg}")
        check_int(self.m, "m", min_value=2)
        check_int(self.n, "n", min_value=2, max_value=self.m)
        check_positive(self.handoff_gate_px, "handoff_gate_px")

    @property
    def label(self) -> str:
        """Short name."""
        return f"classic Hough {self.n}/{self.m}"

    def initiate(self, frames: Sequence) -> list[Track]:
        """Confirmed tracks from ``frames`` (a sequence of ``(time_s, xy)``)."""
        fr = validate_frames(frames)
        perms = [canonical_order(f.xy) for f in fr]
        xys = [f.xy[p] for f, p in zip(fr, perms)]
        work = [Frame(f.time_s, x) for f, x in zip(fr, xys)]
        avail = [np.ones(len(x), dtype=bool) for x in xys]
        r_all = [float(np.max(np.hypot(x[:, 0], x[:, 1]))) for x in xys if len(x)]
        rho_max = max(self.d_rho, math.ceil(max(r_all, default=0.0) / self.d_rho) * self.d_rho)
        handoff = TrackHandOff(self.handoff_gate_px)
        for k in range(len(work)):
            handoff.claim(k, work[k].time_s, xys[k], avail[k])
            if k + 1 < self.n:
                continue
            lo = max(0, k - self.m + 1)
            f_id = np.concatenate([np.full(int(avail[f].sum()), f) for f in range(lo, k + 1)])
            d_id = np.concatenate([np.flatnonzero(avail[f]) for f in range(lo, k + 1)])
            if len(f_id) < self.n:
                continue
            pts = np.concatenate([xys[f][avail[f]] for f in range(lo, k + 1)])
            for hits in self._peaks(pts, f_id, d_id, rho_max):
                for f, d in hits:
                    avail[f][d] = False
                handoff.confirm(hits, k, work, info={"method": self.label})
        return handoff.tracks(perms)

    def _peaks(self, pts: np.ndarray, f_id: np.ndarray, d_id: np.ndarray,
               rho_max: float) -> list[list[tuple[int, int]]]:
        acc = hough_accumulator(pts, self.d_rho, self.d_theta_deg, rho_max=rho_max)
        votes = acc.votes.copy()
        n_theta = votes.shape[1]
        blocked = np.zeros(votes.shape, dtype=bool)
        alive = np.ones(len(pts), dtype=bool)
        out = []
        theta_idx = np.arange(n_theta)
        while True:
            eff = np.where(blocked, 0, votes)
            i = int(np.argmax(eff))
            r, t = divmod(i, n_theta)
            if eff[r, t] < self.n:
                break
            members = np.flatnonzero(alive & (acc.bins[:, t] == r))
            if len(np.unique(f_id[members])) < self.n:
                blocked[r, t] = True
                continue
            th = acc.theta[t]
            rc = 0.5 * (acc.rho_edges[r] + acc.rho_edges[r + 1])
            res = np.abs(pts[members, 0] * math.cos(th) + pts[members, 1] * math.sin(th) - rc)
            order = members[np.lexsort((pts[members, 1], pts[members, 0], res, f_id[members]))]
            first = order[np.r_[True, f_id[order[1:]] != f_id[order[:-1]]]]
            out.append([(int(f_id[j]), int(d_id[j])) for j in first])
            alive[first] = False
            np.subtract.at(votes, (acc.bins[first].ravel(), np.tile(theta_idx, len(first))), 1)
        return out
